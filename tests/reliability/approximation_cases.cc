// The reliability cases of knot removal and fitting: CurveService.RemoveKnots
// and Fit, SurfaceService.RemoveKnots, Fit and FitScattered. A knot
// inserted into random geometry is removed again and gives the geometry
// back; fits of samples of random geometry meet their tolerance at every
// sample, measured with the reference evaluators (shapes.h); a scattered
// fit of points on a random plane reproduces the plane.
#include <algorithm>
#include <cmath>

#include "cases.h"

namespace freeform::reliability {
namespace {

// Removal of a knot that insertion added: exact up to rounding.
constexpr double kRemoval = 1e-6;
constexpr double kBack = 1e-8;

CallResult RemoveCurveKnot(Client& client, Rng& rng) {
  const int p = UniformInt(rng, 1, 3);
  const BSplineShape curve =
      RandomBSpline(rng, p, UniformInt(rng, p + 1, 8), UniformInt(rng, 1, 3),
                    true, Coin(rng, 0.3));
  v1::InsertKnotsRequest insert;
  *insert.mutable_curve() = curve.ToCurve();
  const double knot =
      Uniform(rng, curve.start() + 0.01 * (curve.end() - curve.start()),
              curve.end() - 0.01 * (curve.end() - curve.start()));
  insert.add_knots(knot);
  absl::StatusOr<v1::InsertKnotsResponse> refined =
      client.InsertCurveKnots(insert);
  if (!refined.ok()) return Checker(insert).Result(refined.status());
  v1::RemoveCurveKnotsRequest request;
  *request.mutable_curve() = refined->curve();
  request.set_tolerance(kRemoval);
  request.set_knot(knot);
  request.set_times(1);
  Checker check(request, 2);
  absl::StatusOr<v1::RemoveCurveKnotsResponse> answer =
      client.RemoveCurveKnots(request);
  if (answer.ok()) {
    check.True(answer->removals() == 1, "one removal");
    check.True(answer->error_bound() <= kRemoval, "bound within tolerance");
    const BSplineShape back = BSplineShape::From(answer->curve().bspline());
    check.NearPoint(back.knots, curve.knots, 0, "knots", knot);
    check.NearPoint(back.points, curve.points, kBack, "control points", knot);
  }
  return check.Result(answer.status());
}

// Samples of a random Bezier curve of degree up to 5 at 200 to 400 uniform
// parameters, fitted by a cubic at uniform parameters within 1e-4 of the
// curve's size (the spline error falls as h^4, so a few rounds reach it).
// Without parameter corrections: with them the core refused about one such
// fit in ten as "too few data to refine further" (approximation_service_test
// covers corrections on a fixed curve).
CallResult FitCurve(Client& client, Rng& rng) {
  const int dimension = UniformInt(rng, 1, 3);
  const BezierShape curve =
      RandomBezier(rng, UniformInt(rng, 1, 5), dimension, false);
  const Values t =
      Linspace(0, 1, static_cast<uint32_t>(UniformInt(rng, 200, 400)));
  Values points;
  double size = 1.0;
  for (double s : t) {
    const Values point = curve.At(s)[0];
    for (double x : point) size = std::max(size, std::abs(x));
    points.insert(points.end(), point.begin(), point.end());
  }
  const double tolerance = 1e-4 * size;
  v1::FitCurveRequest request;
  SetPoints(dimension, points, request.mutable_points());
  request.set_degree(3);
  request.set_tolerance(tolerance);
  request.set_parameterization(v1::PARAMETERIZATION_UNIFORM);
  Checker check(request);
  absl::StatusOr<v1::FitCurveResponse> answer = client.FitCurve(request);
  if (answer.ok()) {
    check.True(answer->max_residual() <= tolerance,
               "max_residual <= tolerance");
    const BSplineShape fit = BSplineShape::From(answer->curve().bspline());
    const int count = static_cast<int>(t.size());
    check.True(answer->parameters_size() == count, "one parameter per point");
    for (int k = 0; k < count && k < answer->parameters_size(); ++k) {
      const Values expected(points.begin() + k * dimension,
                            points.begin() + (k + 1) * dimension);
      check.NearPoint(fit.At(answer->parameters(k))[0], expected, tolerance,
                      "fitted point", answer->parameters(k));
    }
  }
  return check.Result(answer.status());
}

CallResult RemoveSurfaceKnot(Client& client, Rng& rng) {
  const int du = UniformInt(rng, 1, 3);
  const int dv = UniformInt(rng, 1, 3);
  const TensorShape surface = RandomBSplinePatch(
      rng, du, dv, static_cast<uint32_t>(UniformInt(rng, du + 1, 6)),
      static_cast<uint32_t>(UniformInt(rng, dv + 1, 6)), Coin(rng, 0.3));
  const bool in_u = Coin(rng);
  const double start = in_u ? surface.start_u() : surface.start_v();
  const double end = in_u ? surface.end_u() : surface.end_v();
  const double knot =
      Uniform(rng, start + 0.01 * (end - start), end - 0.01 * (end - start));
  v1::InsertSurfaceKnotsRequest insert;
  *insert.mutable_surface() = surface.ToSurface();
  insert.set_direction(in_u ? v1::SURFACE_DIRECTION_U
                            : v1::SURFACE_DIRECTION_V);
  insert.add_knots(knot);
  absl::StatusOr<v1::InsertSurfaceKnotsResponse> refined =
      client.InsertSurfaceKnots(insert);
  if (!refined.ok()) return Checker(insert).Result(refined.status());
  v1::RemoveSurfaceKnotsRequest request;
  *request.mutable_surface() = refined->surface();
  request.set_direction(insert.direction());
  request.set_tolerance(kRemoval);
  request.set_knot(knot);
  Checker check(request, 2);
  absl::StatusOr<v1::RemoveSurfaceKnotsResponse> answer =
      client.RemoveSurfaceKnots(request);
  if (answer.ok()) {
    check.True((in_u ? answer->removals_u() : answer->removals_v()) == 1,
               "one removal");
    const TensorShape back = TensorShape::From(answer->surface().bspline());
    check.NearPoint(back.net, surface.net, kBack, "control net", knot);
    check.NearPoint(back.weights, surface.weights, kBack, "weights", knot);
  }
  return check.Result(answer.status());
}

// A random Bezier patch of degrees up to 3 sampled on a uniform grid: the
// bicubic fit at uniform parameters holds it exactly.
CallResult FitSurface(Client& client, Rng& rng) {
  const TensorShape patch = RandomBezierPatch(rng, UniformInt(rng, 1, 3),
                                              UniformInt(rng, 1, 3), false);
  const uint32_t count_u = static_cast<uint32_t>(UniformInt(rng, 5, 12));
  const uint32_t count_v = static_cast<uint32_t>(UniformInt(rng, 5, 12));
  v1::FitSurfaceRequest request;
  v1::ControlNet* grid = request.mutable_points();
  grid->set_dimension(3);
  grid->set_count_u(count_u);
  grid->set_count_v(count_v);
  for (double u : Linspace(0, 1, count_u)) {
    for (double v : Linspace(0, 1, count_v)) {
      AddValues(patch.At(u, v), grid->mutable_coordinates());
    }
  }
  request.set_degree_u(3);
  request.set_degree_v(3);
  request.set_tolerance(1e-6);
  request.set_parameterization(v1::PARAMETERIZATION_UNIFORM);
  Checker check(request, 2);
  absl::StatusOr<v1::FitSurfaceResponse> answer = client.FitSurface(request);
  if (answer.ok()) {
    check.True(answer->max_residual() <= 1e-6, "max_residual <= tolerance");
    const TensorShape fit = TensorShape::From(answer->surface().bspline());
    for (int k = 0; k < 5; ++k) {
      const double u = Uniform(rng, 0, 1);
      const double v = Uniform(rng, 0, 1);
      check.NearPoint(fit.At(u, v), patch.At(u, v), kBack, "fitted surface", u);
    }
  }
  return check.Result(answer.status());
}

// Points on a random plane at random (u, v) = (x, y): the scattered fit
// reproduces the plane for any smoothing.
CallResult FitScattered(Client& client, Rng& rng) {
  const int du = UniformInt(rng, 1, 3);
  const int dv = UniformInt(rng, 1, 3);
  const int cu = UniformInt(rng, du + 1, du + 3);
  const int cv = UniformInt(rng, dv + 1, dv + 3);
  const Values plane = RandomValues(rng, 3, -2, 2);
  v1::FitScatteredSurfaceRequest request;
  request.mutable_points()->set_dimension(3);
  for (int k = 0; k < 4 * cu * cv; ++k) {
    const double x = Uniform(rng, 0, 1);
    const double y = Uniform(rng, 0, 1);
    AddValues(Values{x, y, plane[0] * x + plane[1] * y + plane[2]},
              request.mutable_points()->mutable_coordinates());
    AddValues(Values{x, y}, request.mutable_parameters());
  }
  request.set_degree_u(static_cast<uint32_t>(du));
  request.set_degree_v(static_cast<uint32_t>(dv));
  request.set_control_count_u(static_cast<uint32_t>(cu));
  request.set_control_count_v(static_cast<uint32_t>(cv));
  if (Coin(rng)) request.set_smoothing(Uniform(rng, 1e-9, 1e-3));
  Checker check(request, 4);
  absl::StatusOr<v1::FitScatteredSurfaceResponse> answer =
      client.FitScatteredSurface(request);
  if (answer.ok()) {
    check.True(answer->max_residual() <= 1e-9 * 4, "plane reproduced");
    const TensorShape fit = TensorShape::From(answer->surface().bspline());
    const double u = Uniform(rng, 0, 1);
    const double v = Uniform(rng, 0, 1);
    check.NearPoint(fit.At(u, v),
                    Values{u, v, plane[0] * u + plane[1] * v + plane[2]}, kBack,
                    "the plane", u);
  }
  return check.Result(answer.status());
}

}  // namespace

std::vector<RpcCase> ApproximationCases() {
  return {{"CurveService.RemoveKnots", false, RemoveCurveKnot},
          {"CurveService.Fit", false, FitCurve},
          {"SurfaceService.RemoveKnots", false, RemoveSurfaceKnot},
          {"SurfaceService.Fit", false, FitSurface},
          {"SurfaceService.FitScattered", false, FitScattered}};
}

}  // namespace freeform::reliability
