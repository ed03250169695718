noinst_LTLIBRARIES += libmpm_material.la
libmpm_material_la_SOURCES = src/material/material.c src/material/material.h \
	src/material/elastic.c
