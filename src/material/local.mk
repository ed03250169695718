noinst_LTLIBRARIES += libmpm_material.la
libmpm_material_la_SOURCES = src/material/material.c src/material/material.h \
	src/material/elastic.c src/material/mu_i.c src/material/ngf.c \
	src/material/density.c src/material/density.h \
	src/material/hyper.c src/material/hyper.h src/material/hyper_math.h

check_PROGRAMS += tests/test_mu_i tests/test_ngf
TESTS += tests/test_mu_i tests/test_ngf
tests_test_mu_i_SOURCES = tests/test_mu_i.c
tests_test_mu_i_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_mu_i_LDADD = libmpm_material.la libmpm_core.la $(CHECK_LIBS) -lm
tests_test_ngf_SOURCES = tests/test_ngf.c
tests_test_ngf_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_ngf_LDADD = libmpm_material.la libmpm_core.la $(CHECK_LIBS) -lm

check_PROGRAMS += tests/test_hyper
TESTS += tests/test_hyper
tests_test_hyper_SOURCES = tests/test_hyper.c
tests_test_hyper_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_hyper_LDADD = libmpm_material.la libmpm_core.la $(CHECK_LIBS) -lm

check_PROGRAMS += tests/test_material
TESTS += tests/test_material
tests_test_material_SOURCES = tests/test_material.c
tests_test_material_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_material_LDADD = libmpm_material.la libmpm_core.la $(CHECK_LIBS) -lm

check_PROGRAMS += tests/test_density
TESTS += tests/test_density
tests_test_density_SOURCES = tests/test_density.c
tests_test_density_CFLAGS = $(AM_CFLAGS) $(CHECK_CFLAGS)
tests_test_density_LDADD = libmpm_material.la libmpm_mesh.la libmpm_core.la $(CHECK_LIBS) -lm
