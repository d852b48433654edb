// The options classes of the workflow functions (shellspace.GeodesicOptions,
// ...): a function's keyword arguments with their defaults as one object.
//
// A workflow function takes its inputs (the shapes, F) positionally and its
// options as keyword arguments; its options class holds exactly those
// keyword arguments -- the names and defaults of the function's own
// signature, collected from the same py::arg list that defines it, so the
// two cannot drift -- as attributes:
//
//   options = shellspace.GeodesicOptions(steps=16, eta=1e-3)
//   options.tolerance = 1e-10
//   result = shellspace.geodesic(start, end, F, **options)
//
// An options object is a mapping (keys(), [name]) so that `**options`
// passes it: there is one calling convention, the keywords, and the class
// is a checked, documented, reusable set of them. It also has to_dict(),
// == and a repr that evaluates to an equal object, and it pickles (its
// class is an attribute of the module). Unknown names raise TypeError (in
// the constructor) or AttributeError (on assignment); a value of the wrong
// kind for its default raises TypeError: a bool option takes a bool, an
// int option an integer (not a bool), a float option a real number (not a
// bool), a str option a str; of the options whose default is None, eta and
// time_limit take None or a real number, output, png and gltf None or a
// str, mask anything the function takes (checked by the function). A value
// equal to its option's default is stored as the default itself, so that a
// relative_eta left at its default is not "given" beside an eta.
//
// This binds the front end's options, not the library's Options structs
// (shellspace/workflows/): those also hold the validated inputs and the
// front end's callbacks, and their defaults equal these
// (tests/workflows/options_defaults_test.cc, tests/python/test_docstrings.py).
#ifndef SHELLSPACE_PYTHON_MODULE_OPTIONS_H_
#define SHELLSPACE_PYTHON_MODULE_OPTIONS_H_

#include <pybind11/pybind11.h>

#include <string>
#include <utility>
#include <vector>

#include "python/strict_numbers.h"

namespace shellspace {
namespace pymodule {

namespace py = pybind11;

// One keyword argument of a function: its name and default.
struct KeywordDefault {
  std::string name;
  py::object value;
};

inline void CollectKeyword(std::vector<KeywordDefault>*, const py::arg&) {}
inline void CollectKeyword(std::vector<KeywordDefault>* out,
                           const py::arg_v& keyword) {
  out->push_back({keyword.name, keyword.value});
}

// The arguments with defaults of a py::arg list, in its order (those
// without a default are the function's inputs).
template <class... Args>
std::vector<KeywordDefault> KeywordDefaults(const Args&... args) {
  std::vector<KeywordDefault> out;
  (CollectKeyword(&out, args), ...);
  return out;
}

// Adds the class `class_name` to m: the options of m.`function` with
// `keywords` (KeywordDefaults of its py::arg list), documented by the
// lines of their names in the function's docstring `doc`.
void RegisterOptionsClass(py::module_& m, const char* class_name,
                          const char* function,
                          std::vector<KeywordDefault> keywords,
                          const std::string& doc);

// m.def(function, f, args..., doc) and RegisterOptionsClass of the same
// arguments: a workflow function and its options class from one list.
template <class F, class... Args>
void DefWithOptions(py::module_& m, const char* function,
                    const char* class_name, F&& f, const std::string& doc,
                    const Args&... args) {
  m.def(function, std::forward<F>(f), args..., doc.c_str());
  RegisterOptionsClass(m, class_name, function, KeywordDefaults(args...), doc);
}

}  // namespace pymodule
}  // namespace shellspace

#endif  // SHELLSPACE_PYTHON_MODULE_OPTIONS_H_
