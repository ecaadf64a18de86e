#include <turgor/core/options.h>
#include <turgor/tissue/plates.h>
#include <turgor/tissue/polygon_tissue.h>
#include <algorithm>
#include <cmath>

namespace turgor {

static const char *const kSides[] = {"bottom", "right", "top", "left"};

PetscErrorCode PlateSpec::SetFromOptions(MPI_Comm comm, ParameterList *params)
{
  char     *list[5];
  PetscInt  n = 5;
  PetscBool set;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "tissue_", "Plates around a polygonal tissue", "turgor");
  PetscCall(TurgorOptionsStringArray(params, "-plates",
                                     "Plates to add along the tissue's sides: any of bottom,right,top,left (open one-bar cells 2 r from the tissue)",
                                     "PlateSpec", list, &n, &set));
  PetscCall(TurgorOptionsReal(params, "-plate_overhang", "How far each plate reaches past the tissue [µm] (negative: 10% of the tissue's larger side)",
                              "PlateSpec", overhang, &overhang, NULL));
  PetscOptionsEnd();
  PetscCall(CheckNotEmpty(comm, "-tissue_plates", "sides: bottom, right, top, left"));
  PetscCheck(!set || n < 5, comm, PETSC_ERR_ARG_SIZ, "Option -tissue_plates: more than 4 sides listed");
  PetscCheck(std::isfinite(overhang), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_plate_overhang = %g: must be finite", (double)overhang);
  if (set) {
    sides.clear();
    for (PetscInt k = 0; k < n; k++) {
      const std::string s = list[k];
      PetscCall(PetscFree(list[k]));
      PetscCheck(std::find(std::begin(kSides), std::end(kSides), s) != std::end(kSides), comm, PETSC_ERR_ARG_WRONG,
                 "Option -tissue_plates: unknown side '%s' (bottom, right, top, left)", s.c_str());
      PetscCheck(std::find(sides.begin(), sides.end(), s) == sides.end(), comm, PETSC_ERR_ARG_WRONG, "Option -tissue_plates: side '%s' is listed twice",
                 s.c_str());
      sides.push_back(s);
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode AddPlateRings(MPI_Comm comm, const PlateSpec &spec, PetscReal r, std::vector<PolygonRing> *rings,
                             std::vector<std::pair<std::string, PetscInt>> *names)
{
  PetscFunctionBeginUser;
  if (!spec.Any() || rings->empty()) PetscFunctionReturn(PETSC_SUCCESS);
  PetscReal lo[2] = {PETSC_MAX_REAL, PETSC_MAX_REAL}, hi[2] = {-PETSC_MAX_REAL, -PETSC_MAX_REAL};
  for (const PolygonRing &R : *rings)
    for (const Point2 &p : R.points)
      for (int d = 0; d < 2; d++) lo[d] = std::min(lo[d], p[d]), hi[d] = std::max(hi[d], p[d]);
  const PetscReal e    = spec.overhang >= 0 ? spec.overhang : 0.1 * std::max(hi[0] - lo[0], hi[1] - lo[1]);
  auto            has  = [&](const char *s) { return std::find(spec.sides.begin(), spec.sides.end(), s) != spec.sides.end(); };
  const bool      left = has("left"), right = has("right");
  /* horizontal plates: between the side plates (3 r from their centrelines) where there are some */
  const PetscReal x0 = left ? lo[0] + r : lo[0] - e, x1 = right ? hi[0] - r : hi[0] + e;
  const PetscReal y0 = lo[1] - 2 * r - e, y1 = hi[1] + 2 * r + e;
  std::string     list;
  for (const std::string &s : spec.sides) list += (list.empty() ? "" : ",") + s;
  /* a plate of no length (or turned back on itself) has no direction: its bar could not be made;
     the side plates always reach past the tissue (by 2 r + the overhang) */
  if ((has("bottom") || has("top")) && !(x1 > x0)) {
    const char *what = left && right ? "between the left and right plates" : left ? "from the left plate" : right ? "to the right plate" : "across the tissue";
    const PetscReal need = (left ? r : -e) + (right ? r : -e); /* the plate is the tissue's width less this */
    SETERRQ(comm, PETSC_ERR_ARG_INCOMP,
            "Option -tissue_plates = %s: the %s plate %s would be %g µm long: the tissue is %g µm wide%s, and these plates need it wider than %g µm "
            "(-tissue_bar_radius %g, -tissue_plate_overhang %g); leave out the side plates, or give a wider tissue",
            list.c_str(), has("bottom") ? "bottom" : "top", what, (double)(x1 - x0), (double)(hi[0] - lo[0]), hi[0] > lo[0] ? "" : " (a vertical tissue)",
            (double)need, (double)r, (double)e);
  }
  for (const char *side : kSides) {
    if (!has(side)) continue;
    PolygonRing       P;
    const std::string s = side;
    P.open              = true;
    P.whole             = true;
    if (s == "bottom")
      P.points = {
        Point2{x0, lo[1] - 2 * r},
        Point2{x1, lo[1] - 2 * r}
      };
    else if (s == "top")
      P.points = {
        Point2{x1, hi[1] + 2 * r},
        Point2{x0, hi[1] + 2 * r}
      };
    else if (s == "right")
      P.points = {
        Point2{hi[0] + 2 * r, y0},
        Point2{hi[0] + 2 * r, y1}
      };
    else
      P.points = {
        Point2{lo[0] - 2 * r, y1},
        Point2{lo[0] - 2 * r, y0}
      };
    names->push_back({s, (PetscInt)rings->size()});
    rings->push_back(P);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
