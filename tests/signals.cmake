# SIGTERM outside a step (interrupt_run.py): in the set-up, and a batch system's TERM to the process
# group of an MPI run that writes checkpoints.
set(INTERRUPT ${CMAKE_CURRENT_SOURCE_DIR}/interrupt_run.py)
set(SIGNAL_VOR -mode fine -tissue_type voronoi -tissue_box 0,0,100,100 -physics bars,hinges,contact,pressure -ts_type verlet -ts_max_time 0.5
  -fine_snapshots 0 -fine_progress_interval 0 -fine_clamp none)

# The set-up of a large Laguerre tissue (40 000 cells: many seconds, the signal half a second after
# it begins) stops within seconds of the signal: exit 130, summary.json "interrupted", no step
# taken. On two ranks mpiexec passes the signal on (a second later) and kills the ranks a second
# after that.
set(SIGNAL_LAGUERRE ${SIGNAL_VOR} -tissue_voronoi_cells 40000 -tissue_box 0,0,2800,2800 -tissue_size_cv 0.3)
turgor_add_test(interrupt_setup_voronoi COMMAND ${INTERRUPT} "setup:0.5:Memory estimate" interrupt_setup_voronoi $<TARGET_FILE:turgor_app>
  ${SIGNAL_LAGUERRE} LABELS hard fine)
turgor_add_test(interrupt_setup_voronoi_np2 COMMAND ${INTERRUPT} "setup:0.5:Memory estimate" interrupt_setup_voronoi_np2 ${MPIEXEC_ROOT} -n 2
  $<TARGET_FILE:turgor_app> ${SIGNAL_LAGUERRE} LABELS hard fine mpi)
# A node file that is a FIFO without a writer: the open waits, and the signal ends it.
turgor_add_test(interrupt_setup_fifo COMMAND sh -c [[rm -f interrupt_fifo.nodes && mkfifo interrupt_fifo.nodes && exec "$0" "$@"]] ${INTERRUPT} setup:3
  interrupt_setup_fifo $<TARGET_FILE:turgor_app> -mode fine -tissue_type node_file -tissue_node_file interrupt_fifo.nodes
  -physics bars,hinges,contact,pressure -ts_type verlet -ts_max_time 1 -fine_snapshots 0 -fine_progress_interval 0 -fine_clamp none LABELS hard fine)

# A batch system's TERM to the process group of mpiexec on a glued 64-cell tissue that writes
# checkpoints (every 0.05 µs), then KILL while the interrupt's checkpoint is written (mpiexec passes
# the TERM on to the ranks and kills them a second later; the test kills them as soon as the run
# says it writes that checkpoint): summary.json says "interrupted" and names the last complete
# checkpoint, which a restart reads. (Without Open MPI's shared-memory transport: killed ranks would
# leave its segment files behind.)
set(SIGNAL_GLUE64 -options_file_yaml ${PROJECT_SOURCE_DIR}/config/voronoi_traction.yaml -tissue_voronoi_cells 64 -tissue_box 0,0,200,200
  -control_top_box -1,180,201,201 -control_bottom_box -1,-1,201,20 -control_top_velocity 0,0.2 -control_bottom_velocity 0,-0.2
  -control_top_ramp_time 2.5 -control_bottom_ramp_time 2.5 -fine_snapshots 0 -checkpoint_interval 0.05)
foreach(np 2 3)
  set(tier "")
  if(np GREATER 2) # three ranks on two cores: the long tier (the two-rank case is the default tier's)
    set(tier long)
  endif()
  turgor_add_test(interrupt_kill_checkpoint_np${np} COMMAND ${INTERRUPT} group:0.12 interrupt_kill_np${np} ${MPIEXEC_ROOT} --mca btl self,tcp -n ${np}
    $<TARGET_FILE:turgor_app> ${SIGNAL_GLUE64} -ts_max_time 60 -fine_progress_interval 0.2 LABELS fine mpi restart ${tier} SETUP interrupt_kill_np${np})
  # The restart reads the checkpoint the summary names as the last complete one and runs 0.1 µs past
  # the interrupted run's end (how far that run got depends on the machine's load).
  turgor_add_test(interrupt_kill_restart_np${np} COMMAND sh -c [[exec "$@" $(python3 -c "print(*(lambda s: ['-restart', s['checkpoint_last'], '-ts_max_time', s['t_final'] + 0.1])(__import__('json').load(open('interrupt_kill_np$0/summary.json'))))")]]
    ${np} ${MPIEXEC_ROOT} -n ${np} $<TARGET_FILE:turgor_app> ${SIGNAL_GLUE64} -fine_progress_interval 0
    -output_dir interrupt_kill_np${np}_restart -output_overwrite LABELS fine mpi restart ${tier} REQUIRES interrupt_kill_np${np})
endforeach()

# SIGTERM after the first equilibrium (t = 25 µs) of a 64-cell gripped tissue: the solve on the way to
# the next load time stops within a pseudo step, exit 130, summary.json "interrupted" with the last
# equilibrium's time.
turgor_add_test(interrupt_fine_static COMMAND ${INTERRUPT} 1 interrupt_fine_static $<TARGET_FILE:turgor_app>
  -options_file_yaml ${PROJECT_SOURCE_DIR}/config/voronoi_tangent_fine.yaml -mode fine_static -tissue_voronoi_cells 64 -tissue_box 0,0,200,200
  -control_left_box -1,-1,12.5,201 -control_right_box 187.5,-1,201,201 -control_bottom_box 12.5,-1,187.5,12.5 -control_top_box 12.5,187.5,187.5,201
  -fine_static_times 25,26,27,28,29,30 LABELS hard fine)
