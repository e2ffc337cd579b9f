#include "freeform/core/rational.h"

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "freeform/core/status.h"

namespace freeform {

absl::Status ValidateWeightValues(absl::Span<const double> weights) {
  double largest = 0.0;
  for (size_t i = 0; i < weights.size(); ++i) {
    if (!std::isfinite(weights[i]) || weights[i] < 0) {
      return InvalidFieldError(
          IndexedField("weights", i),
          absl::StrCat("weights must be finite and >= 0, got ", weights[i]));
    }
    largest = std::max(largest, weights[i]);
  }
  const double smallest = largest * kSmallestWeightRatio;
  for (size_t i = 0; i < weights.size(); ++i) {
    if (weights[i] != 0.0 && weights[i] < smallest) {
      return InvalidFieldError(
          IndexedField("weights", i),
          absl::StrCat(
              "a nonzero weight must be at least 2^-1021 of the largest (",
              largest, "), got ", weights[i],
              ": below, its homogeneous point w P underflows and loses its "
              "point; use 0 (a direction) or scale the weights closer"));
    }
  }
  return absl::OkStatus();
}

std::vector<double> HomogeneousPoints(const PointsView& points,
                                      absl::Span<const double> weights) {
  const size_t dimension = static_cast<size_t>(points.dimension);
  std::vector<double> homogeneous(points.size() * (dimension + 1));
  for (size_t i = 0; i < points.size(); ++i) {
    const double* point = points.point(i);
    double* out = &homogeneous[i * (dimension + 1)];
    const double scale = weights[i] == 0.0 ? 1.0 : weights[i];
    for (size_t j = 0; j < dimension; ++j) out[j] = scale * point[j];
    out[dimension] = weights[i];
  }
  return homogeneous;
}

void ProjectHomogeneousDerivatives(const double* homogeneous, int dimension,
                                   int max_order, double* derivatives) {
  const size_t dim = static_cast<size_t>(dimension);
  const size_t stride = dim + 1;
  const double weight = homogeneous[dim];
  for (int k = 0; k <= max_order; ++k) {
    double* out = derivatives + static_cast<size_t>(k) * dim;
    const double* numerator = homogeneous + static_cast<size_t>(k) * stride;
    for (size_t j = 0; j < dim; ++j) out[j] = numerator[j];
    double binomial = 1.0;  // binom(k, i)
    for (int i = 1; i <= k; ++i) {
      binomial = binomial * (k - i + 1) / i;
      const double weight_derivative =
          homogeneous[static_cast<size_t>(i) * stride + dim];
      const double* lower = derivatives + static_cast<size_t>(k - i) * dim;
      for (size_t j = 0; j < dim; ++j) {
        out[j] -= binomial * weight_derivative * lower[j];
      }
    }
    for (size_t j = 0; j < dim; ++j) out[j] /= weight;
  }
}

}  // namespace freeform
