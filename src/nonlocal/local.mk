noinst_LTLIBRARIES += libmpm_nonlocal.la
libmpm_nonlocal_la_SOURCES = src/nonlocal/nonlocal.h src/nonlocal/fluidity.c

check_PROGRAMS += tests/test_nonlocal
TESTS += tests/test_nonlocal
tests_test_nonlocal_SOURCES = tests/test_nonlocal.c
tests_test_nonlocal_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_nonlocal_LDADD = libmpm_nonlocal.la libmpm_material.la libmpm_mesh.la libmpm_core.la \
	$(CHECK_LIBS) -lm
