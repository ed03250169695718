noinst_LTLIBRARIES += libmpm_bc.la
libmpm_bc_la_SOURCES = src/bc/bc.c src/bc/bc.h src/bc/walls.c src/bc/body.c src/bc/body.h

check_PROGRAMS += tests/test_bc
TESTS += tests/test_bc
tests_test_bc_SOURCES = tests/test_bc.c
tests_test_bc_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_bc_LDADD = libmpm_bc.la libmpm_mesh.la libmpm_core.la $(CHECK_LIBS) -lm

check_PROGRAMS += tests/test_body
TESTS += tests/test_body
tests_test_body_SOURCES = tests/test_body.c
tests_test_body_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_body_LDADD = libmpm_bc.la libmpm_mesh.la libmpm_core.la $(CHECK_LIBS) -lm
