// Knot removal, fitting and the OpenCASCADE interpolation rule through the
// in-process server, checked against the mathematics: a removed inserted
// knot gives the original curve back, every simplification and fit is
// measured by evaluating the results through the server, a scattered fit of
// samples of a spline recovers its control net (docs/references.md, 'Knot
// removal', 'Least-squares fitting to a tolerance', 'Scattered-data surface
// fitting', 'Interpolation with knots at the parameters (OpenCASCADE
// rule)').
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "in_process_server.h"

namespace freeform::server {
namespace {

using ::testing::DoubleNear;
using ::testing::ElementsAreArray;
using ::testing::Pointwise;

std::vector<double> Values(const google::protobuf::RepeatedField<double>& f) {
  return {f.begin(), f.end()};
}

void AppendAll(google::protobuf::RepeatedField<double>* field,
               const std::vector<double>& values) {
  field->Add(values.begin(), values.end());
}

class ApproximationServiceTest : public InProcessServerTest {
 protected:
  // Points of `curve` at `parameters` through CurveService.Evaluate.
  std::vector<double> CurvePoints(const v1::Curve& curve,
                                  const std::vector<double>& parameters) {
    v1::EvaluateCurveRequest request;
    *request.mutable_curve() = curve;
    AppendAll(request.mutable_parameters()->mutable_list()->mutable_values(),
              parameters);
    absl::StatusOr<CurveSamples> samples = client_->EvaluateCurve(request);
    EXPECT_TRUE(samples.ok()) << samples.status();
    return samples.ok() ? samples->derivatives[0] : std::vector<double>{};
  }

  // Points of `surface` at (u, v) pairs through SurfaceService.Evaluate.
  std::vector<double> SurfacePoints(const v1::Surface& surface,
                                    const std::vector<double>& uv) {
    v1::EvaluateSurfaceRequest request;
    *request.mutable_surface() = surface;
    AppendAll(request.mutable_parameters()->mutable_points()->mutable_uv(), uv);
    absl::StatusOr<SurfaceEvaluation> samples =
        client_->EvaluateSurface(request);
    EXPECT_TRUE(samples.ok()) << samples.status();
    return samples.ok() ? samples->partials[0].values : std::vector<double>{};
  }
};

// The largest distance between corresponding points of two point lists.
double MaxDistance(const std::vector<double>& a, const std::vector<double>& b,
                   int dimension) {
  EXPECT_EQ(a.size(), b.size());
  double largest = 0.0;
  for (size_t k = 0; k + dimension <= std::min(a.size(), b.size());
       k += dimension) {
    double sum = 0.0;
    for (int j = 0; j < dimension; ++j) {
      sum += (a[k + j] - b[k + j]) * (a[k + j] - b[k + j]);
    }
    largest = std::max(largest, std::sqrt(sum));
  }
  return largest;
}

std::vector<double> Linspace(double start, double end, int count) {
  std::vector<double> values(count);
  for (int k = 0; k < count; ++k) {
    values[k] = start + (end - start) * k / (count - 1);
  }
  values.back() = end;
  return values;
}

// A planar cubic B-spline with two interior knots on [0, 3].
v1::Curve Cubic() {
  v1::Curve curve;
  v1::BSplineCurve* bspline = curve.mutable_bspline();
  bspline->set_degree(3);
  bspline->mutable_control_points()->set_dimension(2);
  Append(bspline->mutable_control_points()->mutable_coordinates(),
         {0, 0, 1, 2, 2, -1, 3, 3, 4, 0, 5, 1});
  Append(bspline->mutable_knots(), {0, 0, 0, 0, 1, 2, 3, 3, 3, 3});
  return curve;
}

// The NURBS circle of examples/nurbs_circle.json.
v1::Curve Circle() {
  v1::Curve curve;
  v1::BSplineCurve* bspline = curve.mutable_bspline();
  bspline->set_degree(2);
  bspline->mutable_control_points()->set_dimension(2);
  Append(bspline->mutable_control_points()->mutable_coordinates(),
         {1, 0, 1, 1, 0, 1, -1, 1, -1, 0, -1, -1, 0, -1, 1, -1, 1, 0});
  Append(bspline->mutable_knots(),
         {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1});
  const double h = std::sqrt(0.5);
  Append(bspline->mutable_weights(), {1, h, 1, h, 1, h, 1, h, 1});
  return curve;
}

// Knot insertion followed by removal of the same knot is the identity
// (Tiller's removal solves the insertion's equations backwards).
TEST_F(ApproximationServiceTest, RemovingAnInsertedKnotGivesTheCurveBack) {
  for (auto [curve, knot] :
       {std::pair{Cubic(), 1.5}, std::pair{Circle(), 0.6}}) {
    v1::InsertKnotsRequest insert;
    *insert.mutable_curve() = curve;
    insert.add_knots(knot);
    absl::StatusOr<v1::InsertKnotsResponse> refined =
        client_->InsertCurveKnots(insert);
    ASSERT_TRUE(refined.ok()) << refined.status();
    v1::RemoveCurveKnotsRequest remove;
    *remove.mutable_curve() = refined->curve();
    remove.set_tolerance(1e-9);
    remove.set_knot(knot);
    absl::StatusOr<v1::RemoveCurveKnotsResponse> removed =
        client_->RemoveCurveKnots(remove);
    ASSERT_TRUE(removed.ok()) << removed.status();
    EXPECT_EQ(removed->removals(), 1u);
    EXPECT_LE(removed->error_bound(), 1e-9);
    const v1::BSplineCurve& got = removed->curve().bspline();
    EXPECT_THAT(Values(got.knots()), ElementsAreArray(curve.bspline().knots()));
    EXPECT_THAT(
        Values(got.control_points().coordinates()),
        Pointwise(DoubleNear(1e-12),
                  Values(curve.bspline().control_points().coordinates())));
    EXPECT_THAT(
        Values(got.weights()),
        Pointwise(DoubleNear(1e-12), Values(curve.bspline().weights())));
  }
}

// Simplifying a curve interpolated through samples of a sine: the distance
// between the input and the result, measured at 2001 parameters, is within
// the certified bound, which is within the tolerance.
TEST_F(ApproximationServiceTest, SimplifiesWithinTheTolerance) {
  v1::InterpolateCurveRequest interpolate;
  interpolate.mutable_points()->set_dimension(2);
  for (double x : Linspace(0, 2 * std::numbers::pi, 40)) {
    Append(interpolate.mutable_points()->mutable_coordinates(),
           {x, std::sin(x)});
  }
  interpolate.mutable_bspline()->set_degree(3);
  absl::StatusOr<v1::InterpolateCurveResponse> wave =
      client_->InterpolateCurve(interpolate);
  ASSERT_TRUE(wave.ok()) << wave.status();
  constexpr double kTolerance = 1e-3;
  v1::RemoveCurveKnotsRequest simplify;
  *simplify.mutable_curve() = wave->curve();
  simplify.set_tolerance(kTolerance);
  absl::StatusOr<v1::RemoveCurveKnotsResponse> simplified =
      client_->RemoveCurveKnots(simplify);
  ASSERT_TRUE(simplified.ok()) << simplified.status();
  EXPECT_GT(simplified->removals(), 10u);
  EXPECT_EQ(simplified->curve().bspline().knots_size() +
                static_cast<int>(simplified->removals()),
            wave->curve().bspline().knots_size());
  EXPECT_LE(simplified->error_bound(), kTolerance);
  const std::vector<double> t = Linspace(0, 1, 2001);
  const double measured = MaxDistance(CurvePoints(wave->curve(), t),
                                      CurvePoints(simplified->curve(), t), 2);
  EXPECT_LE(measured, simplified->error_bound() + 1e-15);
  EXPECT_GT(measured, 0.0);
}

// Points sampled from a known cubic are fitted within the tolerance: the
// returned curve, evaluated through the server at the returned parameters,
// is within the tolerance of every point, and its largest distance is the
// reported max_residual.
TEST_F(ApproximationServiceTest, FitsPointsSampledFromACurve) {
  const v1::Curve cubic = Cubic();
  const std::vector<double> samples = CurvePoints(cubic, Linspace(0, 3, 300));
  for (uint32_t corrections : {0u, 2u}) {
    v1::FitCurveRequest request;
    request.mutable_points()->set_dimension(2);
    AppendAll(request.mutable_points()->mutable_coordinates(), samples);
    request.set_degree(3);
    request.set_tolerance(1e-4);
    request.set_parameter_corrections(corrections);
    absl::StatusOr<v1::FitCurveResponse> fit = client_->FitCurve(request);
    ASSERT_TRUE(fit.ok()) << fit.status();
    EXPECT_LE(fit->max_residual(), 1e-4);
    EXPECT_LE(fit->rms_residual(), fit->max_residual());
    ASSERT_EQ(fit->parameters_size(), 300);
    const double measured = MaxDistance(
        CurvePoints(fit->curve(), Values(fit->parameters())), samples, 2);
    EXPECT_LE(measured, 1e-4);
    EXPECT_NEAR(measured, fit->max_residual(), 1e-12);
    // The ends are interpolated.
    EXPECT_THAT(
        Values(fit->curve().bspline().control_points().coordinates()).front(),
        DoubleNear(0.0, 1e-12));
  }
}

// The cap on the control points: reached before the tolerance, the fit is
// RESOURCE_EXHAUSTED naming the tolerance.
TEST_F(ApproximationServiceTest, FitRefusesATooSmallCap) {
  v1::FitCurveRequest request;
  request.mutable_points()->set_dimension(2);
  AppendAll(request.mutable_points()->mutable_coordinates(),
            CurvePoints(Cubic(), Linspace(0, 3, 100)));
  request.set_degree(3);
  request.set_tolerance(1e-9);
  request.set_max_control_points(4);
  const absl::Status status = client_->FitCurve(request).status();
  EXPECT_EQ(status.code(), absl::StatusCode::kResourceExhausted) << status;
}

// The plan refuses work over the server's limits before it starts, naming
// the field: a scattered fit whose band does not fit the memory budget, a
// control-point cap over the server's point limit.
TEST_F(ApproximationServiceTest, PlansRefuseWorkOverTheLimits) {
  ServiceLimits limits;
  limits.memory_budget_bytes = 4 << 20;
  limits.max_control_points = 1000;
  StartServer(limits);
  v1::FitScatteredSurfaceRequest scattered;
  scattered.mutable_points()->set_dimension(3);
  Append(scattered.mutable_points()->mutable_coordinates(),
         {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 1, 0.5, 0.5, 0.2});
  scattered.set_degree_u(3);
  scattered.set_degree_v(3);
  // 1001 control points in u are over the point limit.
  scattered.set_control_count_u(1001);
  scattered.set_control_count_v(1);
  absl::Status status = client_->FitScatteredSurface(scattered).status();
  EXPECT_EQ(status.code(), absl::StatusCode::kResourceExhausted) << status;
  ASSERT_EQ(FieldViolationsOf(status).size(), 1u) << status;
  EXPECT_EQ(FieldViolationsOf(status)[0].field, "control_count_u");
  // 30 x 30 unknowns in a band of about 3 x 30 + 3 take about 670 kB, over
  // what calls may reserve of a 64 kB budget (3/4 of it), whatever the
  // points.
  scattered.set_control_count_u(30);
  scattered.set_control_count_v(30);
  limits.memory_budget_bytes = 64 << 10;
  StartServer(limits);
  status = client_->FitScatteredSurface(scattered).status();
  EXPECT_EQ(status.code(), absl::StatusCode::kResourceExhausted) << status;
  ASSERT_EQ(FieldViolationsOf(status).size(), 1u) << status;
  EXPECT_EQ(FieldViolationsOf(status)[0].field, "control_count_u");

  v1::FitCurveRequest fit;
  fit.mutable_points()->set_dimension(1);
  Append(fit.mutable_points()->mutable_coordinates(), {0, 1, 4, 9, 16});
  fit.set_degree(2);
  fit.set_tolerance(1e-3);
  fit.set_max_control_points(1001);
  status = client_->FitCurve(fit).status();
  EXPECT_EQ(status.code(), absl::StatusCode::kResourceExhausted) << status;
  ASSERT_EQ(FieldViolationsOf(status).size(), 1u) << status;
  EXPECT_EQ(FieldViolationsOf(status)[0].field, "max_control_points");
}

// The Greville abscissae (t_{i+1} + ... + t_{i+p}) / p of the knots of a
// degree-p B-spline: control points there reproduce linear functions.
std::vector<double> Greville(const google::protobuf::RepeatedField<double>& t,
                             int p) {
  std::vector<double> abscissae;
  for (int i = 0; i + p + 1 < t.size(); ++i) {
    double sum = 0.0;
    for (int k = 1; k <= p; ++k) sum += t[i + k];
    abscissae.push_back(sum / p);
  }
  return abscissae;
}

// Simplification moves the values after each removed knot: its work grows
// with the square of the size, and the plan refuses it beyond
// max_simplify_moves, naming the net, while removing one knot is not
// limited.
TEST_F(ApproximationServiceTest, SimplifyWorkIsBoundedByThePlan) {
  ServiceLimits limits;
  // A planar cubic of 100 control points: 96 interior knots x 200 values
  // = 19,200 moves.
  limits.max_simplify_moves = 19'199;
  StartServer(limits);
  v1::RemoveCurveKnotsRequest curve_request;
  v1::BSplineCurve* curve = curve_request.mutable_curve()->mutable_bspline();
  curve->set_degree(3);
  curve->mutable_control_points()->set_dimension(2);
  Append(curve->mutable_knots(), {0, 0, 0});
  AppendAll(curve->mutable_knots(), Linspace(0, 1, 98));
  Append(curve->mutable_knots(), {1, 1, 1});
  // At the Greville abscissae the control points give the line C(t) = (t, 0)
  // (linear precision), from which every interior knot can go.
  for (const double x : Greville(curve->knots(), 3)) {
    Append(curve->mutable_control_points()->mutable_coordinates(), {x, 0.0});
  }
  curve_request.set_tolerance(1e-9);
  absl::Status status = client_->RemoveCurveKnots(curve_request).status();
  EXPECT_EQ(status.code(), absl::StatusCode::kResourceExhausted) << status;
  ASSERT_EQ(FieldViolationsOf(status).size(), 1u) << status;
  EXPECT_EQ(FieldViolationsOf(status)[0].field, "curve.bspline.control_points");
  curve_request.set_knot(curve->knots(50));
  EXPECT_TRUE(client_->RemoveCurveKnots(curve_request).ok());
  limits.max_simplify_moves = 19'200;
  StartServer(limits);
  curve_request.clear_knot();
  absl::StatusOr<v1::RemoveCurveKnotsResponse> simplified =
      client_->RemoveCurveKnots(curve_request);
  ASSERT_TRUE(simplified.ok()) << simplified.status();
  // A straight segment keeps no interior knot.
  EXPECT_EQ(simplified->removals(), 96u);

  // A bicubic net of 10 x 20 points in 3-D: 6 + 16 interior knots x 600
  // values; both directions are over a limit of 13,199, v alone (9,600)
  // is not.
  v1::RemoveSurfaceKnotsRequest surface_request;
  v1::BSplineSurface* surface =
      surface_request.mutable_surface()->mutable_bspline();
  surface->set_degree_u(3);
  surface->set_degree_v(3);
  v1::ControlNet* net = surface->mutable_control_net();
  net->set_count_u(10);
  net->set_count_v(20);
  net->set_dimension(3);
  Append(surface->mutable_knots_u(), {0, 0, 0});
  AppendAll(surface->mutable_knots_u(), Linspace(0, 1, 8));
  Append(surface->mutable_knots_u(), {1, 1, 1});
  Append(surface->mutable_knots_v(), {0, 0, 0});
  AppendAll(surface->mutable_knots_v(), Linspace(0, 1, 18));
  Append(surface->mutable_knots_v(), {1, 1, 1});
  // The plane S(u, v) = (u, v, 0).
  for (const double x : Greville(surface->knots_u(), 3)) {
    for (const double y : Greville(surface->knots_v(), 3)) {
      Append(net->mutable_coordinates(), {x, y, 0.0});
    }
  }
  surface_request.set_tolerance(1e-9);
  surface_request.set_direction(v1::SURFACE_DIRECTION_BOTH);
  limits.max_simplify_moves = 13'199;
  StartServer(limits);
  status = client_->RemoveSurfaceKnots(surface_request).status();
  EXPECT_EQ(status.code(), absl::StatusCode::kResourceExhausted) << status;
  ASSERT_EQ(FieldViolationsOf(status).size(), 1u) << status;
  EXPECT_EQ(FieldViolationsOf(status)[0].field, "surface.bspline.control_net");
  surface_request.set_direction(v1::SURFACE_DIRECTION_V);
  absl::StatusOr<v1::RemoveSurfaceKnotsResponse> simplified_v =
      client_->RemoveSurfaceKnots(surface_request);
  ASSERT_TRUE(simplified_v.ok()) << simplified_v.status();
  EXPECT_EQ(simplified_v->removals_v(), 16u);
}

// A bicubic B-spline on the clamped uniform knots 0, 0, 0, 0, 1/2, 1, 1, 1,
// 1 sampled at 400 parameter pairs: the scattered fit of the same degrees
// and control counts without smoothing is that spline (a least-squares fit
// reproduces whatever lies in its space).
TEST_F(ApproximationServiceTest, ScatteredFitRecoversASpline) {
  v1::Surface surface;
  v1::BSplineSurface* bspline = surface.mutable_bspline();
  bspline->set_degree_u(3);
  bspline->set_degree_v(3);
  v1::ControlNet* net = bspline->mutable_control_net();
  net->set_dimension(3);
  net->set_count_u(5);
  net->set_count_v(5);
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 5; ++j) {
      Append(net->mutable_coordinates(),
             {i / 4.0, j / 4.0, std::sin(1.0 + i * 0.7) * std::cos(j * 1.3)});
    }
  }
  Append(bspline->mutable_knots_u(), {0, 0, 0, 0, 0.5, 1, 1, 1, 1});
  Append(bspline->mutable_knots_v(), {0, 0, 0, 0, 0.5, 1, 1, 1, 1});
  std::vector<double> uv;
  for (int k = 0; k < 400; ++k) {
    // A low-discrepancy (Kronecker) sequence covers the square.
    uv.push_back(std::fmod(0.5 + k * 0.6180339887498949, 1.0));
    uv.push_back(std::fmod(0.5 + k * 0.7548776662466927, 1.0));
  }
  v1::FitScatteredSurfaceRequest request;
  request.mutable_points()->set_dimension(3);
  AppendAll(request.mutable_points()->mutable_coordinates(),
            SurfacePoints(surface, uv));
  request.set_degree_u(3);
  request.set_degree_v(3);
  request.set_control_count_u(5);
  request.set_control_count_v(5);
  AppendAll(request.mutable_parameters(), uv);
  request.set_smoothing(0.0);
  absl::StatusOr<v1::FitScatteredSurfaceResponse> fit =
      client_->FitScatteredSurface(request);
  ASSERT_TRUE(fit.ok()) << fit.status();
  EXPECT_LE(fit->max_residual(), 1e-10);
  ASSERT_EQ(fit->residuals_size(), 400);
  EXPECT_THAT(Values(fit->surface().bspline().knots_u()),
              Pointwise(DoubleNear(1e-15), Values(bspline->knots_u())));
  EXPECT_THAT(Values(fit->surface().bspline().control_net().coordinates()),
              Pointwise(DoubleNear(1e-9), Values(net->coordinates())));
}

// z = x y on a 5 x 4 grid at uniform parameters is a bilinear patch, so
// the biquadratic fit is exact from the first round; evaluated through the
// server on the grid of its parameters it meets every data point.
TEST_F(ApproximationServiceTest, GridFitMeetsItsPoints) {
  v1::FitSurfaceRequest request;
  v1::ControlNet* grid = request.mutable_points();
  grid->set_dimension(3);
  grid->set_count_u(5);
  grid->set_count_v(4);
  for (double x : Linspace(0, 1, 5)) {
    for (double y : Linspace(0, 1, 4)) {
      Append(grid->mutable_coordinates(), {x, y, x * y});
    }
  }
  request.set_degree_u(2);
  request.set_degree_v(2);
  request.set_tolerance(1e-6);
  request.set_parameterization(v1::PARAMETERIZATION_UNIFORM);
  absl::StatusOr<v1::FitSurfaceResponse> fit = client_->FitSurface(request);
  ASSERT_TRUE(fit.ok()) << fit.status();
  EXPECT_EQ(fit->refinement_rounds(), 0u);
  EXPECT_LE(fit->max_residual(), 1e-12);
  EXPECT_THAT(Values(fit->parameters_u()),
              Pointwise(DoubleNear(1e-15), Linspace(0, 1, 5)));
  std::vector<double> uv;
  for (double u : fit->parameters_u()) {
    for (double v : fit->parameters_v()) {
      uv.insert(uv.end(), {u, v});
    }
  }
  EXPECT_LE(MaxDistance(SurfacePoints(fit->surface(), uv),
                        Values(grid->coordinates()), 3),
            1e-12);
}

// A knot inserted in v is removed again from every row: the surface comes
// back; the simplification of examples/simplify_surface.json removes its
// one u knot, which carries no shape.
TEST_F(ApproximationServiceTest, RemovesSurfaceKnots) {
  v1::Surface surface;
  v1::BSplineSurface* bspline = surface.mutable_bspline();
  bspline->set_degree_u(1);
  bspline->set_degree_v(2);
  v1::ControlNet* net = bspline->mutable_control_net();
  net->set_dimension(3);
  net->set_count_u(2);
  net->set_count_v(3);
  Append(net->mutable_coordinates(),
         {0, 0, 0, 0, 1, 1, 0, 2, 0, 1, 0, 1, 1, 1, 2, 1, 2, 0});
  Append(bspline->mutable_knots_u(), {0, 0, 1, 1});
  Append(bspline->mutable_knots_v(), {0, 0, 0, 1, 1, 1});
  v1::InsertSurfaceKnotsRequest insert;
  *insert.mutable_surface() = surface;
  insert.set_direction(v1::SURFACE_DIRECTION_V);
  insert.add_knots(0.25);
  absl::StatusOr<v1::InsertSurfaceKnotsResponse> refined =
      client_->InsertSurfaceKnots(insert);
  ASSERT_TRUE(refined.ok()) << refined.status();
  v1::RemoveSurfaceKnotsRequest remove;
  *remove.mutable_surface() = refined->surface();
  remove.set_direction(v1::SURFACE_DIRECTION_V);
  remove.set_tolerance(1e-9);
  remove.set_knot(0.25);
  absl::StatusOr<v1::RemoveSurfaceKnotsResponse> removed =
      client_->RemoveSurfaceKnots(remove);
  ASSERT_TRUE(removed.ok()) << removed.status();
  EXPECT_EQ(removed->removals_u(), 0u);
  EXPECT_EQ(removed->removals_v(), 1u);
  EXPECT_THAT(Values(removed->surface().bspline().knots_v()),
              ElementsAreArray(bspline->knots_v()));
  EXPECT_THAT(Values(removed->surface().bspline().control_net().coordinates()),
              Pointwise(DoubleNear(1e-12), Values(net->coordinates())));

  // Simplify both directions: the u knot 1/2 of a linear net whose middle
  // row is the average of its neighbours goes, the v direction has none.
  v1::RemoveSurfaceKnotsRequest simplify;
  v1::BSplineSurface* flat = simplify.mutable_surface()->mutable_bspline();
  flat->set_degree_u(1);
  flat->set_degree_v(1);
  flat->mutable_control_net()->set_dimension(3);
  flat->mutable_control_net()->set_count_u(3);
  flat->mutable_control_net()->set_count_v(2);
  Append(flat->mutable_control_net()->mutable_coordinates(),
         {0, 0, 0, 0, 1, 0, 0.5, 0, 0.5, 0.5, 1, 0.5, 1, 0, 1, 1, 1, 1});
  Append(flat->mutable_knots_u(), {0, 0, 0.5, 1, 1});
  Append(flat->mutable_knots_v(), {0, 0, 1, 1});
  simplify.set_direction(v1::SURFACE_DIRECTION_BOTH);
  simplify.set_tolerance(1e-9);
  absl::StatusOr<v1::RemoveSurfaceKnotsResponse> simplified =
      client_->RemoveSurfaceKnots(simplify);
  ASSERT_TRUE(simplified.ok()) << simplified.status();
  EXPECT_EQ(simplified->removals_u(), 1u);
  EXPECT_EQ(simplified->removals_v(), 0u);
  EXPECT_THAT(Values(simplified->surface().bspline().knots_u()),
              ElementsAreArray({0.0, 0.0, 1.0, 1.0}));
  EXPECT_THAT(
      Values(simplified->surface().bspline().control_net().coordinates()),
      Pointwise(DoubleNear(1e-12),
                std::vector<double>{0, 0, 0, 0, 1, 0, 1, 0, 1, 1, 1, 1}));
}

// KNOT_RULE_AT_PARAMETERS: the knots are the normalized chord-length
// parameters (t_0 and t_4 four times, t_1..t_3 once) and the cubic passes
// through the points there.
TEST_F(ApproximationServiceTest, KnotsAtTheParameters) {
  const std::vector<double> points = {0, 0, 3, 4, 6, 0, 6, 5, 0, 5};
  // Chords 5, 5, 5, 6: parameters 0, 5, 10, 15, 21 over 21.
  const std::vector<double> t = {0, 5 / 21.0, 10 / 21.0, 15 / 21.0, 1};
  v1::InterpolateCurveRequest request;
  request.mutable_points()->set_dimension(2);
  AppendAll(request.mutable_points()->mutable_coordinates(), points);
  request.mutable_bspline()->set_degree(3);
  request.mutable_bspline()->set_knot_rule(v1::KNOT_RULE_AT_PARAMETERS);
  absl::StatusOr<v1::InterpolateCurveResponse> curve =
      client_->InterpolateCurve(request);
  ASSERT_TRUE(curve.ok()) << curve.status();
  EXPECT_THAT(Values(curve->parameters()), Pointwise(DoubleNear(1e-15), t));
  EXPECT_THAT(
      Values(curve->curve().bspline().knots()),
      Pointwise(DoubleNear(1e-15),
                std::vector<double>{0, 0, 0, 0, t[1], t[2], t[3], 1, 1, 1, 1}));
  EXPECT_EQ(curve->curve().bspline().control_points().coordinates_size(), 14);
  EXPECT_LE(MaxDistance(CurvePoints(curve->curve(), t), points, 2), 1e-12);

  // Scaled end derivatives keep the given directions.
  request.mutable_bspline()->mutable_start_derivative()->set_dimension(2);
  Append(request.mutable_bspline()
             ->mutable_start_derivative()
             ->mutable_coordinates(),
         {0, 1});
  request.mutable_bspline()->set_scale_end_derivatives(true);
  absl::StatusOr<v1::InterpolateCurveResponse> scaled =
      client_->InterpolateCurve(request);
  ASSERT_TRUE(scaled.ok()) << scaled.status();
  const std::vector<double> control =
      Values(scaled->curve().bspline().control_points().coordinates());
  // P_1 - P_0 = (t_1 - t_0) D / 3 is along (0, 1).
  EXPECT_NEAR(control[2] - control[0], 0.0, 1e-12);
  EXPECT_GT(control[3] - control[1], 0.0);

  request.mutable_bspline()->set_knot_rule(v1::KNOT_RULE_AVERAGING);
  ExpectInvalid(client_->InterpolateCurve(request).status(),
                "bspline.scale_end_derivatives");

  // The rule is for curves: a grid has no end tangents to give.
  v1::InterpolateSurfaceRequest grid;
  grid.mutable_points()->set_dimension(1);
  grid.mutable_points()->set_count_u(4);
  grid.mutable_points()->set_count_v(4);
  for (int k = 0; k < 16; ++k) {
    grid.mutable_points()->add_coordinates(k * k);
  }
  grid.set_degree_u(3);
  grid.set_degree_v(3);
  grid.set_knot_rule(v1::KNOT_RULE_AT_PARAMETERS);
  ExpectInvalid(client_->InterpolateSurface(grid).status(), "knot_rule");
}

TEST_F(ApproximationServiceTest, ErrorsNameTheirFields) {
  v1::RemoveCurveKnotsRequest remove;
  *remove.mutable_curve() = Cubic();
  remove.set_tolerance(0.0);
  ExpectInvalid(client_->RemoveCurveKnots(remove).status(), "tolerance");
  remove.set_tolerance(1e-6);
  remove.set_knot(1.5);
  ExpectInvalid(client_->RemoveCurveKnots(remove).status(), "knot");
  remove.clear_knot();
  remove.set_times(2);
  ExpectInvalid(client_->RemoveCurveKnots(remove).status(), "times");
  remove.set_times(0);
  remove.mutable_curve()->mutable_bspline()->add_weights(1.0);
  ExpectInvalid(client_->RemoveCurveKnots(remove).status(),
                "curve.bspline.weights", true);

  v1::FitCurveRequest fit;
  fit.mutable_points()->set_dimension(1);
  Append(fit.mutable_points()->mutable_coordinates(), {0, 1, 4, 9, 16});
  fit.set_degree(2);
  fit.set_tolerance(-1.0);
  ExpectInvalid(client_->FitCurve(fit).status(), "tolerance");
  fit.set_tolerance(1e-3);
  fit.set_parameterization(static_cast<v1::Parameterization>(99));
  ExpectInvalid(client_->FitCurve(fit).status(), "parameterization");
  fit.set_parameterization(v1::PARAMETERIZATION_UNIFORM);
  fit.set_parameter_corrections(101);
  ExpectInvalid(client_->FitCurve(fit).status(), "parameter_corrections");

  v1::FitScatteredSurfaceRequest scattered;
  scattered.mutable_points()->set_dimension(3);
  Append(scattered.mutable_points()->mutable_coordinates(),
         {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 1, 0.5, 0.5, 0.2});
  scattered.set_degree_u(1);
  scattered.set_degree_v(1);
  scattered.set_control_count_u(3);
  scattered.set_control_count_v(2);
  ExpectInvalid(client_->FitScatteredSurface(scattered).status(), "points");

  v1::FitSurfaceRequest grid;
  grid.mutable_points()->set_dimension(1);
  grid.mutable_points()->set_count_u(2);
  grid.mutable_points()->set_count_v(2);
  Append(grid.mutable_points()->mutable_coordinates(), {0, 1, 2, 3});
  grid.set_degree_u(1);
  grid.set_degree_v(1);
  grid.set_tolerance(0.0);
  ExpectInvalid(client_->FitSurface(grid).status(), "tolerance");

  v1::RemoveSurfaceKnotsRequest surface;
  v1::BSplineSurface* bspline = surface.mutable_surface()->mutable_bspline();
  bspline->set_degree_u(1);
  bspline->set_degree_v(1);
  bspline->mutable_control_net()->set_dimension(1);
  bspline->mutable_control_net()->set_count_u(2);
  bspline->mutable_control_net()->set_count_v(2);
  Append(bspline->mutable_control_net()->mutable_coordinates(), {0, 1, 2, 3});
  Append(bspline->mutable_knots_u(), {0, 0, 1, 1});
  Append(bspline->mutable_knots_v(), {0, 0, 1, 1});
  surface.set_tolerance(1e-6);
  surface.set_direction(static_cast<v1::SurfaceDirection>(99));
  ExpectInvalid(client_->RemoveSurfaceKnots(surface).status(), "direction");
  surface.set_direction(v1::SURFACE_DIRECTION_BOTH);
  surface.set_knot(0.5);
  ExpectInvalid(client_->RemoveSurfaceKnots(surface).status(), "direction");
  surface.set_direction(v1::SURFACE_DIRECTION_U);
  ExpectInvalid(client_->RemoveSurfaceKnots(surface).status(), "knot");
}

}  // namespace
}  // namespace freeform::server
