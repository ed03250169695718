noinst_LTLIBRARIES += libmpm_bc.la
libmpm_bc_la_SOURCES = src/bc/bc.c src/bc/bc.h src/bc/walls.c src/bc/bc_internal.h
