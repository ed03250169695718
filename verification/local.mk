# Verification cases: each verification/V<n>-<name>/ has a README and an
# executable `check`; `make check` runs `check --quick`, `make verify` runs `check`.
VERIFY_CASES =
include verification/V0-kernels/local.mk
include verification/V1-elastic-waves/local.mk
include verification/V2-constitutive/local.mk
include verification/V3-incline/local.mk
include verification/V4-collapse/local.mk
include verification/ngf1d/local.mk
include verification/V7-ngf-chute/local.mk
include verification/V5-silo/local.mk
include verification/V6-hourglass-slug/local.mk
include verification/V8-vertical-chute/local.mk
include verification/V9-steady-galerkin/local.mk
include verification/V10-silo-jam/local.mk
include verification/V11-3d/local.mk
include verification/V12-annular-shear/local.mk
include verification/V13-earth-pressure/local.mk
