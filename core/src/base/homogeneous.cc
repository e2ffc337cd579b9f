#include "base/homogeneous.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "freeform/core/rational.h"

namespace freeform::internal {

std::vector<double> LiftedValues(const PointsView& points,
                                 absl::Span<const double> weights) {
  if (weights.empty()) {
    return {points.coordinates.begin(), points.coordinates.end()};
  }
  return HomogeneousPoints(points, weights);
}

PointArray Lift(const PointsView& points, absl::Span<const double> weights) {
  return {points.dimension + (weights.empty() ? 0 : 1),
          LiftedValues(points, weights)};
}

void ProjectAllowingDirections(const PointArray& points, bool rational,
                               std::vector<double>& coordinates,
                               std::vector<double>& weights,
                               ZeroWeights zeros) {
  if (!rational) {
    coordinates = points.values;
    weights.clear();
    return;
  }
  const int dim = points.dim - 1;
  const size_t count = points.count();
  double largest = 0.0;
  for (size_t i = 0; i < count; ++i) {
    largest = std::max(largest, std::abs(points.at(i)[dim]));
  }
  const double zero =
      zeros == ZeroWeights::kExact
          ? 0.0
          : 8.0 * std::numeric_limits<double>::epsilon() * largest;
  coordinates.resize(count * dim);
  weights.resize(count);
  for (size_t i = 0; i < count; ++i) {
    const double* h = points.at(i);
    const double w = std::abs(h[dim]) <= zero ? 0.0 : h[dim];
    // A quotient, not a product by 1 / w: below 2^-1024 (a subnormal
    // weight) the reciprocal overflows and 0 * inf would be NaN.
    for (int x = 0; x < dim; ++x) {
      coordinates[i * dim + x] = w == 0.0 ? h[x] : h[x] / w;
    }
    weights[i] = w;
  }
}

bool ProjectPositive(const double* homogeneous, int dimension, double* point) {
  const double w = homogeneous[dimension];
  if (!(w > 0.0)) return false;
  for (int x = 0; x < dimension; ++x) point[x] = homogeneous[x] / w;
  return true;
}

}  // namespace freeform::internal
