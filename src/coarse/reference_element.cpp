#include "reference_element.h"
#include "q1_element.h"
#include "q2_element.h"

namespace turgor {

PetscErrorCode CreateReferenceElement(CoarseElement element, CoarseQuadrature rule, ReferenceElement *ref)
{
  PetscFunctionBeginUser;
  if (element == CoarseElement::Q2) PetscCall(q2::Tabulate(rule, ref));
  else q1::Tabulate(rule, ref);
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
