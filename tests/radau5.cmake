# The Radau IIA integrator registered as TS type radau5 (src/ts/radau5.cpp, docs/radau5.md):
# its constants, measured order, adaptive stiff runs, dense output and domain-error recovery;
# the same checks under PETSc's PI step controller, and a distributed problem on 2 ranks (MUMPS).
turgor_test(test_radau5)
add_test(NAME test_radau5_dsp COMMAND test_radau5 -ts_adapt_type dsp)
add_test(NAME test_radau5_np2 COMMAND ${MPIEXEC_ROOT} -n 2 $<TARGET_FILE:test_radau5>)

# Van der Pol (mu = 1e3) built with makefile.inc as a user program would be; it fails when its
# error against the literature reference exceeds 10x the tolerance.
add_test(NAME radau5_van_der_pol
  COMMAND sh -c "make -s -C ${PROJECT_SOURCE_DIR}/examples TURGOR_BUILD_DIR=${PROJECT_BINARY_DIR} van_der_pol && ${PROJECT_SOURCE_DIR}/examples/van_der_pol; rc=$?; rm -f ${PROJECT_SOURCE_DIR}/examples/van_der_pol; exit $rc")
set_tests_properties(radau5_van_der_pol PROPERTIES PASS_REGULAR_EXPRESSION "van_der_pol: error within")
