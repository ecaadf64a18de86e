# METIS cell partition (issue 13, tests/test_partition.cpp): a 64 x 64-cell square grid on 4 parts
# cuts within 10% of the 128 walls of a 2 x 2 split with every part within 5% of the mean particle
# count; a 400-cell Voronoi tissue on 4 parts has every cell assigned, connected parts and an
# imbalance below 1.05; one part needs no METIS; 0 parts and more parts than cells are refused.
turgor_test_program(test_partition)
turgor_add_test(test_partition COMMAND test_partition LABELS unit fine TIMEOUT 20)

