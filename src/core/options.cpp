#include <turgor/core/options.h>
#include <turgor/core/petsc_compat.h>
#include <cmath>

namespace turgor {

PetscErrorCode CheckNotEmpty(MPI_Comm comm, const char name[], const char known[])
{
  PetscBool given, set;
  char      value[8];
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasName(NULL, NULL, name, &given));
  if (!given) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscOptionsGetString(NULL, NULL, name, value, sizeof value, &set));
  PetscCheck(set && value[0], comm, PETSC_ERR_ARG_WRONG, "Option %s: no value given (%s)", name, known);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode BoxOption::Take(MPI_Comm comm, const char name[], BoxShape shape, PetscReal box[4], bool *has_box) const
{
  const bool flat_ok = shape == BoxShape::MayBeFlat;
  PetscFunctionBeginUser;
  PetscCall(CheckNotEmpty(comm, name, "xmin,ymin,xmax,ymax"));
  if (!set && has_box && !*has_box) PetscFunctionReturn(PETSC_SUCCESS);
  bool ok = !set || n == 4;
  for (int k = 0; k < 4; k++) ok = ok && std::isfinite(value[k]);
  ok = ok && (flat_ok ? value[0] <= value[2] && value[1] <= value[3] : value[0] < value[2] && value[1] < value[3]);
  if (!ok) { /* the value as given (a count too small or too large shows), else the API's box */
    char      given[256];
    PetscBool from_options = PETSC_FALSE;
    if (set) PetscCall(PetscOptionsGetString(NULL, NULL, name, given, sizeof given, &from_options));
    if (!from_options) PetscCall(PetscSNPrintf(given, sizeof given, "%g,%g,%g,%g", (double)value[0], (double)value[1], (double)value[2], (double)value[3]));
    SETERRQ(comm, set && n != 4 ? PETSC_ERR_ARG_SIZ : PETSC_ERR_ARG_OUTOFRANGE, "Option %s = %s: needs 4 finite values xmin,ymin,xmax,ymax with %s", name,
            given, flat_ok ? "xmin <= xmax and ymin <= ymax" : "xmin < xmax and ymin < ymax");
  }
  for (int k = 0; k < 4; k++) box[k] = value[k];
  if (has_box) *has_box = true;
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
