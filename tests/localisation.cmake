# Localisation in FE² (label fe2): the seed's square-grid RVE under compression loses ellipticity
# (its shear stiffness, 8.8 N/m, is overcome by the initial-stress term: -mode rve on
# config/rve_uniaxial.yaml at -2 % strain has min det Q < 0). A 4 x 1 block clamped on the left,
# pushed toward the clamp by a body force of 100 µm/µs^2: the snapshots' acoustic field finds the
# clamped element first (t = 0.75 µs of snapshots every 0.25 µs, its stress -113 N/m against the
# turgor's -98 at rest); -fe2_stop_at_localisation ends the run after the next step, status
# localised. At 20 µm/µs^2 no snapshot (every 0.25 µs) shows an element that lost ellipticity.
set(LOC_BLOCK -options_file_yaml ${PROJECT_SOURCE_DIR}/config/bending_bar_fe2.yaml -coarse_dm_plex_box_faces 4,1 -coarse_dm_plex_box_upper 100,25
  -ts_max_time 5 -fe2_snapshots 20 -output_overwrite)
turgor_add_test(fe2_localisation_stop COMMAND turgor_app ${LOC_BLOCK} -body_force -100,0 -fe2_stop_at_localisation -output_dir fe2_localisation_stop
  LABELS fe2 SETUP fe2_localisation_stop)
turgor_add_test(fe2_localisation_status COMMAND ${CHECK} equals fe2_localisation_stop status localised LABELS fe2 REQUIRES fe2_localisation_stop)
turgor_add_test(fe2_localisation_element COMMAND ${CHECK} equals fe2_localisation_stop localisation_element 0 LABELS fe2 REQUIRES fe2_localisation_stop)
turgor_add_test(fe2_localisation_time COMMAND ${CHECK} between fe2_localisation_stop localisation_time 0.5 1 LABELS fe2 REQUIRES fe2_localisation_stop)
turgor_add_test(fe2_localisation_stopped_there COMMAND ${CHECK} between fe2_localisation_stop t_final 0.75 1 LABELS fe2 REQUIRES fe2_localisation_stop)
turgor_add_test(fe2_no_localisation COMMAND turgor_app ${LOC_BLOCK} -body_force -20,0 -output_dir fe2_no_localisation LABELS fe2 SETUP fe2_no_localisation)
turgor_add_test(fe2_no_localisation_found COMMAND ${CHECK} between fe2_no_localisation localisation_time -1 -1 LABELS fe2 REQUIRES fe2_no_localisation)
