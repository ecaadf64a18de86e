# Declared state (io/declared_state.h, io/checkpoint_file.h; labels restart, mpi): what a restart must
# and must not do, each case a run of the checkpointed scene against the run that was not stopped.

# A force term with history defined in tests/ (test_declared_term.cpp: springs that damage) restarts
# through its declarations alone. The bar bends under a strong gravity, its springs near the clamp
# damage within the first leg. Stopped on 1 rank and continued on 2 with the whole tissue on the
# first (-fine_distribute 0: the same arithmetic), and the other way round, it ends bit for bit as
# the run that was not stopped (final_state_hash, tip.csv byte for byte); stopped on 2 distributed
# ranks and continued on 1, to round-off. The hash is computed in the particles' order, so the
# uninterrupted runs on 1 rank and on 2 (-fine_distribute 0) have the same one.
turgor_test_program(test_declared_term)
set(DAMAGE -tissue_cells_x 8 -tissue_cells_y 2 -physics damage_springs,repulsion,sph,body_force -body_force 0,-4 -damage_onset 1e-4 -damage_failure 2e-2
  -ts_max_time 1.5 -fine_snapshots 0 -fine_progress_interval 0 -fine_tip_samples 100)
set(DAMAGE_RUN $<TARGET_FILE:test_declared_term> ${DAMAGE} -output_overwrite)
turgor_add_test(declared_term_full COMMAND ${DAMAGE_RUN} -output_dir declared_term_full -checkpoint_interval 0.5 LABELS fine restart SETUP declared_term_full)
turgor_add_test(declared_term_damaged COMMAND ${CHECK} positive declared_term_full damage_springs_damaged LABELS fine restart REQUIRES declared_term_full)
turgor_add_test(declared_term_full_np2 COMMAND ${MPIEXEC_ROOT} -n 2 ${DAMAGE_RUN} -fine_distribute 0 -output_dir declared_term_full_np2 LABELS fine restart mpi
  SETUP declared_term_full_np2)
turgor_add_test(declared_term_hash_np2 COMMAND ${CHECK} identical declared_term_full declared_term_full_np2 final_state_hash damage_springs_dissipation
  LABELS fine restart mpi REQUIRES "declared_term_full;declared_term_full_np2")
# 1 -> 2 and 2 -> 1, bit for bit
foreach(way "1;2" "2;1")
  list(GET way 0 a)
  list(GET way 1 b)
  set(dir declared_term_${a}to${b})
  turgor_add_test(${dir}_leg1 COMMAND ${MPIEXEC_ROOT} -n ${a} ${DAMAGE_RUN} -fine_distribute 0 -ts_max_steps 150 -checkpoint_interval 1e6 -output_dir ${dir}
    LABELS fine restart mpi SETUP ${dir}_leg1)
  turgor_add_test(${dir}_stopped COMMAND ${CHECK} equals ${dir} status stopped LABELS fine restart mpi REQUIRES ${dir}_leg1)
  turgor_add_test(${dir}_leg2 COMMAND ${MPIEXEC_ROOT} -n ${b} ${DAMAGE_RUN} -fine_distribute 0 -restart ${dir}/checkpoint.h5 -output_dir ${dir}
    LABELS fine restart mpi REQUIRES ${dir}_leg1 SETUP ${dir}_leg2)
  set_tests_properties(${dir}_leg2 PROPERTIES DEPENDS ${dir}_stopped) # the first leg's summary, before the second's replaces it
  turgor_add_test(${dir}_identical COMMAND ${CHECK} identical declared_term_full ${dir} final_state_hash damage_springs_damaged damage_springs_dissipation
    LABELS fine restart mpi REQUIRES "declared_term_full;${dir}_leg2")
endforeach()
# distributed on 2 ranks -> 1: the damage of each spring found by its id (to round-off: the forces
# of the halo are summed in another order)
turgor_add_test(declared_term_dist_leg1 COMMAND ${MPIEXEC_ROOT} -n 2 ${DAMAGE_RUN} -fine_halo_margin 20 -ts_max_steps 150 -checkpoint_interval 1e6 -output_dir declared_term_dist
  LABELS fine restart mpi SETUP declared_term_dist_leg1)
turgor_add_test(declared_term_dist_leg2 COMMAND ${DAMAGE_RUN} -restart declared_term_dist/checkpoint.h5 -output_dir declared_term_dist
  LABELS fine restart mpi REQUIRES declared_term_dist_leg1 SETUP declared_term_dist_leg2)
turgor_add_test(declared_term_dist_tip COMMAND ${CHECK} tiprel declared_term_dist declared_term_full 1e-10 LABELS fine restart mpi
  REQUIRES "declared_term_full;declared_term_dist_leg2")
turgor_add_test(declared_term_dist_damage COMMAND ${CHECK} samekey declared_term_dist declared_term_full damage_springs_dissipation 1e-9 LABELS fine restart mpi
  REQUIRES "declared_term_full;declared_term_dist_leg2")

# The outputs of a restart into a fresh directory are the whole run's: the rows up to the checkpoint
# are the checkpoint's own (tip.csv byte for byte the uninterrupted run's).
turgor_add_test(declared_term_fresh_first COMMAND ${RESTART_HELPER} first declared_term_full declared_term_first.h5 LABELS fine restart
  REQUIRES declared_term_full SETUP declared_term_fresh_first)
turgor_add_test(declared_term_fresh COMMAND ${DAMAGE_RUN} -restart declared_term_first.h5 -output_dir declared_term_fresh LABELS fine restart
  REQUIRES declared_term_fresh_first SETUP declared_term_fresh)
turgor_add_test(declared_term_fresh_whole COMMAND ${CHECK} identical declared_term_full declared_term_fresh final_state_hash LABELS fine restart
  REQUIRES "declared_term_full;declared_term_fresh")

# A directory holding another run's outputs is refused (its summary.json and tip.csv left as they
# were), unless -output_overwrite, which writes the checkpoint's rows in their place.
turgor_add_test(declared_term_other COMMAND ${DAMAGE_RUN} -fine_tip_samples 50 -output_dir declared_term_other LABELS fine restart SETUP declared_term_other)
turgor_add_test(declared_term_mixed COMMAND ${BAD} "Option -restart declared_term_first.h5: -output_dir .*declared_term_other holds another run's outputs \\(tip.csv"
  $<TARGET_FILE:test_declared_term> ${DAMAGE} -restart declared_term_first.h5 -output_dir ${CMAKE_CURRENT_BINARY_DIR}/declared_term_other
  LABELS fine restart badinput REQUIRES "declared_term_other;declared_term_fresh_first")
turgor_add_test(declared_term_mixed_kept COMMAND ${CHECK} equals declared_term_other status completed LABELS fine restart
  REQUIRES "declared_term_other;declared_term_fresh_first")
set_tests_properties(declared_term_mixed_kept PROPERTIES DEPENDS declared_term_mixed)
turgor_add_test(declared_term_mixed_overwrite COMMAND ${DAMAGE_RUN} -restart declared_term_first.h5 -output_dir declared_term_other -output_overwrite
  LABELS fine restart REQUIRES "declared_term_other;declared_term_fresh_first" SETUP declared_term_mixed_overwrite)
set_tests_properties(declared_term_mixed_overwrite PROPERTIES DEPENDS declared_term_mixed_kept)
turgor_add_test(declared_term_mixed_whole COMMAND ${CHECK} identical declared_term_full declared_term_other final_state_hash LABELS fine restart
  REQUIRES "declared_term_full;declared_term_mixed_overwrite")

# A changed physics parameter, allowed on purpose: recorded in summary.json, and a changed step
# (-fine_dt_safety under verlet, allowed) applies from the restart and the run still ends at its end
# time, in whole steps.
set(DAMAGE_VV ${DAMAGE_RUN} -ts_type verlet -fine_dt_safety 0.5)
turgor_add_test(declared_term_vv_leg1 COMMAND ${DAMAGE_VV} -ts_max_steps 100 -checkpoint_interval 1e6 -output_dir declared_term_vv LABELS fine restart
  SETUP declared_term_vv_leg1)
turgor_add_test(declared_term_vv_leg2 COMMAND ${DAMAGE_VV} -restart declared_term_vv/checkpoint.h5 -fine_dt_safety 0.4 -damage_failure 3e-2
  -restart_allow fine_dt_safety,damage_failure -output_dir declared_term_vv LABELS fine restart REQUIRES declared_term_vv_leg1 SETUP declared_term_vv_leg2)
turgor_add_test(declared_term_vv_end COMMAND ${CHECK} between declared_term_vv t_final 1.4999999999 1.5000000001 LABELS fine restart REQUIRES declared_term_vv_leg2)
turgor_add_test(declared_term_vv_completed COMMAND ${CHECK} equals declared_term_vv status completed LABELS fine restart REQUIRES declared_term_vv_leg2)
turgor_add_test(declared_term_vv_recorded COMMAND ${CHECK} equals declared_term_vv restart_allowed fine_dt_safety,damage_failure LABELS fine restart
  REQUIRES declared_term_vv_leg2)
turgor_add_test(declared_term_vv_changed COMMAND ${CHECK} contains declared_term_vv restart_changed "-damage_failure: 0.02 in the checkpoint, 0.03 now"
  "-fine_dt_safety: 0.5 in the checkpoint, 0.4 now" LABELS fine restart REQUIRES declared_term_vv_leg2)
