// The one check of every array that crosses the Python boundary.
//
// An argument may be a NumPy array of any dtype, byte order and strides, or
// anything numpy.asarray accepts (nested lists, buffers). It is checked
// before any of its values is read:
//  - dtype: real arrays (positions) hold floats or integers; index arrays
//    (faces, masks, keyframe indices) hold integers only -- a float index
//    is refused, not truncated (an empty float array, numpy.asarray([]),
//    holds no index and passes). bool, complex, object, string and date
//    arrays are refused;
//  - shape: the number of axes and the length of every fixed axis (a K x
//    #V x 2 frame stack is refused where K x #V x 3 is expected);
//  - values: real values finite after the conversion to float64, indices
//    within the caller's range (and within int);
// then copied out of a C-contiguous float64 / integer copy, so strided,
// reversed, non-native-byte-order and read-only arrays read correctly.
// Every refusal is a shellspace.InputError naming the argument.
#ifndef SHELLSPACE_PYTHON_ARRAY_ARGUMENTS_H_
#define SHELLSPACE_PYTHON_ARRAY_ARGUMENTS_H_

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "python/strict_numbers.h"
#include "shellspace/geometry/mesh.h"

namespace shellspace {

// An axis of an expected shape: its name in messages ("#V", "K") and its
// length (kAnyLength: any).
inline constexpr pybind11::ssize_t kAnyLength = -1;
struct Axis {
  const char* name;
  pybind11::ssize_t length = kAnyLength;
};

// A real array checked against `axes` (see above): its values as float64
// in C order, and its shape.
struct RealValues {
  std::vector<double> values;
  std::vector<pybind11::ssize_t> shape;
};
RealValues CheckedRealArray(const pybind11::handle& object,
                            const std::string& name,
                            const std::vector<Axis>& axes);

// An integer array checked against `axes` (see above): its values in C
// order, and its shape. The caller checks their range (the messages name
// what an index is); a value outside the range of long long (uint64) is
// refused here.
struct IndexValues {
  std::vector<long long> values;
  std::vector<pybind11::ssize_t> shape;
};
IndexValues CheckedIndexArray(const pybind11::handle& object,
                              const std::string& name,
                              const std::vector<Axis>& axes);

// A #V x 3 array of vertex positions (V, a shell, a variation).
Positions PositionsArgument(const pybind11::handle& object,
                            const std::string& name);

// An n x n sparse matrix of triplets: `rows` and `cols` integer arrays of
// indices in [0, n) and `vals` a real array, all of one length (duplicates
// summed).
Eigen::SparseMatrix<double> TripletsArgument(const pybind11::handle& rows,
                                             const pybind11::handle& cols,
                                             const pybind11::handle& vals,
                                             long long n);

// A list of shapes: a K x #V x 3 array, or a sequence (list, tuple,
// iterable) of #V x 3 arrays ("name[k]" in messages). At least one shape;
// the vertex counts are compared by the caller (CompatiblePositions).
std::vector<Positions> ShapeListArgument(const pybind11::handle& object,
                                         const std::string& name);

// One shape (a #V x 3 array) or a list of them (compare's a and b).
std::vector<Positions> ShapeOrListArgument(const pybind11::handle& object,
                                           const std::string& name);

// A #F x 3 integer array of vertex indices in [0, num_vertices).
Faces FacesArgument(const pybind11::handle& object, const std::string& name,
                    int num_vertices);

// A 1-D sequence of integers in [min, max] (keyframe indices), in order.
std::vector<int> IndexListArgument(const pybind11::handle& object,
                                   const std::string& name, long long min,
                                   long long max);

// The vertex mask: None (no vertex held), a mask file's path (str or
// os.PathLike; io/mesh_io.h's ReadMask), or a 1-D sequence of 0-based
// vertex indices in [0, num_vertices); sorted and made unique, as ReadMask
// returns them.
std::vector<int> MaskArgument(const pybind11::handle& object,
                              int num_vertices);

// The mask file MaskArgument reads, as the input ("mask", path) the output
// checks compare with (module_common.h CheckOutputs); none for None or
// indices.
std::vector<std::pair<std::string, std::string>> MaskInputPaths(
    const pybind11::handle& object);

}  // namespace shellspace

#endif  // SHELLSPACE_PYTHON_ARRAY_ARGUMENTS_H_
