// The metric of a face's surface for meshing (face_mesh.h): bounds of the
// second partials per span rectangle in the surface's own parameters, and
// the a-priori bound of linear interpolation over a parameter triangle or
// segment. Internal to the core; immutable after Create (thread-safe).
#ifndef FREEFORM_CORE_SRC_FACES_FACE_METRIC_H_
#define FREEFORM_CORE_SRC_FACES_FACE_METRIC_H_

#include <array>
#include <optional>
#include <vector>

#include "absl/status/statusor.h"
#include "freeform/core/constrained_delaunay.h"
#include "freeform/core/surface.h"

namespace freeform::internal {

// The weights of the scaled metric Q(d) = a d_u^2 + b d_v^2.
struct MetricWeights {
  double a = 0.0;
  double b = 0.0;
};

// A knot line u = value (in_u) or v = value.
struct KnotLine {
  bool in_u = true;
  double value = 0.0;
};

class FaceMetric {
 public:
  // Create bounds every span rectangle of `surface` and notes its C0 lines
  // (interior knots of multiplicity at least the degree). Fails with
  // INVALID_ARGUMENT naming "surface" for a surface that is not 3D, has a
  // weight that is not positive, or bounds that are not finite.
  static absl::StatusOr<FaceMetric> Create(const Surface& surface);

  // WeightsOver returns A and B over the span rectangles that the box
  // [u0, u1] x [v0, v1] meets: for a box inside one rectangle its bounds in
  // the rectangle's own frame (the planner's), else the largest over the
  // rectangles for a polynomial surface and the sum for a rational one (in
  // one frame for the whole net); each at least 1/100 of the larger.
  MetricWeights WeightsOver(double u0, double u1, double v0, double v1) const;

  // StraddledLine returns a C0 line strictly inside the box, if any.
  std::optional<KnotLine> StraddledLine(double u0, double u1, double v0,
                                        double v1) const;

  // TriangleBound returns R^2 / 2, R the radius of the smallest circle
  // enclosing the triangle in the metric over its box; infinity for a
  // triangle across a C0 line.
  double TriangleBound(const std::array<freeform::Point2, 3>& corners) const;
  // SegmentBound returns (A e_u^2 + B e_v^2) / 8 over the segment's box.
  double SegmentBound(freeform::Point2 a, freeform::Point2 b) const;

  // The span rectangles' breakpoints and second-partial bounds
  // {M_uu, M_uv, M_vv} in the surface's parameters, rectangle (i, j) at
  // i * (breaks_v.size() - 1) + j.
  const std::vector<double>& breaks_u() const { return breaks_u_; }
  const std::vector<double>& breaks_v() const { return breaks_v_; }
  const std::array<double, 3>& second(size_t i, size_t j) const {
    return second_[i * (breaks_v_.size() - 1) + j];
  }

 private:
  FaceMetric() = default;

  std::vector<double> breaks_u_;
  std::vector<double> breaks_v_;
  std::vector<std::array<double, 3>> second_;
  // The same in each rectangle's own frame (its active points), for boxes
  // inside one rectangle.
  std::vector<std::array<double, 3>> own_second_;
  std::vector<double> c0_u_;
  std::vector<double> c0_v_;
  bool rational_ = false;
};

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_FACES_FACE_METRIC_H_
