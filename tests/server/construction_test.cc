// The RPCs that build new geometry (degree elevation and reduction,
// interpolation) through the in-process server: results checked by
// evaluating them through the same server against the mathematics.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>

#include "in_process_server.h"

namespace freeform::server {
namespace {

using ::testing::DoubleNear;
using ::testing::Pointwise;
using ::testing::StartsWith;

class ConstructionTest : public InProcessServerTest {
 protected:
  // Points of `curve` (and first derivatives) at `count` uniform parameters
  // over its domain.
  std::vector<std::vector<double>> Sample(const v1::Curve& curve, int count) {
    v1::EvaluateCurveRequest request;
    *request.mutable_curve() = curve;
    request.mutable_parameters()->mutable_range()->set_count(
        static_cast<uint32_t>(count));
    request.set_derivative_order(1);
    absl::StatusOr<CurveSamples> samples = client_->EvaluateCurve(request);
    EXPECT_TRUE(samples.ok()) << samples.status();
    return samples.ok() ? samples->derivatives
                        : std::vector<std::vector<double>>();
  }

  std::vector<double> At(const v1::Curve& curve,
                         const std::vector<double>& params) {
    v1::EvaluateCurveRequest request;
    *request.mutable_curve() = curve;
    request.mutable_parameters()->mutable_list()->mutable_values()->Add(
        params.begin(), params.end());
    absl::StatusOr<CurveSamples> samples = client_->EvaluateCurve(request);
    EXPECT_TRUE(samples.ok()) << samples.status();
    return samples.ok() ? samples->derivatives[0] : std::vector<double>();
  }
};

// A quadratic elevated to a cubic has Q1 two thirds of the way from P0 to P1
// and Q2 one third of the way from P1 to P2; see
// 'Worked example: a quadratic Bezier curve elevated to a cubic' in
// docs/references.md.
TEST_F(ConstructionTest, ElevatesTheSeedsQuadratic) {
  v1::ElevateCurveDegreeRequest request;
  v1::Points* points =
      request.mutable_curve()->mutable_bezier()->mutable_control_points();
  points->set_dimension(2);
  Append(points->mutable_coordinates(), {0, 0, 3, 6, 6, 0});
  request.set_by(1);
  absl::StatusOr<v1::ElevateCurveDegreeResponse> elevated =
      client_->ElevateCurveDegree(request);
  ASSERT_TRUE(elevated.ok()) << elevated.status();
  const auto& q = elevated->curve().bezier().control_points().coordinates();
  EXPECT_THAT(std::vector<double>(q.begin(), q.end()),
              Pointwise(DoubleNear(1e-15),
                        std::vector<double>{0, 0, 2, 4, 4, 4, 6, 0}));
}

TEST_F(ConstructionTest, ElevatedBSplineIsTheSameCurve) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> uniform(-1, 1);
  v1::ElevateCurveDegreeRequest request;
  v1::BSplineCurve* bspline = request.mutable_curve()->mutable_bspline();
  bspline->set_degree(3);
  bspline->mutable_control_points()->set_dimension(3);
  for (int i = 0; i < 8 * 3; ++i) {
    bspline->mutable_control_points()->add_coordinates(uniform(rng));
  }
  Append(bspline->mutable_knots(),
         {0, 0, 0, 0, 0.2, 0.4, 0.4, 0.7, 1, 1, 1, 1});
  for (int i = 0; i < 8; ++i) bspline->add_weights(1.0 + 0.5 * uniform(rng));
  request.set_by(2);
  absl::StatusOr<v1::ElevateCurveDegreeResponse> elevated =
      client_->ElevateCurveDegree(request);
  ASSERT_TRUE(elevated.ok()) << elevated.status();
  EXPECT_EQ(elevated->curve().bspline().degree(), 5u);
  const auto original = Sample(request.curve(), 1001);
  const auto result = Sample(elevated->curve(), 1001);
  ASSERT_EQ(result.size(), 2u);
  EXPECT_THAT(result[0], Pointwise(DoubleNear(1e-12), original[0]));
  EXPECT_THAT(result[1], Pointwise(DoubleNear(1e-10), original[1]));

  request.set_by(0);
  ExpectInvalid(client_->ElevateCurveDegree(request).status(), "by", true);
  request.set_by(100);
  ExpectInvalid(client_->ElevateCurveDegree(request).status(), "by", true);
}

TEST_F(ConstructionTest, ReductionUndoesElevationAndBoundsItsError) {
  v1::ElevateCurveDegreeRequest elevate;
  v1::Points* points =
      elevate.mutable_curve()->mutable_bezier()->mutable_control_points();
  points->set_dimension(2);
  Append(points->mutable_coordinates(), {0, 0, 1, 3, 4, 2, 5, -1});
  elevate.set_by(2);
  absl::StatusOr<v1::ElevateCurveDegreeResponse> elevated =
      client_->ElevateCurveDegree(elevate);
  ASSERT_TRUE(elevated.ok()) << elevated.status();
  v1::ReduceCurveDegreeRequest reduce;
  *reduce.mutable_curve() = elevated->curve();
  reduce.set_by(2);
  absl::StatusOr<v1::ReduceCurveDegreeResponse> reduced =
      client_->ReduceCurveDegree(reduce);
  ASSERT_TRUE(reduced.ok()) << reduced.status();
  const auto& back = reduced->curve().bezier().control_points().coordinates();
  EXPECT_THAT(std::vector<double>(back.begin(), back.end()),
              Pointwise(DoubleNear(1e-12), points->coordinates()));
  EXPECT_LT(reduced->error_bound(), 1e-12);

  // A genuine cubic reduced to a quadratic: the bound holds.
  *reduce.mutable_curve() = elevate.curve();
  reduce.set_by(1);
  reduced = client_->ReduceCurveDegree(reduce);
  ASSERT_TRUE(reduced.ok()) << reduced.status();
  const auto original = Sample(reduce.curve(), 2001)[0];
  const auto approximation = Sample(reduced->curve(), 2001)[0];
  double distance = 0;
  for (size_t i = 0; i < original.size(); i += 2) {
    distance =
        std::max(distance, std::hypot(original[i] - approximation[i],
                                      original[i + 1] - approximation[i + 1]));
  }
  EXPECT_GT(distance, 0.0);
  EXPECT_GE(reduced->error_bound(), distance * (1 - 1e-12));

  reduce.set_by(0);
  ExpectInvalid(client_->ReduceCurveDegree(reduce).status(), "by", true);
}

TEST_F(ConstructionTest, ElevatedSurfacesAreTheSameSurfaces) {
  v1::ElevateSurfaceDegreeRequest request;
  v1::ControlNet* net =
      request.mutable_surface()->mutable_bezier()->mutable_control_net();
  net->set_dimension(3);
  net->set_count_u(3);
  net->set_count_v(3);
  Append(net->mutable_coordinates(), {0, 0, 0, 2, 0, 0, 4, 0, 0,  //
                                      0, 2, 0, 2, 2, 0, 4, 2, 2,  //
                                      0, 4, 0, 2, 4, 4, 4, 4, 4});
  request.set_by_u(1);
  request.set_by_v(2);
  absl::StatusOr<v1::ElevateSurfaceDegreeResponse> elevated =
      client_->ElevateSurfaceDegree(request);
  ASSERT_TRUE(elevated.ok()) << elevated.status();
  EXPECT_EQ(elevated->surface().bezier().control_net().count_u(), 4u);
  EXPECT_EQ(elevated->surface().bezier().control_net().count_v(), 5u);
  auto grid = [&](const v1::Surface& surface) {
    v1::EvaluateSurfaceRequest evaluate;
    *evaluate.mutable_surface() = surface;
    evaluate.mutable_parameters()
        ->mutable_grid()
        ->mutable_u()
        ->mutable_range()
        ->set_count(21);
    evaluate.mutable_parameters()
        ->mutable_grid()
        ->mutable_v()
        ->mutable_range()
        ->set_count(21);
    absl::StatusOr<SurfaceEvaluation> result =
        client_->EvaluateSurface(evaluate);
    EXPECT_TRUE(result.ok()) << result.status();
    return result->partials[0].values;
  };
  EXPECT_THAT(grid(elevated->surface()),
              Pointwise(DoubleNear(1e-13), grid(request.surface())));
  request.set_by_u(0);
  request.set_by_v(0);
  ExpectInvalid(client_->ElevateSurfaceDegree(request).status(), "by_u", true);
}

// The cubic through five planar points (docs/references.md,
// 'Worked example: a cubic B-spline through five planar points'):
// chord-length parameters 0, 5/17, 9/17, 14/17, 1 with the interior knot
// 28/51; the universal method puts the knot at 1/2 and the parameters at the
// maxima of the B-splines.
TEST_F(ConstructionTest, InterpolatesExerciseFive) {
  v1::InterpolateCurveRequest request;
  request.mutable_points()->set_dimension(2);
  Append(request.mutable_points()->mutable_coordinates(),
         {0, 0, 3, 4, -1, 4, -4, 0, -4, -3});
  request.mutable_bspline()->set_degree(3);
  request.mutable_bspline()->set_parameterization(
      v1::PARAMETERIZATION_CHORD_LENGTH);
  absl::StatusOr<v1::InterpolateCurveResponse> chord =
      client_->InterpolateCurve(request);
  ASSERT_TRUE(chord.ok()) << chord.status();
  EXPECT_THAT(
      std::vector<double>(chord->parameters().begin(),
                          chord->parameters().end()),
      Pointwise(DoubleNear(1e-15),
                std::vector<double>{0, 5.0 / 17, 9.0 / 17, 14.0 / 17, 1}));
  EXPECT_NEAR(chord->curve().bspline().knots(4), 28.0 / 51, 1e-15);
  const std::vector<double> points(request.points().coordinates().begin(),
                                   request.points().coordinates().end());
  EXPECT_THAT(
      At(chord->curve(), std::vector<double>(chord->parameters().begin(),
                                             chord->parameters().end())),
      Pointwise(DoubleNear(1e-12), points));

  request.mutable_bspline()->set_parameterization(
      v1::PARAMETERIZATION_UNIVERSAL);
  absl::StatusOr<v1::InterpolateCurveResponse> universal =
      client_->InterpolateCurve(request);
  ASSERT_TRUE(universal.ok()) << universal.status();
  EXPECT_NEAR(universal->curve().bspline().knots(4), 0.5, 1e-15);
  EXPECT_NEAR(universal->parameters(1), 0.226541, 1e-6);
  EXPECT_NEAR(universal->parameters(2), 0.5, 1e-12);
  EXPECT_NEAR(universal->parameters(3), 0.773459, 1e-6);
  EXPECT_THAT(At(universal->curve(),
                 std::vector<double>(universal->parameters().begin(),
                                     universal->parameters().end())),
              Pointwise(DoubleNear(1e-12), points));
}

TEST_F(ConstructionTest, CubicSplinesAndSurfaces) {
  // A natural spline has zero second derivative at both ends.
  v1::InterpolateCurveRequest spline;
  spline.mutable_points()->set_dimension(1);
  Append(spline.mutable_points()->mutable_coordinates(), {1, 3, 2, 5, 4});
  Append(spline.mutable_cubic_spline()->mutable_parameters(),
         {0, 1, 2.5, 3, 4});
  spline.mutable_cubic_spline()->set_end_condition(
      v1::SPLINE_END_CONDITION_NATURAL);
  absl::StatusOr<v1::InterpolateCurveResponse> natural =
      client_->InterpolateCurve(spline);
  ASSERT_TRUE(natural.ok()) << natural.status();
  v1::EvaluateCurveRequest ends;
  *ends.mutable_curve() = natural->curve();
  Append(ends.mutable_parameters()->mutable_list()->mutable_values(),
         {0, 1, 2.5, 3, 4});
  ends.set_derivative_order(2);
  absl::StatusOr<CurveSamples> values = client_->EvaluateCurve(ends);
  ASSERT_TRUE(values.ok()) << values.status();
  EXPECT_THAT(values->derivatives[0],
              Pointwise(DoubleNear(1e-13), std::vector<double>{1, 3, 2, 5, 4}));
  EXPECT_NEAR(values->derivatives[2][0], 0.0, 1e-12);
  EXPECT_NEAR(values->derivatives[2][4], 0.0, 1e-12);

  // A surface through a 4 x 5 grid.
  v1::InterpolateSurfaceRequest surface;
  v1::ControlNet* grid = surface.mutable_points();
  grid->set_dimension(3);
  grid->set_count_u(4);
  grid->set_count_v(5);
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 5; ++j) {
      Append(grid->mutable_coordinates(),
             {double(i), double(j), std::sin(i) * std::cos(j)});
    }
  }
  surface.set_degree_u(3);
  surface.set_degree_v(3);
  absl::StatusOr<v1::InterpolateSurfaceResponse> interpolated =
      client_->InterpolateSurface(surface);
  ASSERT_TRUE(interpolated.ok()) << interpolated.status();
  v1::EvaluateSurfaceRequest evaluate;
  *evaluate.mutable_surface() = interpolated->surface();
  v1::SurfaceGrid* at = evaluate.mutable_parameters()->mutable_grid();
  at->mutable_u()->mutable_list()->mutable_values()->Add(
      interpolated->parameters_u().begin(), interpolated->parameters_u().end());
  at->mutable_v()->mutable_list()->mutable_values()->Add(
      interpolated->parameters_v().begin(), interpolated->parameters_v().end());
  absl::StatusOr<SurfaceEvaluation> through =
      client_->EvaluateSurface(evaluate);
  ASSERT_TRUE(through.ok()) << through.status();
  EXPECT_THAT(through->partials[0].values,
              Pointwise(DoubleNear(1e-12),
                        std::vector<double>(grid->coordinates().begin(),
                                            grid->coordinates().end())));
}

TEST_F(ConstructionTest, InterpolationErrorsNameTheField) {
  v1::InterpolateCurveRequest request;
  request.mutable_points()->set_dimension(2);
  Append(request.mutable_points()->mutable_coordinates(),
         {0, 0, 1, 1, 1, 1, 2, 0, 3, 1});
  request.mutable_bspline()->set_degree(3);
  // Two equal consecutive points with chord length.
  ExpectInvalid(client_->InterpolateCurve(request).status(), "points", true);
  // Fewer points than degree + 1.
  request.mutable_points()->mutable_coordinates()->Truncate(6);
  ExpectInvalid(client_->InterpolateCurve(request).status(), "points", true);
  // Given parameters must increase.
  request.mutable_points()->clear_coordinates();
  Append(request.mutable_points()->mutable_coordinates(),
         {0, 0, 1, 1, 2, 0, 3, 1});
  Append(request.mutable_bspline()->mutable_parameters(), {0, 0.5, 0.4, 1});
  ExpectInvalid(client_->InterpolateCurve(request).status(),
                "bspline.parameters[2]", true);
}

}  // namespace
}  // namespace freeform::server
