// The second derivatives of MembraneElement (element_hessian.h), compiled once.
#include "shellspace/cost_functions/shell/membrane_element.h"

#include "shellspace/cost_functions/shell/element_hessian-inl.h"

namespace shellspace {

SHELLSPACE_ELEMENT_HESSIAN_TEMPLATES(template, MembraneElement);

}  // namespace shellspace
