# -mode eigen (src/modes/eigen_run.cpp) and the stability monitors (-fe2_eigen_monitor,
# -fe2_static_eigen_monitor): label eigen. Each run is checked against a closed form (Timoshenko's
# beam, Greenhill's column), a second method (the FE^2 run's measured period and DOPRI steps, dense
# LAPACK in test_eigen) or another run (1 vs 2 ranks, snapshot vs relaxed state, monitor vs mode).
turgor_test_program(test_eigen)
find_package(LAPACK REQUIRED) # test_eigen's dense reference (PETSc links LAPACK, but privately)
target_link_libraries(test_eigen PRIVATE LAPACK::LAPACK)
turgor_add_test(test_eigen COMMAND test_eigen LABELS unit eigen TIMEOUT 120)

set(EIGCHECK ${CMAKE_CURRENT_SOURCE_DIR}/check_eigen.py)
set(EIGEN $<TARGET_FILE:turgor_app> -mode eigen -output_overwrite)
set(EIGEN_NH -material neo_hookean -nh_mu 0.38461538461538464 -nh_lambda 0.57692307692307687 -nh_density 1 -nh_viscosity 0)
set(EIGEN_BEAM -coarse_dm_plex_simplex 0 -coarse_dm_plex_box_upper 400,20)
set(BAR ${PROJECT_SOURCE_DIR}/config/bending_bar_fe2.yaml)

# The plane-strain cantilever 400 x 20 (E = 1, nu = 0.3) at its reference state on meshes refined by
# 2: the first three bending frequencies converge to Timoshenko's at order 2 and are within 1% of it
# on 160 x 8 (measured -0.11%, -0.08%, -0.02%; order 2.06 / 2.08 / 2.12).
set(EIGEN_CANTILEVERS "")
foreach(mesh 40,2 80,4 160,8)
  string(REPLACE "," "x" m ${mesh})
  turgor_add_test(eigen_cantilever_${m} COMMAND ${EIGEN} -eigen_state reference ${EIGEN_NH} ${EIGEN_BEAM} -coarse_dm_plex_box_faces ${mesh} -eigen_modes 5
    -output_dir eigen_cantilever_${m} LABELS fe2 eigen TIMEOUT 60 SETUP eigen_cantilever_${m})
  list(APPEND EIGEN_CANTILEVERS eigen_cantilever_${m})
endforeach()
turgor_add_test(eigen_cantilever_timoshenko COMMAND ${EIGCHECK} cantilever ${EIGEN_CANTILEVERS} --tol 0.01 LABELS fe2 eigen REQUIRES "${EIGEN_CANTILEVERS}")
turgor_add_test(eigen_cantilever_xdmf COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/check_xdmf.py eigen_cantilever_40x2/modes.xmf LABELS fe2 eigen
  REQUIRES eigen_cantilever_40x2)

# The FE^2 bending bar (the default scene, RVE material) at the state relaxed under its load: the
# names others rely on (summary keys, residuals < 1e-8), the lowest period against the tip
# oscillation of the FE^2 run (100 µs, radauiia: measured 20.881 vs 20.828 µs), and omega_max against
# DOPRI's accepted steps (30 µs: dt omega_max 2.71, 0.94 of the limit along the damped highest mode);
# these two runs (7 s) are long.
turgor_add_test(eigen_bar COMMAND $<TARGET_FILE:turgor_app> -mode eigen -options_file_yaml ${BAR} -output_dir eigen_bar -output_overwrite
  LABELS fe2 eigen TIMEOUT 60 SETUP eigen_bar)
turgor_add_test(eigen_bar_summary COMMAND ${EIGCHECK} summary eigen_bar LABELS fe2 eigen REQUIRES eigen_bar)
turgor_add_test(eigen_bar_xdmf COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/check_xdmf.py eigen_bar/modes.xmf LABELS fe2 eigen REQUIRES eigen_bar)
turgor_add_test(eigen_bar_fe2_run COMMAND $<TARGET_FILE:turgor_app> -options_file_yaml ${BAR} -ts_max_time 100 -fe2_snapshots 0 -fe2_progress_interval 0
  -output_dir eigen_bar_fe2 -output_overwrite LABELS fe2 eigen long TIMEOUT 120 SETUP eigen_bar_fe2)
turgor_add_test(eigen_bar_period COMMAND ${EIGCHECK} period eigen_bar eigen_bar_fe2 --tol 0.01 LABELS fe2 eigen long REQUIRES "eigen_bar;eigen_bar_fe2")
turgor_add_test(eigen_bar_dopri_run COMMAND $<TARGET_FILE:turgor_app> -options_file_yaml ${BAR} -ts_type rk -ts_rk_type 5dp -ts_max_time 30 -fe2_snapshots 0
  -fe2_progress_interval 0 -output_dir eigen_bar_dopri -output_overwrite LABELS fe2 eigen long TIMEOUT 60 SETUP eigen_bar_dopri)
turgor_add_test(eigen_bar_dopri_step COMMAND ${EIGCHECK} dopri eigen_bar eigen_bar_dopri LABELS fe2 eigen long REQUIRES "eigen_bar;eigen_bar_dopri")
# the spectrum as a PNG (examples/plot_spectrum.py), where matplotlib is installed
turgor_add_test(eigen_bar_spectrum_png COMMAND ${PROJECT_SOURCE_DIR}/examples/plot_spectrum.py eigen_bar -o eigen_bar/spectrum.png LABELS eigen
  REQUIRES eigen_bar PASS_REGEX "wrote eigen_bar/spectrum.png")

# 1 and 2 ranks (the coarse mesh distributed, MUMPS's factorisations): the same eigenvalues to the
# solver's tolerance, the closed-form material on 80 x 4 and the FE^2 bar's relaxed state (the RVEs'
# relaxation at the seed's tolerance, so that the comparison sees the decomposition; long: the
# closed-form material compares the ranks in the default tier)
set(EIGEN_MPI_NH -eigen_state reference ${EIGEN_NH} ${EIGEN_BEAM} -coarse_dm_plex_box_faces 80,4 -eigen_modes 5)
set(EIGEN_MPI_BAR -options_file_yaml ${BAR} -mode eigen -rve_psi_atol 1e-12 -rve_psi_steptol 1e-12 -output_overwrite)
foreach(np 1 2)
  turgor_add_test(eigen_np${np} COMMAND ${MPIEXEC_ROOT} -n ${np} ${EIGEN} ${EIGEN_MPI_NH} -output_dir eigen_np${np} LABELS fe2 eigen mpi TIMEOUT 60
    SETUP eigen_np${np})
  turgor_add_test(eigen_bar_np${np} COMMAND ${MPIEXEC_ROOT} -n ${np} $<TARGET_FILE:turgor_app> ${EIGEN_MPI_BAR} -output_dir eigen_bar_np${np} LABELS fe2 eigen mpi
    long TIMEOUT 60 SETUP eigen_bar_np${np})
endforeach()
turgor_add_test(eigen_ranks_agree COMMAND ${EIGCHECK} agree eigen_np1 eigen_np2 --rtol 1e-9 LABELS fe2 eigen mpi REQUIRES "eigen_np1;eigen_np2")
turgor_add_test(eigen_bar_ranks_agree COMMAND ${EIGCHECK} agree eigen_bar_np1 eigen_bar_np2 --rtol 1e-8 LABELS fe2 eigen mpi long
  REQUIRES "eigen_bar_np1;eigen_bar_np2")

# A snapshot state: the relaxed state written by -mode fe2_static (coarse.h5 on 1 rank), read back by
# -eigen_state snapshot on 2 ranks, gives the relaxed state's spectrum.
set(EIGEN_STATIC_NH ${EIGEN_NH} ${EIGEN_BEAM} -coarse_dm_plex_box_faces 40,2 -body_force 0,-1e-5)
turgor_add_test(eigen_static_state COMMAND $<TARGET_FILE:turgor_app> -mode fe2_static ${EIGEN_STATIC_NH} -output_dir eigen_static_state -output_overwrite
  LABELS fe2 eigen TIMEOUT 60 SETUP eigen_static_state)
turgor_add_test(eigen_relaxed COMMAND ${EIGEN} -eigen_state relaxed ${EIGEN_STATIC_NH} -output_dir eigen_relaxed LABELS fe2 eigen TIMEOUT 60
  SETUP eigen_relaxed)
turgor_add_test(eigen_snapshot COMMAND ${MPIEXEC_ROOT} -n 2 ${EIGEN} -eigen_snapshot_file eigen_static_state/coarse.h5 -eigen_snapshot_time 1 ${EIGEN_STATIC_NH}
  -output_dir eigen_snapshot LABELS fe2 eigen mpi TIMEOUT 60 REQUIRES eigen_static_state SETUP eigen_snapshot)
turgor_add_test(eigen_snapshot_is_relaxed COMMAND ${EIGCHECK} agree eigen_snapshot eigen_relaxed --rtol 1e-9 LABELS fe2 eigen
  REQUIRES "eigen_snapshot;eigen_relaxed")
# its refusals need a file: one of another mesh, a time it does not hold
turgor_add_test(bad_eigen_snapshot_other_mesh COMMAND ${BAD} "Option -eigen_snapshot_file = eigen_static_state/coarse.h5: a snapshot of another mesh"
  ${EIGEN} -eigen_snapshot_file eigen_static_state/coarse.h5 ${EIGEN_NH} ${EIGEN_BEAM} -coarse_dm_plex_box_faces 20,2 -output_dir bad_input/eigen_other_mesh
  LABELS badinput eigen TIMEOUT 60 REQUIRES eigen_static_state)
turgor_add_test(bad_eigen_snapshot_time COMMAND ${BAD} "Option -eigen_snapshot_time = 0.5: no snapshot at this time in eigen_static_state/coarse.h5"
  ${EIGEN} -eigen_snapshot_file eigen_static_state/coarse.h5 -eigen_snapshot_time 0.5 ${EIGEN_STATIC_NH} -output_dir bad_input/eigen_snapshot_time
  LABELS badinput eigen TIMEOUT 60 REQUIRES eigen_static_state)

# Buckling: config/column_buckling.yaml (Greenhill's self-weight column, 320 x 8, -mode fe2_static
# with -fe2_static_eigen_monitor 1): the monitor's zero crossing within 3% of the closed form
# (measured -0.34%); its states around the crossing in stability.xmf.
turgor_add_test(eigen_column_buckling COMMAND $<TARGET_FILE:turgor_app> -options_file_yaml ${PROJECT_SOURCE_DIR}/config/column_buckling.yaml
  -output_dir eigen_column -output_overwrite LABELS fe2 static eigen TIMEOUT 120 SETUP eigen_column)
turgor_add_test(eigen_column_greenhill COMMAND ${EIGCHECK} buckling eigen_column --g 2.2428285256e-6 --H 10 --tol 0.03 LABELS fe2 static eigen
  REQUIRES eigen_column)
# hard: -mode eigen past buckling (config/hard/eigen_buckled_column.yaml): K indefinite, one negative
# eigenvalue, the monitor's at the same load
turgor_add_test(hard_eigen_buckled_column COMMAND $<TARGET_FILE:turgor_app> -options_file_yaml ${PROJECT_SOURCE_DIR}/config/hard/eigen_buckled_column.yaml
  -output_dir hard/eigen_buckled_column -output_overwrite LABELS hard eigen TIMEOUT 120 SETUP hard_eigen_buckled_column)
turgor_add_test(hard_eigen_buckled_column_negative COMMAND ${EIGCHECK} buckled hard/eigen_buckled_column eigen_column --rtol 1e-6 LABELS hard eigen
  REQUIRES "hard_eigen_buckled_column;eigen_column")
turgor_add_test(eigen_column_xdmf COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/check_xdmf.py eigen_column/stability.xmf LABELS fe2 static eigen REQUIRES eigen_column)

# The monitor in -mode fe2: its first check (the initial state) is -mode eigen's reference state
# (the 40 x 2 cantilever above), and a monitored run takes the same steps, bit for bit
set(EIGEN_MON $<TARGET_FILE:turgor_app> -mode fe2 ${EIGEN_NH} ${EIGEN_BEAM} -coarse_dm_plex_box_faces 40,2 -body_force 0,-1e-6 -ts_max_time 2000
  -fe2_snapshots 0 -fe2_progress_interval 0 -output_overwrite)
turgor_add_test(eigen_fe2_monitor COMMAND ${EIGEN_MON} -fe2_eigen_monitor 2 -output_dir eigen_fe2_monitor LABELS fe2 eigen TIMEOUT 60 SETUP eigen_fe2_monitor)
turgor_add_test(eigen_fe2_unmonitored COMMAND ${EIGEN_MON} -output_dir eigen_fe2_unmonitored LABELS fe2 eigen TIMEOUT 60 SETUP eigen_fe2_unmonitored)
turgor_add_test(eigen_fe2_monitor_first_check COMMAND ${EIGCHECK} monitor eigen_fe2_monitor eigen_cantilever_40x2 --rtol 1e-9 LABELS fe2 eigen
  REQUIRES "eigen_fe2_monitor;eigen_cantilever_40x2")
turgor_add_test(eigen_fe2_monitor_changes_nothing COMMAND ${CHECK} identical eigen_fe2_monitor eigen_fe2_unmonitored steps rhs_evals jacobian_evals
  LABELS fe2 eigen REQUIRES "eigen_fe2_monitor;eigen_fe2_unmonitored")

# Ranks without a free dof or without an element: a 1 x 1 and a 2 x 1 mesh on 2 and 3 ranks give the
# one-rank spectrum, undamped and damped (the material points of an empty rank's group computed
# with their tangents; the damped pencil solved in an even row layout where a rank holds no row).
set(EIGEN_EMPTY ${EIGEN_NH} -nh_viscosity 0.01 -coarse_dm_plex_simplex 0 -coarse_dm_plex_box_upper 400,400 -eigen_state reference -eigen_modes 2)
foreach(faces 1,1 2,1)
  string(REPLACE "," "x" f ${faces})
  foreach(np 1 2 3)
    turgor_add_test(eigen_empty_${f}_np${np} COMMAND ${MPIEXEC_ROOT} -n ${np} ${EIGEN} ${EIGEN_EMPTY} -coarse_dm_plex_box_faces ${faces}
      -output_dir eigen_empty_${f}_np${np} LABELS fe2 eigen mpi TIMEOUT 60 SETUP eigen_empty_${f}_np${np})
  endforeach()
  foreach(np 2 3)
    turgor_add_test(eigen_empty_${f}_np${np}_agree COMMAND ${EIGCHECK} agree eigen_empty_${f}_np1 eigen_empty_${f}_np${np} --rtol 1e-9 LABELS fe2 eigen mpi
      REQUIRES "eigen_empty_${f}_np1;eigen_empty_${f}_np${np}")
  endforeach()
endforeach()
