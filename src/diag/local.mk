noinst_LTLIBRARIES += libmpm_diag.la
libmpm_diag_la_SOURCES = src/diag/diag.c src/diag/diag.h src/diag/flow.c src/diag/flow.h \
	src/diag/region.c src/diag/region.h src/diag/jam.c src/diag/jam.h src/diag/rough.c \
	src/diag/rough.h

check_PROGRAMS += tests/test_diag tests/test_flow
TESTS += tests/test_diag tests/test_flow
tests_test_diag_SOURCES = tests/test_diag.c
tests_test_diag_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_diag_LDADD = libmpm_diag.la libmpm_core.la $(CHECK_LIBS) -lm
tests_test_flow_SOURCES = tests/test_flow.c
tests_test_flow_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_flow_LDADD = libmpm_diag.la libmpm_shape.la libmpm_mesh.la libmpm_core.la \
	$(CHECK_LIBS) -lm
