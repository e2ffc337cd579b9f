// Parameters of scattered points from their best-fit plane
// (PlaneParameters); docs/references.md, 'Scattered-data surface fitting'.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/fitting.h"
#include "freeform/core/points.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "linalg/symmetric_eigen.h"

namespace freeform {
namespace {

// Centroid returns the mean point, by running means (no overflow).
absl::StatusOr<std::vector<double>> Centroid(const PointsView& points,
                                             const CancellationToken* cancel) {
  const size_t d = static_cast<size_t>(points.dimension);
  std::vector<double> mean(d, 0.0);
  CancellationPoll poll(cancel);
  for (size_t k = 0; k < points.size(); ++k) {
    RETURN_IF_ERROR(poll.Done(d));
    const double weight = 1.0 / static_cast<double>(k + 1);
    for (size_t c = 0; c < d; ++c) {
      mean[c] += (points.point(k)[c] - mean[c]) * weight;
    }
  }
  return mean;
}

// Covariance returns sum_k y_k y_k^T (upper triangle) of the centred
// points scaled by `scale`, y_k = (x_k - centroid) / scale.
absl::StatusOr<std::vector<double>> Covariance(
    const PointsView& points, absl::Span<const double> centroid, double scale,
    const CancellationToken* cancel) {
  const size_t d = static_cast<size_t>(points.dimension);
  std::vector<double> covariance(d * d, 0.0), y(d);
  CancellationPoll poll(cancel);
  for (size_t k = 0; k < points.size(); ++k) {
    RETURN_IF_ERROR(poll.Done(d * d));
    for (size_t c = 0; c < d; ++c) {
      y[c] = (points.point(k)[c] - centroid[c]) / scale;
    }
    for (size_t r = 0; r < d; ++r) {
      for (size_t c = r; c < d; ++c) covariance[r * d + c] += y[r] * y[c];
    }
  }
  return covariance;
}

// Orient flips `vector` so that its component of largest magnitude (the
// first of equals) is positive.
void Orient(absl::Span<double> vector) {
  const auto largest = std::max_element(
      vector.begin(), vector.end(),
      [](double a, double b) { return std::abs(a) < std::abs(b); });
  if (*largest < 0) {
    for (double& value : vector) value = -value;
  }
}

}  // namespace

absl::StatusOr<std::vector<double>> PlaneParameters(
    const PointsView& points, const CancellationToken* cancel) {
  RETURN_IF_ERROR(ValidatePoints(points, "points", 3));
  if (points.dimension < 2) {
    return InvalidFieldError(
        "points.dimension",
        "computed parameters need points of dimension >= 2; give parameters");
  }
  const size_t d = static_cast<size_t>(points.dimension);
  absl::StatusOr<std::vector<double>> centroid = Centroid(points, cancel);
  if (!centroid.ok()) return centroid.status();
  double scale = 0;
  for (size_t k = 0; k < points.size(); ++k) {
    for (size_t c = 0; c < d; ++c) {
      scale = std::max(scale, std::abs(points.point(k)[c] - (*centroid)[c]));
    }
  }
  absl::StatusOr<std::vector<double>> covariance =
      scale > 0 ? Covariance(points, *centroid, scale, cancel)
                : std::vector<double>(d * d, 0.0);
  if (!covariance.ok()) return covariance.status();
  internal::SymmetricEigenSystem plane =
      internal::SymmetricEigen(d, *std::move(covariance));
  std::vector<double> uv(2 * points.size());
  double lo[2] = {0, 0}, hi[2] = {0, 0};
  for (size_t axis = 0; axis < 2; ++axis) {
    const absl::Span<double> direction =
        absl::MakeSpan(plane.vectors).subspan(axis * d, d);
    Orient(direction);
    for (size_t k = 0; k < points.size(); ++k) {
      double along = 0;
      for (size_t c = 0; c < d; ++c) {
        along += direction[c] * (points.point(k)[c] - (*centroid)[c]);
      }
      uv[2 * k + axis] = along;
      lo[axis] = k == 0 ? along : std::min(lo[axis], along);
      hi[axis] = k == 0 ? along : std::max(hi[axis], along);
    }
  }
  const double extent_u = hi[0] - lo[0], extent_v = hi[1] - lo[1];
  if (!(extent_v > 1e-12 * extent_u)) {
    return InvalidFieldError(
        "points",
        absl::StrCat("the points lie on a line (extents ", extent_u, " and ",
                     extent_v, " in their best-fit plane); give parameters"));
  }
  for (size_t k = 0; k < points.size(); ++k) {
    uv[2 * k] = (uv[2 * k] - lo[0]) / extent_u;
    uv[2 * k + 1] = (uv[2 * k + 1] - lo[1]) / extent_v;
  }
  return uv;
}

}  // namespace freeform
