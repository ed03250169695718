noinst_LTLIBRARIES += libmpm_scenario.la
libmpm_scenario_la_SOURCES = src/scenario/fill.c src/scenario/scenario.h
