# METIS cell partition (tests/test_partition.cpp): a 64 x 64-cell square grid on 4 parts
# cuts within 10% of the 128 walls of a 2 x 2 split with every part within 5% of the mean particle
# count; a 400-cell Voronoi tissue on 4 parts has every cell assigned, connected parts and an
# imbalance below 1.05; one part needs no METIS; 0 parts and more parts than cells are refused.
turgor_test_program(test_partition)
turgor_add_test(test_partition COMMAND test_partition LABELS unit fine TIMEOUT 20)

# -fine_partition_report on a small run (1 and 2 ranks: the tissue is partitioned on rank 0 and
# the numbers reach summary.json from every rank the same): the keys, and a 4 x 4 grid on 4 parts
# cuts the 8 walls of a 2 x 2 split (METIS may do slightly worse on so small a graph).
set(PARTSMALL -mode fine -tissue_cells_x 4 -tissue_cells_y 4 -ts_max_time 2 -fine_snapshots 1 -fine_progress_interval 0 -output_overwrite
  -fine_partition_report 4)
turgor_add_test(fine_partition_report COMMAND turgor_app ${PARTSMALL} -output_dir partition_small LABELS fine SETUP partition_small TIMEOUT 20)
turgor_add_test(fine_partition_report_np2 COMMAND ${MPIEXEC_ROOT} -n 2 $<TARGET_FILE:turgor_app> ${PARTSMALL} -output_dir partition_small_np2
  LABELS fine mpi SETUP partition_small_np2 TIMEOUT 20)
turgor_add_test(fine_partition_keys COMMAND ${CHECK} keys partition_small partition_parts partition_edge_cut partition_edge_cut_length partition_imbalance
  partition_metis_seconds partition_particles_min partition_particles_max LABELS fine REQUIRES partition_small)
turgor_add_test(fine_partition_cut COMMAND ${CHECK} between partition_small partition_edge_cut 8 10 LABELS fine REQUIRES partition_small)
turgor_add_test(fine_partition_np2_same COMMAND ${CHECK} samekey partition_small_np2 partition_small partition_edge_cut 0 LABELS fine mpi
  REQUIRES "partition_small;partition_small_np2")

# -coarse_partitioner metis: the FE^2 run of fe2_mpi1/fe2_mpi2 on 2 ranks with the coarse mesh
# distributed by METIS agrees with 1 rank to the same tolerance.
turgor_add_test(fe2_mpi2_metis COMMAND ${MPIEXEC_ROOT} -n 2 $<TARGET_FILE:turgor_app> ${FE2MPI} -coarse_partitioner metis -output_dir fe2_mpi2_metis
  LABELS fe2 mpi SETUP fe2_mpi2_metis)
turgor_add_test(fe2_mpi_metis_agrees COMMAND ${CHECK} tip fe2_mpi1 fe2_mpi2_metis 1e-10 LABELS fe2 mpi REQUIRES "fe2_mpi1;fe2_mpi2_metis")
