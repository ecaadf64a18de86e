/* -tissue_type polyline: one open chain (by default the L-hyphen model's cantilever: 101 nodes 0.01 apart). */
#include <turgor/tissue/polyline.h>
#include <turgor/core/options.h>
#include <cmath>

namespace turgor {

/* A point option x,y: exactly two finite values (read with one spare slot: PETSc drops extras silently). */
static PetscErrorCode CheckPoint(MPI_Comm comm, const char *name, PetscBool set, PetscInt n, const PetscReal v[3], PetscReal p[2])
{
  PetscFunctionBeginUser;
  PetscCall(CheckNotEmpty(comm, name, "two values x,y"));
  PetscCheck(!set || n == 2, comm, PETSC_ERR_ARG_SIZ, "Option %s needs two values x,y (got %s%" PetscInt_FMT ")", name, n > 2 ? "more than " : "",
             n > 2 ? (PetscInt)2 : n);
  PetscCheck(std::isfinite(v[0]) && std::isfinite(v[1]), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s = %g,%g: must be finite", name, (double)v[0], (double)v[1]);
  p[0] = v[0];
  p[1] = v[1];
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode PolylineSpec::SetFromOptions(MPI_Comm comm, ParameterList *params)
{
  PetscReal a[3] = {start[0], start[1], 0}, b[3] = {end[0], end[1], 0};
  PetscInt  na = 3, nb = 3;
  PetscBool seta, setb;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "tissue_polyline_", "Open polyline tissue (-tissue_type polyline; µm)", "turgor");
  PetscCall(TurgorOptionsRealArray(params, "-start", "First node x,y [µm] (default 0,0)", "PolylineSpec", a, &na, &seta));
  PetscCall(TurgorOptionsRealArray(params, "-end", "Last node x,y [µm] (default 1,0)", "PolylineSpec", b, &nb, &setb));
  PetscCall(TurgorOptionsInt(params, "-nodes", "Nodes on the chain (>= 2)", "PolylineSpec", nodes, &nodes, NULL));
  PetscOptionsEnd();
  PetscCall(CheckPoint(comm, "-tissue_polyline_start", seta, na, a, start));
  PetscCall(CheckPoint(comm, "-tissue_polyline_end", setb, nb, b, end));
  PetscCheck(nodes >= 2, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_polyline_nodes = %" PetscInt_FMT ": must be >= 2", nodes);
  PetscCheck(start[0] != end[0] || start[1] != end[1], comm, PETSC_ERR_ARG_OUTOFRANGE,
             "Options -tissue_polyline_start = %g,%g and -tissue_polyline_end = %g,%g: the chain has zero length", (double)start[0], (double)start[1],
             (double)end[0], (double)end[1]);
  /* the forces multiply lengths (moments, areas): a chain whose length squared overflows has no finite state */
  const PetscReal length = std::hypot(end[0] - start[0], end[1] - start[1]);
  PetscCheck(std::isfinite(length * length), comm, PETSC_ERR_ARG_OUTOFRANGE,
             "Options -tissue_polyline_start = %g,%g and -tissue_polyline_end = %g,%g: the chain is %g µm long, beyond double precision (its length "
             "squared is not finite); give coordinates below 1e150 µm",
             (double)start[0], (double)start[1], (double)end[0], (double)end[1], (double)length);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GeneratePolylineTissue(MPI_Comm comm, const PolylineSpec &spec, const PolygonTissueSpec &poly, Tissue *tissue)
{
  PolygonRing ring;
  PetscFunctionBeginUser;
  ring.open = true;
  /* node k at start + k/(N-1) (end - start): the spacing is as even as floating point allows */
  for (PetscInt k = 0; k < spec.nodes; k++) {
    const PetscReal s = (PetscReal)k / (PetscReal)(spec.nodes - 1);
    ring.points.push_back({spec.start[0] + s * (spec.end[0] - spec.start[0]), spec.start[1] + s * (spec.end[1] - spec.start[1])});
  }
  ring.points.back() = {spec.end[0], spec.end[1]};
  PetscCall(BuildPolygonTissue(comm, {ring}, poly, false, tissue));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode PolylineGenerator::Estimate(PetscReal *particles, PetscReal *springs) const
{
  PetscFunctionBeginUser;
  *particles = (PetscReal)spec.nodes;
  *springs   = (PetscReal)spec.nodes - 1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

std::string PolylineGenerator::SizeOptions() const
{
  return "-tissue_polyline_nodes " + std::to_string((long long)spec.nodes);
}

PetscErrorCode PolylineGenerator::View(PetscViewer viewer) const
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "tissue polyline: %" PetscInt_FMT " nodes from (%g, %g) to (%g, %g), %s\n", spec.nodes, (double)spec.start[0],
                                   (double)spec.start[1], (double)spec.end[0], (double)spec.end[1], PolygonDescription().c_str()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
