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

# The manual page (docs/granmpm.1.in) names every command and option of the
# usage (--help).
TESTS += tests/man-help.sh
EXTRA_DIST += tests/man-help.sh
