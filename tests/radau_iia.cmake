# The Radau IIA integrator registered as TS type radauiia (src/ts/radau_iia.cpp, docs/radau_iia.md):
# its constants, measured order, adaptive stiff runs, dense output, domain-error recovery and its
# registration (radauiia; the radau5 alias where PETSc has no RADAU5); the same checks under PETSc's
# PI step controller, and a distributed problem on 2 ranks (MUMPS).
turgor_test_program(test_radau_iia)
turgor_add_test(radau_iia COMMAND test_radau_iia LABELS ts unit)
turgor_add_test(radau_iia_dsp COMMAND test_radau_iia -ts_adapt_type dsp LABELS ts unit)
turgor_add_test(radau_iia_np2 COMMAND ${MPIEXEC_ROOT} -n 2 $<TARGET_FILE:test_radau_iia> LABELS ts mpi)

# Van der Pol (mu = 1e3) built with makefile.inc as a user program would be (into the build tree);
# it fails when its error against the literature reference exceeds 10x the tolerance.
turgor_add_test(radau_iia_van_der_pol COMMAND sh -c "${EXAMPLES_MAKE} van_der_pol && ./van_der_pol"
  LABELS ts PASS_REGEX "van_der_pol: error within")

# Accuracy against SciPy's Radau on HIRES and Van der Pol (figures measured by
# bench/radau_vs_scipy.py and stored in the test), and the round-off floor of the tolerances.
turgor_test_program(test_radau_iia_accuracy)
turgor_add_test(radau_iia_accuracy COMMAND test_radau_iia_accuracy LABELS ts unit)
target_compile_definitions(test_radau_iia_accuracy PRIVATE TURGOR_TEST_DATA_DIR="${CMAKE_CURRENT_SOURCE_DIR}/data")
