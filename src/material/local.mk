noinst_LTLIBRARIES += libmpm_material.la
libmpm_material_la_SOURCES = src/material/material.c src/material/material.h \
	src/material/elastic.c src/material/mu_i.c src/material/ngf.c \
	src/material/history.c src/material/history.h \
	src/material/pointrun.c src/material/reference.c src/material/reference.h

check_PROGRAMS += tests/test_mu_i tests/test_history tests/test_reference tests/test_ngf
TESTS += tests/test_mu_i tests/test_history tests/test_reference tests/test_ngf
tests_test_mu_i_SOURCES = tests/test_mu_i.c
tests_test_mu_i_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_mu_i_LDADD = libmpm_material.la libmpm_core.la $(GSL_LIBS) $(CHECK_LIBS) -lm
# test_history compiles the CSV reader and writer of io/ directly (no HDF5 or
# libconfuse needed).
tests_test_history_SOURCES = tests/test_history.c src/io/history.c src/io/text.c
tests_test_history_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_history_LDADD = libmpm_material.la libmpm_core.la $(GSL_LIBS) $(CHECK_LIBS) -lm
tests_test_reference_SOURCES = tests/test_reference.c
tests_test_reference_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_reference_LDADD = libmpm_material.la libmpm_core.la $(GSL_LIBS) $(CHECK_LIBS) -lm
tests_test_ngf_SOURCES = tests/test_ngf.c
tests_test_ngf_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_ngf_LDADD = libmpm_material.la libmpm_core.la $(GSL_LIBS) $(CHECK_LIBS) -lm
