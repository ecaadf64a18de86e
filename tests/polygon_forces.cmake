# Force terms of polygonal cells (bars, hinges, contact, pressure, viscosity): closed forms, finite
# differences, conservation laws and the dt^2 energy error (tests/test_polygon_forces.cpp).
turgor_test_program(test_polygon_forces)
turgor_add_test(test_polygon_forces COMMAND test_polygon_forces LABELS unit fine)
