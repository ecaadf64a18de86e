# Polygonal tissues: Voronoi/Laguerre tiling, shrinking by the bar radius, same seed
# same bits, Lloyd, size cv; node-file round trip and refusals; the polyline (tests/test_polygon_tissue.cpp).
turgor_test_program(test_polygon_tissue)
turgor_add_test(test_polygon_tissue COMMAND test_polygon_tissue -data ${CMAKE_CURRENT_SOURCE_DIR}/data LABELS unit)
