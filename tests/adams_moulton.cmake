# The Adams-Moulton integrator with functional iteration registered as TS type am
# (src/ts/adams_moulton.cpp, docs/adams_moulton.md): observed orders 1..5, adaptive runs against
# exact solutions, dense output, exact final time, stiff behaviour, fixed-point failures, domain
# errors and rollback; the adaptive checks again under PETSc's PI step controller.
turgor_test_program(test_adams_moulton)
turgor_add_test(test_adams_moulton COMMAND test_adams_moulton LABELS ts unit)
turgor_add_test(test_adams_moulton_dsp COMMAND test_adams_moulton -ts_adapt_type dsp LABELS ts unit)
