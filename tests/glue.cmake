# Glue bonds and fracture (issue 11).
turgor_test_program(test_glue)
turgor_add_test(test_glue COMMAND test_glue LABELS unit fine)
