VERIFY_CASES += verification/V3-incline
TESTS += verification/V3-incline/check
