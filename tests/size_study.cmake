# The tissue-size study (bench/size_study.py, docs/accuracy-cost.md "tissue size"): quick variants of
# its scenes and of the study itself, labels study and long (52 s together).
#
# The 32 x 32 bar over its first 4 µs: the FE^2 scene (4 x 4 Q2 elements) against the fine scene
# within 3% of the largest deflection (measured 1.0%). The 64 x 64 FE^2 scene over its first 20.48 µs
# (the initial sag, to 45 µm) against the stored fine run (tests/data/fine64_tip_20us: the first 81
# samples of the study's 4670 s fine run, config/bending_bar_64_fine.yaml) within 3% (measured 1.5%).
set(SIZE_FINE -fine_snapshots 0 -fine_progress_interval 0 -output_overwrite)
set(SIZE_FE2 -fe2_snapshots 0 -fe2_progress_interval 0 -output_overwrite)
turgor_add_test(size_fine32_quick COMMAND turgor_app -options_file_yaml ${PROJECT_SOURCE_DIR}/config/bending_bar_32_fine.yaml -ts_max_time 4
  -fine_tip_samples 40 ${SIZE_FINE} -output_dir size_fine32 LABELS study fine long TIMEOUT 120 SETUP size_fine32)
turgor_add_test(size_fe2_32_quick COMMAND turgor_app -options_file_yaml ${PROJECT_SOURCE_DIR}/config/bending_bar_32_fe2.yaml -ts_max_time 4
  -fe2_tip_samples 40 ${SIZE_FE2} -output_dir size_fe2_32 LABELS study fe2 long SETUP size_fe2_32)
turgor_add_test(size_32_agree COMMAND ${CHECK} tiprel size_fe2_32 size_fine32 0.03 LABELS study fe2 long REQUIRES "size_fine32;size_fe2_32")
turgor_add_test(size_fe2_64_quick COMMAND turgor_app -options_file_yaml ${PROJECT_SOURCE_DIR}/config/bending_bar_64_fe2.yaml -ts_max_time 20.48
  -fe2_tip_samples 80 ${SIZE_FE2} -output_dir size_fe2_64 LABELS study fe2 long SETUP size_fe2_64)
turgor_add_test(size_64_agree_stored COMMAND ${CHECK} tiprel size_fe2_64 ${CMAKE_CURRENT_SOURCE_DIR}/data/fine64_tip_20us 0.03 LABELS study fe2 long
  REQUIRES size_fe2_64)
# The study's own pipeline (runs, the bending fit, errors, speed-ups, table, plots) on the 16 x 16 bar
# over 20 µs, Q1 4 x 4 and Q2 2 x 2 against the fine run: max errors measured 13.0% and 9.2%
turgor_add_test(size_fine16_quick COMMAND turgor_app -options_file_yaml ${PROJECT_SOURCE_DIR}/config/bending_bar_fine.yaml -ts_max_time 20
  -fine_tip_samples 200 ${SIZE_FINE} -output_dir size_fine16 LABELS study fine long TIMEOUT 120 SETUP size_fine16)
turgor_add_test(size_study_quick COMMAND ${PROJECT_SOURCE_DIR}/bench/size_study.py --turgor $<TARGET_FILE:turgor_app> --config ${PROJECT_SOURCE_DIR}/config
  --sizes 16 --window 20 --meshes q1:4,q2:2 --tag quick --fine 16=size_fine16 --out size_study_quick --check-max-error 0.15 LABELS study fe2 long TIMEOUT 120
  REQUIRES size_fine16)
