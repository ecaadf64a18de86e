#pragma once
/* turgor: PETSc-native simulation of plant tissue mechanics.
   C++ umbrella header for C++ programs that link libturgor (see makefile.inc): the C API of
   <turgor/turgor.h> plus turgor's C++ classes. */
#include <turgor/turgor.h>
#include <turgor/physics/force_model.h>
#include <turgor/fine/fine_run.h>
#include <turgor/io/output.h>
#include <turgor/particles/neighbour_search.h>
#include <turgor/parallel/cell_partition.h>
#include <turgor/particles/particles.h>
#include <turgor/modes/simulation.h>
#include <turgor/tissue/node_file.h>
#include <turgor/tissue/polygon_tissue.h>
#include <turgor/tissue/polyline.h>
#include <turgor/tissue/square_grid.h>
#include <turgor/tissue/voronoi.h>
