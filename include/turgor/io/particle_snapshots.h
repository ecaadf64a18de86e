#pragma once
/* Particle snapshots for ParaView: one HDF5 file (PetscViewerHDF5) with a group per snapshot
   (position n x 2, velocity n x 3 with z = 0) and /static (kind, cell, fixed as integers, the
   vertex and spring connectivity), and an XDMF file describing a temporal collection of two grids,
   the particles (Polyvertex, one vertex cell per particle, with velocity, kind, cell, fixed) and
   the wall springs (Polyline through the same positions), with units. The XDMF file is rewritten
   after every snapshot, so a run that stops early stays readable.

   Polygonal tissues (ParticleSet::polygons not empty) get a third grid, "cells": the closed
   polygons as XDMF Polygon cells (topology Polygon with NodesPerElement when all have the same
   number of nodes, else Mixed with type code 3 and the node count before each cell's nodes), with
   the cell attributes cell_id, area_ratio A/A0 (A0 at Open) and any fields the caller passes to
   Write (e.g. a pressure); the walls grid then also has each bar's strain l/l0 - 1. Open cells are
   drawn by their bars only. Write also takes per-particle fields (scalars, or 2-vectors written
   with z = 0: the force on every node) for the particle and wall grids, and per-spring fields (a
   bar's axial force) for the walls grid. */
#include <turgor/particles/particles.h>
#include <petscdm.h>
#include <petscviewer.h>
#include <string>
#include <vector>

namespace turgor {

class ParticleSnapshotWriter {
public:
  /* `swarm` holds this rank's owned particles with fields "kind" and "cell" (int); `P` gives the
     fixed flags and this rank's springs and polygons (its owned ones, local indices: a distributed
     run's halo particles are drawn by their owners); x: the local positions (P's numbering) of the
     cells' reference areas. Files: dir/base.h5, dir/base.xmf. */
  PetscErrorCode Open(DM swarm, const ParticleSet &P, const PetscReal *x, const std::string &dir, const std::string &base);
  /* A field of one snapshot: `components` (1, or 2 for a vector) values per item. */
  struct Field {
    std::string            name, unit;
    std::vector<PetscReal> values;
    int                    components = 1;
  };
  /* nodes: one item per local particle; cells: per closed polygon (ParticleSet::polygons order,
     closed cells only: a pressure); bars: per spring (ParticleSet::springs order: a bar's force).
     Every snapshot of a file has the same fields. */
  /* Line segments with their own end points (the glue bonds, node to bar point), x0 y0 x1 y1 each,
     and per-segment scalar fields; a fourth grid named `name`, with the same segments (count and
     order) in every snapshot. */
  struct Segments {
    std::string            name;
    std::vector<PetscReal> xy;
    std::vector<Field>     fields;
  };
  struct Fields {
    std::vector<Field>    nodes, cells, bars;
    std::vector<Segments> segments;
  };
  /* x, v: the positions and velocities of P's particles (owned first; a distributed run's halo
     after them, which its bars' strains need); the owned ones are written. The swarm holds no
     copy of them: they live once, in the time integrator's state. */
  PetscErrorCode Write(DM swarm, PetscReal time, const PetscReal *x, const PetscReal *v, const Fields &fields = {});
  PetscErrorCode Close();
  ~ParticleSnapshotWriter() { PetscCallVoid(Close()); }
  PetscInt Count() const { return (PetscInt)times_.size(); }

private:
  PetscErrorCode WriteXdmf();
  PetscErrorCode WritePolygonFields(const PetscReal *x, const std::vector<Field> &cell_fields);
  PetscErrorCode WriteVector(const std::string &name, const std::vector<PetscReal> &values, int components);

  MPI_Comm    comm_   = MPI_COMM_NULL;
  PetscViewer viewer_ = nullptr;
  std::string dir_, h5name_, xmfpath_;
  PetscInt    n_global_ = 0, n_springs_ = 0;
  size_t      bars_local_ = 0;
  /* polygonal tissues: the closed cells (local node indices), their reference areas, the bars */
  std::vector<std::vector<PetscInt>> polys_;
  std::vector<PetscReal>             area0_;
  std::vector<Spring>                bars_;
  PetscInt                           n_polys_ = 0, mixed_size_ = 0, nodes_per_poly_ = 0; /* global; 0: mixed */
  std::vector<std::string>           field_names_, field_units_;                         /* the callers' cell fields */
  std::vector<Field>                 node_meta_, bar_meta_;                              /* names, units, components of the node and bar fields (no values) */
  struct SegmentsMeta {
    std::string        name;
    PetscInt           count = 0; /* global */
    size_t             first = 0; /* the first snapshot that has them (a term may make them later) */
    std::vector<Field> fields;    /* names and units */
  };
  std::vector<SegmentsMeta> segment_meta_;
  std::vector<PetscReal>    times_;
};

} // namespace turgor
