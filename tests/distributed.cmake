# Distributed fine runs (labels fine mpi): every particle on the rank of its cell, a halo
# exchanged before each evaluation, every interaction computed once. The same scene on 1, 2 and 3
# ranks (oversubscribed on CI's 2 cores) must give the same tip history to 1e-10 of its largest
# value; only the order of the force sums differs.

# name; OPTIONS: the scene; COMPARE: further compare_runs.py checks of each multi-rank run against
# the 1-rank one, as "mode:file-or-key:tolerance" (csvrel and samekey)
# RANKS: the rank counts compared with 1 (default 2 3; three ranks on two cores wait on each other
# at every exchange: those runs are in the long tier, and the longer scenes are compared on two only);
# LONG: the whole case is in the long tier
function(turgor_ranks_agree name)
  cmake_parse_arguments(D "LONG" "TOL" "OPTIONS;COMPARE;RANKS" ${ARGN})
  set(labels fine mpi)
  if(D_LONG)
    list(APPEND labels long)
  endif()
  if(NOT D_TOL)
    set(D_TOL 1e-10)
  endif()
  if(NOT D_RANKS)
    set(D_RANKS 2 3)
  endif()
  foreach(np 1 ${D_RANKS})
    set(l ${labels})
    if(np GREATER 2) # three ranks on two cores wait at every exchange: the long tier
      list(APPEND l long)
    endif()
    turgor_add_test(dist_${name}_np${np} COMMAND ${MPIEXEC_ROOT} -n ${np} $<TARGET_FILE:turgor_app> ${D_OPTIONS} -output_overwrite
      -output_dir dist_${name}_np${np} LABELS ${l} SETUP dist_${name}_np${np})
  endforeach()
  foreach(np ${D_RANKS})
    set(l ${labels})
    if(np GREATER 2)
      list(APPEND l long)
    endif()
    turgor_add_test(dist_${name}_np${np}_tip COMMAND ${CHECK} tiprel dist_${name}_np${np} dist_${name}_np1 ${D_TOL} LABELS ${l}
      REQUIRES "dist_${name}_np1;dist_${name}_np${np}")
    foreach(c ${D_COMPARE})
      string(REPLACE ":" ";" parts ${c})
      list(GET parts 0 mode)
      list(GET parts 1 what)
      list(GET parts 2 tol)
      string(MAKE_C_IDENTIFIER ${what} id)
      turgor_add_test(dist_${name}_np${np}_${id} COMMAND ${CHECK} ${mode} dist_${name}_np${np} dist_${name}_np1 ${what} ${tol} LABELS ${l}
        REQUIRES "dist_${name}_np1;dist_${name}_np${np}")
    endforeach()
  endforeach()
  # the distribution's keys in summary.json
  list(GET D_RANKS 0 np)
  turgor_add_test(dist_${name}_keys COMMAND ${CHECK} keys dist_${name}_np${np} mpi_ranks particles_per_rank_max particles_per_rank_mean
    halo_bytes_per_step load_imbalance LABELS ${labels} REQUIRES dist_${name}_np${np})
endfunction()

# The seed's square-grid bending bar (springs, repulsion, SPH, gravity; DOPRI, adaptive) over 1 µs
# (about 250 steps).
turgor_ranks_agree(bar OPTIONS -options_file_yaml ${PROJECT_SOURCE_DIR}/config/bending_bar_fine.yaml -ts_max_time 1 -fine_snapshots 0
  -fine_progress_interval 0)
# The full halo checks send a cell's box only to the ranks near it: the 256-cell bar's 14 checks on 2
# ranks received 9 856 B (the ranks' regions and the boxes of the cells near the cut), where
# gathering every cell's box would move 14 x 256 x 40 B = 143 360 B.
turgor_add_test(dist_bar_np2_check_bytes COMMAND ${CHECK} between dist_bar_np2 halo_check_bytes 1 30000 LABELS fine mpi REQUIRES dist_bar_np2)
# The same bar under TS verlet without controls: the drift's velocities take their halo in place and
# the accelerations carry room for the halo's forces (no copies of v and f, FineRun::LocalState,
# TSVerletSetAccelerationRoom); a restart on 2 ranks continues it bit for bit.
set(DIST_BAR_VERLET -options_file_yaml ${PROJECT_SOURCE_DIR}/config/bending_bar_fine.yaml -ts_type verlet -ts_max_time 0.5 -fine_snapshots 0
  -fine_progress_interval 0)
turgor_ranks_agree(bar_verlet RANKS 2 OPTIONS ${DIST_BAR_VERLET})
# ... and under the low-storage pair (TS lsrk: its rates carry room for the halo's forces,
# TSLSRKSetRateRoom), continued bit for bit after a restart on 2 ranks
set(DIST_BAR_LSRK -options_file_yaml ${PROJECT_SOURCE_DIR}/config/bending_bar_fine.yaml -ts_type lsrk -ts_max_time 1 -fine_snapshots 0
  -fine_progress_interval 0)
turgor_ranks_agree(bar_lsrk RANKS 2 OPTIONS ${DIST_BAR_LSRK})
turgor_restart_case(dist_bar_lsrk 100 INTERVAL 0.5 LAUNCH ${MPIEXEC_ROOT} -n 2 OPTIONS ${DIST_BAR_LSRK} FILES tip.csv)
# Dealt by cell ranges (-fine_partitioner ranges), the grid is generated in parts: each rank builds
# its cells and those within the halo's width, no rank the whole tissue. The same run to the bit as
# the whole tissue generated on every rank and dealt by the same ranges (-fine_setup_in_parts 0), and
# the 1-rank run's tip to 1e-10.
set(DIST_BAR_RANGES -options_file_yaml ${PROJECT_SOURCE_DIR}/config/bending_bar_fine.yaml -ts_max_time 1 -fine_snapshots 0 -fine_progress_interval 0
  -fine_partitioner ranges -output_overwrite)
turgor_add_test(dist_bar_parts_np2 COMMAND ${MPIEXEC_ROOT} -n 2 $<TARGET_FILE:turgor_app> ${DIST_BAR_RANGES} -output_dir dist_bar_parts_np2 LABELS fine mpi
  SETUP dist_bar_parts_np2)
turgor_add_test(dist_bar_whole_np2 COMMAND ${MPIEXEC_ROOT} -n 2 $<TARGET_FILE:turgor_app> ${DIST_BAR_RANGES} -fine_setup_in_parts 0
  -output_dir dist_bar_whole_np2 LABELS fine mpi SETUP dist_bar_whole_np2)
turgor_add_test(dist_bar_parts_identical COMMAND ${CHECK} identical dist_bar_parts_np2 dist_bar_whole_np2 final_state_hash halo_particles_max
  particles_per_rank_max LABELS fine mpi REQUIRES "dist_bar_parts_np2;dist_bar_whole_np2")
turgor_add_test(dist_bar_parts_built COMMAND ${CHECK} equals dist_bar_parts_np2 setup_in_parts True LABELS fine mpi REQUIRES dist_bar_parts_np2)
turgor_add_test(dist_bar_parts_tip COMMAND ${CHECK} tiprel dist_bar_parts_np2 dist_bar_np1 1e-10 LABELS fine mpi REQUIRES "dist_bar_np1;dist_bar_parts_np2")
# ... on 3 ranks (long: three ranks on two cores): ranges that end inside a row of cells, a middle
# rank with a neighbour on either side
turgor_add_test(dist_bar_parts_np3 COMMAND ${MPIEXEC_ROOT} -n 3 $<TARGET_FILE:turgor_app> ${DIST_BAR_RANGES} -output_dir dist_bar_parts_np3 LABELS fine mpi long
  SETUP dist_bar_parts_np3)
turgor_add_test(dist_bar_whole_np3 COMMAND ${MPIEXEC_ROOT} -n 3 $<TARGET_FILE:turgor_app> ${DIST_BAR_RANGES} -fine_setup_in_parts 0
  -output_dir dist_bar_whole_np3 LABELS fine mpi long SETUP dist_bar_whole_np3)
turgor_add_test(dist_bar_parts_np3_identical COMMAND ${CHECK} identical dist_bar_parts_np3 dist_bar_whole_np3 final_state_hash halo_particles_max
  particles_per_rank_max LABELS fine mpi long REQUIRES "dist_bar_parts_np3;dist_bar_whole_np3")
turgor_add_test(dist_bar_parts_np3_tip COMMAND ${CHECK} tiprel dist_bar_parts_np3 dist_bar_np1 1e-10 LABELS fine mpi long
  REQUIRES "dist_bar_np1;dist_bar_parts_np3")
# A Voronoi tissue in parts: the Lloyd steps run by ranges of seeds on every rank, the cells are
# ordered along the Hilbert curve through their seeds and dealt in ranges of it, each rank builds its
# cells and those near. The same run to the bit as the serial tissue dealt by the same ranges
# (-fine_setup_in_parts 0), on 2 and 3 ranks (3: long), and the 1-rank run's tip to 1e-8 (glue and
# contact summed in another order: 1.5e-12 measured). To 1.5 µs: from about 1.6 µs a node chatters
# against a bar and each contact's onset amplifies the round-off of the sums' order (the runs on 1, 2
# and 3 ranks then part by 2e-10 at 1.8 µs and 4e-7 at 2, 2 against 3 ranks as much), which no bound
# on that order can hold; the exact sums hold through it (restart.cmake, voronoi_exact). A Laguerre
# tissue (-tissue_size_cv: the weights fitted on every rank) the same on 2.
set(DIST_VORONOI_RANGES -options_file_yaml ${PROJECT_SOURCE_DIR}/config/voronoi_bar_fine.yaml -tissue_voronoi_cells 48 -tissue_box 0,0,300,100 -ts_max_time 1.5
  -fine_snapshots 0 -fine_progress_interval 0 -fine_partitioner ranges)
turgor_ranks_agree(voronoi_parts TOL 1e-8 OPTIONS ${DIST_VORONOI_RANGES})
set(DIST_LAGUERRE_RANGES ${DIST_VORONOI_RANGES} -tissue_size_cv 0.3 -ts_max_time 0.5)
foreach(np 2 3)
  set(tier "")
  if(np EQUAL 3)
    set(tier long)
  endif()
  turgor_add_test(dist_voronoi_whole_np${np} COMMAND ${MPIEXEC_ROOT} -n ${np} $<TARGET_FILE:turgor_app> ${DIST_VORONOI_RANGES} -fine_setup_in_parts 0
    -output_overwrite -output_dir dist_voronoi_whole_np${np} LABELS fine mpi ${tier} SETUP dist_voronoi_whole_np${np})
  turgor_add_test(dist_voronoi_parts_np${np}_identical COMMAND ${CHECK} identical dist_voronoi_parts_np${np} dist_voronoi_whole_np${np} final_state_hash
    halo_particles_max particles_per_rank_max tip_displacement_final LABELS fine mpi ${tier} REQUIRES "dist_voronoi_parts_np${np};dist_voronoi_whole_np${np}")
  turgor_add_test(dist_voronoi_parts_np${np}_built COMMAND ${CHECK} equals dist_voronoi_parts_np${np} setup_in_parts True LABELS fine mpi ${tier}
    REQUIRES dist_voronoi_parts_np${np})
endforeach()
foreach(setup parts whole)
  set(in_parts 1)
  if(setup STREQUAL whole)
    set(in_parts 0)
  endif()
  turgor_add_test(dist_laguerre_${setup}_np2 COMMAND ${MPIEXEC_ROOT} -n 2 $<TARGET_FILE:turgor_app> ${DIST_LAGUERRE_RANGES} -fine_setup_in_parts ${in_parts}
    -output_overwrite -output_dir dist_laguerre_${setup}_np2 LABELS fine mpi SETUP dist_laguerre_${setup}_np2)
endforeach()
turgor_add_test(dist_laguerre_parts_identical COMMAND ${CHECK} identical dist_laguerre_parts_np2 dist_laguerre_whole_np2 final_state_hash
  halo_particles_max particles_per_rank_max LABELS fine mpi REQUIRES "dist_laguerre_parts_np2;dist_laguerre_whole_np2")
# A node file read in parts: each rank reads its byte range of the file (a cell where its first line
# starts), the ranges' cells checked and indexed on every rank, the cells dealt along the Hilbert
# curve through their boxes' centres; each rank then reads its cells and those near by seeking to
# them. The file (48 glued Voronoi cells, comments, clockwise cells, ids from 7, an open cell) is
# written by test_tissue. The same run to the bit as the whole file dealt by the same ranges, on 2, 3
# (long) and 5 (long) ranks; the 1-rank run's tip to 1e-8.
# ... and read in parts on 2, 3 and 6 ranks by test_node_file_parts: files whose byte ranges end in
# awkward places (CRLF, no final line break, comments between cells, a comment longer than a range,
# one cell on six ranks), each rank's part against the whole file's tissue, and errors at lines spread
# over the file named as the whole reader names them.
turgor_test_program(test_node_file_parts)
foreach(np 2 3 6)
  set(tier "")
  if(np GREATER 2)
    set(tier long)
  endif()
  turgor_add_test(test_node_file_parts_np${np} COMMAND ${MPIEXEC_ROOT} -n ${np} $<TARGET_FILE:test_node_file_parts> LABELS unit fine mpi ${tier})
endforeach()
set_tests_properties(test_tissue PROPERTIES FIXTURES_SETUP parts_tissue_nodes)
set(DIST_NODES_RANGES -options_file_yaml ${PROJECT_SOURCE_DIR}/config/voronoi_bar_fine.yaml -tissue_type node_file -tissue_node_file parts_tissue.nodes
  -tissue_open_cells 12 -ts_max_time 1 -fine_snapshots 0 -fine_progress_interval 0 -fine_partitioner ranges -output_overwrite)
turgor_add_test(dist_nodes_parts_np1 COMMAND turgor_app ${DIST_NODES_RANGES} -output_dir dist_nodes_parts_np1 LABELS fine mpi
  REQUIRES parts_tissue_nodes SETUP dist_nodes_parts_np1)
foreach(np 2 3 5)
  set(tier "")
  if(np GREATER 2)
    set(tier long)
  endif()
  foreach(setup parts whole)
    set(in_parts 1)
    if(setup STREQUAL whole)
      set(in_parts 0)
    endif()
    turgor_add_test(dist_nodes_${setup}_np${np} COMMAND ${MPIEXEC_ROOT} -n ${np} $<TARGET_FILE:turgor_app> ${DIST_NODES_RANGES} -fine_setup_in_parts ${in_parts}
      -output_dir dist_nodes_${setup}_np${np} LABELS fine mpi ${tier} REQUIRES parts_tissue_nodes SETUP dist_nodes_${setup}_np${np})
  endforeach()
  turgor_add_test(dist_nodes_parts_np${np}_identical COMMAND ${CHECK} identical dist_nodes_parts_np${np} dist_nodes_whole_np${np} final_state_hash
    halo_particles_max particles_per_rank_max LABELS fine mpi ${tier} REQUIRES "dist_nodes_parts_np${np};dist_nodes_whole_np${np}")
  turgor_add_test(dist_nodes_parts_np${np}_built COMMAND ${CHECK} equals dist_nodes_parts_np${np} setup_in_parts True LABELS fine mpi ${tier}
    REQUIRES dist_nodes_parts_np${np})
  turgor_add_test(dist_nodes_parts_np${np}_tip COMMAND ${CHECK} tiprel dist_nodes_parts_np${np} dist_nodes_parts_np1 1e-8 LABELS fine mpi ${tier}
    REQUIRES "dist_nodes_parts_np1;dist_nodes_parts_np${np}")
endforeach()
# A 16-cell polygonal tissue under the lid: contact with friction, plastic hinges, gas-law pressure,
# velocity controls (groups.csv: the lid's reaction), the energy balance (energy.csv: every rank's
# share summed), TS verlet, over 4 µs on 2 ranks; 1.5 µs on 3 (the lid from 0.5 µs; long: 5 s).
# (the default step of this contact-dominated scene keeps Verlet's energy residual at about 5 %: the
# balance is compared between layouts here, not against -fine_energy_tolerance's 1 %)
set(DIST_POLY -fine_energy_tolerance 0.1 -options_file_yaml ${PROJECT_SOURCE_DIR}/config/polygon_compression.yaml -tissue_voronoi_cells 16 -tissue_box 0,0,100,100
  -ts_max_time 4 -control_lid_delay 1 -control_lid_velocity 0,-3 -fine_snapshots 0 -fine_progress_interval 0 -fine_energy -fine_tip_samples 200)
turgor_ranks_agree(polygon_short RANKS 3 LONG OPTIONS ${DIST_POLY} -ts_max_time 1.5 -control_lid_delay 0.5 COMPARE csvrel:groups.csv:1e-9
  csvrel:energy.csv:1e-9)
# (the list rebuilds are the busiest rank's, not the ranks' sum: TermStatistic::MAX)
turgor_ranks_agree(polygon RANKS 2 OPTIONS ${DIST_POLY} COMPARE csvrel:groups.csv:1e-9 csvrel:energy.csv:1e-9 samekey:contact_friction_dissipation:1e-9
  samekey:hinge_plastic_hinges:0 samekey:contact_pair_lists:0 samekey:contact_near_lists:0)
# The glued traction scene on 16 cells: the same bonds (554) and breaks (111) on two ranks as on one;
# fracture amplifies round-off (a break a step earlier or later), so the tip agrees to 1e-7.
turgor_ranks_agree(glue TOL 1e-7 RANKS 2 OPTIONS -options_file_yaml ${PROJECT_SOURCE_DIR}/config/voronoi_traction.yaml -tissue_voronoi_cells 16
  -tissue_box 0,0,100,100 -control_top_box -1,87.5,101,101 -control_bottom_box -1,-1,101,12.5 -fine_snapshots 0 -fine_progress_interval 0
  -fine_energy 0 -fine_dt_safety 0.25 -control_top_velocity 0,0.05 -control_bottom_velocity 0,-0.05 -control_top_ramp_time 5
  -control_bottom_ramp_time 5 -ts_max_time 12 COMPARE samekey:bonds_created:0 samekey:bonds_broken:0 samekey:glue_interface_length:1e-12)
# ... and breaks.csv, gathered to rank 0 step by step, names the same bonds (cells, node, bar in the
# tissue's numbering)
turgor_add_test(dist_glue_breaks COMMAND ${CHECK} samerows dist_glue_np2 dist_glue_np1 breaks.csv cell_node cell_bar node bar LABELS fine mpi
  REQUIRES "dist_glue_np1;dist_glue_np2")

# Snapshots of a distributed run: each rank's particles, bars and cells go to their rows in id order
# in the one file (the connectivity by particle id, halo ends included): the XDMF agrees with its
# HDF5 data, and ParaView shows the 64 cells with the gas-law pressure, as for one rank.
turgor_add_test(dist_box_snapshots COMMAND ${MPIEXEC_ROOT} -n 2 $<TARGET_FILE:turgor_app> ${BOX} -ts_max_time 1 -fine_snapshots 2
  -output_dir dist_box_snapshots LABELS fine mpi SETUP dist_box_snapshots)
turgor_add_test(dist_box_xdmf COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/check_xdmf.py dist_box_snapshots/particles.xmf LABELS fine mpi
  REQUIRES dist_box_snapshots)
turgor_paraview_polygons(dist_box dist_box_snapshots 50)

# Restart of a distributed run (the polygonal tissue above on 2 ranks, 6 µs, stopped after 3000
# steps): bit for bit, with groups.csv and energy.csv (long: 7 s; restart_xr_layout continues a
# 16-cell polygonal tissue on 2 distributed ranks in the default tier).
turgor_restart_case(dist_polygon 3000 INTERVAL 3 LONG LAUNCH ${MPIEXEC_ROOT} -n 2 OPTIONS ${DIST_POLY} -ts_max_time 6 FILES groups.csv energy.csv)
turgor_restart_case(dist_bar_verlet 400 INTERVAL 0.25 LAUNCH ${MPIEXEC_ROOT} -n 2 OPTIONS ${DIST_BAR_VERLET})

# hard: cells that move farther than the halo's margin stop the run with an error naming the
# option (the lid comes down onto the cells with no margin), not with missed contacts.
turgor_add_test(dist_halo_outgrown COMMAND ${MPIEXEC_ROOT} -n 2 $<TARGET_FILE:turgor_app> ${DIST_POLY} -ts_max_time 16 -fine_halo_margin 0
  -output_overwrite -output_dir dist_halo_outgrown LABELS fine mpi hard PASS_REGEX "no longer covers this deformation; rerun with a larger -fine_halo_margin")

# Empty ranks: fewer cells than ranks leaves a rank (or two) without a particle, which must still
# reach every collective call (the halo check, the integrator's set-up, the stability report) and
# give the one-rank answer. A square grid of 2 cells on 2 and 3 ranks (rk), and 2 glued Voronoi
# cells on 2 and 3 ranks (verlet at the step the stability limits give: the glue's Gershgorin rows are
# completed over the halo, so the step is the same on any rank count -- on 3 ranks it was 1.95e-3 µs
# against 1.38e-3 when each rank bounded its own bonds' rows; bonds are built on empty ranks too).
turgor_ranks_agree(empty_grid TOL 1e-9 OPTIONS -mode fine -tissue_cells_x 2 -tissue_cells_y 1 -ts_max_time 0.2 -fine_snapshots 0
  -fine_progress_interval 0)
# ... and one cell generated in parts (-fine_partitioner ranges): the first rank's range is empty,
# its part of the grid too (GeneratePart of no cells), and on 3 ranks two ranks hold nothing
turgor_ranks_agree(empty_parts TOL 1e-9 OPTIONS -mode fine -tissue_cells_x 1 -tissue_cells_y 1 -ts_max_time 0.2 -fine_snapshots 0
  -fine_progress_interval 0 -fine_partitioner ranges)
# ... and one Voronoi cell in parts: PrepareParts' ranges of seeds and the parts empty on all ranks but one
turgor_ranks_agree(empty_voronoi_parts TOL 1e-9 OPTIONS -mode fine -tissue_type voronoi -tissue_voronoi_cells 1 -tissue_box 0,0,40,40
  -physics bars,hinges,pressure -ts_max_time 0.5 -fine_snapshots 0 -fine_progress_interval 0 -fine_partitioner ranges)
turgor_ranks_agree(empty_glue TOL 1e-9 OPTIONS -mode fine -tissue_type voronoi -tissue_voronoi_cells 2 -tissue_box 0,0,100,100
  -physics bars,hinges,contact,pressure,glue -ts_type verlet -ts_max_time 0.5 -fine_snapshots 0 -fine_progress_interval 0 -fine_clamp none
  COMPARE samekey:dt_stable:1e-14)
