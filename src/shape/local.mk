noinst_LTLIBRARIES += libmpm_shape.la
libmpm_shape_la_SOURCES = src/shape/shape.c src/shape/shape.h
