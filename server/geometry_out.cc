#include "geometry_out.h"

namespace freeform::server {
namespace {

void Fill(google::protobuf::RepeatedField<double>& field,
          const std::vector<double>& values) {
  field.Add(values.begin(), values.end());
}

void FillPoints(int dimension, const std::vector<double>& coordinates,
                v1::Points& out) {
  out.set_dimension(static_cast<uint32_t>(dimension));
  Fill(*out.mutable_coordinates(), coordinates);
}

}  // namespace

void ToProto(const BezierCurveData& curve, v1::Curve& out) {
  v1::BezierCurve* bezier = out.mutable_bezier();
  FillPoints(curve.dimension, curve.coordinates,
             *bezier->mutable_control_points());
  Fill(*bezier->mutable_weights(), curve.weights);
}

void ToProto(const BSplineCurveData& curve, v1::Curve& out) {
  v1::BSplineCurve* bspline = out.mutable_bspline();
  bspline->set_degree(static_cast<uint32_t>(curve.degree));
  FillPoints(curve.dimension, curve.coordinates,
             *bspline->mutable_control_points());
  Fill(*bspline->mutable_knots(), curve.knots);
  Fill(*bspline->mutable_weights(), curve.weights);
}

void ToProto(const SurfaceData& surface, v1::Surface& out) {
  v1::ControlNet net;
  net.set_dimension(static_cast<uint32_t>(surface.dimension));
  net.set_count_u(static_cast<uint32_t>(surface.count_u));
  net.set_count_v(static_cast<uint32_t>(surface.count_v));
  Fill(*net.mutable_coordinates(), surface.coordinates);
  if (surface.knots_u.empty() && surface.knots_v.empty()) {
    *out.mutable_bezier()->mutable_control_net() = std::move(net);
    Fill(*out.mutable_bezier()->mutable_weights(), surface.weights);
    return;
  }
  v1::BSplineSurface* bspline = out.mutable_bspline();
  bspline->set_degree_u(static_cast<uint32_t>(surface.degree_u));
  bspline->set_degree_v(static_cast<uint32_t>(surface.degree_v));
  *bspline->mutable_control_net() = std::move(net);
  Fill(*bspline->mutable_knots_u(), surface.knots_u);
  Fill(*bspline->mutable_knots_v(), surface.knots_v);
  Fill(*bspline->mutable_weights(), surface.weights);
}

void ToProto(const TriangularPatchData& patch, v1::Surface& out) {
  v1::TriangularBezierPatch* triangle = out.mutable_triangular_bezier();
  triangle->set_degree(static_cast<uint32_t>(patch.degree));
  FillPoints(patch.dimension, patch.coordinates,
             *triangle->mutable_control_points());
  Fill(*triangle->mutable_weights(), patch.weights);
  if (!patch.domain_triangle.empty()) {
    FillPoints(2, patch.domain_triangle, *triangle->mutable_domain_triangle());
  }
}

}  // namespace freeform::server
