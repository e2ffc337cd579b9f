// Control points of any number of values each (Cartesian, homogeneous, or a
// whole row of a net) in one flat array, and the transpose of a grid of
// such points: the form in which elevation, subdivision and knot insertion
// work on curves and, row by row, on surfaces. Internal to the core;
// thread-safe (a value type and a pure function).
#ifndef FREEFORM_CORE_SRC_BASE_POINT_ARRAY_H_
#define FREEFORM_CORE_SRC_BASE_POINT_ARRAY_H_

#include <algorithm>
#include <cstddef>
#include <vector>

namespace freeform::internal {

// Control points of `dim` values each (homogeneous ones, weight last,
// included; or whole rows of a net) in a flat array, point after point.
struct PointArray {
  int dim = 0;
  std::vector<double> values;

  size_t count() const {
    return dim > 0 ? values.size() / static_cast<size_t>(dim) : 0;
  }
  double* at(size_t i) { return values.data() + i * static_cast<size_t>(dim); }
  const double* at(size_t i) const {
    return values.data() + i * static_cast<size_t>(dim);
  }
};

// TransposeBlocks swaps the two indices of a rows x cols grid of blocks of
// `block` values: block (i, j) at (i * cols + j) * block moves to
// (j * rows + i) * block.
inline std::vector<double> TransposeBlocks(const std::vector<double>& values,
                                           int rows, int cols, int block) {
  std::vector<double> result(values.size());
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      std::copy_n(values.data() + (static_cast<size_t>(i) * cols + j) * block,
                  block,
                  result.data() + (static_cast<size_t>(j) * rows + i) * block);
    }
  }
  return result;
}

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_BASE_POINT_ARRAY_H_
