# Checkpoint and restart of fine and FE^2 runs (label restart): a run of 2T in one go, and the same
# run stopped after some steps (-ts_max_steps) with its end-of-run checkpoint, then continued with
# -restart in the same output directory, end bit for bit the same: tip.csv (and the other time
# series) byte for byte, without duplicated rows, and the same final_state_hash (FNV-1a of the final
# state). Also a restart from a checkpoint written at -checkpoint_interval into a fresh directory.
set(RESTART_HELPER ${CMAKE_CURRENT_SOURCE_DIR}/checkpoint_helper.py)

# name; leg1: the steps of the first leg; INTERVAL: -checkpoint_interval of the full run (it writes
# one checkpoint there and one at the end); FILES: further outputs that must be the same; LAUNCH:
# mpiexec and its arguments; MODE: the label of the mode (fine by default, fe2); LONG: the case is
# in the long tier
function(turgor_restart_case name leg1)
  cmake_parse_arguments(R "LONG" "INTERVAL;MODE" "OPTIONS;FILES;LAUNCH" ${ARGN})
  if(NOT R_MODE)
    set(R_MODE fine)
  endif()
  set(run ${R_LAUNCH} $<TARGET_FILE:turgor_app> ${R_OPTIONS} -output_overwrite)
  set(tier "")
  if(R_LONG)
    set(tier long)
  endif()
  set(labels ${R_MODE} restart ${tier})
  if(R_LAUNCH)
    list(APPEND labels mpi)
  endif()
  turgor_add_test(restart_${name}_full COMMAND ${run} -output_dir restart_${name}_full -checkpoint_interval ${R_INTERVAL}
    LABELS ${labels} SETUP restart_${name}_full)
  turgor_add_test(restart_${name}_leg1 COMMAND ${run} -output_dir restart_${name}_legs -ts_max_steps ${leg1} -checkpoint_interval 1e6
    LABELS ${labels} SETUP restart_${name}_leg1)
  turgor_add_test(restart_${name}_leg2 COMMAND ${R_LAUNCH} $<TARGET_FILE:turgor_app> ${R_OPTIONS} -output_dir restart_${name}_legs
    -restart restart_${name}_legs/checkpoint.h5 LABELS ${labels} REQUIRES restart_${name}_leg1 SETUP restart_${name}_leg2)
  turgor_add_test(restart_${name}_identical COMMAND ${CHECK} identical restart_${name}_full restart_${name}_legs final_state_hash tip_displacement_final
    steps LABELS ${R_MODE} restart ${tier} REQUIRES "restart_${name}_full;restart_${name}_leg2")
  if(R_FILES)
    turgor_add_test(restart_${name}_series COMMAND ${CHECK} samefiles restart_${name}_full restart_${name}_legs ${R_FILES}
      LABELS ${R_MODE} restart ${tier} REQUIRES "restart_${name}_full;restart_${name}_leg2")
  endif()
endfunction()

# A run continued from the first checkpoint (in the run, not at its end) of case `name`'s full run,
# into a fresh directory: the same final tip. label: fine or fe2; the scene's options follow.
function(turgor_restart_fresh name label)
  turgor_add_test(restart_${name}_first COMMAND ${RESTART_HELPER} first restart_${name}_full restart_${name}_first.h5 LABELS ${label} restart
    REQUIRES restart_${name}_full SETUP restart_${name}_first)
  turgor_add_test(restart_${name}_fresh COMMAND turgor_app ${ARGN} -output_dir restart_${name}_fresh -output_overwrite -restart restart_${name}_first.h5
    LABELS ${label} restart REQUIRES restart_${name}_first SETUP restart_${name}_fresh)
  turgor_add_test(restart_${name}_fresh_identical COMMAND ${CHECK} samekey restart_${name}_full restart_${name}_fresh tip_displacement_final 0
    LABELS ${label} restart REQUIRES "restart_${name}_full;restart_${name}_fresh")
endfunction()

# The square-grid bending bar (DOPRI, adaptive: the next step size and the FSAL derivative are
# restored) over 4 µs, stopped after 300 steps (t = 1.19 µs).
set(RESTART_BAR -options_file_yaml ${PROJECT_SOURCE_DIR}/config/bending_bar_fine.yaml -ts_max_time 4 -fine_snapshots 0 -fine_progress_interval 0)
turgor_restart_case(bar 300 INTERVAL 2 OPTIONS ${RESTART_BAR})
# ... and from the checkpoint written at t = 2 µs (not the end) into a fresh directory
turgor_restart_fresh(bar fine ${RESTART_BAR})
# ... and extended: the 4 µs run continued to 6 µs in its own directory (tip.csv: 1000 samples over
# 4 µs, then this run's 1000 over 6 µs from t = 4 on, no row twice)
turgor_add_test(restart_bar_extend_copy COMMAND ${CMAKE_COMMAND} -E copy_directory restart_bar_full restart_bar_extend LABELS fine restart
  REQUIRES restart_bar_full SETUP restart_bar_extend_copy)
turgor_add_test(restart_bar_extend COMMAND turgor_app ${RESTART_BAR} -ts_max_time 6 -output_dir restart_bar_extend -restart restart_bar_extend/checkpoint.h5
  LABELS fine restart REQUIRES restart_bar_extend_copy SETUP restart_bar_extend)
turgor_add_test(restart_bar_extend_rows COMMAND ${CHECK} increasing restart_bar_extend LABELS fine restart REQUIRES restart_bar_extend)
turgor_add_test(restart_bar_fresh_state COMMAND ${CHECK} between restart_bar_full checkpoints_written 2 2 LABELS fine restart REQUIRES restart_bar_full)
# The bar under the low-storage pair (TS lsrk, DSP controller), whose checkpoint holds only the
# solution, the step and the controller's history: the rate at a step's end that tip.csv's
# interpolation evaluated and the next step reuses is evaluated again after the restart, to the bit
turgor_restart_case(bar_lsrk 300 INTERVAL 2 OPTIONS ${RESTART_BAR} -ts_type lsrk FILES tip.csv)

# A 16-cell polygonal tissue under the lid (config/polygon_compression.yaml shortened): contact
# with friction (tangential histories), plastic hinges, cell pressure, velocity controls, the energy
# balance, TS verlet (its last acceleration restored); stopped after 9000 of 25060 steps.
# (-fine_energy_tolerance: the default step of this contact-dominated scene keeps Verlet's energy
# residual at about 5 %; the balance is compared across the restart here)
set(RESTART_POLY -fine_energy_tolerance 0.1 -options_file_yaml ${PROJECT_SOURCE_DIR}/config/polygon_compression.yaml -tissue_voronoi_cells 16 -tissue_box 0,0,100,100
  -ts_max_time 16 -control_lid_delay 1 -control_lid_velocity 0,-3 -fine_snapshots 0 -fine_progress_interval 0 -fine_energy -fine_tip_samples 200)
turgor_restart_case(polygon 9000 INTERVAL 8 OPTIONS ${RESTART_POLY} FILES groups.csv energy.csv)
# the same with the velocity predicted for the dashpots (the last acceleration is checkpointed)
turgor_restart_case(polygon_predicted 6000 INTERVAL 4 OPTIONS ${RESTART_POLY} -ts_max_time 8 -fine_predict_velocity FILES groups.csv energy.csv)

# The glued traction scene on 16 cells (tests/glue.cmake's TRACTION16, v1): stopped after 6000 steps
# (t = 2.74 µs), after the first four bonds broke; breaks.csv continues without duplicates.
set(RESTART_GLUE -options_file_yaml ${PROJECT_SOURCE_DIR}/config/voronoi_traction.yaml -tissue_voronoi_cells 16 -tissue_box 0,0,100,100
  -control_top_box -1,87.5,101,101 -control_bottom_box -1,-1,101,12.5 -fine_snapshots 0 -fine_progress_interval 0 -fine_energy 0
  -fine_dt_safety 0.25 -control_top_velocity 0,0.05 -control_bottom_velocity 0,-0.05 -control_top_ramp_time 5 -control_bottom_ramp_time 5
  -ts_max_time 20)
turgor_restart_case(glue 6000 INTERVAL 10 OPTIONS ${RESTART_GLUE} FILES groups.csv breaks.csv)

# Two ranks (the fine mode keeps the particles on rank 0; the state Vec and the checkpoint are
# parallel), the small square grid with its snapshots.
turgor_restart_case(mpi2 150 INTERVAL 5 LAUNCH ${MPIEXEC_ROOT} -n 2 OPTIONS -mode fine -tissue_cells_x 4 -tissue_cells_y 4 -ts_max_time 10
  -fine_snapshots 2 -fine_progress_interval 0)
turgor_restart_case(mpi2_lsrk 150 INTERVAL 5 LAUNCH ${MPIEXEC_ROOT} -n 2 OPTIONS -mode fine -tissue_cells_x 4 -tissue_cells_y 4 -ts_max_time 10
  -fine_snapshots 2 -fine_progress_interval 0 -ts_type lsrk FILES tip.csv)

# FE^2 with RVEs: the seed's 4 x 4 bending bar (80 material points, one-cell RVEs) over 30 µs with
# DOPRI 5(4) and the DSP step controller (163 steps, 4 rejected), stopped after 80 steps (t = 14.2
# µs): the coarse state, the FSAL derivative, the controller's history and every RVE's warm start,
# kept Jacobian and neighbour lists are restored, so the relaxations after the restart take the same
# iterations and the run ends bit for bit as the uninterrupted one (rve_solves, psi_tc_iterations
# too). On two ranks (two material-point groups, each rank saving its own points), with snapshots
# (the restart's go to coarse_restart_<step>.h5): long, as fe2_rebalance below restarts the bar on
# two ranks bit for bit in the default tier.
set(RESTART_FE2 -options_file_yaml ${PROJECT_SOURCE_DIR}/config/bending_bar_fe2.yaml -ts_max_time 30 -fe2_snapshots 0 -fe2_progress_interval 0
  -ts_type rk -ts_rk_type 5dp)
turgor_restart_case(fe2 80 MODE fe2 INTERVAL 15 OPTIONS ${RESTART_FE2})
turgor_add_test(restart_fe2_work COMMAND ${CHECK} identical restart_fe2_full restart_fe2_legs rve_solves psi_tc_iterations rhs_evals rejected_steps
  LABELS fe2 restart REQUIRES "restart_fe2_full;restart_fe2_leg2")
# with -material_skip_tolerance (an implicit integrator: its tangents are the expansions' bases; the
# checkpoints take explicit ones only): the points rebalanced over 2 ranks move with their expansions
# (base, tangents, measured error; 4 points move after 1 000 evaluations), so the run is the same bits
# as without the rebalance
set(SKIP_FE2 -options_file_yaml ${PROJECT_SOURCE_DIR}/config/bending_bar_fe2.yaml -ts_max_time 30 -fe2_snapshots 0 -fe2_progress_interval 0
  -material_skip_tolerance 3e-3 -output_overwrite)
turgor_add_test(skip_fe2_np2 COMMAND ${MPIEXEC_ROOT} -n 2 $<TARGET_FILE:turgor_app> ${SKIP_FE2} -output_dir skip_fe2_np2 LABELS fe2 mpi
  SETUP skip_fe2_np2)
turgor_add_test(skip_fe2_np2_rebalanced COMMAND ${MPIEXEC_ROOT} -n 2 $<TARGET_FILE:turgor_app> ${SKIP_FE2} -material_rebalance 1000
  -output_dir skip_fe2_np2_rebalanced LABELS fe2 mpi SETUP skip_fe2_np2_rebalanced)
turgor_add_test(skip_fe2_np2_rebalanced_same COMMAND ${CHECK} identical skip_fe2_np2 skip_fe2_np2_rebalanced rve_solves rve_skipped_solves
  psi_tc_iterations LABELS fe2 mpi REQUIRES "skip_fe2_np2;skip_fe2_np2_rebalanced")
turgor_add_test(skip_fe2_np2_skips COMMAND ${CHECK} positive skip_fe2_np2 rve_skipped_solves LABELS fe2 mpi REQUIRES skip_fe2_np2)
turgor_restart_case(fe2_mpi2 80 MODE fe2 INTERVAL 15 LONG LAUNCH ${MPIEXEC_ROOT} -n 2 OPTIONS ${RESTART_FE2} -fe2_snapshots 2)
# ... and under ssp, which cannot interpolate (its tip.csv rows are its step ends; they stopped the
# run before this stop), 2 µs with a checkpoint at 1 µs
turgor_restart_case(fe2_ssp 10 MODE fe2 INTERVAL 1 OPTIONS ${RESTART_FE2} -ts_type ssp -ts_max_time 2 FILES tip.csv)
# ... and from the checkpoint written at t = 15 µs (in the run, not at its end) into a fresh directory
turgor_restart_fresh(fe2 fe2 ${RESTART_FE2})

# FE² of irregular tissue: a 2 x 2 block of polygon RVEs (4 glued, turgid Voronoi cells each) released
# from its turgor prestress under gravity: the RVEs' state, the terms' history (glue damage) included,
# is declared, and the run continues bit for bit. Long (15 s; .ci/run's sanitizer part runs it too).
set(RESTART_FE2_POLYGON -options_file_yaml ${PROJECT_SOURCE_DIR}/config/polygon_rve.yaml -mode fe2 -prve_cells 4 -tissue_bar_length 5
  -coarse_dm_plex_simplex 0 -coarse_dm_plex_box_faces 2,2 -coarse_dm_plex_box_upper 100,100
  -coarse_dirichlet_label "Face Sets" -coarse_dirichlet_values 4 -body_force 0,-0.2 -ts_type rk -ts_rk_type 5dp -ts_max_time 0.4 -fe2_snapshots 0
  -fe2_progress_interval 0)
turgor_restart_case(fe2_polygon 10 MODE fe2 INTERVAL 0.2 LONG OPTIONS ${RESTART_FE2_POLYGON})

# -checkpoint_keep: a checkpoint at every step (warned) of which only the last 3 stay.
turgor_add_test(restart_keep COMMAND turgor_app ${BAD_PRESET_fine} -ts_type rk -output_dir restart_keep -output_overwrite -checkpoint_interval 1e-9
  -checkpoint_keep 3 LABELS fine restart SETUP restart_keep PASS_REGEX "WARNING: a checkpoint at every step.*only the last 3 are kept")
turgor_add_test(restart_keep_count COMMAND ${RESTART_HELPER} count restart_keep 3 LABELS fine restart REQUIRES restart_keep)

# The fixture of the bad-checkpoint cases (tests/bad_input.txt, @RESTART@): a checkpoint of the
# bad-input suite's fine preset, and a copy cut in half; a checkpoint of its fe2 preset (rk 5dp) in
# restart_fixture/fe2.
turgor_add_test(restart_fixture COMMAND turgor_app ${BAD_PRESET_fine} -output_dir restart_fixture -output_overwrite -checkpoint_interval 0.5
  LABELS badinput restart SETUP restart_fixture_run)
turgor_add_test(restart_fixture_fe2 COMMAND turgor_app ${BAD_PRESET_fe2} -ts_type rk -output_dir restart_fixture/fe2 -output_overwrite -checkpoint_interval 0.5
  LABELS badinput restart SETUP restart_fixture)
turgor_add_test(restart_fixture_truncated COMMAND ${RESTART_HELPER} truncate restart_fixture/checkpoint.h5 restart_fixture/truncated.h5
  LABELS badinput restart REQUIRES restart_fixture_run SETUP restart_fixture)
# ... and copies damaged on disk (a byte of the solution's values), edited by HDF5 (a value of the
# solution; the run's time set to -5 with turgor's checksum made to match) and of an older format
# (tests/bad_input.txt, restart_damaged, restart_edited, restart_forged_time, restart_old_format)
turgor_add_test(restart_fixture_damaged COMMAND ${RESTART_HELPER} damage restart_fixture/checkpoint.h5 restart_fixture/damaged.h5
  /state/fine/particles/position LABELS badinput restart REQUIRES restart_fixture_run SETUP restart_fixture)
turgor_add_test(restart_fixture_edited COMMAND ${RESTART_HELPER} edit restart_fixture/checkpoint.h5 restart_fixture/edited.h5
  /state/fine/particles/position 3 0.125 LABELS badinput restart REQUIRES restart_fixture_run SETUP restart_fixture)
turgor_add_test(restart_fixture_forged COMMAND ${RESTART_HELPER} forge restart_fixture/checkpoint.h5 restart_fixture/forged_time.h5
  /state/run/scalars/time 0 -5 LABELS badinput restart REQUIRES restart_fixture_run SETUP restart_fixture)
turgor_add_test(restart_fixture_old COMMAND ${RESTART_HELPER} attribute restart_fixture/checkpoint.h5 restart_fixture/old_format.h5
  format_version 3 LABELS badinput restart REQUIRES restart_fixture_run SETUP restart_fixture)

# SIGTERM: the interrupted run writes its checkpoint after the step it stops at; continued, it ends
# as the uninterrupted one.
turgor_add_test(restart_polygon_interrupted COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/interrupt_run.py 1 restart_polygon_int $<TARGET_FILE:turgor_app>
  ${RESTART_POLY} -fine_progress_interval 0.2 -checkpoint_interval 1e6 LABELS fine restart SETUP restart_polygon_int)
turgor_add_test(restart_polygon_int_continue COMMAND turgor_app ${RESTART_POLY} -output_dir restart_polygon_int -restart restart_polygon_int/checkpoint.h5
  LABELS fine restart REQUIRES restart_polygon_int SETUP restart_polygon_int_continue)
turgor_add_test(restart_polygon_int_identical COMMAND ${CHECK} identical restart_polygon_full restart_polygon_int final_state_hash tip_displacement_final
  steps LABELS fine restart REQUIRES "restart_polygon_full;restart_polygon_int_continue")

# Another rank count (label mpi): a scene whose terms keep no internal state (the small square grid:
# springs, repulsion, SPH, gravity; DOPRI) stopped on 2 ranks, continued on 1 and on 3. The state and
# DOPRI's carried derivative are written in the tissue's particle order; the neighbour lists are
# built afresh, so the forces are summed in another order: the final tip agrees with the
# uninterrupted 1-rank run to 1e-10 of it. (On 3 ranks: long, 6 s on CI's 2 cores.)
set(RESTART_XR -mode fine -tissue_cells_x 4 -tissue_cells_y 4 -ts_max_time 10 -fine_snapshots 0 -fine_progress_interval 0 -output_overwrite)
turgor_add_test(restart_ranks_full COMMAND turgor_app ${RESTART_XR} -output_dir restart_ranks_full LABELS fine restart SETUP restart_ranks_full)
turgor_add_test(restart_ranks_leg1 COMMAND ${MPIEXEC_ROOT} -n 2 $<TARGET_FILE:turgor_app> ${RESTART_XR} -ts_max_steps 150 -checkpoint_interval 1e6
  -output_dir restart_ranks_leg1 LABELS fine restart mpi SETUP restart_ranks_leg1)
foreach(np 1 3)
  set(tier "")
  if(np EQUAL 3)
    set(tier long)
  endif()
  turgor_add_test(restart_ranks_to${np} COMMAND ${MPIEXEC_ROOT} -n ${np} $<TARGET_FILE:turgor_app> ${RESTART_XR} -restart restart_ranks_leg1/checkpoint.h5
    -output_dir restart_ranks_to${np} LABELS fine restart mpi ${tier} REQUIRES restart_ranks_leg1 SETUP restart_ranks_to${np})
  turgor_add_test(restart_ranks_to${np}_agrees COMMAND ${CHECK} samekey restart_ranks_to${np} restart_ranks_full tip_displacement_final 1e-10
    LABELS fine restart mpi ${tier} REQUIRES "restart_ranks_full;restart_ranks_to${np}")
endforeach()

# ... with the tissue generated in parts (-fine_partitioner ranges: no rank holds the whole grid):
# stopped on 2 ranks so built, continued on 1; stopped on 1, continued on 2 so built. The reference
# positions' hash in the checkpoint's fingerprint is the same whatever the ranks and the set-up.
turgor_add_test(restart_ranks_parts_leg1 COMMAND ${MPIEXEC_ROOT} -n 2 $<TARGET_FILE:turgor_app> ${RESTART_XR} -fine_partitioner ranges -ts_max_steps 150
  -checkpoint_interval 1e6 -output_dir restart_ranks_parts_leg1 LABELS fine restart mpi SETUP restart_ranks_parts_leg1)
turgor_add_test(restart_ranks_parts_to1 COMMAND turgor_app ${RESTART_XR} -restart restart_ranks_parts_leg1/checkpoint.h5 -output_dir restart_ranks_parts_to1
  LABELS fine restart mpi REQUIRES restart_ranks_parts_leg1 SETUP restart_ranks_parts_to1)
turgor_add_test(restart_ranks_one_leg1 COMMAND turgor_app ${RESTART_XR} -ts_max_steps 150 -checkpoint_interval 1e6 -output_dir restart_ranks_one_leg1
  LABELS fine restart SETUP restart_ranks_one_leg1)
turgor_add_test(restart_ranks_to2_parts COMMAND ${MPIEXEC_ROOT} -n 2 $<TARGET_FILE:turgor_app> ${RESTART_XR} -fine_partitioner ranges
  -restart restart_ranks_one_leg1/checkpoint.h5 -output_dir restart_ranks_to2_parts LABELS fine restart mpi REQUIRES restart_ranks_one_leg1
  SETUP restart_ranks_to2_parts)
foreach(run parts_to1 to2_parts)
  turgor_add_test(restart_ranks_${run}_agrees COMMAND ${CHECK} samekey restart_ranks_${run} restart_ranks_full tip_displacement_final 1e-10
    LABELS fine restart mpi REQUIRES "restart_ranks_full;restart_ranks_${run}")
endforeach()
turgor_add_test(restart_ranks_to2_parts_built COMMAND ${CHECK} equals restart_ranks_to2_parts setup_in_parts True LABELS fine restart mpi
  REQUIRES restart_ranks_to2_parts)

# Another rank count with internal state: a run stopped on 2 ranks, continued on 1 and on 3 in a copy
# of its directory (the time series go on), against the uninterrupted 1-rank run. Every rank reads
# every writing rank's rank-independent state (global_state: contact histories, plastic and
# reference angles, glue bonds, the dashpots' and the energy balance's sums, Verlet's last drift
# velocities and acceleration, by the tissue's numbers) and keeps its own part.
# name; leg1: steps on 2 ranks; TOL: the tip's; OPTIONS; COMPARE: compare_runs.py checks as
# "mode:file-or-key:tolerance" (or "samerows:file:columns,..."), against the 1-rank run
# FULL_RANKS: the uninterrupted run's ranks (default 1); MODE: the mode's label (fine by default);
# RANKS: the continued runs' rank counts (default 1 3; three ranks on CI's two cores wait on each
# other at every exchange, so the long scenes continue on one, and a continuation on 3 ranks is in
# the long tier: the one on 1 rank reads the same global_state); LONG: the whole case is long;
# LEG_RANKS: the first leg's ranks (default 2); FULL_OPTIONS, LEG_OPTIONS, CONT_OPTIONS: more options
# of the uninterrupted run, the first leg and the continued runs (another -material_comm_size)
function(turgor_restart_other_ranks name leg1)
  cmake_parse_arguments(R "LONG" "TOL;FULL_RANKS;LEG_RANKS;MODE" "OPTIONS;COMPARE;RANKS;FULL_OPTIONS;LEG_OPTIONS;CONT_OPTIONS" ${ARGN})
  if(NOT R_RANKS)
    set(R_RANKS 1 3)
  endif()
  if(NOT R_FULL_RANKS)
    set(R_FULL_RANKS 1)
  endif()
  if(NOT R_LEG_RANKS)
    set(R_LEG_RANKS 2)
  endif()
  if(NOT R_MODE)
    set(R_MODE fine)
  endif()
  set(base restart_xr_${name})
  set(tier "")
  if(R_LONG)
    set(tier long)
  endif()
  turgor_add_test(${base}_full COMMAND ${MPIEXEC_ROOT} -n ${R_FULL_RANKS} $<TARGET_FILE:turgor_app> ${R_OPTIONS} ${R_FULL_OPTIONS} -output_overwrite
    -output_dir ${base}_full LABELS ${R_MODE} restart mpi ${tier} SETUP ${base}_full)
  turgor_add_test(${base}_leg1 COMMAND ${MPIEXEC_ROOT} -n ${R_LEG_RANKS} $<TARGET_FILE:turgor_app> ${R_OPTIONS} ${R_LEG_OPTIONS} -output_overwrite
    -ts_max_steps ${leg1} -checkpoint_interval 1e6 -output_dir ${base}_leg1 LABELS ${R_MODE} restart mpi ${tier} SETUP ${base}_leg1)
  foreach(np ${R_RANKS})
    set(dir ${base}_to${np})
    set(labels ${R_MODE} restart mpi ${tier})
    if(np GREATER 2)
      set(labels ${R_MODE} restart mpi long)
    endif()
    turgor_add_test(${dir}_copy COMMAND ${CMAKE_COMMAND} -E copy_directory ${base}_leg1 ${dir} LABELS ${labels} REQUIRES ${base}_leg1
      SETUP ${dir}_copy)
    turgor_add_test(${dir} COMMAND ${MPIEXEC_ROOT} -n ${np} $<TARGET_FILE:turgor_app> ${R_OPTIONS} ${R_CONT_OPTIONS} -restart ${dir}/checkpoint.h5 -output_dir ${dir}
      LABELS ${labels} REQUIRES ${dir}_copy SETUP ${dir})
    turgor_add_test(${dir}_tip COMMAND ${CHECK} tiprel ${dir} ${base}_full ${R_TOL} LABELS ${labels} REQUIRES "${base}_full;${dir}")
    foreach(c ${R_COMPARE})
      string(REPLACE ":" ";" parts ${c})
      list(GET parts 0 mode)
      list(GET parts 1 what)
      list(LENGTH parts nparts)
      set(rest "")
      if(nparts GREATER 2)
        list(GET parts 2 rest)
        string(REPLACE "," ";" rest "${rest}")
      endif()
      string(MAKE_C_IDENTIFIER ${what} id)
      turgor_add_test(${dir}_${id} COMMAND ${CHECK} ${mode} ${dir} ${base}_full ${what} ${rest} LABELS ${labels}
        REQUIRES "${base}_full;${dir}")
    endforeach()
  endforeach()
endfunction()

# The 16-cell polygonal tissue under the lid (contact with friction, plastic hinges, gas pressure,
# bar dashpots, controls, the energy balance, TS verlet) over 6 µs, stopped after 3000 steps (1.9
# µs, the lid pressing): measured 1.5e-11 (tip), 3.3e-10 (groups.csv), 6e-10 (energy.csv).
set(XR_POLY ${RESTART_POLY} -ts_max_time 6 -bar_damping 0.002)
turgor_restart_other_ranks(polygon 3000 TOL 1e-10 OPTIONS ${XR_POLY}
  COMPARE csvrel:groups.csv:1e-9 csvrel:energy.csv:1e-9)
# A glued Voronoi tissue generated in parts (-fine_partitioner ranges: the Hilbert order of its seeds)
# stopped on 2 ranks after 900 steps, continued on 1 (and 3, long) rank(s) to 1.5 µs: the bonds, hinge
# angles and contact histories read by the tissue's numbers, the tip to 1e-8 of the uninterrupted run
# (the forces summed in another order; past 1.5 µs a contact's chatter amplifies that round-off, as
# in distributed.cmake's runs of this tissue); to 2 µs with exact sums to the bit, below.
set(XR_VORONOI -options_file_yaml ${PROJECT_SOURCE_DIR}/config/voronoi_bar_fine.yaml -tissue_voronoi_cells 48 -tissue_box 0,0,300,100 -ts_max_time 2
  -fine_snapshots 0 -fine_progress_interval 0 -fine_partitioner ranges)
turgor_restart_other_ranks(voronoi_parts 900 TOL 1e-8 OPTIONS ${XR_VORONOI} -ts_max_time 1.5 COMPARE samekey:bonds_intact:0)
# ... with -fine_reproducible_sums (every force share rounded to a grain chosen from the state: the
# sums are exact, so their order does not matter): the continuations on 1 (and 3, long) rank(s) end
# with the uninterrupted 1-rank run's state to the last bit (glue, contact with friction, plastic
# hinges, pressure, dashpots), and tip.csv byte for byte (its kinetic energy summed exactly too).
turgor_restart_other_ranks(voronoi_exact 900 TOL 0 OPTIONS ${XR_VORONOI} -fine_reproducible_sums COMPARE identical:final_state_hash)
# ... and an adaptive integrator (lsrk, its error measured in the maximum norm): the square grid's
# bar stopped on 2 ranks after 300 of 564 steps, continued on 1 (and 3, long): the same steps, the
# same bits.
set(XR_EXACT_LSRK -options_file_yaml ${PROJECT_SOURCE_DIR}/config/bending_bar_fine.yaml -ts_type lsrk -ts_adapt_wnormtype infinity -ts_max_time 3
  -fine_snapshots 0 -fine_progress_interval 0 -fine_reproducible_sums)
turgor_restart_other_ranks(lsrk_exact 300 TOL 0 OPTIONS ${XR_EXACT_LSRK} COMPARE identical:final_state_hash)
# ... and the other way on the square grid's bending bar (springs, repulsion, SPH, gravity; TS
# verlet): stopped on 1 rank, continued on 2 (METIS) and 3 (ranges of rows, long), against the
# uninterrupted run on 2 ranks.
set(XR_EXACT_BAR -options_file_yaml ${PROJECT_SOURCE_DIR}/config/bending_bar_fine.yaml -ts_type verlet -ts_max_time 2 -fine_snapshots 0
  -fine_progress_interval 0 -fine_reproducible_sums)
turgor_add_test(restart_exact_bar_full COMMAND ${MPIEXEC_ROOT} -n 2 $<TARGET_FILE:turgor_app> ${XR_EXACT_BAR} -output_overwrite
  -output_dir restart_exact_bar_full LABELS fine restart mpi SETUP restart_exact_bar_full)
turgor_add_test(restart_exact_bar_leg1 COMMAND turgor_app ${XR_EXACT_BAR} -output_overwrite -ts_max_steps 1200 -checkpoint_interval 1e6
  -output_dir restart_exact_bar_leg1 LABELS fine restart mpi SETUP restart_exact_bar_leg1)
foreach(np 2 3)
  set(labels fine restart mpi)
  set(extra "")
  if(np GREATER 2)
    set(labels fine restart mpi long)
    set(extra -fine_partitioner ranges)
  endif()
  turgor_add_test(restart_exact_bar_to${np}_copy COMMAND ${CMAKE_COMMAND} -E copy_directory restart_exact_bar_leg1 restart_exact_bar_to${np}
    LABELS ${labels} REQUIRES restart_exact_bar_leg1 SETUP restart_exact_bar_to${np}_copy)
  turgor_add_test(restart_exact_bar_to${np} COMMAND ${MPIEXEC_ROOT} -n ${np} $<TARGET_FILE:turgor_app> ${XR_EXACT_BAR} ${extra}
    -restart restart_exact_bar_to${np}/checkpoint.h5 -output_dir restart_exact_bar_to${np} LABELS ${labels} REQUIRES restart_exact_bar_to${np}_copy
    SETUP restart_exact_bar_to${np})
  turgor_add_test(restart_exact_bar_to${np}_same COMMAND ${CHECK} identical restart_exact_bar_to${np} restart_exact_bar_full final_state_hash
    LABELS ${labels} REQUIRES "restart_exact_bar_full;restart_exact_bar_to${np}")
endforeach()
# ... continued on 1 rank reading the checkpoint 7 rows at a time (-restart_read_rows: chunk
# boundaries in every table, between the rows of a key that two ranks wrote): the same continuation,
# bit for bit, as the one that read 65 536 rows at a time.
turgor_add_test(restart_xr_polygon_rows_copy COMMAND ${CMAKE_COMMAND} -E copy_directory restart_xr_polygon_leg1 restart_xr_polygon_rows LABELS fine restart mpi
  REQUIRES restart_xr_polygon_leg1 SETUP restart_xr_polygon_rows_copy)
turgor_add_test(restart_xr_polygon_rows COMMAND turgor_app ${XR_POLY} -restart_read_rows 7 -restart restart_xr_polygon_rows/checkpoint.h5
  -output_dir restart_xr_polygon_rows LABELS fine restart mpi REQUIRES restart_xr_polygon_rows_copy SETUP restart_xr_polygon_rows)
turgor_add_test(restart_xr_polygon_rows_same COMMAND ${CHECK} identical restart_xr_polygon_rows restart_xr_polygon_to1 final_state_hash
  LABELS fine restart mpi REQUIRES "restart_xr_polygon_rows;restart_xr_polygon_to1")
# ... stopped on 2 ranks with the whole tissue on rank 0 (-fine_distribute 0: rank 1 holds nothing; a
# checkpoint of Verlet's acceleration once hung there, the ranks taking different branches of a
# collective call) and continued on 2 distributed ranks: the same rank count, another distribution
# of the state (state_layout differs), so the rank-independent global_state is read.
turgor_add_test(restart_xr_layout_leg1 COMMAND ${MPIEXEC_ROOT} -n 2 $<TARGET_FILE:turgor_app> ${XR_POLY} -fine_distribute 0 -output_overwrite
  -ts_max_steps 3000 -checkpoint_interval 1e6 -output_dir restart_xr_layout LABELS fine restart mpi SETUP restart_xr_layout_leg1)
turgor_add_test(restart_xr_layout_leg2 COMMAND ${MPIEXEC_ROOT} -n 2 $<TARGET_FILE:turgor_app> ${XR_POLY} -restart restart_xr_layout/checkpoint.h5
  -output_dir restart_xr_layout LABELS fine restart mpi REQUIRES restart_xr_layout_leg1 SETUP restart_xr_layout_leg2)
turgor_add_test(restart_xr_layout_tip COMMAND ${CHECK} tiprel restart_xr_layout restart_xr_polygon_full 1e-10 LABELS fine restart mpi
  REQUIRES "restart_xr_polygon_full;restart_xr_layout_leg2")
turgor_add_test(restart_xr_layout_energy COMMAND ${CHECK} csvrel restart_xr_layout restart_xr_polygon_full energy.csv 1e-9 LABELS fine restart mpi
  REQUIRES "restart_xr_polygon_full;restart_xr_layout_leg2")

# The glued traction scene over 12 µs, stopped after 6000 steps (2.74 µs, four bonds broken): the
# same 111 breaks (breaks.csv names the same bonds) and the tip to 1e-7, as the uninterrupted runs on
# 1, 2 and 3 ranks agree (fracture amplifies round-off: a break a step earlier or later; measured
# 4.2e-9; continued on 3 ranks by hand: 4.3e-9). Over 20 µs (205 breaks) even uninterrupted runs on
# 1 and 2 ranks differ by 8e-4. Long: restart_glue restarts the glue's state and restart_xr_polygon
# another rank count's global_state in the default tier.
turgor_restart_other_ranks(glue 6000 TOL 1e-7 RANKS 1 LONG OPTIONS ${RESTART_GLUE} -ts_max_time 12
  COMPARE samekey:bonds_broken:0 samekey:glue_fracture_dissipation:1e-7 samerows:breaks.csv:cell_node,cell_bar,node,bar)

# FE² (the seed's bar, DOPRI with the DSP controller, 80 RVEs on one rank each): stopped on 2 ranks
# after 80 steps, continued on 1 and 3, against the uninterrupted 2-rank run: the unknowns are
# written in the order of their nodes' positions and every RVE's state by its element's position,
# so the continued runs repeat the RVE work exactly (rve_solves, psi_tc_iterations) and end 1.8e-11
# and 5.9e-12 from it. (Uninterrupted runs on 1 and 2 ranks differ by 4.6e-4: round-off flips one
# step-size decision of the controller, 4 rejections against 5.) Long: the default tier restarts the
# FE² bar on 2 ranks bit for bit (fe2_rebalance) and a fine tissue on another rank count (xr_polygon).
turgor_restart_other_ranks(fe2 80 MODE fe2 FULL_RANKS 2 TOL 1e-10 LONG OPTIONS ${RESTART_FE2} COMPARE samekey:rve_solves:0 samekey:psi_tc_iterations:0)
# ... continued on 1 rank reading 3 rows at a time: the RVEs' ragged columns split between chunks; the
# same continuation to the bit
turgor_add_test(restart_xr_fe2_rows_copy COMMAND ${CMAKE_COMMAND} -E copy_directory restart_xr_fe2_leg1 restart_xr_fe2_rows LABELS fe2 restart mpi long
  REQUIRES restart_xr_fe2_leg1 SETUP restart_xr_fe2_rows_copy)
turgor_add_test(restart_xr_fe2_rows COMMAND turgor_app ${RESTART_FE2} -restart_read_rows 3 -restart restart_xr_fe2_rows/checkpoint.h5 -output_dir restart_xr_fe2_rows
  LABELS fe2 restart mpi long REQUIRES restart_xr_fe2_rows_copy SETUP restart_xr_fe2_rows)
turgor_add_test(restart_xr_fe2_rows_same COMMAND ${CHECK} identical restart_xr_fe2_rows restart_xr_fe2_to1 final_state_hash rve_solves
  LABELS fe2 restart mpi long REQUIRES "restart_xr_fe2_rows;restart_xr_fe2_to1")
# The polygon-RVE block (RESTART_FE2_POLYGON above) stopped on 2 ranks after 10 steps, continued on 1, against the uninterrupted 1-rank run: every
# RVE's state (warm start, kept Jacobian, the terms' history) found by its element's position; the
# same RVE work and the tip to 1e-10 of its largest value (1 and 2 ranks agree to 2e-13 µm).
turgor_restart_other_ranks(fe2_polygon 10 MODE fe2 TOL 1e-10 RANKS 1 LONG OPTIONS ${RESTART_FE2_POLYGON} COMPARE samekey:rve_solves:0)

# RVEs solved on groups of two ranks (-material_comm_size 2): a checkpoint holds one state a material
# point, its group's first rank's (the rank that holds the RVE's unknowns and evaluates its forces;
# the group's others take it from there when it is read), so it reads back on groups of any size.
# The small FE² block (SPH RVEs, 14 steps) in one group of 2 ranks, stopped after 7 steps and
# continued on 1 rank, against the uninterrupted run in one group of 2: the same RVE solves, their
# relaxations' iterations within a few (a lost warm start costs hundreds) and the tip to 1e-10.
# Stopped on 1 rank and continued in a group of 2: 3e-10 of the tip from the uninterrupted group run
# on 2 ranks, the coarse problem's difference between 1 and 2 ranks (a run on 1 rank ends as far from
# one on 2), so the tip to 1e-9 — and bit for bit the same leg continued on 2 ranks in groups of one.
# A group's LU is its first rank's, so a group of 2 gives the bits of two groups of one: the
# uninterrupted runs too.
set(XR_GROUPS ${BAD_PRESET_fe2} -ts_type rk)
turgor_restart_other_ranks(fe2_groups 7 MODE fe2 FULL_RANKS 2 TOL 1e-10 RANKS 1 OPTIONS ${XR_GROUPS} FULL_OPTIONS -material_comm_size 2
  LEG_OPTIONS -material_comm_size 2 COMPARE samekey:rve_solves:0 samekey:psi_tc_iterations:0.005)
turgor_restart_other_ranks(fe2_groups_up 7 MODE fe2 FULL_RANKS 2 LEG_RANKS 1 TOL 1e-9 RANKS 2 OPTIONS ${XR_GROUPS} FULL_OPTIONS -material_comm_size 2
  CONT_OPTIONS -material_comm_size 2 COMPARE samekey:rve_solves:0 samekey:psi_tc_iterations:0.005)
turgor_add_test(restart_xr_fe2_groups_ones_copy COMMAND ${CMAKE_COMMAND} -E copy_directory restart_xr_fe2_groups_up_leg1 restart_xr_fe2_groups_ones_to2
  LABELS fe2 restart mpi REQUIRES restart_xr_fe2_groups_up_leg1 SETUP restart_xr_fe2_groups_ones_copy)
turgor_add_test(restart_xr_fe2_groups_ones_to2 COMMAND ${MPIEXEC_ROOT} -n 2 $<TARGET_FILE:turgor_app> ${XR_GROUPS} -restart restart_xr_fe2_groups_ones_to2/checkpoint.h5
  -output_dir restart_xr_fe2_groups_ones_to2 LABELS fe2 restart mpi REQUIRES restart_xr_fe2_groups_ones_copy SETUP restart_xr_fe2_groups_ones_to2)
turgor_add_test(restart_xr_fe2_groups_ones_to2_same COMMAND ${CHECK} identical restart_xr_fe2_groups_up_to2 restart_xr_fe2_groups_ones_to2 final_state_hash
  psi_tc_iterations LABELS fe2 restart mpi REQUIRES "restart_xr_fe2_groups_up_to2;restart_xr_fe2_groups_ones_to2")
turgor_add_test(restart_xr_fe2_groups_ones_full COMMAND ${MPIEXEC_ROOT} -n 2 $<TARGET_FILE:turgor_app> ${XR_GROUPS} -output_overwrite
  -output_dir restart_xr_fe2_groups_ones_full LABELS fe2 restart mpi SETUP restart_xr_fe2_groups_ones_full)
turgor_add_test(restart_xr_fe2_groups_ones_full_same COMMAND ${CHECK} identical restart_xr_fe2_groups_full restart_xr_fe2_groups_ones_full final_state_hash
  psi_tc_iterations LABELS fe2 restart mpi REQUIRES "restart_xr_fe2_groups_full;restart_xr_fe2_groups_ones_full")
# ... and stopped and continued in the same group of 2: bit for bit (the group's LU is its first
# rank's, so a group's run repeats itself to the bit).
turgor_restart_case(fe2_group2 7 MODE fe2 INTERVAL 0.5 LAUNCH ${MPIEXEC_ROOT} -n 2 OPTIONS ${XR_GROUPS} -material_comm_size 2)
# ... and the polygon-RVE block (glue, contact and hinges' history in every RVE) likewise, both ways
# (long: 20 s on two cores; the tip 4e-12 from the group run either way); its two uninterrupted runs
# in a group of 2 (the same options) to the bit.
turgor_restart_other_ranks(fe2_polygon_groups 10 MODE fe2 FULL_RANKS 2 TOL 1e-10 RANKS 1 LONG OPTIONS ${RESTART_FE2_POLYGON}
  FULL_OPTIONS -material_comm_size 2 LEG_OPTIONS -material_comm_size 2 COMPARE samekey:rve_solves:0 samekey:psi_tc_iterations:0.005)
turgor_restart_other_ranks(fe2_polygon_groups_up 10 MODE fe2 FULL_RANKS 2 LEG_RANKS 1 TOL 1e-10 RANKS 2 LONG OPTIONS ${RESTART_FE2_POLYGON}
  FULL_OPTIONS -material_comm_size 2 CONT_OPTIONS -material_comm_size 2 COMPARE samekey:rve_solves:0 samekey:psi_tc_iterations:0.005)
turgor_add_test(restart_xr_fe2_polygon_groups_repeat COMMAND ${CHECK} identical restart_xr_fe2_polygon_groups_full restart_xr_fe2_polygon_groups_up_full
  final_state_hash psi_tc_iterations LABELS fe2 restart mpi long REQUIRES "restart_xr_fe2_polygon_groups_full;restart_xr_fe2_polygon_groups_up_full")

# A rebalanced FE² run (-material_rebalance 5: the points dealt again by cost before the checkpoint)
# continues from its checkpoint with the checkpoint's blocks, bit for bit.
turgor_restart_case(fe2_rebalance 80 MODE fe2 INTERVAL 15 LAUNCH ${MPIEXEC_ROOT} -n 2 OPTIONS ${RESTART_FE2} -material_rebalance 5)
