VERIFY_CASES += verification/V13-earth-pressure
TESTS += verification/V13-earth-pressure/check
