#pragma once
/* Checks of option values that PETSc's readers let through, and the readers of options that several
   owners share. */
#include <petscsys.h>

namespace turgor {

/* An error naming `name` (the full option, e.g. "-physics") when it is given with an empty value
   (-physics "" or a bare -physics): PETSc's list readers then report "not set", and the default
   would run in its place. `known` lists what may be given. Collective. */
PetscErrorCode CheckNotEmpty(MPI_Comm comm, const char name[], const char known[]);

/* Which boxes a box option accepts: one that may be flat (xmin <= xmax and ymin <= ymax: a line or
   a point selects what lies on it), or one with an area (xmin < xmax and ymin < ymax). */
enum class BoxShape {
  MayBeFlat,
  HasArea
};

/* A box option xmin,ymin,xmax,ymax [µm]. Its owner reads it inside its PetscOptionsBegin block with
     PetscOptionsRealArray(opt, text, man, b.value, &b.n, &b.set)
   (into one value more than a box has, so that a fifth value is counted, not dropped), then calls
   Take() after PetscOptionsEnd. */
struct BoxOption {
  PetscReal value[5] = {0, 0, 0, 0, 0};
  PetscInt  n        = 5;
  PetscBool set      = PETSC_FALSE;

  BoxOption() = default;
  /* Starting from `box` (the API default, shown by -help). */
  explicit BoxOption(const PetscReal box[4]) : value{box[0], box[1], box[2], box[3], 0} { }
  /* `name` is the full option (-tissue_box). Refuses an empty value (CheckNotEmpty), and with one
     message naming the option and its value a count other than 4, a value that is not finite and a
     box of the wrong shape. The box is checked and copied into `box` when the option was given or
     the box is in use anyway: `has_box` NULL (the owner always has a box) or *has_box (set through
     the API); a given option sets *has_box. Collective. */
  PetscErrorCode Take(MPI_Comm comm, const char name[], BoxShape shape, PetscReal box[4], bool *has_box) const;
};

} // namespace turgor
