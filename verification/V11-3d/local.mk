VERIFY_CASES += verification/V11-3d
TESTS += verification/V11-3d/check
