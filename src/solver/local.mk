noinst_LTLIBRARIES += libmpm_solver.la
libmpm_solver_la_SOURCES = src/solver/step.c src/solver/run.c src/solver/solver.h \
	src/solver/solver_internal.h src/solver/remove.c src/solver/kernels.c src/solver/kernels.inc src/solver/separable.inc \
	src/solver/units.c src/solver/health.c src/solver/plan.c src/solver/state.c src/solver/bodies.c

check_PROGRAMS += tests/test_solver
TESTS += tests/test_solver
tests_test_solver_SOURCES = tests/test_solver.c tests/sim_config.h tests/plane.h
tests_test_solver_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_solver_LDADD = libmpm_solver.la libmpm_diag.la libmpm_scenario.la libmpm_bc.la \
	libmpm_nonlocal.la libmpm_material.la libmpm_shape.la libmpm_mesh.la libmpm_linalg.la \
	libmpm_core.la $(SUITESPARSE_LIBS) $(CHECK_LIBS) -lm

check_PROGRAMS += tests/test_threads
TESTS += tests/test_threads
tests_test_threads_SOURCES = tests/test_threads.c tests/sim_config.h
tests_test_threads_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_threads_LDADD = $(tests_test_solver_LDADD)
check_PROGRAMS += tests/test_silo
TESTS += tests/test_silo
tests_test_silo_SOURCES = tests/test_silo.c tests/sim_config.h tests/plane.h
tests_test_silo_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_silo_LDADD = libmpm_solver.la libmpm_diag.la libmpm_scenario.la libmpm_bc.la \
	libmpm_nonlocal.la libmpm_material.la libmpm_shape.la libmpm_mesh.la libmpm_linalg.la \
	libmpm_core.la $(SUITESPARSE_LIBS) $(CHECK_LIBS) -lm
check_PROGRAMS += tests/test_solver_box
TESTS += tests/test_solver_box
tests_test_solver_box_SOURCES = tests/test_solver_box.c tests/sim_config.h
tests_test_solver_box_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_solver_box_LDADD = $(tests_test_solver_LDADD)

check_PROGRAMS += tests/test_bodies
TESTS += tests/test_bodies
tests_test_bodies_SOURCES = tests/test_bodies.c tests/sim_config.h
tests_test_bodies_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_bodies_LDADD = $(tests_test_solver_LDADD)
