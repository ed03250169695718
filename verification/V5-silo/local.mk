VERIFY_CASES += verification/V5-silo
TESTS += verification/V5-silo/check
