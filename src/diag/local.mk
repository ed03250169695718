noinst_LTLIBRARIES += libmpm_diag.la
libmpm_diag_la_SOURCES = src/diag/diag.c src/diag/diag.h src/diag/region.c src/diag/region.h

check_PROGRAMS += tests/test_diag
TESTS += tests/test_diag
tests_test_diag_SOURCES = tests/test_diag.c
tests_test_diag_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_diag_LDADD = libmpm_diag.la libmpm_core.la $(CHECK_LIBS) -lm
