# The polygon RVE material (-material polygon_rve, config/polygon_rve.yaml) in every mode: its unit
# checks are test_polygon_rve (periodicity, symmetry, objectivity, tangents, history, the square
# lattice's closed form); here the runs a user makes, on 4 cells of 2.5 µm bars (one material point)
# and on a 2 x 2 coarse block of 4-cell RVEs with 5 µm bars.
set(PRVE_SCENE -options_file_yaml ${PROJECT_SOURCE_DIR}/config/polygon_rve.yaml -prve_cells 4 -output_overwrite)
set(PRVE_BLOCK ${PRVE_SCENE} -tissue_bar_length 5 -coarse_dm_plex_simplex 0 -coarse_dm_plex_box_faces 2,2 -coarse_dm_plex_box_upper 100,100
  -coarse_dirichlet_label "Face Sets" -coarse_dirichlet_values 4 -body_force 0,-0.2)

# -mode rve: the turgor prestress released and the tissue in tension at 0.6 % (sigma11 from -4.7 to
# +5 N/m), every evaluation relaxed, the tangent elliptic all along; summary.json names the RVE
turgor_add_test(polygon_rve_path COMMAND turgor_app ${PRVE_SCENE} -output_dir polygon_rve_path LABELS rve SETUP polygon_rve_path)
turgor_add_test(polygon_rve_path_summary COMMAND ${CHECK} equals polygon_rve_path rve_cells 4 LABELS rve REQUIRES polygon_rve_path)
turgor_add_test(polygon_rve_path_bonds COMMAND ${CHECK} between polygon_rve_path rve_bonds_intact_per_point 100 1e4 LABELS rve REQUIRES polygon_rve_path)
turgor_add_test(polygon_rve_path_elliptic COMMAND ${CHECK} between polygon_rve_path ellipticity_lost_at -1 -1 LABELS rve REQUIRES polygon_rve_path)
turgor_add_test(polygon_rve_path_prestress COMMAND ${CHECK} column polygon_rve_path/rve.csv s11 0 -4.744 0.01 LABELS rve REQUIRES polygon_rve_path)
turgor_add_test(polygon_rve_path_tension COMMAND ${CHECK} column polygon_rve_path/rve.csv s11 -1 5.747 0.01 LABELS rve REQUIRES polygon_rve_path)
# ... and its first 0.1 % follows the tangent at rest (with the Truesdell terms) to second order:
# 2.1e-3 of the change, 1.73 N/m (without the relaxation, -rve_relax cauchy_born, the change is 3.22)
turgor_add_test(polygon_rve_path_tangent COMMAND ${CHECK} pathtangent polygon_rve_path 1e-2 LABELS rve REQUIRES polygon_rve_path)

# -mode fe2_static and -mode eigen on the block: the prestressed block relaxes (Newton to 1e-10 of the
# prestress's force) and sags; its spectrum is positive definite
turgor_add_test(polygon_fe2_static COMMAND turgor_app ${PRVE_BLOCK} -mode fe2_static -output_dir polygon_fe2_static LABELS fe2 static
  SETUP polygon_fe2_static)
turgor_add_test(polygon_fe2_static_sags COMMAND ${CHECK} between polygon_fe2_static tip_displacement_final -1 -1e-3 LABELS fe2 static
  REQUIRES polygon_fe2_static)
# the RVEs' tangent solver is made at its first tangent: its options are not reported unused at the
# set-up (-strict refused them), and a tighter tangent solve finds the same tip
turgor_add_test(polygon_fe2_static_tangent_options COMMAND turgor_app ${PRVE_BLOCK} -mode fe2_static -rve_tangent_ksp_rtol 1e-10
  -rve_tangent_ksp_max_it 300 -output_dir polygon_fe2_static_tangent_options LABELS fe2 static SETUP polygon_fe2_static_tangent_options)
set_property(TEST polygon_fe2_static_tangent_options APPEND PROPERTY FAIL_REGULAR_EXPRESSION "not used by this -mode[^\n]*rve_tangent")
turgor_add_test(polygon_fe2_static_tangent_options_tip COMMAND ${CHECK} final polygon_fe2_static_tangent_options polygon_fe2_static 1e-6
  LABELS fe2 static REQUIRES "polygon_fe2_static_tangent_options;polygon_fe2_static")
# ... and without a load: the increment starts at the RVEs' accuracy floor (the residual the released
# block reached), where Newton cannot gain 1e-4; the block stays where its prestress put it
turgor_add_test(polygon_fe2_static_unloaded COMMAND turgor_app ${PRVE_BLOCK} -mode fe2_static -body_force 0,0 -output_dir polygon_fe2_static_unloaded
  LABELS fe2 static hard SETUP polygon_fe2_static_unloaded)
turgor_add_test(polygon_fe2_static_unloaded_released COMMAND ${CHECK} between polygon_fe2_static_unloaded tip_displacement_final 5.3332e-3 5.3334e-3
  LABELS fe2 static hard REQUIRES polygon_fe2_static_unloaded)
turgor_add_test(polygon_eigen COMMAND turgor_app ${PRVE_BLOCK} -mode eigen -output_dir polygon_eigen LABELS fe2 eigen SETUP polygon_eigen)
turgor_add_test(polygon_eigen_positive COMMAND ${CHECK} equals polygon_eigen positive_definite True LABELS fe2 eigen REQUIRES polygon_eigen)

# -mode fe2 on 2 ranks against the one-rank run of the restart case (restart_fe2_polygon_full): the
# same tip history to 1e-11 µm (measured 2e-13). Long, with the restart case.
turgor_add_test(polygon_fe2_np2 COMMAND ${MPIEXEC_ROOT} -n 2 $<TARGET_FILE:turgor_app> ${PRVE_BLOCK} -mode fe2 -ts_type rk -ts_rk_type 5dp -ts_max_time 0.4
  -fe2_snapshots 0 -fe2_progress_interval 0 -output_dir polygon_fe2_np2 LABELS fe2 mpi long SETUP polygon_fe2_np2)
turgor_add_test(polygon_fe2_np2_agree COMMAND ${CHECK} tip restart_fe2_polygon_full polygon_fe2_np2 1e-11 LABELS fe2 mpi long
  REQUIRES "restart_fe2_polygon_full;polygon_fe2_np2")

# -path_stop_after_failures: seed 4's four cells in tension collapse at 0.825 % (the 331st evaluation
# of the bench's path, bench/prve_ensemble.py --tension), after which every relaxation fails; with 3
# the path ends at the 333rd instead of relaxing the 68 after it (each a full, failing relaxation)
turgor_add_test(polygon_rve_path_stop COMMAND turgor_app ${PRVE_SCENE} -prve_seed 4 -path_t_final 10 -path_steps 400 -path_tangents 0
  -path_allow_failures -path_stop_after_failures 3 -output_dir polygon_rve_path_stop LABELS rve SETUP polygon_rve_path_stop)
turgor_add_test(polygon_rve_path_stop_evaluations COMMAND ${CHECK} between polygon_rve_path_stop evaluations 333 333 LABELS rve
  REQUIRES polygon_rve_path_stop)
turgor_add_test(polygon_rve_path_stop_failures COMMAND ${CHECK} between polygon_rve_path_stop failures 3 3 LABELS rve REQUIRES polygon_rve_path_stop)
