VERIFY_CASES += verification/V6-hourglass-slug
TESTS += verification/V6-hourglass-slug/check
