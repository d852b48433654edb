// The second derivatives of ShapeOperatorElement<0> (element_hessian.h),
// compiled once (one file per kInterior, compiled in parallel).
#include "shellspace/cost_functions/shell/element_hessian-inl.h"
#include "shellspace/cost_functions/shell/shape_operator_element.h"

namespace shellspace {

SHELLSPACE_ELEMENT_HESSIAN_TEMPLATES(template, ShapeOperatorElement<0>);

}  // namespace shellspace
