noinst_LTLIBRARIES += libmpm_scenario.la
libmpm_scenario_la_SOURCES = src/scenario/fill.c src/scenario/scenario.h

check_PROGRAMS += tests/test_scenario
TESTS += tests/test_scenario
tests_test_scenario_SOURCES = tests/test_scenario.c
tests_test_scenario_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_scenario_LDADD = libmpm_scenario.la libmpm_material.la libmpm_mesh.la libmpm_core.la \
	$(CHECK_LIBS) -lm
