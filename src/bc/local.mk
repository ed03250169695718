noinst_LTLIBRARIES += libmpm_bc.la
libmpm_bc_la_SOURCES = src/bc/bc.c src/bc/bc.h src/bc/walls.c src/bc/bc_internal.h \
	src/bc/bc3.c src/bc/bc3.h

check_PROGRAMS += tests/test_bc3
TESTS += tests/test_bc3
tests_test_bc3_SOURCES = tests/test_bc3.c
tests_test_bc3_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_bc3_LDADD = libmpm_bc.la libmpm_mesh.la libmpm_core.la $(CHECK_LIBS) -lm
