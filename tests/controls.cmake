# Load controls (-controls, -control_<name>_*) and the fine driver's polygon outputs.
turgor_test_program(test_controls)
turgor_add_test(test_controls COMMAND test_controls LABELS unit fine)

# Controls cost nothing and change nothing they should not: a velocity-0 control on the left side
# (-fine_clamp none) gives the same bits as -fine_clamp left, and a zero force control the same
# bits as no control at all (tip.csv byte for byte, the same steps and evaluations).
set(CTL_SMALL -mode fine -tissue_cells_x 3 -tissue_cells_y 2 -ts_max_time 5 -fine_snapshots 0 -fine_progress_interval 0 -fine_tip_samples 50 -output_overwrite)
turgor_add_test(controls_clamp COMMAND turgor_app ${CTL_SMALL} -output_dir ctl_clamp LABELS fine SETUP ctl_clamp)
turgor_add_test(controls_hold COMMAND turgor_app ${CTL_SMALL} -fine_clamp none -controls hold -control_hold_box -1,-1000,1e-9,1000
  -control_hold_velocity 0,0 -output_dir ctl_hold LABELS fine SETUP ctl_hold)
turgor_add_test(controls_hold_is_clamp COMMAND ${CHECK} identical ctl_hold ctl_clamp steps rhs_evals LABELS fine REQUIRES "ctl_hold;ctl_clamp")
turgor_add_test(controls_zero_force COMMAND turgor_app ${CTL_SMALL} -controls z -control_z_cells 1 -control_z_force 0,0 -output_dir ctl_zero
  LABELS fine SETUP ctl_zero)
turgor_add_test(controls_zero_force_changes_nothing COMMAND ${CHECK} identical ctl_zero ctl_clamp steps rhs_evals LABELS fine REQUIRES "ctl_zero;ctl_clamp")
turgor_add_test(controls_summary COMMAND ${CHECK} keys ctl_hold n_nodes n_cells n_bars node_steps_per_s dt_stable n_wall_particles n_springs
  LABELS fine REQUIRES ctl_hold)

# Polygon snapshots: a hand-built tissue of a quadrilateral and a pentagon (XDMF Mixed) and one of
# two quadrilaterals (Polygon, NodesPerElement 4); the mixed one's XDMF agrees with its HDF5 data, and
# where pvpython is found, they are opened in ParaView (cells, cell_id, area_ratio against the points' areas):
# the mixed one with the default reader in the default tier, the quadrilaterals and the legacy reader in
# the long one.
turgor_test_program(test_polygon_snapshots)
turgor_add_test(polygon_snapshots_mixed COMMAND test_polygon_snapshots -dir poly_mixed LABELS fine SETUP poly_mixed)
turgor_add_test(polygon_snapshots_mixed_xdmf COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/check_xdmf.py poly_mixed/particles.xmf LABELS fine REQUIRES poly_mixed)
turgor_add_test(polygon_snapshots_quads COMMAND test_polygon_snapshots -quads -dir poly_quads LABELS fine long SETUP poly_quads)
find_program(TURGOR_PVPYTHON pvpython)
if(TURGOR_PVPYTHON)
  set(tier_quads long)
  set(PVPOLY ${TURGOR_PVPYTHON} --force-offscreen-rendering ${CMAKE_CURRENT_SOURCE_DIR}/check_paraview.py polygons)
  foreach(run mixed quads)
    turgor_add_test(paraview_polygons_${run} COMMAND ${PVPOLY} poly_${run} LABELS paraview fine ${tier_${run}} REQUIRES poly_${run} TIMEOUT 120)
    turgor_add_test(paraview_polygons_${run}_legacy COMMAND ${PVPOLY} poly_${run} --reader XDMFReader LABELS paraview fine long REQUIRES poly_${run}
                    TIMEOUT 120)
  endforeach()
endif()

# -help lists the control options (with a placeholder group name when no -controls is given)
turgor_add_test(help_fine_controls COMMAND ${HELP} fine -controls -control_<name>_nodes -control_<name>_plates -control_<name>_box -control_<name>_velocity
  -control_<name>_force -control_<name>_profile -control_<name>_ramp_time -control_<name>_half_period -control_<name>_delay -control_<name>_duration LABELS unit)

# The tensile scene (config/tensile_pull_fine.yaml), 2 µs into its 20 µs ramp: the pulled side has
# moved v t^2 / (2 T) = 0.05 x 4 / 40 = 0.005 µm
turgor_add_test(controls_scene COMMAND turgor_app -options_file_yaml ${PROJECT_SOURCE_DIR}/config/tensile_pull_fine.yaml -ts_max_time 2
  -fine_snapshots 0 -fine_progress_interval 0 -output_dir ctl_scene -output_overwrite LABELS fine SETUP ctl_scene)
turgor_add_test(controls_scene_ramp COMMAND ${CHECK} column ctl_scene/groups.csv pull_ux -1 0.005 1e-12 LABELS fine REQUIRES ctl_scene)
