// Least-squares fitting (fitting.h): curves and gridded surfaces to a
// tolerance, scattered-point surfaces, and the internal banded Cholesky
// and Jacobi eigen-solver they use. Known splines and polynomials are
// reproduced; noisy data are fitted within the noise.
#include "freeform/core/fitting.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "freeform/core/bspline.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/geometry_data.h"
#include "freeform/core/interpolation.h"
#include "freeform/core/status.h"
#include "freeform/core/surface_output.h"
#include "freeform/core/tensor_surface.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "linalg/banded_cholesky.h"
#include "linalg/symmetric_eigen.h"
#include "test_util.h"

namespace freeform {
namespace {

using ::testing::HasSubstr;
using testing_util::EvenlySpaced;
using testing_util::RandomValues;

void ExpectField(const absl::Status& status, const std::string& field,
                 absl::StatusCode code = absl::StatusCode::kInvalidArgument) {
  EXPECT_EQ(status.code(), code) << status;
  EXPECT_EQ(FieldPathOf(status).value_or(""), field) << status;
}

std::vector<double> EvaluateCurve(const BSplineCurveData& curve,
                                  absl::Span<const double> t) {
  std::vector<double> values(t.size() * static_cast<size_t>(curve.dimension));
  const std::vector<absl::Span<double>> output = {absl::MakeSpan(values)};
  EXPECT_TRUE(EvaluateBSplineCurve(curve.view(), t, output).ok());
  return values;
}

std::vector<double> EvaluateSurface(const SurfaceData& surface,
                                    const SurfaceSamples& samples) {
  std::vector<double> values(samples.size() *
                             static_cast<size_t>(surface.dimension));
  const std::vector<absl::Span<double>> output = {absl::MakeSpan(values)};
  EXPECT_TRUE(
      EvaluateBSplineSurface(surface.bspline_view(), samples, output).ok());
  return values;
}

// Largest distance between corresponding points of two arrays.
double MaxDistance(absl::Span<const double> a, absl::Span<const double> b,
                   size_t dimension) {
  double max = 0;
  for (size_t k = 0; k * dimension < a.size(); ++k) {
    double sum = 0;
    for (size_t c = 0; c < dimension; ++c) {
      const double d = a[k * dimension + c] - b[k * dimension + c];
      sum += d * d;
    }
    max = std::max(max, std::sqrt(sum));
  }
  return max;
}

double MaxDifference(absl::Span<const double> a, absl::Span<const double> b) {
  return MaxDistance(a, b, 1);
}

// A cubic space curve with 9 control points and uneven knots.
BSplineCurveData KnownCurve() {
  return {.degree = 3,
          .dimension = 3,
          .coordinates = {0, 0, 0, 1,   2, 0.5, 2, 3, -0.5, 3,  1, 1, 4, -1,
                          0, 5, 0, 1.5, 6, 2,   1, 7, 1,    -1, 8, 0, 0},
          .knots = {0, 0, 0, 0, 0.15, 0.3, 0.45, 0.6, 0.8, 1, 1, 1, 1},
          .weights = {}};
}

// ---------------------------------------------------------- curves --

TEST(FitCurve, NoisySamplesMeetTheToleranceAndStayNearTheCurve) {
  const BSplineCurveData known = KnownCurve();
  const size_t count = 100000;
  const std::vector<double> t = EvenlySpaced(0, 1, count);
  std::vector<double> points = EvaluateCurve(known, t);
  std::mt19937_64 rng(20240611);
  const double noise = 1e-4;  // per coordinate
  const std::vector<double> offsets =
      RandomValues(rng, points.size(), -noise, noise);
  for (size_t i = 0; i < points.size(); ++i) points[i] += offsets[i];
  const double tolerance = 5e-4;
  absl::StatusOr<CurveFit> fit =
      FitCurve({.dimension = 3, .coordinates = points},
               {.degree = 3, .tolerance = tolerance, .parameters = t});
  ASSERT_TRUE(fit.ok()) << fit.status();
  EXPECT_LE(fit->max_residual, tolerance);
  // The residual measured again by the evaluator.
  EXPECT_LE(MaxDistance(EvaluateCurve(fit->curve, fit->parameters), points, 3),
            tolerance * (1 + 1e-12));
  // rms of uniform noise in [-a, a]^3 is a; the fit leaves about that.
  EXPECT_LT(fit->rms_residual, 1.5 * noise);
  EXPECT_GT(fit->rms_residual, 0.9 * noise);
  // Near the curve itself: within the noise (|offset| <= sqrt(3) a) plus
  // the tolerance at 10^4 parameters.
  const std::vector<double> s = EvenlySpaced(0, 1, 10000);
  EXPECT_LE(
      MaxDistance(EvaluateCurve(fit->curve, s), EvaluateCurve(known, s), 3),
      std::sqrt(3.0) * noise + tolerance);
  // Few control points, and a number of rounds logarithmic in them.
  const size_t controls = fit->curve.coordinates.size() / 3;
  EXPECT_LE(controls, 80u);
  EXPECT_LE(fit->refinement_rounds,
            static_cast<int>(std::ceil(std::log2(controls))) + 2);
  EXPECT_EQ(fit->curve.knots.front(), 0.0);
  EXPECT_EQ(fit->curve.knots.back(), 1.0);
}

// 1024 parameters k / 1023: the first split of [0, 1] is halfway between
// t_511 and t_512, i.e. 1/2; the next ones between t_255 and t_256 and
// between t_767 and t_768.
TEST(FitCurve, ReproducesSplinesWithTheKnotsOfTheRefinement) {
  const std::vector<double> t = EvenlySpaced(0, 1, 1024);
  // The knot between the parameters a - 1 and a, by the documented rule.
  const auto split = [&](size_t a) {
    return t[a - 1] + 0.5 * (t[a] - t[a - 1]);
  };
  const BSplineCurveData one_knot = {
      .degree = 3,
      .dimension = 2,
      .coordinates = {0, 0, 1, 3, 2, -1, 4, 2, 5, 0},
      .knots = {0, 0, 0, 0, split(512), 1, 1, 1, 1},
      .weights = {}};
  EXPECT_NEAR(split(512), 0.5, 1e-16);
  const BSplineCurveData three_knots = {
      .degree = 3,
      .dimension = 2,
      .coordinates = {0, 0, 1, 3, 2, -1, 4, 2, 5, 0, 6, 1, 7, -2},
      .knots = {0, 0, 0, 0, split(256), split(512), split(768), 1, 1, 1, 1},
      .weights = {}};
  for (const auto& [known, rounds] :
       {std::pair{one_knot, 1}, std::pair{three_knots, 2}}) {
    const std::vector<double> points = EvaluateCurve(known, t);
    absl::StatusOr<CurveFit> fit =
        FitCurve({.dimension = 2, .coordinates = points},
                 {.degree = 3, .tolerance = 1e-10, .parameters = t});
    ASSERT_TRUE(fit.ok()) << fit.status();
    EXPECT_EQ(fit->refinement_rounds, rounds);
    EXPECT_EQ(fit->curve.knots, known.knots);
    ASSERT_EQ(fit->curve.coordinates.size(), known.coordinates.size());
    EXPECT_LE(MaxDifference(fit->curve.coordinates, known.coordinates), 1e-12);
    EXPECT_LE(fit->max_residual, 1e-13);
  }
}

TEST(FitCurve, PolynomialDataNeedNoRefinement) {
  // A parabola sampled at equally spaced x with uniform parameters is a
  // polynomial of degree 2 in t: a cubic reproduces it with one span (4
  // control points) and no knot inserted.
  std::vector<double> points;
  for (double x : EvenlySpaced(-1, 2, 40)) {
    points.insert(points.end(), {x, x * x - 0.5 * x});
  }
  absl::StatusOr<CurveFit> fit =
      FitCurve({.dimension = 2, .coordinates = points},
               {.degree = 3,
                .tolerance = 1e-12,
                .parameterization = Parameterization::kUniform});
  ASSERT_TRUE(fit.ok()) << fit.status();
  EXPECT_EQ(fit->refinement_rounds, 0);
  EXPECT_EQ(fit->curve.coordinates.size(), 8u);
  EXPECT_LE(fit->max_residual, 1e-12);
  // The curve is the parabola: y = x^2 - x / 2 at every evaluated point.
  const std::vector<double> values =
      EvaluateCurve(fit->curve, EvenlySpaced(0, 1, 101));
  for (size_t k = 0; k < values.size(); k += 2) {
    const double x = values[k];
    EXPECT_NEAR(values[k + 1], x * x - 0.5 * x, 1e-12);
  }
}

TEST(FitCurve, ParameterCorrectionRepairsPoorParameters) {
  // Samples of a circle arc at jittered angles 3 (k + j_k) / N, |j_k| <=
  // 0.4, with uniform parameters k / N: a point lies up to 6e-4 along the
  // arc from C(t_k), so without correction the tolerance 1e-6 is out of
  // reach of spans of two points; with correction t_k moves to the closest
  // point and the residual becomes the distance to the curve.
  const size_t count = 2000;
  std::mt19937_64 rng(3);
  const std::vector<double> jitter = RandomValues(rng, count, -0.4, 0.4);
  std::vector<double> points;
  for (size_t k = 0; k < count; ++k) {
    const bool end = k == 0 || k + 1 == count;
    const double angle = 3 * (static_cast<double>(k) + (end ? 0 : jitter[k])) /
                         static_cast<double>(count - 1);
    points.insert(points.end(), {std::cos(angle), std::sin(angle)});
  }
  const PointsView view{.dimension = 2, .coordinates = points};
  const CurveFitOptions options{.degree = 3,
                                .tolerance = 1e-6,
                                .parameterization = Parameterization::kUniform};
  absl::StatusOr<CurveFit> plain = FitCurve(view, options);
  ExpectField(plain.status(), "tolerance",
              absl::StatusCode::kResourceExhausted);
  CurveFitOptions correcting = options;
  correcting.parameter_corrections = 3;
  absl::StatusOr<CurveFit> corrected = FitCurve(view, correcting);
  ASSERT_TRUE(corrected.ok()) << corrected.status();
  EXPECT_LT(corrected->curve.coordinates.size() / 2, 40u);
  EXPECT_LE(corrected->max_residual, 1e-6);
  // The corrected parameters stay strictly increasing with the ends in
  // place, and the residuals measured by the evaluator hold.
  EXPECT_TRUE(std::adjacent_find(
                  corrected->parameters.begin(), corrected->parameters.end(),
                  std::greater_equal<>()) == corrected->parameters.end());
  EXPECT_EQ(corrected->parameters.front(), 0.0);
  EXPECT_EQ(corrected->parameters.back(), 1.0);
  EXPECT_LE(MaxDistance(EvaluateCurve(corrected->curve, corrected->parameters),
                        points, 2),
            1e-6 * (1 + 1e-9));
  // And the curve is the circle to the tolerance between the points too.
  const std::vector<double> values =
      EvaluateCurve(corrected->curve, EvenlySpaced(0, 1, 5000));
  for (size_t k = 0; k < values.size(); k += 2) {
    EXPECT_NEAR(std::hypot(values[k], values[k + 1]), 1.0, 2e-6);
  }
}

// The worked example of docs/references.md, 'Least-squares fitting to a
// tolerance': degree 1 on knots 0, 0, 1/2, 1, 1 through 0, 0, 1, 0, 0 at
// t = 0, 1/4, 1/2, 3/4, 1 gives P_1 = 2/3, residuals 0, 1/3, 1/3, 1/3, 0.
// DeCasteljau returns the point at t of the planar Bezier curve `control`.
std::array<double, 2> DeCasteljau(std::vector<std::array<double, 2>> control,
                                  double t) {
  for (size_t level = control.size() - 1; level > 0; --level) {
    for (size_t i = 0; i < level; ++i) {
      for (size_t c = 0; c < 2; ++c) {
        control[i][c] = (1 - t) * control[i][c] + t * control[i + 1][c];
      }
    }
  }
  return control[0];
}

TEST(FitCurve, ParameterCorrectionNeverFailsWhereThePlainFitSucceeds) {
  // Uniform samples of random quintic Bezier curves fitted by cubics with
  // uniform parameters: corrections on the first coarse fits once bunched
  // the parameters where the error was, so that no failing span held the
  // four points a split needs (RESOURCE_EXHAUSTED in most of these cases).
  std::mt19937_64 rng(41);
  int corrected_fits = 0;
  for (int trial = 0; trial < 40; ++trial) {
    std::vector<std::array<double, 2>> control(6);
    for (auto& point : control) {
      for (double& x : point) {
        x = std::uniform_real_distribution<double>(-1, 1)(rng);
      }
    }
    const size_t count = trial % 2 == 0 ? 50 : 204;
    std::vector<double> points;
    for (size_t k = 0; k < count; ++k) {
      const std::array<double, 2> point = DeCasteljau(
          control, static_cast<double>(k) / static_cast<double>(count - 1));
      points.insert(points.end(), point.begin(), point.end());
    }
    const PointsView view{.dimension = 2, .coordinates = points};
    for (const double tolerance : {1e-3, 1e-4, 1e-5}) {
      const CurveFitOptions plain{
          .degree = 3,
          .tolerance = tolerance,
          .parameterization = Parameterization::kUniform};
      if (!FitCurve(view, plain).ok()) continue;
      for (const int corrections : {1, 2, 5}) {
        SCOPED_TRACE(testing::Message()
                     << "trial " << trial << ", tolerance " << tolerance << ", "
                     << corrections << " corrections");
        CurveFitOptions options = plain;
        options.parameter_corrections = corrections;
        absl::StatusOr<CurveFit> fit = FitCurve(view, options);
        ASSERT_TRUE(fit.ok()) << fit.status();
        EXPECT_LE(fit->max_residual, tolerance);
        EXPECT_LE(
            MaxDistance(EvaluateCurve(fit->curve, fit->parameters), points, 2),
            tolerance * (1 + 1e-9));
        ++corrected_fits;
      }
    }
  }
  EXPECT_GT(corrected_fits, 200);
}

TEST(FitCurveToKnots, WorkedExample) {
  const std::vector<double> values = {0, 0, 1, 0, 0};
  const std::vector<double> t = {0, 0.25, 0.5, 0.75, 1};
  absl::StatusOr<CurveApproximation> fit =
      FitCurveToKnots({.dimension = 1, .coordinates = values}, 1,
                      std::vector<double>{0, 0, 0.5, 1, 1}, t);
  ASSERT_TRUE(fit.ok()) << fit.status();
  ASSERT_EQ(fit->curve.coordinates.size(), 3u);
  EXPECT_EQ(fit->curve.coordinates[0], 0.0);
  EXPECT_NEAR(fit->curve.coordinates[1], 2.0 / 3, 1e-15);
  EXPECT_EQ(fit->curve.coordinates[2], 0.0);
  EXPECT_NEAR(fit->max_residual, 1.0 / 3, 1e-15);
  EXPECT_NEAR(fit->rms_residual, std::sqrt(1.0 / 15), 1e-15);
  // FitCurve with tolerance 0.1 on the same data: the line 0 fails at t_2
  // and its 5 parameters are cut at 3/8; then both spans fail (residuals
  // 3/7, 17/35, 9/35) but hold 2 and 3 parameters, fewer than 4.
  absl::StatusOr<CurveFit> refined =
      FitCurve({.dimension = 1, .coordinates = values},
               {.degree = 1, .tolerance = 0.1, .parameters = t});
  ExpectField(refined.status(), "tolerance",
              absl::StatusCode::kResourceExhausted);
  EXPECT_THAT(refined.status().message(), HasSubstr("fewer than 4"));
  EXPECT_THAT(refined.status().message(), HasSubstr("0.485714"));  // 17/35
}

TEST(FitCurveToKnots, AgreesWithApproximateCurve) {
  // ApproximateCurve (A9.7 with eq. 9.69 knots, banded LU) and the banded
  // Cholesky fit on the same knots and parameters.
  std::vector<double> points;
  for (double s : EvenlySpaced(0, 6, 57)) {
    points.insert(points.end(), {s, std::sin(s), 0.3 * std::cos(2 * s)});
  }
  const PointsView view{.dimension = 3, .coordinates = points};
  absl::StatusOr<CurveApproximation> reference =
      ApproximateCurve(view, 3, 12, Parameterization::kCentripetal, {});
  ASSERT_TRUE(reference.ok()) << reference.status();
  absl::StatusOr<CurveApproximation> fit =
      FitCurveToKnots(view, 3, reference->curve.knots, reference->parameters);
  ASSERT_TRUE(fit.ok()) << fit.status();
  EXPECT_LE(MaxDifference(fit->curve.coordinates, reference->curve.coordinates),
            1e-12);
  EXPECT_NEAR(fit->max_residual, reference->max_residual, 1e-13);
  EXPECT_NEAR(fit->rms_residual, reference->rms_residual, 1e-13);
}

TEST(FitCurve, Errors) {
  const std::vector<double> six = {0, 0, 1, 1, 2, 0, 3, 1, 4, 0, 5, 1};
  const PointsView view{.dimension = 2, .coordinates = six};
  ExpectField(FitCurve(view, {.degree = 0, .tolerance = 1}).status(), "degree");
  ExpectField(FitCurve(view, {.degree = 6, .tolerance = 1}).status(),
              "points.coordinates");
  ExpectField(FitCurve(view, {.degree = 3, .tolerance = 0}).status(),
              "tolerance");
  ExpectField(FitCurve(view, {.degree = 3, .tolerance = NAN}).status(),
              "tolerance");
  ExpectField(FitCurve(view, {.degree = 3,
                              .tolerance = 1,
                              .parameters = std::vector<double>{0, 1}})
                  .status(),
              "parameters");
  ExpectField(FitCurve(view, {.degree = 3,
                              .tolerance = 1,
                              .parameters = std::vector<double>{0, 0.2, 0.4,
                                                                0.4, 0.8, 1}})
                  .status(),
              "parameters[3]");
  ExpectField(
      FitCurve(view, {.degree = 3,
                      .tolerance = 1,
                      .parameters =
                          std::vector<double>{0, 0.2, INFINITY, 0.6, 0.8, 1}})
          .status(),
      "parameters[2]");
  ExpectField(
      FitCurve(view, {.degree = 3, .tolerance = 1, .max_control_points = 3})
          .status(),
      "max_control_points");
  ExpectField(
      FitCurve(view, {.degree = 3, .tolerance = 1, .parameter_corrections = -1})
          .status(),
      "parameter_corrections");
  const std::vector<double> repeated = {0, 0, 1, 1, 1, 1, 2, 0};
  ExpectField(FitCurve({.dimension = 2, .coordinates = repeated},
                       {.degree = 1, .tolerance = 1})
                  .status(),
              "points.coordinates[4]");
}

TEST(FitCurve, CapReachedIsResourceExhausted) {
  const BSplineCurveData known = KnownCurve();
  const std::vector<double> t = EvenlySpaced(0, 1, 500);
  const std::vector<double> points = EvaluateCurve(known, t);
  absl::StatusOr<CurveFit> fit = FitCurve(
      {.dimension = 3, .coordinates = points}, {.degree = 3,
                                                .tolerance = 1e-9,
                                                .parameters = t,
                                                .max_control_points = 6});
  ExpectField(fit.status(), "tolerance", absl::StatusCode::kResourceExhausted);
  EXPECT_THAT(fit.status().message(), HasSubstr("max_control_points = 6"));
}

TEST(FitCurve, CancelledTokenStops) {
  CancellationToken token;
  token.Cancel();
  const std::vector<double> points =
      EvaluateCurve(KnownCurve(), EvenlySpaced(0, 1, 200000));
  absl::StatusOr<CurveFit> fit =
      FitCurve({.dimension = 3, .coordinates = points},
               {.degree = 3, .tolerance = 1e-6, .cancel = &token});
  EXPECT_EQ(fit.status().code(), absl::StatusCode::kCancelled);
}

TEST(FitCurveToKnots, Errors) {
  const std::vector<double> points = {0, 1, 2, 3, 4, 5};
  const PointsView view{.dimension = 1, .coordinates = points};
  const std::vector<double> t = {0, 0.2, 0.4, 0.6, 0.8, 1};
  ExpectField(
      FitCurveToKnots(view, 2, std::vector<double>{0, 0, 0.5, 1, 1, 1}, t)
          .status(),
      "knots");
  ExpectField(FitCurveToKnots(
                  view, 2, std::vector<double>{0, 0, 0, 0.6, 0.5, 1, 1, 1}, t)
                  .status(),
              "knots[4]");
  ExpectField(
      FitCurveToKnots(
          view, 1, std::vector<double>{0, 0, 0.1, 0.2, 0.3, 0.5, 0.7, 1, 1}, t)
          .status(),
      "knots");  // 7 control points for 6 points
  // Every interior parameter in one span: P_1 and P_2 have no data.
  ExpectField(
      FitCurveToKnots(view, 1, std::vector<double>{0, 0, 0.05, 0.1, 1, 1}, t)
          .status(),
      "parameters");
  ExpectField(FitCurveToKnots(view, 1, std::vector<double>{0, 0, 0.5, 1, 1},
                              std::vector<double>{0, 1})
                  .status(),
              "parameters");
}

// -------------------------------------------------- gridded surfaces --

// A grid of `f` at (u_k, v_l) in net order.
template <typename F>
std::vector<double> SampleGrid(absl::Span<const double> u,
                               absl::Span<const double> v, int dimension, F f) {
  std::vector<double> grid;
  for (double a : u) {
    for (double b : v) {
      const std::vector<double> point = f(a, b);
      grid.insert(grid.end(), point.begin(), point.begin() + dimension);
    }
  }
  return grid;
}

TEST(FitSurfaceToGrid, ReproducesPolynomialPatches) {
  std::mt19937_64 rng(7);
  std::vector<double> u = RandomValues(rng, 9, 0, 1);
  std::vector<double> v = RandomValues(rng, 11, 0, 1);
  u.insert(u.end(), {0.0, 1.0});
  v.insert(v.end(), {0.0, 1.0});
  std::sort(u.begin(), u.end());
  std::sort(v.begin(), v.end());
  const auto biquadratic = [](double a, double b) {
    return std::vector<double>{a + 0.2 * b * b, b - a * b,
                               a * a - 2 * a * b + 0.5 * b * b * a * a};
  };
  const auto bilinear = [](double a, double b) {
    return std::vector<double>{a, 2 * b, 1 + a - 3 * a * b};
  };
  for (int degree : {1, 2}) {
    const std::vector<double> grid = degree == 1
                                         ? SampleGrid(u, v, 3, bilinear)
                                         : SampleGrid(u, v, 3, biquadratic);
    absl::StatusOr<SurfaceFit> fit = FitSurfaceToGrid(
        {.dimension = 3, .count_u = 11, .count_v = 13, .coordinates = grid},
        {.degree_u = degree,
         .degree_v = degree,
         .tolerance = 1e-12,
         .parameters_u = u,
         .parameters_v = v});
    ASSERT_TRUE(fit.ok()) << fit.status();
    EXPECT_EQ(fit->refinement_rounds, 0);
    EXPECT_EQ(fit->surface.count_u, degree + 1);
    EXPECT_EQ(fit->surface.count_v, degree + 1);
    EXPECT_LE(fit->max_residual, 1e-12);
    // The patch everywhere, not only at the data.
    const std::vector<double> uv = RandomValues(rng, 200, 0, 1);
    const std::vector<double> values =
        EvaluateSurface(fit->surface, SurfaceSamples::Pairs(uv));
    for (size_t k = 0; k < 100; ++k) {
      const std::vector<double> expected =
          degree == 1 ? bilinear(uv[2 * k], uv[2 * k + 1])
                      : biquadratic(uv[2 * k], uv[2 * k + 1]);
      for (size_t c = 0; c < 3; ++c) {
        EXPECT_NEAR(values[3 * k + c], expected[c], 1e-12);
      }
    }
  }
}

// A 64 x 48 grid at k / 63 and l / 47: the first splits are halfway
// between the middle parameters, 1/2 in both directions (to rounding).
TEST(FitSurfaceToGrid, ReproducesABicubicWithTheKnotsOfTheRefinement) {
  const std::vector<double> u = EvenlySpaced(0, 1, 64);
  const std::vector<double> v = EvenlySpaced(0, 1, 48);
  const double half_u = u[31] + 0.5 * (u[32] - u[31]);
  const double half_v = v[23] + 0.5 * (v[24] - v[23]);
  EXPECT_NEAR(half_u, 0.5, 1e-16);
  EXPECT_NEAR(half_v, 0.5, 1e-16);
  std::mt19937_64 rng(11);
  const SurfaceData known = {.degree_u = 3,
                             .degree_v = 3,
                             .dimension = 3,
                             .count_u = 5,
                             .count_v = 5,
                             .coordinates = RandomValues(rng, 75, -1, 1),
                             .knots_u = {0, 0, 0, 0, half_u, 1, 1, 1, 1},
                             .knots_v = {0, 0, 0, 0, half_v, 1, 1, 1, 1},
                             .weights = {}};
  const std::vector<double> grid =
      EvaluateSurface(known, SurfaceSamples::Grid(u, v));
  absl::StatusOr<SurfaceFit> fit = FitSurfaceToGrid(
      {.dimension = 3, .count_u = 64, .count_v = 48, .coordinates = grid},
      {.tolerance = 1e-10, .parameters_u = u, .parameters_v = v});
  ASSERT_TRUE(fit.ok()) << fit.status();
  EXPECT_EQ(fit->refinement_rounds, 1);
  EXPECT_EQ(fit->surface.knots_u, known.knots_u);
  EXPECT_EQ(fit->surface.knots_v, known.knots_v);
  EXPECT_LE(MaxDifference(fit->surface.coordinates, known.coordinates), 1e-12);
  EXPECT_LE(fit->max_residual, 1e-13);
}

TEST(FitSurfaceToGrid, SmoothFunctionWithinTolerance) {
  // A Gaussian bump over [-1, 1] x [0, 2] on a 121 x 101 grid, with the
  // grid coordinates as parameters.
  const std::vector<double> x = EvenlySpaced(-1, 1, 121);
  const std::vector<double> y = EvenlySpaced(0, 2, 101);
  const auto bump = [](double a, double b) {
    return std::vector<double>{
        a, b, std::exp(-2 * (a * a + (b - 1) * (b - 1))) * std::cos(a + b)};
  };
  const std::vector<double> grid = SampleGrid(x, y, 3, bump);
  const double tolerance = 1e-5;
  absl::StatusOr<SurfaceFit> fit = FitSurfaceToGrid(
      {.dimension = 3, .count_u = 121, .count_v = 101, .coordinates = grid},
      {.tolerance = tolerance, .parameters_u = x, .parameters_v = y});
  ASSERT_TRUE(fit.ok()) << fit.status();
  EXPECT_LE(fit->max_residual, tolerance);
  EXPECT_LE(fit->rms_residual, fit->max_residual);
  EXPECT_GE(fit->refinement_rounds, 2);
  EXPECT_LT(fit->surface.count_u, 60);
  EXPECT_LT(fit->surface.count_v, 50);
  // Measured again by the evaluator, and between the grid points against
  // the function itself.
  EXPECT_LE(MaxDistance(EvaluateSurface(fit->surface, SurfaceSamples::Grid(
                                                          fit->parameters_u,
                                                          fit->parameters_v)),
                        grid, 3),
            tolerance * (1 + 1e-9));
  const std::vector<double> fine_x = EvenlySpaced(-1, 1, 481);
  const std::vector<double> fine_y = EvenlySpaced(0, 2, 401);
  EXPECT_LE(MaxDistance(EvaluateSurface(fit->surface,
                                        SurfaceSamples::Grid(fine_x, fine_y)),
                        SampleGrid(fine_x, fine_y, 3, bump), 3),
            2 * tolerance);
  // The corners are interpolated.
  EXPECT_LE(MaxDistance(absl::MakeConstSpan(fit->surface.coordinates).first(3),
                        absl::MakeConstSpan(grid).first(3), 3),
            1e-15);
}

TEST(FitSurfaceToGrid, ComputedParametersAndMixedDegrees) {
  const std::vector<double> x = EvenlySpaced(0, 2, 161);
  const std::vector<double> y = EvenlySpaced(-1, 1, 121);
  const auto height = [](double a, double b) {
    return std::vector<double>{a, b, std::sin(2 * a) * std::cos(3 * b)};
  };
  const std::vector<double> grid = SampleGrid(x, y, 3, height);
  const double tolerance = 1e-4;
  absl::StatusOr<SurfaceFit> fit = FitSurfaceToGrid(
      {.dimension = 3, .count_u = 161, .count_v = 121, .coordinates = grid},
      {.degree_u = 3, .degree_v = 2, .tolerance = tolerance});
  ASSERT_TRUE(fit.ok()) << fit.status();
  EXPECT_LE(fit->max_residual, tolerance);
  EXPECT_LE(MaxDistance(EvaluateSurface(fit->surface, SurfaceSamples::Grid(
                                                          fit->parameters_u,
                                                          fit->parameters_v)),
                        grid, 3),
            tolerance * (1 + 1e-9));
  // The parameters are InterpolateSurface's (chord length averaged over
  // the grid lines).
  absl::StatusOr<SurfaceInterpolation> interpolation = InterpolateSurface(
      {.dimension = 3, .count_u = 161, .count_v = 121, .coordinates = grid}, 3,
      2, Parameterization::kChordLength, KnotRule::kAveraging);
  ASSERT_TRUE(interpolation.ok());
  EXPECT_EQ(fit->parameters_u, interpolation->parameters_u);
  EXPECT_EQ(fit->parameters_v, interpolation->parameters_v);
  EXPECT_EQ(fit->surface.degree_v, 2);
}

TEST(FitSurfaceToGrid, Errors) {
  const std::vector<double> grid(4 * 5 * 3, 0.0);
  const ControlNetView net{
      .dimension = 3, .count_u = 4, .count_v = 5, .coordinates = grid};
  const std::vector<double> u = {0, 0.3, 0.6, 1};
  const std::vector<double> v = {0, 0.25, 0.5, 0.75, 1};
  const GridFitOptions base{.degree_u = 2,
                            .degree_v = 2,
                            .tolerance = 1e-3,
                            .parameters_u = u,
                            .parameters_v = v};
  GridFitOptions options = base;
  options.degree_u = 0;
  ExpectField(FitSurfaceToGrid(net, options).status(), "degree_u");
  options = base;
  options.degree_v = 5;
  ExpectField(FitSurfaceToGrid(net, options).status(), "points.count_v");
  options = base;
  options.tolerance = -1;
  ExpectField(FitSurfaceToGrid(net, options).status(), "tolerance");
  options = base;
  options.parameters_u = absl::MakeConstSpan(u).first(3);
  ExpectField(FitSurfaceToGrid(net, options).status(), "parameters_u");
  options = base;
  const std::vector<double> bad_v = {0, 0.25, 0.5, 0.5, 1};
  options.parameters_v = bad_v;
  ExpectField(FitSurfaceToGrid(net, options).status(), "parameters_v[3]");
  options = base;
  options.max_control_points_u = 2;
  ExpectField(FitSurfaceToGrid(net, options).status(), "max_control_points_u");
  ExpectField(
      FitSurfaceToGrid(
          {.dimension = 3, .count_u = 4, .count_v = 4, .coordinates = grid},
          base)
          .status(),
      "points.coordinates");
}

TEST(FitSurfaceToGrid, CapReachedIsResourceExhausted) {
  const std::vector<double> x = EvenlySpaced(0, 3, 40);
  const std::vector<double> y = EvenlySpaced(0, 1, 30);
  const std::vector<double> grid = SampleGrid(x, y, 3, [](double a, double b) {
    return std::vector<double>{a, b, std::sin(4 * a) + b * b * b * b};
  });
  absl::StatusOr<SurfaceFit> fit = FitSurfaceToGrid(
      {.dimension = 3, .count_u = 40, .count_v = 30, .coordinates = grid},
      {.tolerance = 1e-9, .max_control_points_u = 5});
  ExpectField(fit.status(), "tolerance", absl::StatusCode::kResourceExhausted);
  EXPECT_THAT(fit.status().message(), HasSubstr("max_control_points_u = 5"));
}

// --------------------------------------------------- scattered points --

SurfaceData KnownSurface() {
  std::mt19937_64 rng(5);
  return {.degree_u = 3,
          .degree_v = 3,
          .dimension = 3,
          .count_u = 7,
          .count_v = 6,
          .coordinates = RandomValues(rng, 7 * 6 * 3, -1, 1),
          .knots_u = {0, 0, 0, 0, 0.25, 0.5, 0.75, 1, 1, 1, 1},
          .knots_v = {0, 0, 0, 0, 1.0 / 3, 2.0 / 3, 1, 1, 1, 1},
          .weights = {}};
}

TEST(FitScatteredSurface, RecoversControlPointsFromExactData) {
  const SurfaceData known = KnownSurface();
  std::mt19937_64 rng(17);
  const std::vector<double> uv = RandomValues(rng, 2 * 3000, 0, 1);
  const std::vector<double> points =
      EvaluateSurface(known, SurfaceSamples::Pairs(uv));
  absl::StatusOr<ScatteredFit> fit = FitScatteredSurface(
      {.dimension = 3, .coordinates = points}, {.control_count_u = 7,
                                                .control_count_v = 6,
                                                .parameters = uv,
                                                .smoothing = 0});
  ASSERT_TRUE(fit.ok()) << fit.status();
  EXPECT_EQ(fit->surface.knots_u, known.knots_u);
  EXPECT_EQ(fit->surface.knots_v, known.knots_v);
  EXPECT_LE(MaxDifference(fit->surface.coordinates, known.coordinates), 1e-9);
  EXPECT_LE(fit->max_residual, 1e-12);
  EXPECT_EQ(fit->residuals.size(), 3000u);
  // The default smoothing moves them by little.
  absl::StatusOr<ScatteredFit> smoothed = FitScatteredSurface(
      {.dimension = 3, .coordinates = points},
      {.control_count_u = 7, .control_count_v = 6, .parameters = uv});
  ASSERT_TRUE(smoothed.ok()) << smoothed.status();
  EXPECT_LE(MaxDifference(smoothed->surface.coordinates, known.coordinates),
            2e-5);
}

TEST(FitScatteredSurface, NoisyDataStayWithinTheNoise) {
  const SurfaceData known = KnownSurface();
  std::mt19937_64 rng(19);
  const std::vector<double> uv = RandomValues(rng, 2 * 20000, 0, 1);
  std::vector<double> points =
      EvaluateSurface(known, SurfaceSamples::Pairs(uv));
  const double noise = 1e-4;
  const std::vector<double> offsets =
      RandomValues(rng, points.size(), -noise, noise);
  for (size_t i = 0; i < points.size(); ++i) points[i] += offsets[i];
  absl::StatusOr<ScatteredFit> fit = FitScatteredSurface(
      {.dimension = 3, .coordinates = points},
      {.control_count_u = 7, .control_count_v = 6, .parameters = uv});
  ASSERT_TRUE(fit.ok()) << fit.status();
  const std::vector<double> grid = EvenlySpaced(0, 1, 50);
  EXPECT_LE(MaxDistance(
                EvaluateSurface(fit->surface, SurfaceSamples::Grid(grid, grid)),
                EvaluateSurface(known, SurfaceSamples::Grid(grid, grid)), 3),
            noise);
  // The residuals are the noise: rms a (uniform in [-a, a]^3).
  EXPECT_NEAR(fit->rms_residual, noise, 0.05 * noise);
  EXPECT_LE(fit->max_residual, std::sqrt(3.0) * noise * 1.1);
}

TEST(FitScatteredSurface, HeightFieldWithComputedParameters) {
  // z = f(x, y) on [0, 2] x [0, 1] with noise 1e-4: the best-fit plane is
  // close to z = 0 with x the long axis.
  const auto f = [](double x, double y) {
    return 0.1 * std::sin(2 * x) * std::cos(3 * y) + 0.05 * x * y;
  };
  std::mt19937_64 rng(23);
  const double noise = 1e-4;
  std::vector<double> points;
  for (int k = 0; k < 20000; ++k) {
    const double x = RandomValues(rng, 1, 0, 2)[0];
    const double y = RandomValues(rng, 1, 0, 1)[0];
    points.insert(points.end(),
                  {x, y, f(x, y) + RandomValues(rng, 1, -noise, noise)[0]});
  }
  absl::StatusOr<ScatteredFit> fit =
      FitScatteredSurface({.dimension = 3, .coordinates = points},
                          {.control_count_u = 12, .control_count_v = 8});
  ASSERT_TRUE(fit.ok()) << fit.status();
  EXPECT_LE(fit->rms_residual, 1.1 * noise / std::sqrt(3.0) * 1.2);
  // The surface lies on the graph of f wherever it covers data.
  const std::vector<double> grid = EvenlySpaced(0.05, 0.95, 40);
  const std::vector<double> values =
      EvaluateSurface(fit->surface, SurfaceSamples::Grid(grid, grid));
  size_t inside = 0;
  for (size_t k = 0; k < values.size(); k += 3) {
    const double x = values[k], y = values[k + 1];
    if (x < 0.02 || x > 1.98 || y < 0.02 || y > 0.98) continue;
    ++inside;
    EXPECT_NEAR(values[k + 2], f(x, y), 2 * noise) << x << " " << y;
  }
  EXPECT_GT(inside, 1000u);
}

TEST(FitScatteredSurface, ReproducesPlanesForAnySmoothing) {
  // Q = o + u a + v b with data only where u < 0.4: the energy vanishes on
  // planes, so every lambda > 0 gives the plane, over the hole too.
  std::mt19937_64 rng(47);
  std::vector<double> uv = RandomValues(rng, 2 * 400, 0, 1);
  for (size_t k = 0; k < uv.size(); k += 2) uv[k] *= 0.4;
  const auto plane = [](double u, double v) {
    return std::vector<double>{1 + 2 * u - v, -1 + 0.5 * u + 3 * v, u + v};
  };
  std::vector<double> points;
  for (size_t k = 0; k < uv.size(); k += 2) {
    const std::vector<double> point = plane(uv[k], uv[k + 1]);
    points.insert(points.end(), point.begin(), point.end());
  }
  const std::vector<double> grid = EvenlySpaced(0, 1, 21);
  for (double lambda : {kDefaultScatteredSmoothing, 1e-6, 1e-3, 1.0}) {
    absl::StatusOr<ScatteredFit> fit = FitScatteredSurface(
        {.dimension = 3, .coordinates = points}, {.control_count_u = 6,
                                                  .control_count_v = 5,
                                                  .parameters = uv,
                                                  .smoothing = lambda});
    ASSERT_TRUE(fit.ok()) << fit.status();
    EXPECT_LE(fit->max_residual, 1e-11) << lambda;
    const std::vector<double> values =
        EvaluateSurface(fit->surface, SurfaceSamples::Grid(grid, grid));
    const std::vector<double> expected = SampleGrid(grid, grid, 3, plane);
    EXPECT_LE(MaxDistance(values, expected, 3), 1e-9) << lambda;
  }
}

TEST(PlaneParameters, AffineOnATiltedPlane) {
  // Points o + x a + y b on a tilted plane in 4D, (x, y) in [0, 3] x [0, 1].
  std::mt19937_64 rng(29);
  const std::vector<double> o = {1, -2, 0.5, 3};
  const std::vector<double> a = {0.6, 0.0, 0.8, 0.0};
  const std::vector<double> b = {0.0, 0.6, -0.3, 0.7};
  std::vector<double> xy, points;
  for (int k = 0; k < 500; ++k) {
    const double x = RandomValues(rng, 1, 0, 3)[0];
    const double y = RandomValues(rng, 1, 0, 1)[0];
    xy.insert(xy.end(), {x, y});
    for (size_t c = 0; c < 4; ++c) points.push_back(o[c] + x * a[c] + y * b[c]);
  }
  absl::StatusOr<std::vector<double>> uv =
      PlaneParameters({.dimension = 4, .coordinates = points});
  ASSERT_TRUE(uv.ok()) << uv.status();
  // u and v are exactly affine in (x, y): the affine map through the first
  // three points reproduces the rest.
  for (size_t axis = 0; axis < 2; ++axis) {
    double lo = 1, hi = 0;
    const auto at = [&](size_t k) { return (*uv)[2 * k + axis]; };
    // Solve w0 + w1 x + w2 y = value on points 0, 1, 2 by Cramer's rule.
    const double x0 = xy[0], y0 = xy[1], x1 = xy[2], y1 = xy[3], x2 = xy[4],
                 y2 = xy[5];
    const double det = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0);
    const double w1 =
        ((at(1) - at(0)) * (y2 - y0) - (at(2) - at(0)) * (y1 - y0)) / det;
    const double w2 =
        ((x1 - x0) * (at(2) - at(0)) - (x2 - x0) * (at(1) - at(0))) / det;
    for (size_t k = 0; k < 500; ++k) {
      const double predicted =
          at(0) + w1 * (xy[2 * k] - x0) + w2 * (xy[2 * k + 1] - y0);
      EXPECT_NEAR(at(k), predicted, 1e-11);
      lo = std::min(lo, at(k));
      hi = std::max(hi, at(k));
    }
    EXPECT_EQ(lo, 0.0);
    EXPECT_EQ(hi, 1.0);
  }
}

// The worked example of docs/references.md, 'Scattered-data surface
// fitting': a bilinear 2 x 2 net through z = 0, 0, 0, 1 at the corners with
// lambda = 1/32 gives P = z - (1, -1, -1, 1) / 8.
TEST(FitScatteredSurface, WorkedExample) {
  const std::vector<double> z = {0, 0, 0, 1};
  const std::vector<double> uv = {0, 0, 1, 0, 0, 1, 1, 1};
  absl::StatusOr<ScatteredFit> fit = FitScatteredSurface(
      {.dimension = 1, .coordinates = z}, {.degree_u = 1,
                                           .degree_v = 1,
                                           .control_count_u = 2,
                                           .control_count_v = 2,
                                           .parameters = uv,
                                           .smoothing = 1.0 / 32});
  ASSERT_TRUE(fit.ok()) << fit.status();
  // Net order P00, P01, P10, P11 (u-major): z - s / 8 with s = (1, -1, -1, 1).
  const std::vector<double> expected = {-0.125, 0.125, 0.125, 0.875};
  EXPECT_LE(MaxDifference(fit->surface.coordinates, expected), 1e-15);
  for (double residual : fit->residuals) EXPECT_NEAR(residual, 0.125, 1e-15);
  EXPECT_NEAR(fit->rms_residual, 0.125, 1e-15);
}

TEST(EstimateScatteredFit, ChoosesTheNarrowerBand) {
  EXPECT_EQ(EstimateScatteredFit(1000, 3,
                                 {.control_count_u = 8, .control_count_v = 8})
                .bandwidth,
            27u);  // 3 * 8 + 3
  EXPECT_EQ(EstimateScatteredFit(1000, 3,
                                 {.control_count_u = 20, .control_count_v = 5})
                .bandwidth,
            18u);  // u-major 3 * 5 + 3; v-major would be 3 * 20 + 3
  EXPECT_EQ(EstimateScatteredFit(1000, 3,
                                 {.degree_u = 1,
                                  .degree_v = 1,
                                  .control_count_u = 10,
                                  .control_count_v = 10})
                .bandwidth,
            20u);  // the second differences two rows apart
  const ScatteredFitWork small = EstimateScatteredFit(
      1000, 3, {.control_count_u = 8, .control_count_v = 8});
  const ScatteredFitWork large = EstimateScatteredFit(
      1000, 3, {.control_count_u = 80, .control_count_v = 80});
  EXPECT_GT(large.operations, 100 * small.operations);
  EXPECT_GE(large.memory_bytes, 6400u * 244 * sizeof(double));
  // Saturates instead of overflowing.
  EXPECT_EQ(EstimateScatteredFit(
                size_t{1} << 62, 64,
                {.control_count_u = 1 << 30, .control_count_v = 1 << 30})
                .operations,
            std::numeric_limits<size_t>::max());
}

TEST(FitScatteredSurface, Errors) {
  std::mt19937_64 rng(31);
  const std::vector<double> points = RandomValues(rng, 3 * 100, 0, 1);
  const PointsView view{.dimension = 3, .coordinates = points};
  ExpectField(
      FitScatteredSurface(view, {.control_count_u = 11, .control_count_v = 10})
          .status(),
      "points");
  ExpectField(FitScatteredSurface(view, {.degree_u = 0}).status(), "degree_u");
  ExpectField(FitScatteredSurface(view, {.control_count_u = 3}).status(),
              "control_count_u");
  ExpectField(
      FitScatteredSurface(view, {.degree_v = 2, .control_count_v = 2}).status(),
      "control_count_v");
  ExpectField(FitScatteredSurface(view, {.smoothing = -1}).status(),
              "smoothing");
  ExpectField(FitScatteredSurface(view, {.smoothing = INFINITY}).status(),
              "smoothing");
  std::vector<double> uv = RandomValues(rng, 2 * 100, 0, 1);
  ExpectField(FitScatteredSurface(
                  view, {.parameters = absl::MakeConstSpan(uv).first(199)})
                  .status(),
              "parameters");
  uv[5] = 1.5;
  ExpectField(FitScatteredSurface(view, {.parameters = uv}).status(),
              "parameters[5]");
  uv[5] = NAN;
  ExpectField(FitScatteredSurface(view, {.parameters = uv}).status(),
              "parameters[5]");
  // No data where u > 0.4: without smoothing, the control points there are
  // free.
  uv = RandomValues(rng, 2 * 100, 0, 1);
  for (size_t k = 0; k < uv.size(); k += 2) uv[k] *= 0.4;
  ExpectField(FitScatteredSurface(view, {.control_count_u = 8,
                                         .control_count_v = 4,
                                         .parameters = uv,
                                         .smoothing = 0})
                  .status(),
              "parameters");
  // With the default smoothing the hole is filled.
  EXPECT_TRUE(
      FitScatteredSurface(
          view, {.control_count_u = 8, .control_count_v = 4, .parameters = uv})
          .ok());
  ExpectField(FitScatteredSurface(
                  {.dimension = 1, .coordinates = absl::MakeConstSpan(points)},
                  {.control_count_u = 4, .control_count_v = 4})
                  .status(),
              "points.dimension");
  std::vector<double> line;
  for (double s : EvenlySpaced(0, 1, 100))
    line.insert(line.end(), {s, 2 * s, 1 - s});
  ExpectField(FitScatteredSurface({.dimension = 3, .coordinates = line},
                                  {.control_count_u = 4, .control_count_v = 4})
                  .status(),
              "points");
  // Over the cap: on "points" when the per-point work alone exceeds it,
  // else on the larger control count.
  ScatteredFitOptions capped{.control_count_u = 8, .control_count_v = 4};
  const ScatteredFitWork work = EstimateScatteredFit(100, 3, capped);
  ASSERT_LT(work.point_operations, work.operations);
  capped.max_operations = work.operations;
  EXPECT_TRUE(FitScatteredSurface(view, capped).ok());
  capped.max_operations = work.operations - 1;
  ExpectField(FitScatteredSurface(view, capped).status(), "control_count_u",
              absl::StatusCode::kResourceExhausted);
  capped.max_operations = work.point_operations - 1;
  ExpectField(FitScatteredSurface(view, capped).status(), "points",
              absl::StatusCode::kResourceExhausted);
}

TEST(FitScatteredSurface, CancelledTokenStops) {
  CancellationToken token;
  token.Cancel();
  std::mt19937_64 rng(37);
  const std::vector<double> points = RandomValues(rng, 3 * 200000, 0, 1);
  absl::StatusOr<ScatteredFit> fit = FitScatteredSurface(
      {.dimension = 3, .coordinates = points}, {.cancel = &token});
  EXPECT_EQ(fit.status().code(), absl::StatusCode::kCancelled);
}

// ------------------------------------------------- internal solvers --

TEST(BandedCholesky, SolvesABandedSpdSystem) {
  // A = B B^T + I for a random lower band B: SPD with bandwidth 2 w.
  const size_t n = 40, w = 3;
  std::mt19937_64 rng(41);
  std::vector<double> b(n * n, 0.0), a(n * n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = i >= w ? i - w : 0; j <= i; ++j) {
      b[i * n + j] = RandomValues(rng, 1)[0];
    }
  }
  internal::BandedCholesky matrix(n, 2 * w);
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = 0; j <= i; ++j) {
      double sum = i == j ? 1.0 : 0.0;
      for (size_t k = 0; k < n; ++k) sum += b[i * n + k] * b[j * n + k];
      a[i * n + j] = a[j * n + i] = sum;
      if (i - j <= 2 * w)
        matrix.lower(i, j) = sum;
      else
        EXPECT_EQ(sum, 0.0);
    }
  }
  ASSERT_TRUE(matrix.Factor(nullptr).ok());
  const std::vector<double> x = RandomValues(rng, 2 * n);  // two columns
  std::vector<double> rhs(2 * n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = 0; j < n; ++j) {
      for (size_t c = 0; c < 2; ++c)
        rhs[2 * i + c] += a[i * n + j] * x[2 * j + c];
    }
  }
  ASSERT_TRUE(matrix.Solve(rhs.data(), 2, nullptr).ok());
  EXPECT_LE(MaxDifference(rhs, x), 1e-12);
}

TEST(BandedCholesky, ReportsASingularRow) {
  // [[1, 1], [1, 1]] is singular at row 1.
  internal::BandedCholesky matrix(2, 1);
  matrix.lower(0, 0) = 1;
  matrix.lower(1, 0) = 1;
  matrix.lower(1, 1) = 1;
  EXPECT_EQ(matrix.Factor(nullptr).code(),
            absl::StatusCode::kFailedPrecondition);
  EXPECT_EQ(matrix.failed_row(), 1u);
}

TEST(SymmetricEigen, DiagonalizesARotatedDiagonal) {
  // A = R diag(3, 2, 1) R^T with R the rotation by 30 degrees about z,
  // then about x by 45 degrees.
  const double c = std::sqrt(3.0) / 2, s = 0.5, h = std::sqrt(0.5);
  const std::vector<double> rz = {c, -s, 0, s, c, 0, 0, 0, 1};
  const std::vector<double> rx = {1, 0, 0, 0, h, -h, 0, h, h};
  std::vector<double> r(9, 0.0), a(9, 0.0);
  for (size_t i = 0; i < 3; ++i) {
    for (size_t j = 0; j < 3; ++j) {
      for (size_t k = 0; k < 3; ++k)
        r[i * 3 + j] += rx[i * 3 + k] * rz[k * 3 + j];
    }
  }
  const double lambda[3] = {3, 2, 1};
  for (size_t i = 0; i < 3; ++i) {
    for (size_t j = 0; j < 3; ++j) {
      for (size_t k = 0; k < 3; ++k) {
        a[i * 3 + j] += r[i * 3 + k] * lambda[k] * r[j * 3 + k];
      }
    }
  }
  const internal::SymmetricEigenSystem system = internal::SymmetricEigen(3, a);
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_NEAR(system.values[k], lambda[k], 1e-14);
    // Eigenvector k is column k of R, up to sign.
    double dot = 0;
    for (size_t i = 0; i < 3; ++i)
      dot += system.vectors[k * 3 + i] * r[i * 3 + k];
    EXPECT_NEAR(std::abs(dot), 1.0, 1e-14);
  }
}

TEST(SymmetricEigen, RandomMatrixSatisfiesTheEigenEquations) {
  const size_t n = 12;
  std::mt19937_64 rng(43);
  std::vector<double> a = RandomValues(rng, n * n);
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = 0; j < i; ++j) a[i * n + j] = a[j * n + i];
  }
  const internal::SymmetricEigenSystem system = internal::SymmetricEigen(n, a);
  EXPECT_TRUE(std::is_sorted(system.values.rbegin(), system.values.rend()));
  for (size_t k = 0; k < n; ++k) {
    for (size_t i = 0; i < n; ++i) {
      double product = 0;
      for (size_t j = 0; j < n; ++j) {
        product += a[i * n + j] * system.vectors[k * n + j];
      }
      EXPECT_NEAR(product, system.values[k] * system.vectors[k * n + i], 1e-13);
    }
    for (size_t l = 0; l < n; ++l) {
      double dot = 0;
      for (size_t i = 0; i < n; ++i) {
        dot += system.vectors[k * n + i] * system.vectors[l * n + i];
      }
      EXPECT_NEAR(dot, k == l ? 1.0 : 0.0, 1e-14);
    }
  }
}

}  // namespace
}  // namespace freeform
