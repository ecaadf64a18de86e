# Repulsion from wall springs: a straight wall pushes the same however many springs it is cut into;
# corners (L, T, +) keep energy, forces and momenta consistent (tests/test_repulsion_subdivision.cpp);
# the force is smooth across the joints of bent walls and the gradient of the energy there
# (tests/test_repulsion_joints.cpp).
turgor_test_program(test_repulsion_subdivision)
turgor_add_test(test_repulsion_subdivision COMMAND test_repulsion_subdivision LABELS unit fine)
turgor_test_program(test_repulsion_joints)
turgor_add_test(test_repulsion_joints COMMAND test_repulsion_joints LABELS unit fine)
