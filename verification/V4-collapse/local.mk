VERIFY_CASES += verification/V4-collapse
TESTS += verification/V4-collapse/check
