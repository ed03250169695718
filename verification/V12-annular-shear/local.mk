VERIFY_CASES += verification/V12-annular-shear
TESTS += verification/V12-annular-shear/check
