// The runtime docstrings' "Parameters:" blocks: one line per parameter, as
// in the type stubs (help(shellspace.geodesic) shows them). The blocks are
// generated with the stubs by python/make_stubs.py into
// python/parameter_docs.inc from the CLI flags' descriptions (docs/cli.md)
// and the arrays' lines of the script; ctest python_stubs fails when the
// file is not the one of this build's module.
#ifndef SHELLSPACE_PYTHON_PARAMETER_DOCS_H_
#define SHELLSPACE_PYTHON_PARAMETER_DOCS_H_

#include <string>

namespace shellspace {
namespace pymodule {

// `text`, then a blank line and the function's "Parameters:" block when
// python/parameter_docs.inc has one (a function added since the file was
// generated has none until make_stubs.py runs again). pybind11 copies the
// docstring, so m.def(..., WithParameters("name", "text").c_str()) is safe.
std::string WithParameters(const char* function, const char* text);

}  // namespace pymodule
}  // namespace shellspace

#endif  // SHELLSPACE_PYTHON_PARAMETER_DOCS_H_
