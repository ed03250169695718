noinst_LTLIBRARIES += libmpm_core.la
libmpm_core_la_SOURCES = src/core/error.c src/core/error.h src/core/points.c \
	src/core/points.h src/core/tensor3.h src/core/config.h src/core/names.h src/core/state.h

check_PROGRAMS += tests/test_core
TESTS += tests/test_core
tests_test_core_SOURCES = tests/test_core.c
tests_test_core_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_core_LDADD = libmpm_material.la libmpm_core.la $(CHECK_LIBS) -lm
