#pragma once
/* Particle snapshots for ParaView: one HDF5 file (PetscViewerHDF5) with a group per snapshot
   (position n x 2, velocity n x 3 with z = 0) and /static (kind, cell, fixed and particle_id as
   integers, the vertex and spring connectivity, bar_id), and an XDMF file describing a temporal
   collection of two grids, the particles (Polyvertex, one vertex cell per particle, with velocity,
   kind, cell, fixed, particle_id) and the wall springs (Polyline through the same positions, with
   bar_id), with units. The XDMF file is rewritten after every snapshot, so a run that stops early
   stays readable.

   Every table is written in the order of its items' ids, whatever the number of ranks (KeyOrder):
   the particles by particle id (row = id: the ids are 0..N-1), the bars by bar id, the cells by cell
   id, a term's segments by their ids (a glue bond's PairKey(node, bar)); the connectivity names the
   particles by id. A run on any number of ranks, distributed or not, writes the same datasets.

   Polygonal tissues (ParticleSet::polygons not empty) get a third grid, "cells": the closed
   polygons as XDMF Polygon cells (topology Polygon with NodesPerElement when all have the same
   number of nodes, else Mixed with type code 3 and the node count before each cell's nodes), with
   the cell attributes cell_id, area_ratio A/A0 (A0 at Open) and any fields the caller passes to
   Write (e.g. a pressure); the walls grid then also has each bar's strain l/l0 - 1. Open cells are
   drawn by their bars only. Write also takes per-particle fields (scalars, or 2-vectors written
   with z = 0: the force on every node) for the particle and wall grids, and per-spring fields (a
   bar's axial force) for the walls grid. Every rank passes the same fields (names), with values for
   its own items (none on a rank that holds none). */
#include <turgor/io/key_order.h>
#include <turgor/particles/particles.h>
#include <petscdm.h>
#include <petscviewer.h>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace turgor {

class ParticleSnapshotWriter {
public:
  /* Collective. `swarm` holds this rank's owned particles with fields "kind" and "cell" (int); `P`
     gives their ids (gid: 0..N-1 over the ranks), the fixed flags and this rank's springs and
     polygons (its owned ones, local indices, with their ids: a distributed run's halo particles are
     drawn by their owners, named by id); x: the local positions (P's numbering) of the cells'
     reference areas. Files: dir/base.h5, dir/base.xmf. */
  PetscErrorCode Open(DM swarm, const ParticleSet &P, const PetscReal *x, const std::string &dir, const std::string &base);
  /* A field of one snapshot: `components` (1, or 2 for a vector) values per item, held in `values`
     or, where `view` is set, read from there (`count` values: the caller's array, not copied). */
  struct Field {
    std::string            name, unit;
    std::vector<PetscReal> values;
    int                    components = 1;
    const PetscReal       *view       = nullptr;
    size_t                 count      = 0;
    const PetscReal       *Data() const { return view ? view : values.data(); }
    size_t                 Size() const { return view ? count : values.size(); }
  };
  /* nodes: one item per local particle; cells: per closed polygon (ParticleSet::polygons order,
     closed cells only: a pressure); bars: per spring (ParticleSet::springs order: a bar's force).
     Every snapshot of a file has the same fields. */
  /* Line segments with their own end points (the glue bonds, node to bar point), x0 y0 x1 y1 each,
     their ids (unique over the ranks; written as /static/NAME_id) and per-segment scalar fields; a
     fourth grid named `name`, with the same segments (the same ids) in every snapshot. */
  struct Segments {
    std::string                name;
    std::vector<PetscReal>     xy;
    std::vector<std::uint64_t> id;
    std::vector<Field>         fields;
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
  /* closed cells over all ranks (0: no cells grid, Write takes no cell fields) */
  PetscInt Cells() const { return n_polys_; }

private:
  PetscErrorCode WriteXdmf();
  PetscErrorCode WritePolygonFields(const PetscReal *x, const std::vector<Field> &cell_fields);
  PetscErrorCode WriteOrdered(KeyOrder &order, const std::string &name, const PetscReal *values, int components);
  PetscErrorCode CheckSameFields(const Fields &fields);

  MPI_Comm    comm_   = MPI_COMM_NULL;
  PetscViewer viewer_ = nullptr;
  std::string dir_, h5name_, xmfpath_;
  PetscInt    n_global_ = 0, n_springs_ = 0;
  size_t      bars_local_ = 0;
  KeyOrder    nodes_, bars_order_, cells_order_; /* by particle, bar and cell id */
  /* polygonal tissues: the closed cells (local node indices), their reference areas, the bars */
  std::vector<std::vector<PetscInt>> polys_;
  std::vector<PetscReal>             area0_;
  std::vector<Spring>                bars_;
  PetscInt                           n_polys_ = 0, mixed_size_ = 0, nodes_per_poly_ = 0; /* global; 0: mixed */
  std::vector<std::string>           field_names_, field_units_;                         /* the callers' cell fields */
  std::vector<Field>                 node_meta_, bar_meta_;                              /* names, units, components of the node and bar fields (no values) */
  struct SegmentsMeta {
    std::string                name;
    PetscInt                   count = 0; /* global */
    size_t                     first = 0; /* the first snapshot that has them (a term may make them later) */
    std::vector<Field>         fields;    /* names and units */
    std::vector<std::uint64_t> ids;       /* this rank's, in the order given */
    std::unique_ptr<KeyOrder>  order;
  };
  std::vector<SegmentsMeta> segment_meta_;
  std::vector<PetscReal>    times_;
};

} // namespace turgor
