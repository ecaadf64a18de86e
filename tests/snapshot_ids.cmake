# Snapshots in id order (io/particle_snapshots.h): the particles by particle id, the bars, cells and
# glue bonds by their ids, the connectivity by particle id, whatever the ranks. Labels fine mpi.

# The glued traction scene on 16 cells (bars, cells, pressure, glue bonds, 100 breaks in 1.5 µs) on
# 1 rank, on 2 ranks with every particle on rank 0 (-fine_distribute 0: the same sums, rank 1 holds
# nothing) and on 2 distributed ranks.
set(IDS_GLUE -options_file_yaml ${PROJECT_SOURCE_DIR}/config/voronoi_traction.yaml -tissue_voronoi_cells 16 -tissue_box 0,0,100,100
  -control_top_box -1,87.5,101,101 -control_bottom_box -1,-1,101,12.5 -fine_snapshots 2 -fine_progress_interval 0 -fine_dt_safety 0.25 -fine_energy
  -control_top_velocity 0,0.5 -control_bottom_velocity 0,-0.5 -control_top_ramp_time 1 -control_bottom_ramp_time 1 -ts_max_time 1.5 -output_overwrite)
turgor_add_test(ids_glue_np1 COMMAND ${MPIEXEC_ROOT} -n 1 $<TARGET_FILE:turgor_app> ${IDS_GLUE} -output_dir ids_glue_np1 LABELS fine mpi SETUP ids_glue_np1)
turgor_add_test(ids_glue_np2_serial COMMAND ${MPIEXEC_ROOT} -n 2 $<TARGET_FILE:turgor_app> ${IDS_GLUE} -fine_distribute 0 -output_dir ids_glue_np2_serial
  LABELS fine mpi SETUP ids_glue_np2_serial)
turgor_add_test(ids_glue_np2 COMMAND ${MPIEXEC_ROOT} -n 2 $<TARGET_FILE:turgor_app> ${IDS_GLUE} -output_dir ids_glue_np2 LABELS fine mpi SETUP ids_glue_np2)
set(SNAPCHECK ${CMAKE_CURRENT_SOURCE_DIR}/check_snapshots.py)
# rank 1 empty: the same snapshots (every dataset bit for bit, the XDMF text), breaks.csv, energy.csv,
# tip.csv and final_state_hash as one rank
turgor_add_test(ids_glue_np2_serial_snapshots COMMAND ${SNAPCHECK} ids_glue_np2_serial ids_glue_np1 LABELS fine mpi
  REQUIRES "ids_glue_np1;ids_glue_np2_serial")
turgor_add_test(ids_glue_np2_serial_files COMMAND ${CHECK} samefiles ids_glue_np2_serial ids_glue_np1 breaks.csv energy.csv groups.csv LABELS fine mpi
  REQUIRES "ids_glue_np1;ids_glue_np2_serial")
turgor_add_test(ids_glue_np2_serial_hash COMMAND ${CHECK} identical ids_glue_np2_serial ids_glue_np1 final_state_hash LABELS fine mpi
  REQUIRES "ids_glue_np1;ids_glue_np2_serial")
# distributed: the same ids, connectivity and integers (the same bonds intact); the reals to the
# round-off of the force sums' order, which the breaks amplify (3e-10 of the largest value at
# 1.5 µs; a row out of place differs by the order of the values themselves); breaks.csv names the
# same bonds (node:bar) with the same cells
turgor_add_test(ids_glue_np2_snapshots COMMAND ${SNAPCHECK} ids_glue_np2 ids_glue_np1 --rtol 1e-8 --extra rank LABELS fine mpi
  REQUIRES "ids_glue_np1;ids_glue_np2")
turgor_add_test(ids_glue_np2_breaks COMMAND ${CHECK} samerows ids_glue_np2 ids_glue_np1 breaks.csv bond cell_node cell_bar node bar mode LABELS fine mpi
  REQUIRES "ids_glue_np1;ids_glue_np2")
turgor_add_test(ids_glue_np2_xdmf COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/check_xdmf.py ids_glue_np2/particles.xmf LABELS fine mpi REQUIRES ids_glue_np2)

# An empty rank reaches every collective write: a Voronoi tissue with pressure (cell fields) on 2
# and 3 ranks, every particle on rank 0, writes the one-rank run's snapshots (it used to wait
# forever in the cell fields' writes).
set(IDS_EMPTY -mode fine -tissue_type voronoi -tissue_voronoi_cells 16 -tissue_box 0,0,100,100 -physics bars,hinges,contact,pressure -ts_type verlet
  -ts_max_time 0.5 -fine_snapshots 2 -fine_progress_interval 0 -fine_clamp none -output_overwrite)
foreach(np 1 2 3)
  turgor_add_test(ids_empty_rank_np${np} COMMAND ${MPIEXEC_ROOT} -n ${np} $<TARGET_FILE:turgor_app> ${IDS_EMPTY} -fine_distribute 0
    -output_dir ids_empty_rank_np${np} LABELS fine mpi TIMEOUT 60 SETUP ids_empty_rank_np${np})
endforeach()
foreach(np 2 3)
  turgor_add_test(ids_empty_rank_np${np}_snapshots COMMAND ${SNAPCHECK} ids_empty_rank_np${np} ids_empty_rank_np1 LABELS fine mpi
    REQUIRES "ids_empty_rank_np1;ids_empty_rank_np${np}")
endforeach()
