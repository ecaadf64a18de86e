# The polygonal-tissue scenes (config/polygon_*.yaml, config/voronoi_compression.yaml),
# each run by a test against a closed form, a balance law or a second method.
set(CANT -options_file_yaml ${PROJECT_SOURCE_DIR}/config/polygon_cantilever.yaml -fine_snapshots 0 -fine_progress_interval 0 -output_overwrite)
set(CANT_CHECK ${CMAKE_CURRENT_SOURCE_DIR}/check_cantilever.py)
# The cantilever chain at a load small enough for linear theory (F = 1): the static tip deflection is
# the discrete value F/k_r sum (k l0)^2 within 1e-4, Euler-Bernoulli within 2%, the root moment F x_tip
# within 1e-6 of F L.
turgor_add_test(polygon_cantilever_linear COMMAND turgor_app ${CANT} -control_tip_force 0,-1 -output_dir cant_linear LABELS fine SETUP cant_linear)
turgor_add_test(polygon_cantilever_linear_check COMMAND ${CANT_CHECK} cant_linear 1 2e5 101 1 1e-4 0.02 1e-6 LABELS fine REQUIRES cant_linear)
# The scene as it is (F = 100: a deflection of 1.6% of the length): within 1% of the linear discrete
# value, Euler-Bernoulli within 2%, the root moment balances the load in the deformed geometry.
turgor_add_test(polygon_cantilever COMMAND turgor_app ${CANT} -output_dir cant_scene LABELS fine SETUP cant_scene)
turgor_add_test(polygon_cantilever_check COMMAND ${CANT_CHECK} cant_scene 100 2e5 101 1 0.01 0.02 1e-6 LABELS fine REQUIRES cant_scene)
# Plastic hinges (M_max = 40 µN µm: the hinges near the root yield) committed once per accepted step
# by velocity Verlet and by DOPRI (rtol 1e-8): the same static tip and plastic dissipation within 1e-5.
# Long (8 s; test_polygon_forces checks the hinges' return mapping in the default tier).
turgor_add_test(polygon_cantilever_plastic_verlet COMMAND turgor_app ${CANT} -hinge_max_moment 40 -output_dir cant_plastic_verlet LABELS fine long
  SETUP cant_plastic_verlet)
turgor_add_test(polygon_cantilever_plastic_dopri COMMAND turgor_app ${CANT} -hinge_max_moment 40 -ts_type rk -ts_rk_type 5dp -ts_rtol 1e-8 -ts_atol 1e-10
  -output_dir cant_plastic_dopri LABELS fine long SETUP cant_plastic_dopri)
turgor_add_test(polygon_cantilever_plastic_agree COMMAND ${CHECK} final cant_plastic_dopri cant_plastic_verlet 1e-5 LABELS fine long
  REQUIRES "cant_plastic_verlet;cant_plastic_dopri")
turgor_add_test(polygon_cantilever_plastic_dissipation COMMAND ${CHECK} samekey cant_plastic_dopri cant_plastic_verlet hinge_plastic_dissipation 1e-5
  LABELS fine long REQUIRES "cant_plastic_verlet;cant_plastic_dopri")

# The box compression: the cells settle under their turgor for 10 µs with the lid held, when the
# lid's and the other plates' vertical reactions balance (0.5%); and the first 1.5 µs of the lid's
# descent with the default step and half of it: the lid force within 1% (long: the half step takes 8 s).
set(BOX -options_file_yaml ${PROJECT_SOURCE_DIR}/config/polygon_compression.yaml -fine_snapshots 0 -fine_progress_interval 0 -fine_tip_samples 23
  -ts_max_time 11.5 -output_overwrite)
turgor_add_test(polygon_compression COMMAND turgor_app ${BOX} -output_dir box_scene LABELS fine SETUP box_scene)
turgor_add_test(polygon_compression_half_step COMMAND turgor_app ${BOX} -fine_dt_safety 0.25 -output_dir box_half LABELS fine long SETUP box_half)
turgor_add_test(polygon_compression_settled COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/check_groups.py balance box_scene/groups.csv lid walls 5 9.5 0.005
  LABELS fine REQUIRES box_scene)
turgor_add_test(polygon_compression_converged COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/check_groups.py agree box_half/groups.csv box_scene/groups.csv lid_fy 10
  11.5 0.01 LABELS fine long REQUIRES "box_scene;box_half")
turgor_add_test(polygon_compression_summary COMMAND ${CHECK} keys box_scene n_nodes n_cells n_bars steps wall_time_s node_steps_per_s contact_mean_contacts
  stability_limits_dt hinge_plastic_dissipation LABELS fine REQUIRES box_scene)

# The 400-cell uniaxial compression scene, its first µs with the default step and half of it: the top
# plate's reaction within 1%. (Its sides are free: the tissue keeps spreading under its turgor, so
# the plates' reactions do not settle to a balance within the scene's 10 µs delay.) Long: 9 s; the box
# above is a Voronoi tissue too.
set(VOR -options_file_yaml ${PROJECT_SOURCE_DIR}/config/voronoi_compression.yaml -ts_max_time 1 -fine_tip_samples 10 -fine_snapshots 0
  -fine_progress_interval 0 -output_overwrite)
turgor_add_test(voronoi_compression COMMAND turgor_app ${VOR} -output_dir voronoi_scene LABELS fine long SETUP voronoi_scene)
turgor_add_test(voronoi_compression_half_step COMMAND turgor_app ${VOR} -fine_dt_safety 0.25 -output_dir voronoi_half LABELS fine long SETUP voronoi_half)
turgor_add_test(voronoi_compression_converged COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/check_groups.py agree voronoi_half/groups.csv voronoi_scene/groups.csv
  top_fy 0.1 1 0.01 LABELS fine long REQUIRES "voronoi_scene;voronoi_half")

# SIGTERM: once, the run stops after its step (exit 130, summary "interrupted"); twice, at once.
set(INTERRUPT ${CMAKE_CURRENT_SOURCE_DIR}/interrupt_run.py)
turgor_add_test(interrupt_once COMMAND ${INTERRUPT} 1 interrupt_once $<TARGET_FILE:turgor_app> ${BOX} -ts_max_time 90 -fine_progress_interval 0.5 LABELS fine)
turgor_add_test(interrupt_twice COMMAND ${INTERRUPT} 2 interrupt_twice $<TARGET_FILE:turgor_app> ${BOX} -ts_max_time 90 -fine_progress_interval 0.5 -ts_type rk
  -ts_rtol 1e-6 -ts_atol 1e-6 LABELS fine)

# Snapshots of the box (1 µs, 2 snapshots): the XDMF agrees with its HDF5 data, and ParaView (both
# XDMF readers) shows the 64 cells as polygons with area_ratio, a pressure equal to p0 A0/A (the gas
# law, p0 = 50 N/m), the bars' strain and axial force (same sign), and a force on every node.
turgor_add_test(polygon_compression_snapshots COMMAND turgor_app ${BOX} -ts_max_time 1 -fine_snapshots 2 -output_dir box_snapshots LABELS fine
  SETUP box_snapshots)
turgor_add_test(polygon_compression_xdmf COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/check_xdmf.py box_snapshots/particles.xmf LABELS fine
  REQUIRES box_snapshots)
turgor_paraview_polygons(polygon_compression box_snapshots 50)

# The neighbour lists' skin (a length in µm) against a scene of smaller lengths: the default 1 µm in a
# 1 µm long chain is warned about.
turgor_add_test(skin_scene_scale COMMAND turgor_app -mode fine -tissue_type polyline -tissue_bar_radius 0.005 -physics bars,hinges -ts_type verlet
  -ts_max_time 0.01 -fine_snapshots 0 -fine_progress_interval 0 -output_dir skin_scene_scale -output_overwrite LABELS fine
  PASS_REGEX "WARNING: -neighbour_skin 1\\.? µm is more than a quarter of the tissue's size \\(1\\.? µm\\).*about 0\\.005 µm \\(the bar radius\\)")

# The Voronoi bar (config/voronoi_bar_fine.yaml) on 16 cells, 25 µs: the turgor built up over 20 µs
# breaks no bond; at once, its first swing breaks the top surface's (19 bonds)
set(VBAR -options_file_yaml ${PROJECT_SOURCE_DIR}/config/voronoi_bar_fine.yaml -tissue_voronoi_cells 16 -tissue_box 0,0,200,50 -ts_max_time 25
  -fine_snapshots 0 -fine_progress_interval 0 -output_overwrite)
turgor_add_test(voronoi_bar_ramped COMMAND turgor_app ${VBAR} -output_dir vbar_ramped LABELS fine SETUP vbar_ramped)
turgor_add_test(voronoi_bar_ramped_intact COMMAND ${CHECK} between vbar_ramped bonds_broken 0 0 LABELS fine REQUIRES vbar_ramped)
turgor_add_test(voronoi_bar_sudden COMMAND turgor_app ${VBAR} -pressure_ramp_time 0 -output_dir vbar_sudden LABELS fine hard SETUP vbar_sudden)
turgor_add_test(voronoi_bar_sudden_breaks COMMAND ${CHECK} between vbar_sudden bonds_broken 1 1e9 LABELS fine hard REQUIRES vbar_sudden)
# ... and by FE² (config/voronoi_bar_fe2.yaml) with 4-cell RVEs: the released prestress lifts the tip,
# the weight bends it down
turgor_add_test(voronoi_bar_fe2 COMMAND turgor_app -options_file_yaml ${PROJECT_SOURCE_DIR}/config/voronoi_bar_fe2.yaml -prve_cells 4 -output_dir vbar_fe2
  -output_overwrite LABELS fe2 static SETUP vbar_fe2)
turgor_add_test(voronoi_bar_fe2_release COMMAND ${CHECK} column vbar_fe2/tip.csv tip_displacement_y 0 0.063877989 1e-6 LABELS fe2 static REQUIRES vbar_fe2)
turgor_add_test(voronoi_bar_fe2_bends COMMAND ${CHECK} between vbar_fe2 tip_displacement_final -40 -5 LABELS fe2 static REQUIRES vbar_fe2)
# -material_skip_tolerance 1e-4 N/m: points answered from their last solve's expansion, the same bar
# to 1e-5 (measured 1.1e-6 here, 1.4e-8 at K = 16)
turgor_add_test(voronoi_bar_fe2_skip COMMAND turgor_app -options_file_yaml ${PROJECT_SOURCE_DIR}/config/voronoi_bar_fe2.yaml -prve_cells 4
  -material_skip_tolerance 1e-4 -output_dir vbar_fe2_skip -output_overwrite LABELS fe2 static SETUP vbar_fe2_skip)
turgor_add_test(voronoi_bar_fe2_skip_same COMMAND ${CHECK} final vbar_fe2_skip vbar_fe2 1e-5 LABELS fe2 static REQUIRES "vbar_fe2;vbar_fe2_skip")
turgor_add_test(voronoi_bar_fe2_skip_skips COMMAND ${CHECK} positive vbar_fe2_skip rve_skipped_solves LABELS fe2 static REQUIRES vbar_fe2_skip)
