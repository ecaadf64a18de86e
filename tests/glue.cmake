# Glue bonds and fracture (issue 11).
turgor_test_program(test_glue)
turgor_add_test(test_glue COMMAND test_glue LABELS unit fine)

# A refused option over an earlier run's output directory (-output_overwrite): the directory is
# cleared first, so that the summary left behind says "failed", not the earlier run's "completed".
turgor_add_test(output_refused_option_overwrites COMMAND sh -c
  "$<TARGET_FILE:turgor_app> -mode fine -tissue_cells_x 2 -tissue_cells_y 2 -ts_max_time 0.1 -fine_progress_interval 0 -output_dir refused_over -output_overwrite > /dev/null && ! $<TARGET_FILE:turgor_app> -mode fine -tissue_cells_x 2 -tissue_cells_y 2 -wall_stiffness -1 -output_dir refused_over -output_overwrite > /dev/null 2>&1 && grep -q '\"status\": \"failed\"' refused_over/summary.json && ! test -e refused_over/tip.csv"
  LABELS badinput)
