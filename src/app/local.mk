bin_PROGRAMS += src/app/granmpm
src_app_granmpm_SOURCES = src/app/main.c src/app/constitutive.c src/app/constitutive.h \
	src/app/analyse.c src/app/analyse.h \
	src/app/state.c src/app/state.h \
	src/app/args.c src/app/args.h \
	src/app/run.c src/app/run.h src/app/plan.c src/app/plan.h src/app/info.c src/app/info.h \
	src/app/threads.c src/app/threads.h
src_app_granmpm_LDADD = libgranmpm.la $(DEP_LIBS)

# The command line of runs that stop and continue (signals, checkpoints,
# resume, --force) and of a sweep killed halfway and started again (the
# sweep scripts through scripts/run-once); they need only the program.
TESTS += tests/cli-survive.sh tests/cli-sweep.sh
EXTRA_DIST += tests/cli-survive.sh tests/cli-sweep.sh

# No two files of src/ call each other in a circle (scripts/call-cycles on
# the objects of the build).
TESTS += tests/cli-calls.sh
EXTRA_DIST += tests/cli-calls.sh

# The examples of docs/output.md (examples/python, examples/paraview) on
# small runs: their pictures and the values they print; skipped without
# python3 with h5py and matplotlib, or without pvpython.
TESTS += tests/python-example.sh tests/paraview-example.sh
EXTRA_DIST += tests/python-example.sh tests/paraview-example.sh examples tests/display.sh \
	tests/small-runs.sh

# The bodies' outlines of run.xdmf as ParaView's three XDMF readers see
# them, plane and 3D (skipped without pvpython).
TESTS += tests/paraview-bodies.sh
EXTRA_DIST += tests/paraview-bodies.sh

# check's size estimate against the peak resident memory and the bytes
# written of a plane run and a 3D run (tests/maxrss runs a command and
# reports its peak).
check_PROGRAMS += tests/maxrss
tests_maxrss_SOURCES = tests/maxrss.c
TESTS += tests/cli-size.sh
EXTRA_DIST += tests/cli-size.sh

# scripts/bench --callgrind gives no figure from a failed measurement (a
# program that fails or does nothing under valgrind, or a build valgrind
# cannot decode), and a plausible one on its tiny case.
TESTS += tests/bench-callgrind.sh
EXTRA_DIST += tests/bench-callgrind.sh

# The manual page (docs/granmpm.1.in) names every command and option of the
# usage (--help).
TESTS += tests/man-help.sh
EXTRA_DIST += tests/man-help.sh
