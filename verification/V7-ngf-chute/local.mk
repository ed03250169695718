VERIFY_CASES += verification/V7-ngf-chute
TESTS += verification/V7-ngf-chute/check
