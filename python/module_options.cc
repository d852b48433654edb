#include "python/module_options.h"

#include <sstream>

namespace shellspace {
namespace pymodule {
namespace {

// The options whose default is None and what else they take: a real
// number (eta, time_limit), a path (output, png, gltf: a str) or a mask (a
// path, str or os.PathLike, or a sequence of vertex indices: not a single
// number). Any other None option takes anything its function takes.
bool RealOrNone(const std::string& name) {
  return name == "eta" || name == "time_limit";
}
bool PathOrNone(const std::string& name) {
  return name == "output" || name == "png" || name == "gltf";
}

bool MaskOrNone(const std::string& name) { return name == "mask"; }
bool IsMask(PyObject* v) {
  return PyUnicode_Check(v) || PyObject_HasAttrString(v, "__fspath__") ||
         (PySequence_Check(v) && !PyBytes_Check(v));
}

bool IsReal(PyObject* v) {
  return !IsBoolLike(v) && !PyUnicode_Check(v) && !PyBytes_Check(v) &&
         (PyFloat_Check(v) || PyIndex_Check(v) ||
          PyObject_HasAttrString(v, "__float__"));
}

// Whether `value` is of the kind of the option `name`, whose default is
// `default_value` (module_options.h).
bool OfKind(const std::string& name, const py::handle& default_value,
            const py::handle& value) {
  PyObject* d = default_value.ptr();
  PyObject* v = value.ptr();
  if (d == Py_None) {
    if (v == Py_None) return true;
    if (RealOrNone(name)) return IsReal(v);
    if (PathOrNone(name)) return PyUnicode_Check(v);
    if (MaskOrNone(name)) return IsMask(v);
    return true;
  }
  if (PyBool_Check(d)) return PyBool_Check(v);
  if (PyLong_Check(d)) return !IsBoolLike(v) && PyIndex_Check(v);
  if (PyFloat_Check(d)) return IsReal(v);
  if (PyUnicode_Check(d)) return PyUnicode_Check(v);
  return true;
}

std::string KindName(const std::string& name,
                     const py::handle& default_value) {
  PyObject* d = default_value.ptr();
  if (d == Py_None) {
    if (RealOrNone(name)) return "None or a real number";
    if (PathOrNone(name)) return "None or a str (a path)";
    if (MaskOrNone(name)) {
      return "None, a mask file's path or a sequence of vertex indices";
    }
    return "any value";
  }
  if (PyBool_Check(d)) return "a bool";
  if (PyLong_Check(d)) return "an integer";
  if (PyFloat_Check(d)) return "a real number";
  if (PyUnicode_Check(d)) return "a str";
  return "any value";
}

std::string Names(const std::vector<KeywordDefault>& keywords) {
  std::string out;
  for (const KeywordDefault& k : keywords) {
    out += (out.empty() ? "" : ", ") + k.name;
  }
  return out;
}

// "Options:" and the lines of the "Parameters:" block of `doc` that name
// one of `keywords` (the inputs' lines left out).
std::string OptionLines(const std::string& doc,
                        const std::vector<KeywordDefault>& keywords) {
  const size_t block = doc.find("\nParameters:\n");
  if (block == std::string::npos) return "";
  std::istringstream lines(doc.substr(block + 13));
  std::string line, options;
  while (std::getline(lines, line)) {
    for (const KeywordDefault& k : keywords) {
      if (line.rfind("    " + k.name + ": ", 0) == 0) {
        options += line + "\n";
        break;
      }
    }
  }
  return "Options:\n" + options;
}

}  // namespace

void RegisterOptionsClass(py::module_& m, const char* class_name,
                          const char* function,
                          std::vector<KeywordDefault> keywords,
                          const std::string& doc) {
  const std::string name = class_name;
  py::list slots;
  for (const KeywordDefault& k : keywords) slots.append(k.name);
  py::dict attributes;
  attributes["__slots__"] = py::tuple(slots);
  attributes["__module__"] = m.attr("__name__");
  attributes["__qualname__"] = name;
  attributes["__doc__"] = "The keyword options of " + std::string(function) +
                          " with their defaults, as attributes: pass them "
                          "as " +
                          function + "(inputs..., **options).\n\n" +
                          OptionLines(doc, keywords);
  attributes["function"] = function;
  const py::object type = py::reinterpret_borrow<py::object>(
      reinterpret_cast<PyObject*>(&PyType_Type));
  const py::object base = py::reinterpret_borrow<py::object>(
      reinterpret_cast<PyObject*>(&PyBaseObject_Type));
  py::object cls = type(name, py::make_tuple(base), attributes);
  const auto find =
      [keywords](const std::string& key) -> const KeywordDefault* {
    for (const KeywordDefault& k : keywords) {
      if (k.name == key) return &k;
    }
    return nullptr;
  };
  // Assignment with the kind check (the constructor goes through it too).
  const auto set = [name, find, keywords](py::handle self,
                                          const std::string& key,
                                          py::handle value) {
    const KeywordDefault* k = find(key);
    if (!k) {
      throw py::attribute_error(name + " has no option '" + key +
                                "' (its options: " + Names(keywords) + ")");
    }
    if (!OfKind(key, k->value, value)) {
      throw py::type_error(
          name + "." + key + " takes " + KindName(key, k->value) + ", got " +
          std::string(py::str(py::type::handle_of(value).attr("__name__"))));
    }
    // A value equal to the default (of its type) is kept as the default
    // object itself: a function tells a given relative_eta from its default
    // by that object (module_common.h RelativeEtaArg), and an options
    // object unpickled, copied or built from to_dict() keeps its defaults
    // as defaults.
    py::handle stored = value;
    if (!value.is(k->value) && k->value.ptr() != Py_None &&
        py::type::handle_of(value).is(py::type::handle_of(k->value)) &&
        PyObject_RichCompareBool(value.ptr(), k->value.ptr(), Py_EQ) == 1) {
      stored = k->value;
    }
    PyErr_Clear();
    const py::object object_type = py::reinterpret_borrow<py::object>(
        reinterpret_cast<PyObject*>(&PyBaseObject_Type));
    object_type.attr("__setattr__")(self, key, stored);
  };
  cls.attr("__setattr__") =
      py::cpp_function([set](py::handle self, const std::string& key,
                             py::handle value) { set(self, key, value); },
                       py::name("__setattr__"), py::is_method(cls));
  // Every option always has a value: assign its default instead.
  cls.attr("__delattr__") = py::cpp_function(
      [name](py::handle, const std::string& key) {
        throw py::attribute_error(name + "." + key +
                                  " cannot be deleted (assign a value)");
      },
      py::name("__delattr__"), py::is_method(cls));
  // __new__, not __init__: pybind11 takes a function named __init__ for the
  // constructor of one of its own classes.
  cls.attr("__new__") = py::staticmethod(py::cpp_function(
      [name, set, find, keywords](py::handle cls, const py::args& positional,
                                  const py::kwargs& given) {
        if (!positional.empty()) {
          throw py::type_error(name + "() takes keyword arguments only");
        }
        for (const auto& [key, value] : given) {
          const std::string k = py::str(key);
          if (!find(k)) {
            throw py::type_error(name +
                                 "() got an unexpected keyword "
                                 "argument '" +
                                 k + "' (its options: " + Names(keywords) +
                                 ")");
          }
        }
        const py::object object_type = py::reinterpret_borrow<py::object>(
            reinterpret_cast<PyObject*>(&PyBaseObject_Type));
        py::object self = object_type.attr("__new__")(cls);
        for (const KeywordDefault& k : keywords) {
          const py::str key(k.name);
          set(self, k.name, given.contains(key) ? given[key] : k.value);
        }
        return self;
      },
      py::name("__new__")));
  const auto to_dict = [keywords](py::handle self) {
    py::dict out;
    for (const KeywordDefault& k : keywords) {
      out[py::str(k.name)] = self.attr(k.name.c_str());
    }
    return out;
  };
  cls.attr("to_dict") =
      py::cpp_function(to_dict, py::name("to_dict"), py::is_method(cls),
                       "The options as a dict, in the function's order.");
  cls.attr("keys") = py::cpp_function(
      [keywords](py::handle) {
        py::list out;
        for (const KeywordDefault& k : keywords) out.append(k.name);
        return out;
      },
      py::name("keys"), py::is_method(cls),
      "The option names (with __getitem__: ** passes the options).");
  cls.attr("__getitem__") = py::cpp_function(
      [find](py::handle self, const std::string& key) {
        if (!find(key)) throw py::key_error(key);
        return py::reinterpret_borrow<py::object>(self.attr(key.c_str()));
      },
      py::name("__getitem__"), py::is_method(cls));
  cls.attr("__iter__") = py::cpp_function(
      [to_dict](py::handle self) { return py::iter(to_dict(self)); },
      py::name("__iter__"), py::is_method(cls));
  cls.attr("__len__") =
      py::cpp_function([n = keywords.size()](py::handle) { return n; },
                       py::name("__len__"), py::is_method(cls));
  cls.attr("__eq__") = py::cpp_function(
      [to_dict](py::handle self, py::handle other) -> py::object {
        if (!py::type::handle_of(other).is(py::type::handle_of(self))) {
          return py::reinterpret_borrow<py::object>(Py_NotImplemented);
        }
        return to_dict(self).attr("__eq__")(to_dict(other));
      },
      py::name("__eq__"), py::is_method(cls));
  cls.attr("__hash__") = py::none();
  cls.attr("__repr__") = py::cpp_function(
      [name, keywords](py::handle self) {
        std::string out = name + "(";
        for (size_t i = 0; i < keywords.size(); ++i) {
          out += (i ? ", " : "") + keywords[i].name + "=" +
                 std::string(py::repr(self.attr(keywords[i].name.c_str())));
        }
        return out + ")";
      },
      py::name("__repr__"), py::is_method(cls));
  m.attr(class_name) = cls;
}

}  // namespace pymodule
}  // namespace shellspace
