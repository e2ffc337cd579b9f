// Curvature combs of plane curves (curvature_comb.h).
#include "curvature_comb.h"

#include <algorithm>
#include <cmath>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"

namespace freeform::cli {

int CurveDimension(const v1::Curve& curve) {
  switch (curve.kind_case()) {
    case v1::Curve::kBezier:
      return static_cast<int>(curve.bezier().control_points().dimension());
    case v1::Curve::kBspline:
      return static_cast<int>(curve.bspline().control_points().dimension());
    case v1::Curve::kLagrange:
      return static_cast<int>(curve.lagrange().points().dimension());
    case v1::Curve::kHermite:
      return static_cast<int>(curve.hermite().points().dimension());
    case v1::Curve::kPower:
      return static_cast<int>(curve.power().coefficients().dimension());
    case v1::Curve::KIND_NOT_SET:
      break;
  }
  return 0;
}

double DefaultCombScale(absl::Span<const double> curvatures, double extent) {
  double largest = 0;
  for (double curvature : curvatures) {
    if (std::isfinite(curvature)) largest = std::max(largest, curvature);
  }
  return largest > 0 ? kCombFraction * extent / largest : 0.0;
}

std::vector<double> CombTips(absl::Span<const double> points,
                             absl::Span<const double> normals,
                             absl::Span<const double> curvatures,
                             double scale) {
  std::vector<double> tips(points.begin(), points.end());
  for (size_t k = 0; k < curvatures.size() && 2 * k + 1 < tips.size() &&
                     2 * k + 1 < normals.size();
       ++k) {
    const double length = scale * curvatures[k];
    tips[2 * k] -= length * normals[2 * k];
    tips[2 * k + 1] -= length * normals[2 * k + 1];
  }
  return tips;
}

absl::Status AddCurvatureComb(Client& client, const v1::Curve& curve,
                              const v1::TessellateCurveResponse& polyline,
                              std::optional<double> scale,
                              SvgDrawing& drawing) {
  v1::CurveCurvatureRequest request;
  *request.mutable_curve() = curve;
  request.mutable_parameters()->mutable_list()->mutable_values()->Add(
      polyline.parameters().begin(), polyline.parameters().end());
  absl::StatusOr<v1::CurveCurvatureResponse> curvature =
      client.Unary(&v1::CurveService::Stub::Curvature, request);
  if (!curvature.ok()) return curvature.status();
  const auto& points = polyline.points().coordinates();
  const auto& curvatures = curvature->curvatures();
  const std::vector<double> tips =
      CombTips(points, curvature->normals().coordinates(), curvatures,
               scale.value_or(DefaultCombScale(curvatures, drawing.Extent())));
  drawing.AddSegments(points, tips, 2,
                      {.color = "#d95f02", .width = 0.75, .label = "comb"});
  drawing.AddPolyline(tips, 2,
                      {.color = "#d95f02", .width = 1.5, .label = "envelope"});
  return absl::OkStatus();
}

}  // namespace freeform::cli
