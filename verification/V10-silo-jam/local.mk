VERIFY_CASES += verification/V10-silo-jam
TESTS += verification/V10-silo-jam/check
