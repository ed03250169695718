VERIFY_CASES += verification/V1-elastic-waves
TESTS += verification/V1-elastic-waves/check
