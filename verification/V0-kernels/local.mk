VERIFY_CASES += verification/V0-kernels
TESTS += verification/V0-kernels/check
check_PROGRAMS += verification/V0-kernels/v0
verification_V0_kernels_v0_SOURCES = verification/V0-kernels/v0.c
verification_V0_kernels_v0_LDADD = libgranmpm.la $(DEP_LIBS)
