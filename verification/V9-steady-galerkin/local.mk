VERIFY_CASES += verification/V9-steady-galerkin
TESTS += verification/V9-steady-galerkin/check
check_PROGRAMS += verification/V9-steady-galerkin/v9
verification_V9_steady_galerkin_v9_SOURCES = verification/V9-steady-galerkin/v9.c
verification_V9_steady_galerkin_v9_LDADD = libgranmpm.la $(DEP_LIBS)
