noinst_LTLIBRARIES += libmpm_diag.la
libmpm_diag_la_SOURCES = src/diag/diag.c src/diag/diag.h
