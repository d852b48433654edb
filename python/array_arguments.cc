#include "python/array_arguments.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include "shellspace/io/mesh_io.h"

namespace py = pybind11;

namespace shellspace {
namespace {

std::string TypeName(const py::handle& object) {
  return py::str(py::type::handle_of(object).attr("__name__"));
}

std::string FirstLine(const std::string& text) {
  return text.substr(0, text.find('\n'));
}

// "K x #V x 3", or "1-D" for one axis of any length.
std::string ShapeText(const std::vector<Axis>& axes) {
  if (axes.size() == 1 && axes[0].length == kAnyLength) return "1-D";
  std::string text;
  for (size_t i = 0; i < axes.size(); ++i) {
    text += (i ? " x " : "") + std::string(axes[i].name);
  }
  return text;
}

std::string ShapeOf(const py::array& array) {
  std::ostringstream text;
  text << "(";
  for (py::ssize_t i = 0; i < array.ndim(); ++i) {
    text << (i ? ", " : "") << array.shape(i);
  }
  text << (array.ndim() == 1 ? ",)" : ")");
  return text.str();
}

// "[i, j, k]" of the flat C-order position `flat` in `shape`.
std::string PositionText(size_t flat, const std::vector<py::ssize_t>& shape) {
  std::vector<size_t> index(shape.size());
  for (size_t axis = shape.size(); axis-- > 0;) {
    const size_t length = static_cast<size_t>(shape[axis]);
    index[axis] = length ? flat % length : 0;
    flat = length ? flat / length : 0;
  }
  std::string text = "[";
  for (size_t i = 0; i < index.size(); ++i) {
    text += (i ? ", " : "") + std::to_string(index[i]);
  }
  return text + "]";
}

// `object` as a NumPy array (numpy.asarray unless it is one), or
// InputError. Python's own BaseExceptions (KeyboardInterrupt) pass.
py::array AsArray(const py::handle& object, const std::string& name,
                  const std::vector<Axis>& axes) {
  const std::string expected =
      name + " must be a " + ShapeText(axes) + " array, got ";
  if (object.is_none() || py::isinstance<py::str>(object) ||
      py::isinstance<py::bytes>(object)) {
    throw InputError(expected + TypeName(object));
  }
  if (py::isinstance<py::array>(object)) {
    return py::reinterpret_borrow<py::array>(object);
  }
  try {
    return py::module_::import("numpy").attr("asarray")(object);
  } catch (py::error_already_set& error) {
    if (!error.matches(PyExc_Exception)) throw;
    throw InputError(expected + TypeName(object) + " (" +
                     FirstLine(error.what()) + ")");
  }
}

// The dtype and shape checks of both kinds: returns the array.
py::array CheckedArray(const py::handle& object, const std::string& name,
                       const std::vector<Axis>& axes, bool integers) {
  py::array array = AsArray(object, name, axes);
  const char kind = array.dtype().kind();
  const std::string dtype = py::str(array.dtype());
  const bool integer = kind == 'i' || kind == 'u';
  // numpy.asarray([]) is float64: an empty array holds no float index.
  const bool empty_float = kind == 'f' && array.size() == 0;
  if (integers && !integer && !empty_float) {
    throw InputError(name + " must hold integers, got dtype " + dtype +
                     (kind == 'f' ? " (indices are not rounded)" : ""));
  }
  if (!integers && !integer && kind != 'f') {
    throw InputError(name + " must hold real numbers, got dtype " + dtype);
  }
  bool shape_ok = array.ndim() == static_cast<py::ssize_t>(axes.size());
  for (size_t i = 0; shape_ok && i < axes.size(); ++i) {
    shape_ok = axes[i].length == kAnyLength ||
               array.shape(static_cast<py::ssize_t>(i)) == axes[i].length;
  }
  if (!shape_ok) {
    throw InputError(name + " must be a " + ShapeText(axes) +
                     " array, got shape " + ShapeOf(array));
  }
  return array;
}

std::vector<py::ssize_t> ShapeVector(const py::array& array) {
  return std::vector<py::ssize_t>(array.shape(), array.shape() + array.ndim());
}

// A C-contiguous copy of `array` as T (or the array itself if it is one).
template <class T>
py::array_t<T, py::array::c_style> Contiguous(const py::array& array,
                                              const std::string& name) {
  auto out = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(
      array);
  if (!out) throw InputError(name + ": cannot be read as " +
                             std::string(py::str(py::dtype::of<T>())));
  return out;
}

}  // namespace

RealValues CheckedRealArray(const py::handle& object, const std::string& name,
                            const std::vector<Axis>& axes) {
  const py::array array = CheckedArray(object, name, axes, false);
  RealValues out;
  out.shape = ShapeVector(array);
  const auto values = Contiguous<double>(array, name);
  out.values.assign(values.data(), values.data() + values.size());
  for (size_t i = 0; i < out.values.size(); ++i) {
    if (!std::isfinite(out.values[i])) {
      std::ostringstream value;
      value << out.values[i];
      throw InputError(name + " has the non-finite value " + value.str() +
                       " at " + PositionText(i, out.shape));
    }
  }
  return out;
}

IndexValues CheckedIndexArray(const py::handle& object,
                              const std::string& name,
                              const std::vector<Axis>& axes) {
  const py::array array = CheckedArray(object, name, axes, true);
  IndexValues out;
  out.shape = ShapeVector(array);
  if (array.size() == 0) return out;
  if (array.dtype().kind() == 'u') {
    const auto values = Contiguous<unsigned long long>(array, name);
    for (py::ssize_t i = 0; i < values.size(); ++i) {
      const unsigned long long v = values.data()[i];
      if (v > static_cast<unsigned long long>(
                  std::numeric_limits<long long>::max())) {
        throw InputError(name + ": the value " + std::to_string(v) + " at " +
                         PositionText(i, out.shape) + " is out of range");
      }
      out.values.push_back(static_cast<long long>(v));
    }
  } else {
    const auto values = Contiguous<long long>(array, name);
    out.values.assign(values.data(), values.data() + values.size());
  }
  return out;
}

Eigen::SparseMatrix<double> TripletsArgument(const py::handle& rows_object,
                                             const py::handle& cols_object,
                                             const py::handle& vals_object,
                                             long long n) {
  const IndexValues rows = CheckedIndexArray(rows_object, "rows", {{"nnz"}});
  const auto nnz = static_cast<py::ssize_t>(rows.values.size());
  const IndexValues cols = CheckedIndexArray(cols_object, "cols", {{"nnz", nnz}});
  const RealValues vals = CheckedRealArray(vals_object, "vals", {{"nnz", nnz}});
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(rows.values.size());
  for (size_t k = 0; k < rows.values.size(); ++k) {
    const long long r = rows.values[k], c = cols.values[k];
    if (r < 0 || r >= n || c < 0 || c >= n) {
      throw InputError("rows/cols: index outside 0.." + std::to_string(n - 1));
    }
    triplets.emplace_back(static_cast<int>(r), static_cast<int>(c),
                          vals.values[k]);
  }
  Eigen::SparseMatrix<double> matrix(n, n);
  matrix.setFromTriplets(triplets.begin(), triplets.end());
  return matrix;
}

Positions PositionsArgument(const py::handle& object,
                            const std::string& name) {
  const RealValues v = CheckedRealArray(object, name, {{"#V"}, {"3", 3}});
  Positions positions(v.shape[0], 3);
  std::copy(v.values.begin(), v.values.end(), positions.data());
  return positions;
}

std::vector<Positions> ShapeListArgument(const py::handle& object,
                                         const std::string& name) {
  std::vector<Positions> shapes;
  if (py::isinstance<py::array>(object)) {
    const RealValues v =
        CheckedRealArray(object, name, {{"K"}, {"#V"}, {"3", 3}});
    const size_t size = static_cast<size_t>(v.shape[1]) * 3;
    for (py::ssize_t k = 0; k < v.shape[0]; ++k) {
      Positions shape(v.shape[1], 3);
      std::copy(v.values.begin() + k * size, v.values.begin() + (k + 1) * size,
                shape.data());
      shapes.push_back(std::move(shape));
    }
  } else {
    const std::string expected =
        name + " must be a K x #V x 3 array or a sequence of #V x 3 arrays, "
               "got ";
    if (object.is_none() || py::isinstance<py::str>(object) ||
        py::isinstance<py::bytes>(object) || !py::isinstance<py::iterable>(object)) {
      throw InputError(expected + TypeName(object));
    }
    for (const py::handle item : object) {
      shapes.push_back(PositionsArgument(
          item, name + "[" + std::to_string(shapes.size()) + "]"));
    }
  }
  if (shapes.empty()) throw InputError(name + " is empty");
  return shapes;
}

std::vector<Positions> ShapeOrListArgument(const py::handle& object,
                                           const std::string& name) {
  if (py::isinstance<py::array>(object)) {
    if (py::reinterpret_borrow<py::array>(object).ndim() == 2) {
      return {PositionsArgument(object, name)};
    }
    return ShapeListArgument(object, name);
  }
  // A nested list of rows is one shape too.
  if (!object.is_none() && !py::isinstance<py::str>(object) &&
      !py::isinstance<py::bytes>(object)) {
    try {
      const py::array array = py::module_::import("numpy").attr("asarray")(object);
      if (array.ndim() == 2) return {PositionsArgument(array, name)};
    } catch (py::error_already_set& error) {
      if (!error.matches(PyExc_Exception)) throw;  // a ragged list: below
    }
  }
  return ShapeListArgument(object, name);
}

Faces FacesArgument(const py::handle& object, const std::string& name,
                    int num_vertices) {
  const IndexValues v = CheckedIndexArray(object, name, {{"#F"}, {"3", 3}});
  Faces faces(v.shape[0], 3);
  for (size_t i = 0; i < v.values.size(); ++i) {
    const long long index = v.values[i];
    if (index < 0 || index >= num_vertices) {
      throw InputError(name + ": face " + std::to_string(i / 3) +
                       " has the vertex index " + std::to_string(index) +
                       ", outside [0, " + std::to_string(num_vertices) + ")");
    }
    faces.data()[i] = static_cast<int>(index);
  }
  return faces;
}

std::vector<int> IndexListArgument(const py::handle& object,
                                   const std::string& name, long long min,
                                   long long max) {
  const IndexValues v = CheckedIndexArray(object, name, {{"#indices"}});
  std::vector<int> out;
  for (const long long index : v.values) {
    if (index < min || index > max) {
      throw InputError(name + ": index " + std::to_string(index) +
                       " outside [" + std::to_string(min) + ", " +
                       std::to_string(max) + "]");
    }
    out.push_back(static_cast<int>(index));
  }
  return out;
}

namespace {

// The mask file's path if `object` names one (a str or os.PathLike whose
// fspath is a str); nothing for None or indices.
std::optional<std::string> MaskFilePath(const py::handle& object) {
  if (object.is_none()) return std::nullopt;
  const py::object path_like = py::module_::import("os").attr("PathLike");
  if (!py::isinstance<py::str>(object) && !py::isinstance(object, path_like)) {
    return std::nullopt;
  }
  const py::object path = py::module_::import("os").attr("fspath")(object);
  if (!py::isinstance<py::str>(path)) {
    throw InputError("mask: a path must be a str, got " + TypeName(path));
  }
  return path.cast<std::string>();
}

}  // namespace

std::vector<std::pair<std::string, std::string>> MaskInputPaths(
    const py::handle& object) {
  const std::optional<std::string> path = MaskFilePath(object);
  if (!path) return {};
  return {{"mask", *path}};
}

std::vector<int> MaskArgument(const py::handle& object, int num_vertices) {
  if (object.is_none()) return {};
  if (const std::optional<std::string> path = MaskFilePath(object)) {
    return ReadMask(*path, num_vertices);
  }
  const IndexValues v = CheckedIndexArray(object, "mask", {{"#indices"}});
  std::vector<int> indices;
  for (const long long index : v.values) {
    if (index < 0 || index >= num_vertices) {
      throw InputError("mask: vertex index " + std::to_string(index) +
                       " outside [0, " + std::to_string(num_vertices) + ")");
    }
    indices.push_back(static_cast<int>(index));
  }
  std::sort(indices.begin(), indices.end());
  indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
  return indices;
}

}  // namespace shellspace
