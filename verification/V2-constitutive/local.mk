VERIFY_CASES += verification/V2-constitutive
TESTS += verification/V2-constitutive/check
