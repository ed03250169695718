noinst_LTLIBRARIES += libmpm_mesh.la
libmpm_mesh_la_SOURCES = src/mesh/mesh.c src/mesh/mesh.h \
	src/mesh/bands.c

check_PROGRAMS += tests/test_mesh
TESTS += tests/test_mesh
tests_test_mesh_SOURCES = tests/test_mesh.c tests/box.h tests/plane.h
tests_test_mesh_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_mesh_LDADD = libmpm_mesh.la libmpm_core.la $(CHECK_LIBS) -lm
