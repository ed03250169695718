noinst_LTLIBRARIES += libmpm_solver.la
libmpm_solver_la_SOURCES = src/solver/step.c src/solver/run.c src/solver/solver.h
