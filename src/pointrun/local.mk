# pointrun: one material point driven by a velocity-gradient history (the
# constitutive driver's numerics). The only module that uses GSL (rkf45 in
# reference.c), so only it and the tests that link it carry $(GSL_LIBS).
noinst_LTLIBRARIES += libmpm_pointrun.la
libmpm_pointrun_la_SOURCES = src/pointrun/history.c src/pointrun/history.h \
	src/pointrun/series.c src/pointrun/series.h \
	src/pointrun/pointrun.c src/pointrun/pointrun.h \
	src/pointrun/reference.c src/pointrun/reference.h
libmpm_pointrun_la_LIBADD = $(GSL_LIBS)

# test_history compiles the CSV reader and writer of io/ directly (no HDF5 or
# libconfuse needed).
check_PROGRAMS += tests/test_history tests/test_reference
TESTS += tests/test_history tests/test_reference
tests_test_history_SOURCES = tests/test_history.c src/io/history.c src/io/text.c
tests_test_history_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_history_LDADD = libmpm_pointrun.la libmpm_material.la libmpm_core.la $(GSL_LIBS) \
	$(CHECK_LIBS) -lm
tests_test_reference_SOURCES = tests/test_reference.c
tests_test_reference_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_reference_LDADD = libmpm_pointrun.la libmpm_material.la libmpm_core.la $(GSL_LIBS) \
	$(CHECK_LIBS) -lm
