# Repulsion from wall springs: a straight wall pushes the same however many springs it is cut into;
# corners (L, T, +) keep energy, forces and momenta consistent (tests/test_repulsion_subdivision.cpp).
turgor_test_program(test_repulsion_subdivision)
turgor_add_test(test_repulsion_subdivision COMMAND test_repulsion_subdivision LABELS unit fine)
