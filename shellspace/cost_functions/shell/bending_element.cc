// The second derivatives of BendingElement (element_hessian.h), compiled once.
#include "shellspace/cost_functions/shell/bending_element.h"

#include "shellspace/cost_functions/shell/element_hessian-inl.h"

namespace shellspace {

SHELLSPACE_ELEMENT_HESSIAN_TEMPLATES(template, BendingElement);

}  // namespace shellspace
