# Verification cases: each verification/V<n>-<name>/ has a README and an
# executable `check`; `make check` runs `check --quick`, `make verify` runs `check`.
VERIFY_CASES =
