// Homogeneous form of rational geometry.
//
// A rational curve or surface with Cartesian control points P_i and weights
// w_i is the projection of the polynomial one with homogeneous points
// (w_i P_i, w_i). A zero weight makes the point a direction: its coordinates
// D are kept and the homogeneous point is (D, 0), a point at infinity, as in
// the half circle (1,0,1), (0,1,0), (-1,0,1) (docs/references.md,
// 'Worked example: the half circle with a point at infinity'). Derivatives of
// the projection follow from the homogeneous ones by the quotient rule (The
// NURBS Book, eq. 4.8). Thread-safe.
#ifndef FREEFORM_CORE_RATIONAL_H_
#define FREEFORM_CORE_RATIONAL_H_

#include <vector>

#include "absl/status/status.h"
#include "absl/types/span.h"
#include "freeform/core/points.h"

namespace freeform {

// The smallest ratio of a nonzero weight to the largest weight. Geometry is
// computed on a copy whose largest weight is about 1 (scaled_geometry.h);
// a weight below 2^-1022 there is subnormal, and its homogeneous point
// w P loses the low bits of P, all of them at 5e-324.
inline constexpr double kSmallestWeightRatio = 0x1p-1021;

// ValidateWeightValues checks that every weight is finite and >= 0 and
// that every nonzero one is at least kSmallestWeightRatio of the largest,
// naming "weights[i]". Weights scaled alike give the same geometry, so only
// their ratios count: 1e-300 and 1e-310 together are fine, 1 and 1e-310
// are not.
absl::Status ValidateWeightValues(absl::Span<const double> weights);

// HomogeneousPoints returns (w_i P_i, w_i) for every point, dimension + 1
// values each ((D, 0) for a zero weight). `weights` has one weight per point.
std::vector<double> HomogeneousPoints(const PointsView& points,
                                      absl::Span<const double> weights);

// ProjectHomogeneousDerivatives turns derivatives of a homogeneous curve
// (dimension + 1 values per order, weight last) into the derivatives of its
// projection: C^(k) = (A^(k) - sum_{i=1..k} binom(k,i) w^(i) C^(k-i)) / w.
// Reads `homogeneous[k * (dimension + 1) + j]`, writes
// `derivatives[k * dimension + j]` for k = 0..max_order.
void ProjectHomogeneousDerivatives(const double* homogeneous, int dimension,
                                   int max_order, double* derivatives);

}  // namespace freeform

#endif  // FREEFORM_CORE_RATIONAL_H_
