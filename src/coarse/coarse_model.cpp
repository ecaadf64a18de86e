#include <turgor/core/options.h>
#include <turgor/core/errors.h>
#include "q1_element.h"
#include "reference_element.h"
#include <turgor/coarse/coarse_model.h>
#include <turgor/coarse/gmsh_check.h>
#include <turgor/material/acoustic_tensor.h>
#include <turgor/core/memory.h>
#include <turgor/core/log.h>
#include <turgor/parallel/metis_partition.h>
#include <petscsf.h>
#include <cmath>
#include <cstring>

namespace turgor {

CoarseModel::CoarseModel(MPI_Comm comm) : comm_(comm), pool_(comm) { }

CoarseModel::~CoarseModel()
{
  PetscCallVoid(KSPDestroy(&mass_ksp_));
  PetscCallVoid(MatDestroy(&Mt_));
  PetscCallVoid(MatDestroy(&KC_));
  PetscCallVoid(VecDestroy(&Uloc_));
  PetscCallVoid(VecDestroy(&Floc_));
  PetscCallVoid(VecDestroy(&rhs_r_));
  PetscCallVoid(VecDestroy(&rhs_z_));
  PetscCallVoid(ISDestroy(&rank_free_order_));
  PetscCallVoid(DMDestroy(&dm_));
}

PetscErrorCode CoarseSpec::SetFromOptions(MPI_Comm comm, ParameterList *params)
{
  const char *const elements[] = {"q1", "q2"};
  PetscInt          element    = (PetscInt)this->element;
  char              label[64], rule[64], partitioner[64];
  PetscInt          values[8], n = 8;
  PetscBool         set, lumped = lumped_mass ? PETSC_TRUE : PETSC_FALSE, acoustic = acoustic_field ? PETSC_TRUE : PETSC_FALSE, hset;
  PetscReal         h[4] = {boundary_gradient(0, 0), boundary_gradient(0, 1), boundary_gradient(1, 0), boundary_gradient(1, 1)};
  PetscInt          nh   = 4;
  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(label, dirichlet_label.c_str(), sizeof label));
  PetscCall(PetscStrncpy(rule, quadrature == CoarseQuadrature::SRI ? "sri" : "full", sizeof rule));
  PetscCall(PetscStrncpy(partitioner, metis ? "metis" : "petsc", sizeof partitioner));
  for (const char *o : {"-coarse_faces", "-coarse_lower", "-coarse_upper"}) {
    PetscBool gone;
    PetscCall(PetscOptionsHasName(NULL, NULL, o, &gone));
    PetscCheck(!gone, comm, PETSC_ERR_ARG_WRONG,
               "Option %s was replaced by PETSc's mesh options: -coarse_dm_plex_simplex 0 -coarse_dm_plex_box_faces nx,ny -coarse_dm_plex_box_lower x0,y0 "
               "-coarse_dm_plex_box_upper x1,y1",
               o);
  }
  PetscOptionsBegin(comm, NULL, "Renamed options of the coarse model", "turgor");
  PetscCall(PetscOptionsDeprecated("-coarse_mesh_file", "-coarse_dm_plex_filename", "0.2", "the mesh is read by DMSetFromOptions"));
  PetscOptionsEnd();
  PetscOptionsBegin(comm, "coarse_",
                    "Coarse FE^2 model (TW 562 §3.3). The mesh is PETSc's (DMSetFromOptions, -coarse_dm_plex_*): a box, -coarse_dm_plex_simplex 0 "
                    "-coarse_dm_plex_box_faces nx,ny -coarse_dm_plex_box_lower x0,y0 -coarse_dm_plex_box_upper x1,y1 (default 4,4 and 0,0 to 400,400 µm), "
                    "or a file, -coarse_dm_plex_filename mesh.msh; -coarse_dm_refine n refines it",
                    "turgor");
  PetscCall(TurgorOptionsString(params, "-dirichlet_label", "Label of the clamped boundary", "CoarseSpec", label, label, sizeof label, NULL));
  PetscCall(
    PetscOptionsIntArray("-dirichlet_values", "Label values clamped (box: 1 bottom, 2 right, 3 top, 4 left; default 4)", "CoarseSpec", values, &n, &set));
  PetscCall(TurgorOptionsBool(params, "-lumped_mass", "Lumped (row-sum) instead of consistent mass matrix (eq 32)", "CoarseSpec", lumped, &lumped, NULL));
  PetscCall(TurgorOptionsEList(params, "-element", "Coarse element: q1 (bilinear, 4 nodes: the seed's) or q2 (biquadratic, 9 nodes, bends without locking)",
                               "CoarseSpec", elements, 2, elements[element], &element, NULL));
  PetscCall(TurgorOptionsString(params, "-quadrature",
                                "Material points of an element: sri (selective reduced: the deviatoric stress at the full Gauss points, the pressure at "
                                "fewer; q1: 2 x 2 and the centre, 5 points; q2: 3 x 3 and 2 x 2, 13 points) or full (the whole stress at the full Gauss "
                                "points; q1: 2 x 2, 4 points; q2: 3 x 3, 9 points)",
                                "CoarseSpec", rule, rule, sizeof rule, NULL));
  PetscCall(PetscOptionsBool("-acoustic_field",
                             "Snapshots carry acoustic_min_det, per element the smallest det of the acoustic tensor of D^e and the stress over directions and "
                             "material points (loss of ellipticity where <= 0); needs the material tangents at every snapshot (3 more material "
                             "evaluations per point, counted as output solves)",
                             "CoarseSpec", acoustic, &acoustic, NULL));
  PetscCall(PetscOptionsRealArray("-boundary_gradient",
                                  "H11,H12,H21,H22: the clamped vertices are moved to u = lambda H X, X their reference position and lambda the load "
                                  "factor of -mode fe2_static (default 0: clamped in place); e.g. the left and right sides clamped "
                                  "(-coarse_dirichlet_values 2,4) with H = e,0,0,0 stretch the block by e along x, every side clamped "
                                  "(1,2,3,4) deforms it homogeneously",
                                  "CoarseSpec", h, &nh, &hset));
  PetscCall(PetscOptionsString("-partitioner",
                               "How the coarse mesh is distributed over the ranks: petsc (DMSetFromOptions with PETSc's partitioner, "
                               "-coarse_petscpartitioner_type) or metis (the serial mesh's cell dual graph partitioned by METIS_PartGraphKway and "
                               "distributed through a PETSCPARTITIONERSHELL; PETSc's own distribution and -coarse_dm_distribute are then not used, "
                               "and -coarse_dm_refine refines before the distribution)",
                               "CoarseSpec", partitioner, partitioner, sizeof partitioner, NULL));
  PetscOptionsEnd();
  /* (checked after PetscOptionsEnd: a return from inside the block leaks its options object) */
  PetscCheck(!hset || nh == 4, comm, PETSC_ERR_ARG_SIZ, "Option -coarse_boundary_gradient: %" PetscInt_FMT " values given, 4 needed (H11,H12,H21,H22)", nh);
  for (int k = 0; k < 4; k++)
    PetscCheck(std::isfinite(h[k]) && std::fabs(h[k]) < 0.5, comm, PETSC_ERR_ARG_OUTOFRANGE,
               "Option -coarse_boundary_gradient: entry %d = %g; each must be finite and of magnitude below 0.5 (a displacement gradient)", k + 1,
               (double)h[k]);
  boundary_gradient = Tensor2{
    {{h[0], h[1]}, {h[2], h[3]}}
  };
  this->element = (CoarseElement)element;
  PetscCall(CheckNotEmpty(comm, "-coarse_partitioner", "petsc or metis"));
  PetscCheck(!std::strcmp(partitioner, "petsc") || !std::strcmp(partitioner, "metis"), comm, PETSC_ERR_ARG_UNKNOWN_TYPE,
             "Option -coarse_partitioner = %s: unknown partitioner (known: petsc, metis)", partitioner);
  metis = !std::strcmp(partitioner, "metis");
  {
    /* every element defines both rules; a rule of another name is refused naming the element's */
    const char *const rules[] = {"sri", "full"};
    bool              known   = false;
    for (int r = 0; r < 2; r++)
      if (!std::strcmp(rule, rules[r])) {
        quadrature = (CoarseQuadrature)r;
        known      = true;
      }
    PetscCheck(known, comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "Option -coarse_quadrature = %s: not a quadrature rule of -coarse_element %s (its rules: sri, full)",
               rule, elements[element]);
  }
  PetscCheck(!set || n < 8, comm, PETSC_ERR_ARG_SIZ, "Option -coarse_dirichlet_values: more than 7 label values listed");
  PetscCall(CheckNotEmpty(comm, "-coarse_dirichlet_values", "label values, e.g. 4 (the left side of a box)"));
  dirichlet_label = label;
  if (set) dirichlet_values.assign(values, values + n);
  if (params) params->Set("-coarse_dirichlet_values", ParameterValue(dirichlet_values.data(), (PetscInt)dirichlet_values.size()));
  lumped_mass    = lumped;
  acoustic_field = acoustic;
  PetscCheck(!dirichlet_values.empty(), comm, PETSC_ERR_ARG_WRONG, "Option -coarse_dirichlet_values: no value given");
  if (params && HasBoundaryGradient()) params->Set("-coarse_boundary_gradient", ParameterValue(&boundary_gradient.a[0][0], 4));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseSpec::RequireNoBoundaryGradient(MPI_Comm comm, const char *mode) const
{
  PetscFunctionBeginUser;
  PetscCheck(!HasBoundaryGradient(), comm, PETSC_ERR_ARG_INCOMP,
             "Option -coarse_boundary_gradient: -mode %s has no load factor to apply it with; it moves the clamped vertices in -mode fe2_static "
             "(and -mode eigen at the relaxed state)",
             mode);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseModel::SetFromOptions(ParameterList *params)
{
  PetscFunctionBeginUser;
  PetscCall(spec_.SetFromOptions(comm_, params));
  PetscCall(skin_.SetFromOptions(comm_, params));
  PetscCall(pool_.SetFromOptions(params));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseModel::SetMesh(DM dm)
{
  PetscFunctionBeginUser;
  PetscCall(PetscObjectReference((PetscObject)dm));
  PetscCall(DMDestroy(&dm_));
  dm_ = dm;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The mesh is PETSc's: DMSetFromOptions with prefix coarse_ builds it from -coarse_dm_plex_box_*
   or -coarse_dm_plex_filename (Gmsh physical lines become "Face Sets"), distributes it and applies
   -coarse_dm_refine, -coarse_dm_view, ... Without any of those options the default is the seed's
   bar, a 4 x 4 box of quadrilaterals on [0, 400]^2 µm, set through the API. */
PetscErrorCode CoarseModel::CreateMesh()
{
  PetscFunctionBeginUser;
  if (!dm_) {
    PetscBool file, simplex, box = PETSC_FALSE;
    for (const char *o : {"-coarse_dm_plex_box_faces", "-coarse_dm_plex_box_lower", "-coarse_dm_plex_box_upper", "-coarse_dm_plex_shape"}) {
      PetscBool has;
      PetscCall(PetscOptionsHasName(NULL, NULL, o, &has));
      box = (PetscBool)(box || has);
    }
    PetscCall(PetscOptionsHasName(NULL, NULL, "-coarse_dm_plex_filename", &file));
    {
      PetscInt  dim = 2;
      PetscBool dset;
      PetscCall(PetscOptionsGetInt(NULL, NULL, "-coarse_dm_plex_dim", &dim, &dset));
      PetscCheck(dim == 2, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -coarse_dm_plex_dim = %" PetscInt_FMT ": the coarse mesh must be 2D", dim);
    }
    PetscCall(PetscOptionsHasName(NULL, NULL, "-coarse_dm_plex_simplex", &simplex));
    PetscCheck(!box || simplex || file, comm_, PETSC_ERR_ARG_WRONG,
               "Options -coarse_dm_plex_box_*: PETSc's box mesh is made of triangles unless -coarse_dm_plex_simplex 0 is given, and the coarse model needs "
               "quadrilaterals (the default mesh is -coarse_dm_plex_simplex 0 -coarse_dm_plex_box_faces 4,4 -coarse_dm_plex_box_upper 400,400)");
    {
      PetscInt  faces[3] = {1, 1, 1}, n = 3;
      PetscBool set;
      PetscCall(PetscOptionsGetIntArray(NULL, NULL, "-coarse_dm_plex_box_faces", faces, &n, &set));
      PetscCheck(!set || (n == 2 && faces[0] >= 1 && faces[1] >= 1), comm_, PETSC_ERR_ARG_OUTOFRANGE,
                 "Option -coarse_dm_plex_box_faces = %" PetscInt_FMT ",%" PetscInt_FMT ": needs two numbers of elements, each >= 1", faces[0],
                 n > 1 ? faces[1] : 0);
      if (set) { /* before DMPlex builds it: a box too large for this machine is refused here */
        PetscInt  refine = 0;
        PetscBool rset;
        PetscCall(PetscOptionsGetInt(NULL, NULL, "-coarse_dm_refine", &refine, &rset));
        PetscCall(CheckSize((PetscReal)faces[0] * (PetscReal)faces[1] * std::pow(4.0, (PetscReal)refine)));
      }
    }
    if (file) {
      char      path[PETSC_MAX_PATH_LEN];
      PetscBool msh;
      PetscCall(PetscOptionsGetString(NULL, NULL, "-coarse_dm_plex_filename", path, sizeof path, NULL));
      PetscCall(PetscStrendswith(path, ".msh", &msh));
      if (msh) PetscCall(CheckGmshFile(comm_, "-coarse_dm_plex_filename", path));
    }
    if (box || simplex || file) { /* DMSetFromOptions builds it */
      PetscCall(DMCreate(comm_, &dm_));
      PetscCall(DMSetType(dm_, DMPLEX));
    } else {
      const PetscInt  faces[2] = {4, 4};
      const PetscReal lower[2] = {0, 0}, upper[2] = {400, 400};
      PetscCall(DMPlexCreateBoxMesh(comm_, 2, PETSC_FALSE, faces, lower, upper, NULL, PETSC_TRUE, &dm_));
    }
  }
  PetscCall(PetscObjectSetName((PetscObject)dm_, "coarse"));
  PetscCall(PetscObjectSetOptionsPrefix((PetscObject)dm_, "coarse_"));
  if (spec_.metis) PetscCall(DMPlexDistributeSetDefault(dm_, PETSC_FALSE)); /* DistributeWithMetis does it */
  PetscCall(DMSetFromOptions(dm_));
  if (spec_.metis) PetscCall(DistributeWithMetis());
  PetscCall(DMViewFromOptions(dm_, NULL, "-dm_view"));
  PetscInt dim;
  PetscCall(DMGetDimension(dm_, &dim));
  PetscCheck(dim == 2, comm_, PETSC_ERR_ARG_WRONG, "Options -coarse_dm_plex_*: the coarse mesh must be 2D (got %" PetscInt_FMT "D)", dim);
  PetscCall(DMPlexGetHeightStratum(dm_, 0, &c_start_, &c_end_));
  {
    std::string wrong; /* found on one rank, reported on all */
    for (PetscInt c = c_start_; c < c_end_ && wrong.empty(); c++) {
      DMPolytopeType ct;
      PetscCall(DMPlexGetCellType(dm_, c, &ct));
      if (ct != DM_POLYTOPE_QUADRILATERAL) wrong = std::string("a cell is a ") + DMPolytopeTypes[ct];
    }
    std::string msg;
    PetscCall(FirstMessage(comm_, wrong, &msg));
    PetscCheck(msg.empty(), comm_, PETSC_ERR_ARG_WRONG,
               "Options -coarse_dm_plex_*: %s; the coarse model needs quadrilaterals (-coarse_dm_plex_simplex 0 for a box)", msg.c_str());
  }
  PetscCall(DMPlexGetDepthStratum(dm_, 0, &v_start_, &v_end_));
  {
    IS              cells;
    const PetscInt *g;
    PetscCall(DMPlexGetCellNumbering(dm_, &cells));
    PetscCall(ISGetIndices(cells, &g));
    cell_gid_.resize(c_end_ - c_start_);
    for (PetscInt c = c_start_; c < c_end_; c++) cell_gid_[c - c_start_] = g[c - c_start_] >= 0 ? g[c - c_start_] : -(g[c - c_start_] + 1);
    PetscCall(ISRestoreIndices(cells, &g));
  }
  PetscCallMPI(MPI_Comm_rank(comm_, &rank_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* -coarse_partitioner metis: the cell dual graph (cells sharing an edge) of the mesh, still whole on
   the rank that built or read it, partitioned into one part per rank by METIS_PartGraphKway and
   handed to DMPlexDistribute through a PETSCPARTITIONERSHELL (Debian's PETSc has no ParMETIS). */
PetscErrorCode CoarseModel::DistributeWithMetis()
{
  const char *option = "-coarse_partitioner metis";
  PetscMPIInt size;
  PetscBool   distributed;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  if (size == 1) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(DMPlexIsDistributed(dm_, &distributed));
  PetscCheck(!distributed, comm_, PETSC_ERR_ARG_WRONG,
             "Option %s: the coarse mesh is already distributed (-coarse_dm_distribute, or a mesh given through the API); METIS partitions a serial mesh",
             option);
  PetscInt cStart, cEnd, ncells;
  PetscCall(DMPlexGetHeightStratum(dm_, 0, &cStart, &cEnd));
  ncells = cEnd - cStart;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &ncells, 1, MPIU_INT, MPI_SUM, comm_));
  PetscCheck(ncells >= size, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option %s: %" PetscInt_FMT " coarse elements cannot be split over %d ranks", option, ncells,
             (int)size);
  PetscInt nv = 0, *offsets = nullptr, *adjacency = nullptr;
  CSRGraph graph;
  PetscCall(DMPlexCreateNeighborCSR(dm_, 0, &nv, &offsets, &adjacency));
  if (nv > 0) {
    graph.xadj.assign(offsets, offsets + nv + 1);
    graph.adjncy.assign(adjacency, adjacency + offsets[nv]);
  }
  PetscCall(PetscFree(offsets));
  PetscCall(PetscFree(adjacency));
  std::vector<PetscInt> part, sizes((size_t)size, 0), points;
  if (nv > 0) { /* the rank holding the serial mesh; METIS_OPTION_SEED fixed: the same mesh, the same parts */
    MetisOptions opt;
    PetscCall(MetisPartGraphKway(PETSC_COMM_SELF, graph, size, opt, option, &part));
    for (PetscInt c = 0; c < nv; c++) sizes[part[c]]++;
    for (PetscMPIInt r = 0; r < size; r++)
      for (PetscInt c = 0; c < nv; c++)
        if (part[c] == r) points.push_back(cStart + c);
  }
  PetscPartitioner partitioner;
  DM               pdm = nullptr;
  PetscCall(DMPlexGetPartitioner(dm_, &partitioner));
  PetscCall(PetscPartitionerSetType(partitioner, PETSCPARTITIONERSHELL));
  PetscCall(PetscPartitionerShellSetPartition(partitioner, size, sizes.data(), points.empty() ? nullptr : points.data()));
  PetscCall(DMPlexDistribute(dm_, 0, NULL, &pdm));
  if (pdm) {
    PetscCall(DMDestroy(&dm_));
    dm_ = pdm;
    PetscCall(PetscObjectSetName((PetscObject)dm_, "coarse"));
    PetscCall(PetscObjectSetOptionsPrefix((PetscObject)dm_, "coarse_"));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Elements of about 3 kB (mesh, section, matrices) and the rule's material points each (5 or 4),
   dealt evenly to the ranks: refused before the points are created if the nodes cannot hold them. */
PetscErrorCode CoarseModel::CheckSize(PetscReal elements)
{
  PetscMPIInt       size;
  const PetscReal   points = npts_ * elements;
  const std::string what   = std::to_string((long long)elements) + " coarse elements (-coarse_dm_plex_box_faces, -coarse_dm_refine or the mesh file) with " +
                           std::to_string((long long)points) + " material points (" + pool_.MaterialName() + ")";
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  PetscCall(CheckCount(comm_, 4 * points, what));
  PetscCall(CheckMemory(comm_, 45e6 + (3e3 * elements + points * pool_.Model().BytesPerPoint()) / size, what));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Essential condition (DMAddBoundary): u = g(X) and v = 0 on the clamped vertices. */
PetscErrorCode CoarseModel::BoundaryValues(PetscInt dim, PetscReal time, const PetscReal X[], PetscInt Nc, PetscScalar *u, void *ctx)
{
  return TURGOR_GUARDED({
    const CoarseModel *model = (const CoarseModel *)ctx;
    PetscReal          g[2]  = {0, 0};
    if (model->boundary_) model->boundary_(X, g);
    if (model->spec_.HasBoundaryGradient()) {
      PetscReal hx[2];
      model->spec_.boundary_gradient.Apply(X, hx);
      for (int d = 0; d < 2; d++) g[d] += model->load_factor_ * hx[d];
    }
    u[0] = g[0];
    u[1] = g[1];
    u[2] = u[3] = 0;
    return PETSC_SUCCESS;
  });
}

/* Four dofs per node [ux, uy, vx, vy]: a Lagrange field of 4 components and the element's degree
   (PetscFE: Q1 puts a node on every vertex, Q2 also on every edge and cell) gives the section; the
   essential condition on the Dirichlet label values constrains all four on the label's closure
   (its vertices, and for Q2 its edges), so they drop out of the global vectors and matrices, and
   DMPlexInsertBoundaryValues fills them in local ones (for Q2 by the dual basis: the values at the
   nodes). */
PetscErrorCode CoarseModel::CreateSection()
{
  DMLabel  label;
  PetscFE  fe;
  PetscInt depth;
  PetscFunctionBeginUser;
  PetscCall(DMPlexGetDepth(dm_, &depth));
  PetscCheck(ref_->degree == 1 || depth == 2, comm_, PETSC_ERR_ARG_WRONG,
             "Option -coarse_element = %s: the coarse mesh has no edges (it is not interpolated: -coarse_dm_plex_interpolate 0?), so it cannot carry the "
             "nodes of Q2 at the edge midpoints; interpolate it or use -coarse_element q1",
             ref_->element.c_str());
  PetscCall(DMGetLabel(dm_, spec_.dirichlet_label.c_str(), &label));
  PetscCheck(label, comm_, PETSC_ERR_ARG_WRONG, "Option -coarse_dirichlet_label = %s: the mesh has no such label", spec_.dirichlet_label.c_str());
  PetscCall(PetscFECreateLagrange(comm_, 2, 4, PETSC_FALSE, ref_->degree, PETSC_DETERMINE, &fe));
  PetscCall(PetscObjectSetName((PetscObject)fe, "state"));
  PetscCall(DMSetField(dm_, 0, NULL, (PetscObject)fe));
  PetscCall(PetscFEDestroy(&fe));
  PetscCall(DMCreateDS(dm_));
  PetscCall(DMAddBoundary(dm_, DM_BC_ESSENTIAL, "clamp", label, (PetscInt)spec_.dirichlet_values.size(), spec_.dirichlet_values.data(), 0, 0, NULL,
                          (void (*)(void))BoundaryValues, NULL, this, NULL));
  PetscSection ls, gs;
  PetscInt     storage, free_storage, nc;
  PetscCall(DMGetLocalSection(dm_, &ls));
  PetscCall(PetscSectionGetStorageSize(ls, &storage));
  PetscCall(PetscSectionGetConstrainedStorageSize(ls, &free_storage));
  nc = storage - free_storage;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nc, 1, MPIU_INT, MPI_SUM, comm_));
  PetscCheck(nc > 0, comm_, PETSC_ERR_ARG_WRONG,
             "Options -coarse_dirichlet_label %s / -coarse_dirichlet_values: no vertex is clamped; the problem would be singular",
             spec_.dirichlet_label.c_str());
  PetscCall(DMCreateLocalVector(dm_, &Uloc_));
  PetscCall(VecDuplicate(Uloc_, &Floc_));
  PetscCall(InsertBoundaryValues(Uloc_));
  /* the rows the residual and Jacobian touch node by node (udot - v), found once: every point with
     a node (Q1: the vertices; Q2: also the edges and cells), in chart order */
  PetscCall(DMGetGlobalSection(dm_, &gs));
  free_rows_.clear();
  PetscInt p_start, p_end;
  PetscCall(PetscSectionGetChart(gs, &p_start, &p_end));
  for (PetscInt p = p_start; p < p_end; p++) {
    PetscInt off, dof, cdof;
    PetscCall(PetscSectionGetDof(gs, p, &dof));
    if (!dof) continue;
    PetscCall(PetscSectionGetOffset(gs, p, &off));
    PetscCall(PetscSectionGetConstraintDof(gs, p, &cdof));
    if (off >= 0 && dof - cdof == 4) free_rows_.push_back(off); /* owned and not clamped */
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseModel::SetBoundaryDisplacement(std::function<void(const PetscReal X[2], PetscReal u[2])> g)
{
  PetscFunctionBeginUser;
  boundary_ = std::move(g);
  if (Uloc_) PetscCall(InsertBoundaryValues(Uloc_));
  cached_valid_ = false;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseModel::SetLoadFactor(PetscReal factor)
{
  PetscFunctionBeginUser;
  load_factor_ = factor;
  if (spec_.HasBoundaryGradient() && Uloc_) { /* the clamped vertices move with it */
    PetscCall(InsertBoundaryValues(Uloc_));
    cached_valid_ = false;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseModel::InsertBoundaryValues(Vec Uloc)
{
  PetscFunctionBeginUser;
  PetscCall(DMPlexInsertBoundaryValues(dm_, PETSC_TRUE, Uloc, 0.0, NULL, NULL, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseModel::PrecomputeElements()
{
  DM           cdm;
  Vec          coords;
  PetscSection cs;
  PetscFunctionBeginUser;
  const PetscInt nc = c_end_ - c_start_;
  PetscCall(DMGetCoordinateDM(dm_, &cdm));
  PetscCall(DMGetCoordinatesLocal(dm_, &coords));
  PetscCall(DMGetLocalSection(cdm, &cs));
  Xref_.resize(8 * nc);
  dN_.resize(nc * npts_ * nn_ * 2);
  wdet_.resize(nc * npts_);
  std::string bad; /* the first bad element of this rank */
  for (PetscInt c = c_start_; c < c_end_; c++) {
    PetscScalar   *x = NULL;
    PetscInt       n = 0;
    const PetscInt k = c - c_start_;
    PetscCall(DMPlexVecGetClosure(dm_, cs, coords, c, &n, &x));
    PetscCheck(n == 8, PETSC_COMM_SELF, PETSC_ERR_PLIB, "cell %" PetscInt_FMT ": expected 4 vertices", c);
    for (int i = 0; i < 8; i++) Xref_[8 * k + i] = PetscRealPart(x[i]);
    PetscCall(DMPlexVecRestoreClosure(dm_, cs, coords, c, &n, &x));
    const PetscReal(*X)[2] = (const PetscReal(*)[2]) & Xref_[8 * k];
    /* a bilinear quadrilateral maps one-to-one iff det J has one sign at its four corners (det J
       is bilinear in xi, eta): two coincident vertices or a folded (non-convex) quadrilateral fail
       there even where the quadrature points still see det J != 0. A consistently clockwise
       element is fine: dN/dX = J^-T dN/dxi holds for either sign, and the weights take |det J|. */
    if (bad.empty()) {
      PetscReal size2 = 0, detc[4];
      for (int a = 0; a < 4; a++) size2 = PetscMax(size2, PetscSqr(X[(a + 2) % 4][0] - X[a][0]) + PetscSqr(X[(a + 2) % 4][1] - X[a][1]));
      for (int a = 0; a < 4; a++) {
        PetscReal dNc[4][2];
        detc[a] = q1::Gradients(X, q1::kXi[a][0], q1::kXi[a][1], dNc);
      }
      const PetscReal sign = detc[0] < 0 ? -1 : 1;
      for (int a = 0; a < 4 && bad.empty(); a++)
        if (!(sign * detc[a] > 1e-10 * size2)) {
          char buf[512];
          PetscCall(PetscSNPrintf(buf, sizeof buf,
                                  "element %" PetscInt_FMT " with vertices (%g, %g) (%g, %g) (%g, %g) (%g, %g) is degenerate or folded: det J = %g at its "
                                  "vertex %d and %g at its vertex 1 (two vertices coincide, or the quadrilateral is not convex)",
                                  cell_gid_[k], (double)X[0][0], (double)X[0][1], (double)X[1][0], (double)X[1][1], (double)X[2][0], (double)X[2][1],
                                  (double)X[3][0], (double)X[3][1], (double)detc[a], a + 1, (double)detc[0]));
          bad = buf;
        }
    }
    for (int q = 0; q < npts_; q++) {
      PetscReal        Ji[2][2];
      const PetscReal  det = GeometryMap(X, ref_->xi[2 * q], ref_->xi[2 * q + 1], Ji);
      const PetscReal *dNr = &ref_->dN[q * nn_ * 2];
      PetscReal       *dN  = &dN_[(k * npts_ + q) * nn_ * 2];
      for (PetscInt a = 0; a < nn_; a++) /* dN/dX = dN/dxi (dX/dxi)^-1 */
        for (int i = 0; i < 2; i++) dN[2 * a + i] = dNr[2 * a] * Ji[0][i] + dNr[2 * a + 1] * Ji[1][i];
      wdet_[k * npts_ + q] = ref_->w[q] * PetscAbsReal(det);
    }
  }
  std::string msg;
  PetscCall(FirstMessage(comm_, bad, &msg));
  PetscCheck(msg.empty(), comm_, PETSC_ERR_ARG_WRONG, "Coarse mesh: %s", msg.c_str());
  PetscCall(ComputeRankFreeCellIds()); /* reports name elements by them from here on */
  /* the tip: the middle of the right side of the mesh's bounding box (the fine run's tip particle),
     on the mesh edge nearest to it. The displacement there is the element's interpolation along
     that edge (linear for Q1, quadratic through the edge's middle node for Q2), so that an odd
     number of elements along y does not move the tip off centre to the nearest vertex. */
  PetscReal lo[2], hi[2], best = PETSC_MAX_REAL;
  PetscCall(DMGetBoundingBox(dm_, lo, hi));
  const PetscReal    target[2] = {hi[0], 0.5 * (lo[1] + hi[1])};
  const PetscScalar *xc;
  PetscSection       vs;
  PetscInt           e_start, e_end;
  PetscCall(DMGetLocalSection(cdm, &vs));
  PetscCall(DMPlexGetDepthStratum(dm_, 1, &e_start, &e_end));
  PetscCall(VecGetArrayRead(coords, &xc));
  PetscMPIInt rank;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  for (PetscInt e = e_start; e < e_end; e++) {
    const PetscInt *cone;
    PetscInt        size, oa, ob;
    PetscCall(DMPlexGetConeSize(dm_, e, &size));
    if (size != 2) continue;
    PetscCall(DMPlexGetCone(dm_, e, &cone));
    PetscCall(PetscSectionGetOffset(vs, cone[0], &oa));
    PetscCall(PetscSectionGetOffset(vs, cone[1], &ob));
    const PetscReal ax = PetscRealPart(xc[oa]), ay = PetscRealPart(xc[oa + 1]), ex = PetscRealPart(xc[ob]) - ax, ey = PetscRealPart(xc[ob + 1]) - ay;
    const PetscReal L2 = ex * ex + ey * ey;
    if (!(L2 > 0)) continue;
    PetscReal sp = std::clamp(((target[0] - ax) * ex + (target[1] - ay) * ey) / L2, (PetscReal)0, (PetscReal)1);
    if (sp < 1e-12) sp = 0; /* at a vertex: its value, bit for bit */
    if (sp > 1 - 1e-12) sp = 1;
    const PetscReal d = std::hypot(ax + sp * ex - target[0], ay + sp * ey - target[1]);
    if (d < best) {
      best    = d;
      tip_.a  = cone[0];
      tip_.b  = cone[1];
      tip_.e  = e;
      tip_.sp = sp;
    }
  }
  PetscCall(VecRestoreArrayRead(coords, &xc));
  struct {
    PetscReal d;
    int       r;
  } mine = {best, rank}, win;
  PetscCallMPI(MPI_Allreduce(&mine, &win, 1, MPI_DOUBLE_INT, MPI_MINLOC, comm_)); /* PetscReal is double */
  if (win.r != rank) tip_.e = -1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Mt = diag(I, M): the consistent mass M_ab = int rho0 N_a N_b dV (3 x 3 Gauss, exact on any quad;
   rho dv = rho0 dV keeps it constant) or its row sums; the identity on the displacement dofs. */
PetscErrorCode CoarseModel::AssembleMass()
{
  PetscFunctionBeginUser;
  PetscCall(DMCreateMatrix(dm_, &Mt_));
  PetscCall(MatSetOption(Mt_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  const PetscInt nc = c_end_ - c_start_, ne = 4 * nn_;
  f_ext_.assign(2 * nn_ * nc, 0);
  std::vector<PetscReal> m(nn_ * nn_);
  for (PetscInt c = c_start_; c < c_end_; c++) {
    const PetscInt k       = c - c_start_;
    const PetscReal(*X)[2] = (const PetscReal(*)[2]) & Xref_[8 * k];
    PetscScalar *me        = work_.data();
    std::fill(work_.begin(), work_.begin() + ne * ne, 0.0);
    std::fill(m.begin(), m.end(), 0.0);
    for (PetscInt p = 0; p < ref_->mass_points; p++) {
      PetscReal        Ji[2][2];
      const PetscReal  det = GeometryMap(X, ref_->mass_xi[2 * p], ref_->mass_xi[2 * p + 1], Ji);
      const PetscReal *N   = &ref_->mass_N[p * nn_];
      const PetscReal  w   = ref_->mass_w[p] * PetscAbsReal(det) * rho0_;
      for (PetscInt a = 0; a < nn_; a++) {
        for (PetscInt b = 0; b < nn_; b++) m[a * nn_ + b] += w * N[a] * N[b];
        for (int d = 0; d < 2; d++) f_ext_[2 * nn_ * k + 2 * a + d] += w * N[a] * g_[d];
      }
    }
    for (PetscInt a = 0; a < nn_; a++) {
      PetscReal row = 0;
      for (PetscInt b = 0; b < nn_; b++) row += m[a * nn_ + b];
      for (PetscInt b = 0; b < nn_; b++) {
        const PetscReal mab = spec_.lumped_mass ? (a == b ? row : 0.0) : m[a * nn_ + b];
        for (int d = 0; d < 2; d++) me[(4 * a + 2 + d) * ne + 4 * b + 2 + d] = mab;
      }
    }
    PetscCall(DMPlexMatSetClosure(dm_, NULL, NULL, Mt_, c, me, ADD_VALUES));
  }
  for (PetscInt off : free_rows_)
    for (PetscInt d = 0; d < 2; d++) PetscCall(MatSetValue(Mt_, off + d, off + d, 1.0, ADD_VALUES));
  PetscCall(MatAssemblyBegin(Mt_, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(Mt_, MAT_FINAL_ASSEMBLY));
  PetscCall(KSPCreate(comm_, &mass_ksp_));
  PetscCall(KSPSetOptionsPrefix(mass_ksp_, "coarse_mass_"));
  PetscCall(KSPSetOperators(mass_ksp_, Mt_, Mt_));
  PetscCall(KSPSetType(mass_ksp_, KSPCG));
  {
    PC pc;
    PetscCall(KSPGetPC(mass_ksp_, &pc));
    PetscCall(PCSetType(pc, PCJACOBI));
  }
  PetscCall(KSPSetTolerances(mass_ksp_, 1e-12, 1e-30, PETSC_DEFAULT, 200));
  PetscCall(KSPSetFromOptions(mass_ksp_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseModel::SetUp()
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventRegister("TgCoarseResidual", PETSC_OBJECT_CLASSID, &ev_residual_));
  PetscCall(PetscLogEventRegister("TgCoarseJacobian", PETSC_OBJECT_CLASSID, &ev_jacobian_));
  PetscCall(PetscLogEventRegister("TgCoarseTangentAt", PETSC_OBJECT_CLASSID, &ev_tangent_at_));
  ref_ = std::make_unique<ReferenceElement>();
  PetscCall(CreateReferenceElement(spec_.element, spec_.quadrature, ref_.get()));
  npts_ = ref_->points;
  nn_   = ref_->nodes;
  work_.assign(16 * nn_ * nn_ + 4 * nn_, 0.0);
  PetscCall(CreateMesh());
  {
    PetscInt n = c_end_ - c_start_;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &n, 1, MPIU_INT, MPI_SUM, comm_));
    PetscCall(CheckSize((PetscReal)n));
  }
  PetscCall(CreateSection());
  PetscCall(PrecomputeElements());
  PetscCall(skin_.SetUp(dm_, c_start_, c_end_, spec_.element == CoarseElement::Q2 ? 3 : 2));
  const PetscInt np = (c_end_ - c_start_) * npts_;
  PetscCall(pool_.SetUp(np));
  first_point_ = 0;
  PetscCallMPI(MPI_Exscan(&np, &first_point_, 1, MPIU_INT, MPI_SUM, comm_));
  if (rank_ == 0) first_point_ = 0;
  F_.assign(np, Tensor2::Identity());
  Fdot_.assign(np, Tensor2::Zero());
  response_.resize(np);
  tangent_.resize(np);
  cell_stress_.assign(3 * (c_end_ - c_start_), 0);
  cell_acoustic_.assign(c_end_ - c_start_, NAN);
  /* the reference density from the material at rest (an RVE: its mass over its area) */
  PetscBool   ok;
  std::string why;
  {
    Vec U0;
    PetscCall(DMCreateGlobalVector(dm_, &U0));
    PetscCall(VecZeroEntries(U0));
    PetscCall(EvaluateMaterials(U0, false, &ok, &why));
    PetscCall(VecDestroy(&U0));
  }
  PetscCheck(ok, comm_, PETSC_ERR_NOT_CONVERGED, "The material fails at rest (F = I): %s", why.c_str());
  PetscReal r = 0;
  for (PetscInt k = 0; k < np; k++) r = PetscMax(r, response_[k].rho);
  PetscCallMPI(MPI_Allreduce(&r, &rho0_, 1, MPIU_REAL, MPIU_MAX, comm_));
  PetscCall(pool_.Commit());
  PetscCall(AssembleMass());
  n_elements_ = c_end_ - c_start_;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &n_elements_, 1, MPIU_INT, MPI_SUM, comm_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseModel::NodeState(Vec U, const std::function<bool(const PetscReal X[2], PetscReal state[4])> &f, std::string *missing)
{
  DM                 cdm;
  Vec                coords, Uloc;
  PetscSection       cs, ls;
  const PetscScalar *xc;
  PetscScalar       *u;
  PetscInt           p_start, p_end;
  std::string        mine;
  PetscFunctionBeginUser;
  PetscCall(DMGetCoordinateDM(dm_, &cdm));
  PetscCall(DMGetLocalSection(cdm, &cs));
  PetscCall(DMGetCoordinatesLocal(dm_, &coords));
  PetscCall(DMGetLocalSection(dm_, &ls));
  PetscCall(DMCreateLocalVector(dm_, &Uloc));
  PetscCall(VecZeroEntries(Uloc));
  PetscCall(VecGetArrayRead(coords, &xc));
  PetscCall(VecGetArray(Uloc, &u));
  PetscCall(PetscSectionGetChart(ls, &p_start, &p_end));
  for (PetscInt p = p_start; p < p_end && mine.empty(); p++) {
    PetscInt  off, dof, cdof, n = 0, *cl = NULL;
    PetscReal state[4] = {0, 0, 0, 0}, X[2] = {0, 0};
    PetscCall(PetscSectionGetDof(ls, p, &dof));
    PetscCall(PetscSectionGetConstraintDof(ls, p, &cdof));
    if (dof - cdof != 4) continue; /* no node, or clamped */
    PetscCall(PetscSectionGetOffset(ls, p, &off));
    /* the node's reference position: the vertex, or the mean of the point's vertices (an edge's
       midpoint, a cell's centre: the bilinear map at the node's reference coordinates) */
    PetscCall(DMPlexGetTransitiveClosure(dm_, p, PETSC_TRUE, &n, &cl));
    PetscInt nv = 0;
    for (PetscInt r = 0; r < n; r++)
      if (cl[2 * r] >= v_start_ && cl[2 * r] < v_end_) {
        PetscInt coff;
        PetscCall(PetscSectionGetOffset(cs, cl[2 * r], &coff));
        X[0] += PetscRealPart(xc[coff]);
        X[1] += PetscRealPart(xc[coff + 1]);
        nv++;
      }
    PetscCall(DMPlexRestoreTransitiveClosure(dm_, p, PETSC_TRUE, &n, &cl));
    X[0] /= nv;
    X[1] /= nv;
    if (!f(X, state)) {
      char where[96];
      PetscCall(PetscSNPrintf(where, sizeof where, "(%g, %g)", (double)X[0], (double)X[1]));
      mine = where;
    }
    for (int d = 0; d < 4; d++) u[off + d] = state[d];
  }
  PetscCall(VecRestoreArray(Uloc, &u));
  PetscCall(VecRestoreArrayRead(coords, &xc));
  PetscCall(FirstMessage(comm_, mine, missing));
  PetscCall(VecZeroEntries(U));
  PetscCall(DMLocalToGlobal(dm_, Uloc, INSERT_VALUES, U));
  PetscCall(VecDestroy(&Uloc));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The constrained entries of a local vector are not touched by DMGlobalToLocal: the model's own
   local vector keeps the boundary values inserted once (and again when they change); any other one
   gets them here. */
PetscErrorCode CoarseModel::GlobalToLocal(Vec U, Vec Uloc)
{
  PetscFunctionBeginUser;
  if (Uloc != Uloc_) PetscCall(InsertBoundaryValues(Uloc));
  PetscCall(DMGlobalToLocal(dm_, U, INSERT_VALUES, Uloc));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Where a material point is and what it was asked: global element, which of its points, F, Fdot,
   the reason and the last residual. */
PetscErrorCode CoarseModel::DescribePoint(PetscInt m, const std::vector<Tensor2> &Fs, const std::vector<Tensor2> &Fdots, const std::vector<MaterialResponse> &r,
                                          std::string *text) const
{
  const Tensor2 &F = Fs[m], &Fd = Fdots[m];
  char           buf[512];
  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(buf, sizeof buf,
                          "element %" PetscInt_FMT " (%s), F = [%.6g %.6g; %.6g %.6g] (det %.4g), Fdot = [%.4g %.4g; %.4g %.4g] /µs, residual %.3g: %s",
                          cell_id_[m / npts_], ref_->where[m % npts_].c_str(), (double)F(0, 0), (double)F(0, 1), (double)F(1, 0), (double)F(1, 1),
                          (double)F.Det(), (double)Fd(0, 0), (double)Fd(0, 1), (double)Fd(1, 0), (double)Fd(1, 1), (double)r[m].residual, r[m].reason.c_str()));
  *text = buf;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* F = I + sum_a u_a (x) grad_X N_a and Fdot = sum_a v_a (x) grad_X N_a at every material point;
   the pool answers (from the cache when U is unchanged). */
PetscErrorCode CoarseModel::CacheHolds(Vec Uloc, bool tangents, bool *holds)
{
  const PetscScalar *u;
  PetscInt           n;
  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(Uloc, &n));
  PetscCall(VecGetArrayRead(Uloc, &u));
  int same = cached_valid_ && (PetscInt)cached_U_.size() == n &&
             (n == 0 || !std::memcmp(cached_U_.data(), u, n * sizeof(PetscScalar))) /* an empty rank's arrays may be null */ && (cached_tangents_ || !tangents),
      all_same;
  PetscCall(VecRestoreArrayRead(Uloc, &u));
  PetscCallMPI(MPI_Allreduce(&same, &all_same, 1, MPI_INT, MPI_MIN, comm_));
  *holds = all_same;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseModel::DeformationAt(Vec Uloc, std::vector<Tensor2> &F, std::vector<Tensor2> &Fdot)
{
  PetscFunctionBeginUser;
  F.resize((c_end_ - c_start_) * npts_);
  Fdot.resize(F.size());
  for (PetscInt c = c_start_; c < c_end_; c++) {
    PetscScalar   *x  = NULL;
    PetscInt       nx = 0;
    const PetscInt k  = c - c_start_;
    PetscCall(DMPlexVecGetClosure(dm_, NULL, Uloc, c, &nx, &x));
    PetscCheck(nx == 4 * nn_, PETSC_COMM_SELF, PETSC_ERR_PLIB, "cell %" PetscInt_FMT ": %" PetscInt_FMT " closure values, expected %" PetscInt_FMT, c, nx,
               4 * nn_);
    for (int q = 0; q < npts_; q++) {
      const PetscReal *dN = &dN_[(k * npts_ + q) * nn_ * 2];
      Tensor2          Fq = Tensor2::Identity(), Fd;
      for (PetscInt a = 0; a < nn_; a++)
        for (int i = 0; i < 2; i++)
          for (int j = 0; j < 2; j++) {
            Fq(i, j) += PetscRealPart(x[4 * a + i]) * dN[2 * a + j];
            Fd(i, j) += PetscRealPart(x[4 * a + 2 + i]) * dN[2 * a + j];
          }
      F[k * npts_ + q]    = Fq;
      Fdot[k * npts_ + q] = Fd;
    }
    PetscCall(DMPlexVecRestoreClosure(dm_, NULL, Uloc, c, &nx, &x));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseModel::EvaluateCellStress(Vec U, PetscBool *ok)
{
  bool                                 holds;
  const std::vector<MaterialResponse> *r = &response_;
  PetscFunctionBeginUser;
  PetscCall(GlobalToLocal(U, Uloc_));
  PetscCall(CacheHolds(Uloc_, false, &holds));
  if (spec_.acoustic_field) { /* one output evaluation with D^e serves both (the stress from the cache when it holds) */
    PetscBool aok;
    PetscCall(EvaluateForOutput(Uloc_, false, &aok, NULL));
    AcousticFromOutput();
    if (!holds) r = &out_response_;
  } else if (!holds) {
    PetscCall(DeformationAt(Uloc_, out_F_, out_Fdot_));
    out_response_.resize(out_F_.size());
    PetscCall(pool_.Evaluate(out_F_.data(), out_Fdot_.data(), out_response_.data(), false, NULL, EvaluationKind::Output));
    r = &out_response_;
  }
  int local_ok = 1, global_ok;
  for (const MaterialResponse &m : *r) local_ok = local_ok && m.ok;
  PetscCallMPI(MPI_Allreduce(&local_ok, &global_ok, 1, MPI_INT, MPI_MIN, comm_));
  *ok = global_ok ? PETSC_TRUE : PETSC_FALSE;
  /* each part (pressure, deviator, whole stress) averaged over the points that carry it, weighted
     as the rule weighs them; the pressure first (sri: p + the mean deviator of the Gauss points) */
  PetscReal wpart[3] = {0, 0, 0};
  for (int q = 0; q < npts_; q++) wpart[(int)ref_->part[q]] += ref_->w[q];
  for (PetscInt k = 0; k < c_end_ - c_start_; k++) {
    PetscReal mean[3] = {0, 0, 0};
    for (int pass = 0; pass < 2; pass++)
      for (int q = 0; q < npts_; q++) {
        const PointPart part = ref_->part[q];
        if ((part == PointPart::Pressure) != (pass == 0)) continue;
        const Tensor2   sg = (*r)[k * npts_ + q].sigma.Sym(); /* as InternalForce takes it */
        const PetscReal f  = ref_->w[q] / wpart[(int)part];
        switch (part) {
        case PointPart::Pressure:
          mean[0] += f * (0.5 * sg.Trace());
          mean[1] += f * (0.5 * sg.Trace());
          break;
        case PointPart::Deviatoric:
          mean[0] += f * (0.5 * (sg(0, 0) - sg(1, 1)));
          mean[1] += f * (0.5 * (sg(1, 1) - sg(0, 0)));
          mean[2] += f * sg(0, 1);
          break;
        case PointPart::Whole:
          mean[0] += f * sg(0, 0);
          mean[1] += f * sg(1, 1);
          mean[2] += f * sg(0, 1);
          break;
        }
      }
    bool cell_ok = true;
    for (int q = 0; q < npts_; q++) cell_ok = cell_ok && (*r)[k * npts_ + q].ok;
    for (int i = 0; i < 3; i++) cell_stress_[3 * k + i] = cell_ok ? mean[i] : NAN; /* not a failed point's stress */
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseModel::EvaluateMaterials(Vec U, bool tangents, PetscBool *ok, std::string *why)
{
  bool holds;
  PetscFunctionBeginUser;
  PetscCall(GlobalToLocal(U, Uloc_));
  PetscCall(CacheHolds(Uloc_, tangents, &holds));
  if (holds) {
    *ok                 = cached_ok_ ? PETSC_TRUE : PETSC_FALSE;
    last_stress_failed_ = !cached_stress_ok_;
    if (why) *why = cached_ok_ ? "" : "cached failure";
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  {
    const PetscScalar *u;
    PetscInt           n;
    PetscCall(VecGetLocalSize(Uloc_, &n));
    PetscCall(VecGetArrayRead(Uloc_, &u));
    cached_U_.assign(u, u + n);
    PetscCall(VecRestoreArrayRead(Uloc_, &u));
  }
  PetscCall(DeformationAt(Uloc_, F_, Fdot_));
  PetscCall(pool_.Evaluate(F_.data(), Fdot_.data(), response_.data(), tangents, tangent_.data()));
  counters_.material_evals++;
  if (tangents) counters_.tangent_evals++;
  int         local[2] = {1, 1}, global[2]; /* every point ok; every point's stress found */
  PetscInt    nfailed = 0, lowest = PETSC_MAX_INT;
  std::string first;
  for (size_t k = 0; k < response_.size(); k++)
    if (!response_[k].ok) {
      if (!nfailed) PetscCall(DescribePoint((PetscInt)k, F_, Fdot_, response_, &first));
      nfailed++;
      local[0] = 0;
      if (!response_[k].tangent_failed) local[1] = 0;
      lowest = PetscMin(lowest, cell_id_[k / npts_]);
    }
  PetscCallMPI(MPI_Allreduce(local, global, 2, MPI_INT, MPI_MIN, comm_));
  const int local_ok = local[0], global_ok = global[0];
  last_stress_failed_ = !global[1];
  cached_stress_ok_   = global[1];
  stress_failures_ += !global[1];
  if (why) *why = local_ok ? (global_ok ? "" : "on another rank") : first;
  if (!global_ok) {
    /* every failure is reported where it happened, without -info: the cause of a rejected step */
    counters_.failures++;
    PetscCallMPI(MPI_Allreduce(&lowest, &failed_element_, 1, MPIU_INT, MPI_MIN, comm_));
    if (nfailed) {
      char when[128];
      if (eval_where_.empty()) PetscCall(PetscSNPrintf(when, sizeof when, "at t = %g µs", (double)eval_time_));
      else PetscCall(PetscStrncpy(when, eval_where_.c_str(), sizeof when));
      PetscCall(PetscSynchronizedPrintf(comm_, "[%d] material points failed %s%s: %" PetscInt_FMT " of %zu on this rank; the first: %s\n", rank_, when,
                                        tangents ? " (with tangents)" : "", nfailed, response_.size(), first.c_str()));
    }
    PetscCall(PetscSynchronizedFlush(comm_, PETSC_STDOUT));
  }
  *ok              = global_ok ? PETSC_TRUE : PETSC_FALSE;
  cached_valid_    = true;
  cached_ok_       = global_ok;
  cached_tangents_ = tangents;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* [counters (5), cache: valid, ok, tangents, U, per point F, Fdot (8), response (10), tangents (18)
   when cached with them; the material points] */
PetscErrorCode CoarseModel::DeclareState(std::deque<StateDeclaration> &decls, Vec U)
{
  CoarseCounters &c = counters_;
  PetscFunctionBeginUser;
  {
    /* whether the cache is of U (an explicit integrator's last stage): on another layout it is kept
       only if it was on every writing rank */
    bool at_u = false;
    if (cached_valid_) {
      PetscCall(GlobalToLocal(U, Uloc_));
      PetscCall(CacheHolds(Uloc_, cached_tangents_, &at_u));
    }
    cache_stale_ = !at_u;
  }
  PetscCall(RankFreePointIds(rank_free_ids_));
  const size_t n = response_.size();
  F_.resize(n, Tensor2::Identity());
  Fdot_.resize(n, Tensor2::Zero());
  tangent_.resize(n);
  decls.emplace_back("coarse");
  StateDeclaration &d = decls.back();
  d.Scalar("residuals", &c.residuals, Combine::Owner);
  d.Scalar("jacobians", &c.jacobians, Combine::Owner);
  d.Scalar("material_evaluations", &c.material_evals, Combine::Owner);
  d.Scalar("tangent_evaluations", &c.tangent_evals, Combine::Owner);
  d.Scalar("failures", &c.failures, Combine::Owner);
  d.Scalar("cache_valid", &cached_valid_, Combine::Local);
  d.Scalar("cache_stale", &cache_stale_, Combine::Max);
  d.Scalar("cache_ok", &cached_ok_, Combine::Owner);
  d.Scalar("cache_tangents", &cached_tangents_, Combine::Owner);
  d.Sequence(
    "cache_state", [this](std::vector<PetscReal> &v) { v.assign(cached_U_.begin(), cached_U_.end()); },
    [this](const PetscReal *v, size_t m) {
      cached_U_.assign(v, v + m);
      return PETSC_SUCCESS;
    },
    Combine::Local);
  /* the cache of this rank's points, each by its id */
  d.Table("points", StateEntity::MaterialPoint)
    .Rows([this] { return response_.size(); }, [this](size_t r) { return first_point_ + (PetscInt)r; }, [](size_t) { return true; })
    .Packed("F", F_)
    .Packed("Fdot", Fdot_)
    .Field("stress", response_, &MaterialResponse::sigma)
    .Field("density", response_, &MaterialResponse::rho)
    .Column(
      "ok", 1, [this](size_t r, PetscReal *v) { v[0] = response_[r].ok; },
      [this](size_t r, const PetscReal *v) {
        response_[r].ok     = v[0] != 0;
        response_[r].reason = response_[r].ok ? "" : "(restored from the checkpoint)";
      },
      Combine::Owner, true)
    .Field("iterations", response_, &MaterialResponse::iterations)
    .Field("snes_iterations", response_, &MaterialResponse::snes_its)
    .Field("ksp_iterations", response_, &MaterialResponse::ksp_its)
    .Field("residual", response_, &MaterialResponse::residual)
    .Packed("tangents", tangent_);
  decls.emplace_back("material");
  PetscCall(pool_.DeclareState(decls.back(), rank_free_ids_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseModel::AfterStateRead(Vec U, bool own_layout)
{
  PetscFunctionBeginUser;
  if (!own_layout) { /* the cache of the checkpoint's state, which U is: its local form here */
    cached_valid_ = !cache_stale_;
    cached_U_.clear();
    if (cached_valid_) {
      const PetscScalar *u;
      PetscInt           nl;
      PetscCall(GlobalToLocal(U, Uloc_));
      PetscCall(VecGetLocalSize(Uloc_, &nl));
      PetscCall(VecGetArrayRead(Uloc_, &u));
      cached_U_.assign(u, u + nl);
      PetscCall(VecRestoreArrayRead(Uloc_, &u));
    }
  }
  PetscCall(pool_.AfterStateRead(own_layout));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The part of a material point's (symmetric) stress that its rule integrates there: the whole
   stress, its deviator sigma - tr(sigma)/2 I, or its pressure tr(sigma)/2 I. */
static Tensor2 StressPart(PointPart part, const Tensor2 &sg)
{
  switch (part) {
  case PointPart::Pressure:
    return (0.5 * sg.Trace()) * Tensor2::Identity();
  case PointPart::Deviatoric:
    return sg - (0.5 * sg.Trace()) * Tensor2::Identity();
  default:
    return sg;
  }
}

PetscErrorCode CoarseModel::RevertMaterials()
{
  PetscFunctionBeginUser;
  PetscCall(pool_.Revert());
  cached_valid_ = false; /* the cached responses came from the states just dropped */
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseModel::CreateFreeIS(IS *displacement, IS *velocity) const
{
  std::vector<PetscInt> u, v;
  PetscFunctionBeginUser;
  for (PetscInt off : free_rows_) {
    u.insert(u.end(), {off, off + 1});
    v.insert(v.end(), {off + 2, off + 3});
  }
  PetscCall(ISCreateGeneral(comm_, (PetscInt)u.size(), u.data(), PETSC_COPY_VALUES, displacement));
  PetscCall(ISCreateGeneral(comm_, (PetscInt)v.size(), v.data(), PETSC_COPY_VALUES, velocity));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Local [0; f_int - lambda f_ext], f_int,a = sum_q w_q J_q s_q F_q^-T grad_X N_a(q) with s_q the part of
   sigma_q the rule takes there: sri, the deviatoric stress at the 2 x 2 Gauss points and the
   pressure tr(sigma)/2 at the centre (selective reduced integration); full, the whole stress at
   the 2 x 2 Gauss points. */
PetscErrorCode CoarseModel::InternalForce(Vec Floc)
{
  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(Floc));
  for (PetscInt c = c_start_; c < c_end_; c++) {
    const PetscInt k  = c - c_start_;
    PetscScalar   *fe = work_.data();
    std::fill(work_.begin(), work_.begin() + 4 * nn_, 0.0);
    for (int q = 0; q < npts_; q++) {
      const PetscInt   m  = k * npts_ + q;
      const Tensor2   &F  = F_[m];
      const Tensor2    Fi = F.Inverse();
      const PetscReal  W  = wdet_[m] * F.Det();
      const PetscReal *dN = &dN_[m * nn_ * 2];
      const Tensor2    s  = StressPart(ref_->part[q], response_[m].sigma.Sym());
      for (PetscInt a = 0; a < nn_; a++) {
        const PetscReal gx = Fi(0, 0) * dN[2 * a] + Fi(1, 0) * dN[2 * a + 1]; /* grad_x N = F^-T grad_X N */
        const PetscReal gy = Fi(0, 1) * dN[2 * a] + Fi(1, 1) * dN[2 * a + 1];
        fe[4 * a + 2] += W * (s(0, 0) * gx + s(0, 1) * gy);
        fe[4 * a + 3] += W * (s(1, 0) * gx + s(1, 1) * gy);
      }
    }
    for (PetscInt a = 0; a < nn_; a++)
      for (int d = 0; d < 2; d++) fe[4 * a + 2 + d] -= load_factor_ * f_ext_[2 * nn_ * k + 2 * a + d];
    PetscCall(DMPlexVecSetClosure(dm_, NULL, Floc, c, fe, ADD_VALUES));
  }
  if (skin_.Active()) PetscCall(skin_.AddForce(dm_, Uloc_, Floc));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseModel::FillNaN(Vec F)
{
  PetscFunctionBeginUser;
  PetscCall(VecSet(F, NAN));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseModel::IFunction(Vec U, Vec Udot, Vec F, PetscBool *ok)
{
  PetscInt           rstart;
  PetscScalar       *f;
  const PetscScalar *u;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ev_residual_, 0, 0, 0, 0));
  counters_.residuals++;
  std::string why;
  PetscCall(EvaluateMaterials(U, false, ok, &why));
  if (!*ok) {
    PetscCall(FillNaN(F));
    PetscCall(PetscLogEventEnd(ev_residual_, 0, 0, 0, 0));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscLogDouble t0, t1;
  PetscCall(PetscTime(&t0));
  PetscCall(InternalForce(Floc_));
  PetscCall(VecZeroEntries(F));
  PetscCall(DMLocalToGlobal(dm_, Floc_, ADD_VALUES, F));
  PetscCall(MatMultAdd(Mt_, Udot, F, F)); /* + [udot; M vdot] */
  /* - v on the displacement rows */
  PetscCall(VecGetOwnershipRange(F, &rstart, NULL));
  PetscCall(VecGetArray(F, &f));
  PetscCall(VecGetArrayRead(U, &u));
  for (PetscInt row : free_rows_) {
    const PetscInt off = row - rstart;
    f[off] -= u[off + 2];
    f[off + 1] -= u[off + 3];
  }
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(PetscTime(&t1));
  coarse_time_ += t1 - t0;
  PetscCall(PetscLogEventEnd(ev_residual_, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseModel::RHSFunction(Vec U, Vec G, PetscBool *ok)
{
  PetscFunctionBeginUser;
  if (!rhs_r_) { /* work vectors kept: this is called at every stage */
    PetscCall(VecDuplicate(U, &rhs_r_));
    PetscCall(VecDuplicate(U, &rhs_z_));
    PetscCall(VecZeroEntries(rhs_z_));
  }
  PetscCall(IFunction(U, rhs_z_, rhs_r_, ok)); /* R = -[v; f_ext - f_int] */
  if (*ok) {
    PetscLogDouble t0, t1;
    PetscCall(PetscTime(&t0));
    PetscCall(VecScale(rhs_r_, -1.0));
    PetscCall(KSPSolve(mass_ksp_, rhs_r_, G));
    PetscCall(PetscTime(&t1));
    coarse_time_ += t1 - t0;
    KSPConvergedReason reason;
    PetscCall(KSPGetConvergedReason(mass_ksp_, &reason));
    PetscCheck(reason > 0, comm_, PETSC_ERR_NOT_CONVERGED, "Mass matrix solve failed (%s)", KSPConvergedReasons[reason]);
  } else PetscCall(FillNaN(G));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The part of a material point's tangents that goes with the part of its stress (StressPart), so
   that K is the exact derivative of f_int under either rule: the whole D for the whole stress, and
   for sri's split, in Voigt form on (11, 22, 12) acting on [dd11, dd22, 2 dd12], with
   e = [1, 1, 0] and sv = [s11, s22, s12]:
     dev:       D - e e^T D / 2 - e sv^T + tr(sigma) diag(1, 1, 1/2)
     pressure:  e e^T D / 2 + e sv^T - tr(sigma) diag(1, 1, 1/2)
   (the Truesdell rates of dev(sigma) and of tr(sigma)/2 I; the two add up to D); the viscous D^v
   splits without the geometric terms. */
static void SplitTangent(const PetscReal D[3][3], const Tensor2 &s, PointPart part, bool viscous, PetscReal out[3][3])
{
  const PetscReal e[3] = {1, 1, 0}, sv[3] = {s(0, 0), s(1, 1), 0.5 * (s(0, 1) + s(1, 0))}, tr = s.Trace();
  const PetscReal diag[3] = {1, 1, 0.5};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      if (part == PointPart::Whole) {
        out[i][j] = D[i][j];
        continue;
      }
      const PetscReal vol = 0.5 * e[i] * (D[0][j] + D[1][j]);
      PetscReal       geo = viscous ? 0.0 : e[i] * sv[j] - (i == j ? tr * diag[i] : 0.0);
      out[i][j]           = part == PointPart::Pressure ? vol + geo : D[i][j] - vol - geo;
    }
}

/* [[0, -I], [K, C]]: per element, K from each point's part of D^e with the initial-stress term
   and C from its part of D^v (SplitTangent), on the current configuration; -I on the free
   displacement rows. */
PetscErrorCode CoarseModel::AssembleKC(const std::vector<Tensor2> &Fs, const std::vector<MaterialResponse> &r, const std::vector<Tangents> &D, Mat J)
{
  PetscFunctionBeginUser;
  PetscCall(MatZeroEntries(J));
  const PetscInt         ne = 4 * nn_;
  std::vector<PetscReal> g(2 * nn_); /* grad_x N_a at a point */
  for (PetscInt c = c_start_; c < c_end_; c++) {
    const PetscInt k  = c - c_start_;
    PetscScalar   *ke = work_.data();
    std::fill(work_.begin(), work_.begin() + ne * ne, 0.0);
    for (int q = 0; q < npts_; q++) {
      const PetscInt   m     = k * npts_ + q;
      const Tensor2   &F     = Fs[m];
      const Tensor2    Fi    = F.Inverse();
      const PetscReal  W     = wdet_[m] * F.Det();
      const PetscReal *dN    = &dN_[m * nn_ * 2];
      const PointPart  part  = ref_->part[q];
      const Tensor2    sigma = r[m].sigma.Sym();
      const Tensor2    s     = StressPart(part, sigma);
      PetscReal        De[3][3], Dv[3][3];
      SplitTangent(D[m].De, sigma, part, false, De);
      SplitTangent(D[m].Dv, sigma, part, true, Dv);
      for (PetscInt a = 0; a < nn_; a++) {
        g[2 * a]     = Fi(0, 0) * dN[2 * a] + Fi(1, 0) * dN[2 * a + 1];
        g[2 * a + 1] = Fi(0, 1) * dN[2 * a] + Fi(1, 1) * dN[2 * a + 1];
      }
      for (PetscInt a = 0; a < nn_; a++)
        for (PetscInt b = 0; b < nn_; b++) {
          /* B_a^T D B_b with B = [[Nx, 0], [0, Ny], [Ny, Nx]] */
          const PetscReal ax = g[2 * a], ay = g[2 * a + 1], bx = g[2 * b], by = g[2 * b + 1];
          const PetscReal Ba[3][2] = {
            {ax, 0 },
            {0,  ay},
            {ay, ax}
          };
          const PetscReal Bb[3][2] = {
            {bx, 0 },
            {0,  by},
            {by, bx}
          };
          const PetscReal geo = ax * (s(0, 0) * bx + s(0, 1) * by) + ay * (s(1, 0) * bx + s(1, 1) * by);
          for (int i = 0; i < 2; i++)
            for (int j = 0; j < 2; j++) {
              PetscReal kij = i == j ? geo : 0.0, cij = 0;
              for (int r = 0; r < 3; r++)
                for (int t = 0; t < 3; t++) {
                  kij += Ba[r][i] * De[r][t] * Bb[t][j];
                  cij += Ba[r][i] * Dv[r][t] * Bb[t][j];
                }
              ke[(4 * a + 2 + i) * ne + 4 * b + j] += W * kij;     /* d f_int / d u */
              ke[(4 * a + 2 + i) * ne + 4 * b + 2 + j] += W * cij; /* d f_int / d v */
            }
        }
    }
    PetscCall(DMPlexMatSetClosure(dm_, NULL, NULL, J, c, ke, ADD_VALUES));
  }
  if (skin_.Active()) PetscCall(skin_.AddStiffness(dm_, Uloc_, J)); /* at Uloc_: every caller has just set it to the state of Fs */
  /* -I: d(udot - v)/dv, per owned free node */
  for (PetscInt off : free_rows_)
    for (PetscInt d = 0; d < 2; d++) PetscCall(MatSetValue(J, off + d, off + 2 + d, -1.0, ADD_VALUES));
  PetscCall(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseModel::IJacobian(Vec U, PetscReal shift, Mat J, PetscBool *ok, bool refresh)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ev_jacobian_, 0, 0, 0, 0));
  counters_.jacobians++;
  PetscLogDouble t0, t1;
  if (!refresh && KC_) { /* modified Newton: the last K, C with the new shift */
    *ok = PETSC_TRUE;
    tangent_age_++;
    PetscCall(PetscTime(&t0));
    PetscCall(MatCopy(KC_, J, SAME_NONZERO_PATTERN));
    PetscCall(MatAXPY(J, shift, Mt_, SAME_NONZERO_PATTERN));
    PetscCall(PetscTime(&t1));
    coarse_time_ += t1 - t0;
    PetscCall(PetscLogEventEnd(ev_jacobian_, 0, 0, 0, 0));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(EvaluateMaterials(U, true, ok, NULL));
  PetscCall(MatZeroEntries(J));
  if (!*ok) { /* the caller rejects the state; leave a harmless matrix */
    PetscCall(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAXPY(J, shift, Mt_, SAME_NONZERO_PATTERN));
    PetscCall(PetscLogEventEnd(ev_jacobian_, 0, 0, 0, 0));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PetscTime(&t0));
  PetscCall(AssembleKC(F_, response_, tangent_, J));
  if (!KC_) PetscCall(MatDuplicate(J, MAT_COPY_VALUES, &KC_));
  else PetscCall(MatCopy(J, KC_, SAME_NONZERO_PATTERN));
  tangent_age_ = 0;
  PetscCall(MatAXPY(J, shift, Mt_, SAME_NONZERO_PATTERN));
  PetscCall(PetscTime(&t1));
  coarse_time_ += t1 - t0;
  PetscCall(PetscLogEventEnd(ev_jacobian_, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseModel::EvaluateForOutput(Vec Uloc, bool viscous, PetscBool *ok, std::string *why)
{
  TangentOptions &opt  = pool_.Tangent();
  const bool      keep = opt.viscosity;
  PetscFunctionBeginUser;
  PetscCall(DeformationAt(Uloc, out_F_, out_Fdot_));
  out_response_.resize(out_F_.size());
  out_tangent_.resize(out_F_.size());
  opt.viscosity             = viscous; /* D^v only when asked: 3 material evaluations per point */
  const PetscErrorCode ierr = pool_.Evaluate(out_F_.data(), out_Fdot_.data(), out_response_.data(), true, out_tangent_.data(), EvaluationKind::Output);
  opt.viscosity             = keep;
  PetscCall(ierr);
  int         local_ok = 1, global_ok;
  std::string first;
  for (size_t k = 0; k < out_response_.size() && local_ok; k++)
    if (!out_response_[k].ok) {
      local_ok = 0;
      PetscCall(DescribePoint((PetscInt)k, out_F_, out_Fdot_, out_response_, &first));
    }
  PetscCallMPI(MPI_Allreduce(&local_ok, &global_ok, 1, MPI_INT, MPI_MIN, comm_));
  *ok = global_ok ? PETSC_TRUE : PETSC_FALSE;
  if (why) *why = local_ok ? (global_ok ? "" : "on another rank") : first;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseModel::LowestOverCells(const std::vector<PetscReal> &per_cell, PetscReal *value, PetscInt *element) const
{
  struct {
    double v;
    int    gid;
  } mine = {PETSC_MAX_REAL, -1}, all;
  PetscFunctionBeginUser;
  for (size_t k = 0; k < per_cell.size(); k++)
    if (std::isfinite(per_cell[k]) && (per_cell[k] < mine.v || (per_cell[k] == mine.v && (int)cell_id_[k] < mine.gid)))
      mine = {(double)per_cell[k], (int)cell_id_[k]};
  PetscCallMPI(MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE_INT, MPI_MINLOC, comm_));
  *value   = all.v;
  *element = all.gid;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseModel::LowestAcoustic(PetscReal *det, PetscInt *element) const
{
  return LowestOverCells(cell_acoustic_, det, element);
}

PetscErrorCode CoarseModel::SofteningSinceLast(PetscReal stress_floor, PetscReal *cosine, PetscInt *element)
{
  const PetscInt         nc    = c_end_ - c_start_;
  const bool             first = softening_last_.empty();
  std::vector<PetscReal> per_cell(nc, 1.0);
  PetscFunctionBeginUser;
  PetscCheck(cached_valid_ && cached_ok_, PETSC_COMM_SELF, PETSC_ERR_ORDER, "SofteningSinceLast needs a successful evaluation of the material points");
  if (first) softening_last_.resize((size_t)(nc * npts_));
  for (PetscInt k = 0; k < nc; k++)
    for (PetscInt q = 0; q < npts_; q++) {
      const PetscInt     p   = k * npts_ + q;
      const StrainStress now = GreenLagrangeAndPiola(F_[p], response_[p].sigma);
      /* 1e-12: a strain increment at round-off of the deformation is not judged */
      if (!first) per_cell[k] = PetscMin(per_cell[k], SecondOrderWorkCosine(softening_last_[p], now, 1e-12, stress_floor));
      softening_last_[p] = now;
    }
  PetscCall(LowestOverCells(per_cell, cosine, element));
  if (*element < 0 || *cosine >= 1) { /* nothing judged (the first call, or an empty mesh) */
    *cosine  = 1;
    *element = -1;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseModel::MeanStress(PetscReal s[3]) const
{
  PetscReal      sum[4] = {0, 0, 0, 0}, all[4];
  const PetscInt nc     = c_end_ - c_start_;
  PetscFunctionBeginUser;
  PetscCheck(cached_valid_ && cached_ok_, PETSC_COMM_SELF, PETSC_ERR_ORDER, "MeanStress needs a successful evaluation of the material points");
  for (PetscInt k = 0; k < nc; k++)
    for (PetscInt q = 0; q < npts_; q++) {
      const PetscInt  p = k * npts_ + q;
      const PetscReal w = wdet_[p];
      const Tensor2  &t = response_[p].sigma;
      sum[0] += w * t(0, 0);
      sum[1] += w * t(1, 1);
      sum[2] += w * 0.5 * (t(0, 1) + t(1, 0));
      sum[3] += w;
    }
  PetscCallMPI(MPI_Allreduce(sum, all, 4, MPIU_REAL, MPIU_SUM, comm_));
  for (int c = 0; c < 3; c++) s[c] = all[3] > 0 ? all[c] / all[3] : 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

void CoarseModel::AcousticFromOutput()
{
  for (PetscInt k = 0; k < c_end_ - c_start_; k++) {
    PetscReal m = PETSC_MAX_REAL;
    for (PetscInt q = 0; q < npts_ && !std::isnan(m); q++) {
      const PetscInt p = k * npts_ + q;
      m                = out_response_[p].ok ? PetscMin(m, MinAcousticDeterminant(out_tangent_[p].De, out_response_[p].sigma.Sym()).det) : NAN;
    }
    cell_acoustic_[k] = m;
  }
}

PetscErrorCode CoarseModel::AssembleTangentAt(Vec U, bool damping, Mat J, PetscBool *ok, std::string *why)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ev_tangent_at_, 0, 0, 0, 0));
  PetscCall(GlobalToLocal(U, Uloc_));
  PetscCall(EvaluateForOutput(Uloc_, damping, ok, why));
  if (*ok) {
    PetscCall(AssembleKC(out_F_, out_response_, out_tangent_, J));
    AcousticFromOutput();
  } else {
    PetscCall(MatZeroEntries(J));
    PetscCall(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  }
  PetscCall(PetscLogEventEnd(ev_tangent_at_, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscInt CoarseModel::PointsPerElement() const
{
  return npts_;
}

PetscInt CoarseModel::NodesPerElement() const
{
  return nn_;
}

const char *CoarseModel::ElementName() const
{
  return spec_.element == CoarseElement::Q2 ? "q2" : "q1";
}

const char *CoarseModel::QuadratureName() const
{
  return spec_.quadrature == CoarseQuadrature::SRI ? "sri" : "full";
}

const char *CoarseModel::QuadratureDescription() const
{
  return ref_ ? ref_->description.c_str() : "";
}

PetscErrorCode CoarseModel::TipDisplacement(Vec U, PetscReal *uy, PetscReal *ux)
{
  PetscReal val[2] = {0, 0}, sum[2];
  PetscFunctionBeginUser;
  PetscCall(GlobalToLocal(U, Uloc_));
  if (tip_.e >= 0) {
    PetscSection       ls;
    PetscInt           oa, ob, oe, ne;
    const PetscScalar *u;
    PetscCall(DMGetLocalSection(dm_, &ls));
    PetscCall(PetscSectionGetOffset(ls, tip_.a, &oa));
    PetscCall(PetscSectionGetOffset(ls, tip_.b, &ob));
    PetscCall(PetscSectionGetOffset(ls, tip_.e, &oe));
    PetscCall(PetscSectionGetDof(ls, tip_.e, &ne));
    PetscCall(VecGetArrayRead(Uloc_, &u));
    const PetscReal t = tip_.sp;
    for (int d = 0; d < 2; d++) { /* val[0]: y, val[1]: x */
      const int       c  = 1 - d;
      const PetscReal ua = PetscRealPart(u[oa + c]), ub = PetscRealPart(u[ob + c]);
      if (t == 0) val[d] = ua;
      else if (t == 1) val[d] = ub;
      else if (ne > 0) val[d] = ua * (1 - t) * (1 - 2 * t) + PetscRealPart(u[oe + c]) * 4 * t * (1 - t) + ub * t * (2 * t - 1); /* Q2: the edge's middle node */
      else val[d] = (1 - t) * ua + t * ub;
    }
    PetscCall(VecRestoreArrayRead(Uloc_, &u));
  }
  PetscCallMPI(MPI_Allreduce(val, sum, 2, MPIU_REAL, MPIU_SUM, comm_));
  *uy = sum[0];
  if (ux) *ux = sum[1];
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
