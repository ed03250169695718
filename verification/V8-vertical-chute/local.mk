VERIFY_CASES += verification/V8-vertical-chute
TESTS += verification/V8-vertical-chute/check
