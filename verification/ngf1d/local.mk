# Steady 1D NGF reference solver (chute, vertical chute), its self-checks, and
# the comparison of the granmpm NGF kernels with it.
VERIFY_CASES += verification/ngf1d
TESTS += verification/ngf1d/check
# ngf1d itself is built by `make` and installed (in $(pkglibexecdir)): the
# figure drivers draw its reference profiles; its self-checks are not.
pkglibexec_PROGRAMS += verification/ngf1d/ngf1d
check_PROGRAMS += verification/ngf1d/ngf1d-check verification/ngf1d/ngf1d-kernels
verification_ngf1d_ngf1d_SOURCES = verification/ngf1d/main.c verification/ngf1d/ngf1d.c \
	verification/ngf1d/ngf1d.h
verification_ngf1d_ngf1d_LDADD = $(GSL_LIBS) -lm
verification_ngf1d_ngf1d_check_SOURCES = verification/ngf1d/selftest.c verification/ngf1d/ngf1d.c \
	verification/ngf1d/ngf1d.h
verification_ngf1d_ngf1d_check_LDADD = $(GSL_LIBS) -lm
verification_ngf1d_ngf1d_kernels_SOURCES = verification/ngf1d/kernels.c verification/ngf1d/ngf1d.c \
	verification/ngf1d/ngf1d.h
verification_ngf1d_ngf1d_kernels_LDADD = libmpm_nonlocal.la libmpm_shape.la libmpm_material.la libmpm_mesh.la \
	libmpm_core.la $(GSL_LIBS) -lm
