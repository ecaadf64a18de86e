#pragma once
/* turgor: PETSc-native simulation of plant tissue mechanics.
   Umbrella header for programs that link libturgor (see makefile.inc). */
#include <turgor/core/register_all.h>
#include <turgor/physics/force_model.h>
#include <turgor/fine/fine_run.h>
#include <turgor/io/output.h>
#include <turgor/particles/neighbour_search.h>
#include <turgor/particles/particles.h>
#include <turgor/tissue/square_grid.h>
#include <turgor/ts/adams_moulton.h>
#include <turgor/ts/radau_iia.h>
#include <turgor/ts/ts_register.h>

#define TURGOR_VERSION_STRING "0.1.0"
