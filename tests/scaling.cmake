# The scaling-study driver bench/scaling.py (docs/scaling.md "Running a scaling study"),
# checked by tests/check_scaling.py: --collect on a fabricated study (CSV columns, best of repeats,
# strong and weak efficiencies, missing summary keys), --slurm job scripts and their collection, and
# a real strong and weak study of the fine mode on 1 and 2 ranks (4 x 4 cells, 5 steps, seconds;
# long: its repeated runs take 4 s, and the fine mode on 2 ranks is checked in the default tier).
set(SCALING ${PROJECT_SOURCE_DIR}/bench/scaling.py)
turgor_add_test(scaling_collect COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/check_scaling.py collect ${SCALING} scaling_collect
  LABELS unit study TIMEOUT 30)
turgor_add_test(scaling_slurm COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/check_scaling.py slurm ${SCALING} scaling_slurm
  LABELS unit study TIMEOUT 30)
turgor_add_test(scaling_local COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/check_scaling.py local ${SCALING} scaling_local
  $<TARGET_FILE:turgor_app> ${MPIEXEC_EXECUTABLE} ${PROJECT_SOURCE_DIR}/config/bending_bar_fine.yaml
  LABELS study fine mpi long TIMEOUT 60)

# bench/setup_memory.py (docs/scaling.md, "Generated in parts"): a node file and a Voronoi tissue of
# 400 cells on 1 rank, 2 ranks by METIS and 2 in parts; both 2-rank runs own every particle of the
# 1-rank run exactly once, with a halo (the figures themselves are the benchmark's, not the test's).
foreach(tissue node_file voronoi)
  turgor_add_test(setup_memory_${tissue} COMMAND ${PROJECT_SOURCE_DIR}/bench/setup_memory.py --tissue ${tissue} --sizes 400 --check
    --binary $<TARGET_FILE:turgor_app> --out setup_memory_${tissue} LABELS study mpi long)
endforeach()
