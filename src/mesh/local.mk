noinst_LTLIBRARIES += libmpm_mesh.la
libmpm_mesh_la_SOURCES = src/mesh/mesh.c src/mesh/mesh.h
