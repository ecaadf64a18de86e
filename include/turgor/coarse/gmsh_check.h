#pragma once
#include <petscsys.h>

namespace turgor {

/* Reads an ASCII Gmsh file (format 2.2 or 4.1) on rank 0 and checks what PETSc's reader takes on
   trust: that the $Nodes and $Elements sections exist, hold as many entries as they announce, and
   that every element refers only to nodes $Nodes defines. PETSc 3.18's reader dereferences an
   undefined node tag (a segmentation fault); this turns that into an error naming `option`, the
   file, the line and the tag. Binary files and other formats pass through unchecked. Collective. */
PetscErrorCode CheckGmshFile(MPI_Comm comm, const char option[], const char path[]);

} // namespace turgor
