noinst_LTLIBRARIES += libmpm_io.la
libmpm_io_la_SOURCES = src/io/input.c src/io/output.c src/io/extract.c src/io/io.h
