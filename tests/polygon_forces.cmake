# Force terms of polygonal cells (bars, hinges, contact, pressure, viscosity): closed forms, finite
# differences, conservation laws and the dt^2 energy error (tests/test_polygon_forces.cpp).
turgor_test_program(test_polygon_forces)
turgor_add_test(test_polygon_forces COMMAND test_polygon_forces LABELS unit fine)

# Hinges with no polygon to act on (a tissue of wall springs only, as a rank without cells) cost
# nothing and change nothing: the same tip.csv, steps and evaluations as without the term.
set(NO_POLYGONS -mode fine -tissue_cells_x 3 -tissue_cells_y 2 -ts_max_time 5 -fine_snapshots 0 -fine_progress_interval 0 -fine_tip_samples 50 -output_overwrite)
turgor_add_test(hinges_no_polygons COMMAND turgor_app ${NO_POLYGONS} -physics springs,hinges -output_dir hinges_no_polygons LABELS fine hard
  SETUP hinges_no_polygons)
turgor_add_test(hinges_no_polygons_reference COMMAND turgor_app ${NO_POLYGONS} -physics springs -output_dir hinges_no_polygons_ref LABELS fine hard
  SETUP hinges_no_polygons_ref)
turgor_add_test(hinges_no_polygons_change_nothing COMMAND ${CHECK} identical hinges_no_polygons hinges_no_polygons_ref steps rhs_evals LABELS fine hard
  REQUIRES "hinges_no_polygons;hinges_no_polygons_ref")
# The hinges' atan2 without branches, in ulps against long double's and libm's
turgor_test_program(test_hinge_atan2)
turgor_add_test(test_hinge_atan2 COMMAND test_hinge_atan2 LABELS unit fine)
