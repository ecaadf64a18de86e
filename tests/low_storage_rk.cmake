# The low-storage Runge-Kutta pair registered as TS type lsrk (src/ts/low_storage_rk.cpp): order
# conditions of its tableau, observed orders of the step and the interpolation, adaptive runs
# against exact solutions and DOPRI, stability function, domain errors, rollback, the work vectors
# (PETSc's malloc tracing counts them), and the same again under the basic step controller (the default is DSP).
turgor_test_program(test_low_storage_rk)
turgor_add_test(test_low_storage_rk COMMAND test_low_storage_rk -malloc_debug LABELS ts unit)
turgor_add_test(test_low_storage_rk_basic COMMAND test_low_storage_rk -malloc_debug -ts_adapt_type basic LABELS ts unit)
