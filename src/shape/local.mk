noinst_LTLIBRARIES += libmpm_shape.la
libmpm_shape_la_SOURCES = src/shape/shape.c src/shape/shape.h \
	src/shape/delta.c src/shape/ugimp.c src/shape/corners.h src/shape/corner.c

check_PROGRAMS += tests/test_shape
TESTS += tests/test_shape
tests_test_shape_SOURCES = tests/test_shape.c tests/plane.h
tests_test_shape_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_shape_LDADD = libmpm_shape.la libmpm_mesh.la libmpm_core.la $(CHECK_LIBS) -lm

check_PROGRAMS += tests/test_box_shape
TESTS += tests/test_box_shape
tests_test_box_shape_SOURCES = tests/test_box_shape.c tests/box.h
tests_test_box_shape_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_box_shape_LDADD = libmpm_shape.la libmpm_mesh.la libmpm_core.la $(CHECK_LIBS) -lm
