noinst_LTLIBRARIES += libmpm_linalg.la
libmpm_linalg_la_SOURCES = src/linalg/linalg.h src/linalg/linalg.c

check_PROGRAMS += tests/test_linalg
TESTS += tests/test_linalg
tests_test_linalg_SOURCES = tests/test_linalg.c
tests_test_linalg_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_linalg_LDADD = libmpm_linalg.la libmpm_core.la $(SUITESPARSE_LIBS) $(CHECK_LIBS) -lm
