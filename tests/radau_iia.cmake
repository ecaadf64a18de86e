# The Radau IIA integrator registered as TS type radauiia (src/ts/radau_iia.cpp, docs/radau_iia.md):
# its constants, measured order, adaptive stiff runs, dense output, domain-error recovery and its
# registration (radauiia; the radau5 alias where PETSc has no RADAU5); the same checks under PETSc's
# PI step controller, and a distributed problem on 2 ranks (MUMPS).
add_executable(test_radau_iia test_radau_iia.cpp)
target_link_libraries(test_radau_iia PRIVATE turgor)
add_test(NAME radau_iia COMMAND test_radau_iia)
add_test(NAME radau_iia_dsp COMMAND test_radau_iia -ts_adapt_type dsp)
add_test(NAME radau_iia_np2 COMMAND ${MPIEXEC_ROOT} -n 2 $<TARGET_FILE:test_radau_iia>)

# Van der Pol (mu = 1e3) built with makefile.inc as a user program would be; it fails when its
# error against the literature reference exceeds 10x the tolerance.
add_test(NAME radau_iia_van_der_pol
  COMMAND sh -c "make -s -C ${PROJECT_SOURCE_DIR}/examples TURGOR_BUILD_DIR=${PROJECT_BINARY_DIR} van_der_pol && ${PROJECT_SOURCE_DIR}/examples/van_der_pol; rc=$?; rm -f ${PROJECT_SOURCE_DIR}/examples/van_der_pol; exit $rc")
set_tests_properties(radau_iia_van_der_pol PROPERTIES PASS_REGULAR_EXPRESSION "van_der_pol: error within")
