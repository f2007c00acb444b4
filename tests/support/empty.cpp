// Keeps lumis_test_support non-empty.
