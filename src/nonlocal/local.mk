noinst_LTLIBRARIES += libmpm_nonlocal.la
libmpm_nonlocal_la_SOURCES = src/nonlocal/nonlocal.h src/nonlocal/fluidity.c \
	src/nonlocal/grid.h src/nonlocal/grid.c \
	src/nonlocal/implicit.h src/nonlocal/implicit.c src/nonlocal/field.h src/nonlocal/field.c \
	src/nonlocal/steady.h src/nonlocal/steady.c

check_PROGRAMS += tests/test_nonlocal
TESTS += tests/test_nonlocal
tests_test_nonlocal_SOURCES = tests/test_nonlocal.c
tests_test_nonlocal_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_nonlocal_LDADD = libmpm_nonlocal.la libmpm_shape.la libmpm_linalg.la libmpm_material.la libmpm_mesh.la \
	libmpm_core.la $(SUITESPARSE_LIBS) $(CHECK_LIBS) -lm

check_PROGRAMS += tests/test_implicit
TESTS += tests/test_implicit
tests_test_implicit_SOURCES = tests/test_implicit.c
tests_test_implicit_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_implicit_LDADD = libmpm_nonlocal.la libmpm_shape.la libmpm_linalg.la libmpm_mesh.la libmpm_core.la \
	$(SUITESPARSE_LIBS) $(CHECK_LIBS) -lm

check_PROGRAMS += tests/test_field
TESTS += tests/test_field
tests_test_field_SOURCES = tests/test_field.c
tests_test_field_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_field_LDADD = libmpm_nonlocal.la libmpm_shape.la libmpm_linalg.la libmpm_material.la libmpm_mesh.la \
	libmpm_core.la $(SUITESPARSE_LIBS) $(CHECK_LIBS) -lm

check_PROGRAMS += tests/test_steady
TESTS += tests/test_steady
tests_test_steady_SOURCES = tests/test_steady.c tests/plane.h
tests_test_steady_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_steady_LDADD = libmpm_nonlocal.la libmpm_linalg.la libmpm_shape.la libmpm_material.la \
	libmpm_mesh.la libmpm_core.la $(SUITESPARSE_LIBS) $(CHECK_LIBS) -lm

check_PROGRAMS += tests/test_grid
TESTS += tests/test_grid
tests_test_grid_SOURCES = tests/test_grid.c
tests_test_grid_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_grid_LDADD = libmpm_nonlocal.la libmpm_shape.la libmpm_linalg.la libmpm_mesh.la \
	libmpm_core.la $(SUITESPARSE_LIBS) $(CHECK_LIBS) -lm
