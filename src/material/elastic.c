/* placeholder */ typedef int mpm_placeholder_;
