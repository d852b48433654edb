// The numbers of the module's parameters, stricter than pybind11's own
// conversions. Python's bool is a subclass of int, so pybind11 passes True
// as 1 to an int parameter and as 1.0 to a float one (steps=True ran one
// step). Here an int or float parameter (also inside Optional, a list)
// refuses a bool, and numpy.bool_, with a TypeError naming the value: a
// bool is neither a count nor a number. Everything else converts as before
// (an int, a numpy integer or any object with __index__ for an int; a
// float, an int or any object with __float__ for a float). The options
// classes check their attributes the same way (python/module_options.h).
//
// The specialisations below replace pybind11's casters of int and double. Every file of the module that binds or casts includes this header
// through the module's headers (right after <pybind11/pybind11.h>), so that
// no file converts these types another way.
#ifndef SHELLSPACE_PYTHON_STRICT_NUMBERS_H_
#define SHELLSPACE_PYTHON_STRICT_NUMBERS_H_

#include <pybind11/pybind11.h>

#include <climits>
#include <cstring>
#include <string>

namespace shellspace {
namespace pymodule {

// True for Python's bool and NumPy's bool_.
inline bool IsBoolLike(PyObject* object) {
  if (PyBool_Check(object)) return true;
  const char* name = Py_TYPE(object)->tp_name;
  return std::strcmp(name, "numpy.bool_") == 0 ||
         std::strcmp(name, "numpy.bool") == 0;
}

// The TypeError of a bool passed where `kind` ("an int", "a float") is
// expected.
[[noreturn]] inline void RefuseBool(PyObject* object, const char* kind) {
  const pybind11::handle value(object);
  throw pybind11::type_error(
      "expected " + std::string(kind) + ", got the bool " +
      std::string(pybind11::str(value)) +
      " (a bool is not a count or a number here; pass " + kind + ")");
}

}  // namespace pymodule
}  // namespace shellspace

namespace pybind11 {
namespace detail {

template <>
class type_caster<int> {
 public:
  bool load(handle src, bool convert) {
    if (!src) return false;
    if (shellspace::pymodule::IsBoolLike(src.ptr())) {
      shellspace::pymodule::RefuseBool(src.ptr(), "an int");
    }
    make_caster<long long> wide;
    if (!wide.load(src, convert)) return false;
    const long long v = cast_op<long long>(wide);
    if (v < INT_MIN || v > INT_MAX) return false;
    value = static_cast<int>(v);
    return true;
  }
  static handle cast(int src, return_value_policy /* policy */,
                     handle /* parent */) {
    return PyLong_FromLong(src);
  }
  PYBIND11_TYPE_CASTER(int, const_name("int"));
};

template <>
class type_caster<double> {
 public:
  bool load(handle src, bool convert) {
    if (!src) return false;
    if (shellspace::pymodule::IsBoolLike(src.ptr())) {
      shellspace::pymodule::RefuseBool(src.ptr(), "a float");
    }
    if (!convert && !PyFloat_Check(src.ptr())) return false;
    const double v = PyFloat_AsDouble(src.ptr());
    if (v == -1.0 && PyErr_Occurred()) {
      PyErr_Clear();
      return false;
    }
    value = v;
    return true;
  }
  static handle cast(double src, return_value_policy /* policy */,
                     handle /* parent */) {
    return PyFloat_FromDouble(src);
  }
  PYBIND11_TYPE_CASTER(double, const_name("float"));
};

}  // namespace detail
}  // namespace pybind11

#endif  // SHELLSPACE_PYTHON_STRICT_NUMBERS_H_
