noinst_LTLIBRARIES += libmpm_io.la
# The run output: output.c, with run.xdmf in xdmf.c (output_internal.h).
OUTPUT_PARTS = src/io/output.c src/io/xdmf.c src/io/output_internal.h src/io/bodies_out.c
libmpm_io_la_SOURCES = src/io/input.c $(OUTPUT_PARTS) src/io/extract.c src/io/frame.c \
	src/io/io.h src/io/h5err.c src/io/h5err.h src/io/checkpoint.c
libmpm_io_la_SOURCES += src/io/history.c src/io/history.h src/io/text.c src/io/text.h

# test_output compiles the output and extract sources directly, so it does not
# need the input parser (libconfuse, name tables) that libmpm_io.la carries.
check_PROGRAMS += tests/test_output
TESTS += tests/test_output
tests_test_output_SOURCES = tests/test_output.c tests/tmpdir.h $(OUTPUT_PARTS) src/io/extract.c \
	src/io/frame.c src/io/h5err.c src/io/checkpoint.c
tests_test_output_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_output_LDADD = libmpm_diag.la libmpm_mesh.la libmpm_core.la $(HDF5_LIBS) \
	$(CHECK_LIBS) -lm

# The input reader is input.c (above) and the parts it is split into by
# concern; src/io/input_internal.h says which file holds what.
INPUT_PARTS = src/io/input_internal.h src/io/input_keys.c src/io/input_text.c \
	src/io/input_parse.c src/io/input_value.c src/io/input_override.c src/io/input_check.c \
	src/io/input_shared.c src/io/input_fill.c src/io/input_body.c src/io/input_write.c
libmpm_io_la_SOURCES += $(INPUT_PARTS)

# test_input compiles the input parser directly, so it needs libconfuse and the
# name tables (material, shape, bc, mesh, nonlocal) but not HDF5. cli-input.sh runs
# `granmpm check` on every file under tests/inputs/bad and on the good inputs;
# cli-cylinders.sh runs the 3D cylinders of tests/inputs/good/cylinders.conf.
check_PROGRAMS += tests/test_input
TESTS += tests/test_input tests/cli-input.sh tests/cli-extract.sh tests/cli-faults.sh \
	tests/cli-cylinders.sh
tests_test_input_SOURCES = tests/test_input.c tests/input_case.h src/io/input.c $(INPUT_PARTS) \
	src/io/text.c
tests_test_input_CPPFLAGS = $(AM_CPPFLAGS) -DTEST_SRCDIR='"$(abs_top_srcdir)"'
tests_test_input_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_input_LDADD = libmpm_material.la libmpm_shape.la libmpm_bc.la libmpm_nonlocal.la \
	libmpm_mesh.la libmpm_linalg.la libmpm_core.la $(SUITESPARSE_LIBS) $(CONFUSE_LIBS) $(CHECK_LIBS) -lm
EXTRA_DIST += tests/cli-input.sh tests/cli-extract.sh tests/cli-faults.sh tests/cli-cylinders.sh \
	tests/inputs

# The fuzz targets of the input reader and of resume (tests/fuzz/fuzz_*.c) and
# their seed corpora: built with clang and run by scripts/fuzz, not by make.
EXTRA_DIST += tests/fuzz

# test_input_body: the body sections, built as test_input.
check_PROGRAMS += tests/test_input_body
TESTS += tests/test_input_body
tests_test_input_body_SOURCES = tests/test_input_body.c tests/input_case.h src/io/input.c \
	$(INPUT_PARTS) src/io/text.c
tests_test_input_body_CPPFLAGS = $(tests_test_input_CPPFLAGS)
tests_test_input_body_CFLAGS = $(tests_test_input_CFLAGS)
tests_test_input_body_LDADD = $(tests_test_input_LDADD)

# test_output3: the store's dimension and the output of a 3D store; it also
# writes the 3D run that cli-extract3.sh and paraview3.sh read (--write3).
check_PROGRAMS += tests/test_output3
TESTS += tests/test_output3 tests/cli-extract3.sh tests/paraview3.sh
tests_test_output3_SOURCES = tests/test_output3.c tests/tmpdir.h $(OUTPUT_PARTS) src/io/extract.c \
	src/io/frame.c src/io/h5err.c src/io/checkpoint.c
tests_test_output3_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_output3_LDADD = libmpm_diag.la libmpm_mesh.la libmpm_core.la $(HDF5_LIBS) \
	$(CHECK_LIBS) -lm
EXTRA_DIST += tests/cli-extract3.sh tests/paraview3.sh
