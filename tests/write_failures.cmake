# Write failures (label badinput): a run whose outputs cannot be written ends with an error naming
# the file, never a crash, and never a summary that says completed.
#
# An output directory that exists but cannot be written, in every mode (unwritable_dir.py: chattr +i,
# which stops root too; skipped where the flag cannot be set): refused before any work, naming the
# option and the directory.
set(UNWRITABLE ${CMAKE_CURRENT_SOURCE_DIR}/unwritable_dir.py)
set(UNWRITABLE_REGEX "Option -output_dir = .*unwritable_[a-z0-9_]+: cannot write into the directory")
foreach(preset fine rve fe2)
  turgor_add_test(unwritable_dir_${preset} COMMAND ${UNWRITABLE} unwritable_${preset} ${UNWRITABLE_REGEX} $<TARGET_FILE:turgor_app> ${BAD_PRESET_${preset}}
    LABELS badinput)
endforeach()
turgor_add_test(unwritable_dir_fe2_static COMMAND ${UNWRITABLE} unwritable_fe2_static ${UNWRITABLE_REGEX} $<TARGET_FILE:turgor_app> -mode fe2_static
  -coarse_dm_plex_simplex 0 -coarse_dm_plex_box_faces 2,2 -coarse_dm_plex_box_upper 400,400 LABELS badinput)
# eigen: before the spectrum is computed (it used to fail only when writing eigen.csv)
turgor_add_test(unwritable_dir_eigen COMMAND ${UNWRITABLE} unwritable_eigen ${UNWRITABLE_REGEX} $<TARGET_FILE:turgor_app> -mode eigen -material neo_hookean
  -coarse_dm_plex_simplex 0 -coarse_dm_plex_box_upper 400,400 -coarse_dm_plex_box_faces 2,2 LABELS badinput)
turgor_add_test(unwritable_dir_fine_np2 COMMAND ${UNWRITABLE} unwritable_fine_np2 ${UNWRITABLE_REGEX} ${MPIEXEC_ROOT} -n 2 $<TARGET_FILE:turgor_app>
  ${BAD_PRESET_fine} LABELS badinput mpi)
set_tests_properties(unwritable_dir_fine unwritable_dir_rve unwritable_dir_fe2 unwritable_dir_fe2_static unwritable_dir_eigen unwritable_dir_fine_np2
  PROPERTIES SKIP_RETURN_CODE 77)

# A file system that fills up during the run, as a file size limit (ulimit -f 40: 20 kB in sh's
# 512-byte blocks, beyond the 16 kB that summary.json reserves at the start; the rank alone is
# limited, not mpiexec's own files): the first write beyond it fails, the run fails naming the file,
# and summary.json (written in the space reserved at the start) says "failed". Before, the rank died
# of SIGXFSZ, or with the signal ignored the run completed with truncated files. Several ranks run
# without Open MPI's shared-memory transport, whose 4 MB segment files the limit would refuse.
set(NO_SHM --mca btl self,tcp)
set(FILE_LIMIT sh -c [[ulimit -f 40 && exec "$0" "$@"]] $<TARGET_FILE:turgor_app>)
set(FULL_BOX -options_file_yaml ${PROJECT_SOURCE_DIR}/config/polygon_compression.yaml -tissue_voronoi_cells 16 -tissue_box 0,0,100,100 -ts_max_time 3
  -fine_snapshots 0 -fine_progress_interval 0 -fine_energy -fine_energy_tolerance 0.1)
turgor_add_test(full_disk_fine COMMAND ${BAD} "cannot write .*full_disk_fine/[a-z]+.csv: File too large" ${MPIEXEC_ROOT} -n 1 ${FILE_LIMIT} ${FULL_BOX}
  -output_dir full_disk_fine LABELS badinput fine)
turgor_add_test(full_disk_fine_np2 COMMAND ${BAD} "cannot write .*full_disk_fine_np2/[a-z]+.csv: File too large" ${MPIEXEC_ROOT} ${NO_SHM} -n 2 ${FILE_LIMIT}
  ${FULL_BOX} -output_dir full_disk_fine_np2 LABELS badinput fine mpi)
turgor_add_test(full_disk_rve COMMAND ${BAD} "cannot write .*full_disk_rve/rve.csv: File too large" ${MPIEXEC_ROOT} -n 1 ${FILE_LIMIT} ${BAD_PRESET_rve}
  -path_steps 400 -output_dir full_disk_rve LABELS badinput)
