#include "freeform/core/tessellation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "freeform/core/curve.h"
#include "freeform/core/status.h"
#include "freeform/core/surface_output.h"
#include "shapes.h"
#include "test_util.h"

namespace freeform {
namespace {

constexpr auto Distance = testing_util::PointDistance;

using testing_util::RandomValues;

double DistanceToSegment(const double* p, const double* a, const double* b,
                         int dimension) {
  double ab2 = 0.0, dot = 0.0;
  for (int j = 0; j < dimension; ++j) {
    ab2 += (b[j] - a[j]) * (b[j] - a[j]);
    dot += (p[j] - a[j]) * (b[j] - a[j]);
  }
  const double s = ab2 > 0 ? std::clamp(dot / ab2, 0.0, 1.0) : 0.0;
  std::vector<double> q(dimension);
  for (int j = 0; j < dimension; ++j) q[j] = a[j] + s * (b[j] - a[j]);
  return Distance(p, q.data(), dimension);
}

// CheckPolyline checks the polyline against the curve evaluated by
// `evaluate`: parameters increase from `start` to `end`, every point is the
// curve point of its parameter, and the curve between consecutive
// parameters (32 samples per segment) stays within `tolerance` of the
// segment. Returns the largest distance seen.
template <typename Evaluate>
double CheckPolyline(const Polyline& polyline, int dimension, double start,
                     double end, double tolerance, Evaluate evaluate) {
  const std::vector<double>& t = polyline.parameters;
  EXPECT_EQ(polyline.dimension, dimension);
  EXPECT_EQ(polyline.points.size(), t.size() * dimension);
  EXPECT_GE(t.size(), 2u);
  EXPECT_EQ(t.front(), start);
  EXPECT_EQ(t.back(), end);
  const std::vector<double> exact = evaluate(t);
  for (size_t r = 0; r < t.size(); ++r) {
    EXPECT_LE(Distance(&exact[r * dimension], &polyline.points[r * dimension],
                       dimension),
              1e-14);
  }
  constexpr int kSamples = 32;
  std::vector<double> between;
  for (size_t r = 0; r + 1 < t.size(); ++r) {
    EXPECT_LT(t[r], t[r + 1]);
    for (int k = 1; k < kSamples; ++k) {
      between.push_back(t[r] + (t[r + 1] - t[r]) * k / kSamples);
    }
  }
  const std::vector<double> curve = evaluate(between);
  double worst = 0.0;
  for (size_t s = 0; s < between.size(); ++s) {
    const size_t r = s / (kSamples - 1);
    worst = std::max(worst,
                     DistanceToSegment(
                         &curve[s * dimension], &polyline.points[r * dimension],
                         &polyline.points[(r + 1) * dimension], dimension));
  }
  EXPECT_LE(worst, tolerance * (1 + 1e-12));
  return worst;
}

std::vector<double> EvaluateBezier(const BezierCurveView& curve,
                                   const std::vector<double>& t) {
  std::vector<double> points(t.size() * curve.control_points.dimension);
  const std::vector<absl::Span<double>> output = {absl::MakeSpan(points)};
  EXPECT_TRUE(EvaluateBezierCurve(curve, t, output).ok());
  return points;
}

std::vector<double> EvaluateBSpline(const BSplineCurveView& curve,
                                    const std::vector<double>& t) {
  std::vector<double> points(t.size() * curve.control_points.dimension);
  const std::vector<absl::Span<double>> output = {absl::MakeSpan(points)};
  EXPECT_TRUE(EvaluateBSplineCurve(curve, t, output).ok());
  return points;
}

TEST(TessellationTest, RandomBezierCurvesStayWithinTolerance) {
  std::mt19937_64 rng(7);
  for (int degree = 1; degree <= 15; ++degree) {
    for (int dimension : {2, 3}) {
      const std::vector<double> points =
          RandomValues(rng, static_cast<size_t>(degree + 1) * dimension);
      const BezierCurveView curve{
          .control_points = {.dimension = dimension, .coordinates = points},
          .weights = {}};
      for (double tolerance : {1e-2, 1e-3, 1e-4, 1e-5}) {
        SCOPED_TRACE(testing::Message() << "degree " << degree << " dim "
                                        << dimension << " tol " << tolerance);
        const absl::StatusOr<Polyline> polyline =
            TessellateBezierCurve(curve, tolerance, 1 << 20);
        ASSERT_TRUE(polyline.ok()) << polyline.status();
        CheckPolyline(*polyline, dimension, 0.0, 1.0, tolerance,
                      [&](const std::vector<double>& t) {
                        return EvaluateBezier(curve, t);
                      });
        if (degree == 1) {
          EXPECT_EQ(polyline->parameters.size(), 2u);
        }
      }
    }
  }
}

TEST(TessellationTest, PointCountGrowsLikeInverseSquareRootOfTolerance) {
  std::mt19937_64 rng(11);
  for (int degree : {3, 7}) {
    const std::vector<double> points = RandomValues(rng, 3 * (degree + 1));
    const BezierCurveView curve{
        .control_points = {.dimension = 3, .coordinates = points},
        .weights = {}};
    const auto count = [&](double tolerance) {
      return static_cast<double>(
          TessellateBezierCurve(curve, tolerance, 1 << 22)->parameters.size());
    };
    // 100x smaller tolerance: about 10x more points (dyadic steps make the
    // ratio jumpy, hence the wide band).
    const double ratio = count(1e-7) / count(1e-5);
    EXPECT_GT(ratio, 5.0) << degree;
    EXPECT_LT(ratio, 20.0) << degree;
  }
}

TEST(TessellationTest, RationalCurvesIncludingPointsAtInfinity) {
  // The half circle with a point at infinity, and a random rational curve.
  const std::vector<double> half = {1, 0, 0, 1, -1, 0};
  const std::vector<double> half_weights = {1, 0, 1};
  std::mt19937_64 rng(3);
  const std::vector<double> random = RandomValues(rng, 3 * 6);
  std::vector<double> random_weights = RandomValues(rng, 6);
  for (double& w : random_weights) w = 0.2 + std::abs(w) * 3;
  const std::vector<BezierCurveView> curves = {
      {.control_points = {.dimension = 2, .coordinates = half},
       .weights = half_weights},
      {.control_points = {.dimension = 3, .coordinates = random},
       .weights = random_weights}};
  for (const BezierCurveView& curve : curves) {
    for (double tolerance : {1e-2, 1e-4, 1e-6}) {
      const absl::StatusOr<Polyline> polyline =
          TessellateBezierCurve(curve, tolerance, 1 << 20);
      ASSERT_TRUE(polyline.ok()) << polyline.status();
      CheckPolyline(*polyline, curve.control_points.dimension, 0.0, 1.0,
                    tolerance, [&](const std::vector<double>& t) {
                      return EvaluateBezier(curve, t);
                    });
    }
  }
}

TEST(TessellationTest, BSplineCurvesWithKnots) {
  std::mt19937_64 rng(5);
  const std::vector<double> points = RandomValues(rng, 3 * 9);
  std::vector<double> weights = RandomValues(rng, 9);
  for (double& w : weights) w = 0.3 + std::abs(w);
  // Clamped with a double interior knot, and unclamped uniform.
  const std::vector<std::vector<double>> knot_vectors = {
      {0, 0, 0, 0, 0.5, 1, 1, 2, 2.5, 3, 3, 3, 3},
      {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}};
  for (const std::vector<double>& knots : knot_vectors) {
    for (bool rational : {false, true}) {
      const BSplineCurveView curve{
          .degree = 3,
          .control_points = {.dimension = 3, .coordinates = points},
          .knots = knots,
          .weights = rational ? absl::Span<const double>(weights)
                              : absl::Span<const double>()};
      for (double tolerance : {1e-2, 1e-4, 1e-6}) {
        const absl::StatusOr<Polyline> polyline =
            TessellateBSplineCurve(curve, tolerance, 1 << 20);
        ASSERT_TRUE(polyline.ok()) << polyline.status();
        CheckPolyline(*polyline, 3, knots[3], knots[knots.size() - 4],
                      tolerance, [&](const std::vector<double>& t) {
                        return EvaluateBSpline(curve, t);
                      });
        // Every interior knot of the domain is a polyline point.
        for (size_t i = 4; i + 4 < knots.size(); ++i) {
          EXPECT_TRUE(std::binary_search(polyline->parameters.begin(),
                                         polyline->parameters.end(), knots[i]));
        }
      }
    }
  }
}

// The parabola (0,0), (1,2), (2,0): the middle control point of a piece at
// depth d lies 2 4^-d from the midpoint of its chord (the bound
// n^2 |D2| 4^-d / 8 with n = 2 and |D2| = 4, exact for a parabola). The
// bound asks for 2 4^-d <= 0.05 at tolerance 0.1: d = 3, 9 points. The
// flatness test measures the distance to the chord itself, which is shorter
// once the pieces are no longer symmetric: 7 points.
TEST(TessellationTest, PointBoundOfAParabola) {
  const std::vector<double> points = {0, 0, 1, 2, 2, 0};
  const BezierCurveView curve{
      .control_points = {.dimension = 2, .coordinates = points}, .weights = {}};
  const absl::StatusOr<Polyline> polyline =
      TessellateBezierCurve(curve, 0.1, 1 << 10);
  ASSERT_TRUE(polyline.ok()) << polyline.status();
  EXPECT_EQ(polyline->parameters.size(), 7u);
  EXPECT_EQ(BezierCurvePointBound(curve, 0.1), 9u);
  // Lines and points need their two ends only.
  const std::vector<double> line = {0, 0, 1, 1, 2, 2};
  EXPECT_EQ(BezierCurvePointBound(
                {.control_points = {.dimension = 2, .coordinates = line},
                 .weights = {}},
                1e-9),
            2u);
}

// Tessellates `curve` and expects at most BezierCurvePointBound points.
void ExpectBoundHolds(const BezierCurveView& curve, double tolerance) {
  const absl::StatusOr<Polyline> polyline =
      TessellateBezierCurve(curve, tolerance, 1 << 22);
  ASSERT_TRUE(polyline.ok()) << polyline.status();
  EXPECT_GE(BezierCurvePointBound(curve, tolerance),
            polyline->parameters.size());
}

// The same for a B-spline; returns false, checking nothing, when `curve`
// is not valid.
bool ExpectBoundHolds(const BSplineCurveView& curve, double tolerance) {
  if (!ValidateBSplineCurve(curve).ok()) return false;
  const absl::StatusOr<Polyline> polyline =
      TessellateBSplineCurve(curve, tolerance, 1 << 22);
  EXPECT_TRUE(polyline.ok()) << polyline.status();
  if (!polyline.ok()) return false;
  EXPECT_GE(BSplineCurvePointBound(curve, tolerance),
            polyline->parameters.size());
  return true;
}

// Random knots in [0, 4] for `count` control points of `degree`, with the
// ends repeated degree + 1 times when `clamped`.
std::vector<double> RandomKnots(std::mt19937_64& rng, int count, int degree,
                                bool clamped) {
  std::vector<double> knots =
      RandomValues(rng, static_cast<size_t>(count + degree + 1), 0, 4);
  std::sort(knots.begin(), knots.end());
  if (clamped) {
    std::fill(knots.begin(), knots.begin() + degree + 1, knots[0]);
    std::fill(knots.end() - degree - 1, knots.end(), knots.back());
  }
  return knots;
}

TEST(TessellationTest, PointBoundsHoldForRandomCurves) {
  std::mt19937_64 rng(23);
  int splines_checked = 0;
  for (int degree = 0; degree <= 9; ++degree) {
    for (int dimension : {1, 2, 3, 5}) {
      for (double tolerance : {1e-1, 1e-3, 1e-5, 1e-7}) {
        SCOPED_TRACE(testing::Message() << "degree " << degree << " dim "
                                        << dimension << " tol " << tolerance);
        const std::vector<double> points =
            RandomValues(rng, static_cast<size_t>(degree + 1) * dimension);
        const BezierCurveView bezier{
            .control_points = {.dimension = dimension, .coordinates = points},
            .weights = {}};
        ExpectBoundHolds(bezier, tolerance);

        // A B-spline with random interior knots (some doubled), clamped or
        // not, with 3 to 12 control points more than its degree needs.
        const int count = degree + 1 + static_cast<int>(rng() % 10);
        std::vector<double> knots =
            RandomKnots(rng, count, degree, /*clamped=*/rng() % 2 == 0);
        if (rng() % 2 == 0 && count > degree + 2 && degree > 1) {
          knots[degree + 2] = knots[degree + 1];
        }
        const std::vector<double> control =
            RandomValues(rng, static_cast<size_t>(count) * dimension);
        const BSplineCurveView bspline{
            .degree = degree,
            .control_points = {.dimension = dimension, .coordinates = control},
            .knots = knots,
            .weights = {}};
        if (ExpectBoundHolds(bspline, tolerance)) ++splines_checked;
      }
    }
  }
  EXPECT_GT(splines_checked, 100);
}

// The bound does not change under an affine change of parameter: the same
// cubic over knots scaled from 1e-150 to 1e169 (a fuzzer's request, whose
// derivative control points of 1 / width^2 ~ 1e-338 were subnormal and
// gave a bound below the polyline) has the bound of its unit knots, and
// the bound holds.
TEST(TessellationTest, PointBoundIsTheSameAtEveryKnotScale) {
  const std::vector<double> points = {1,   0,    0.5, 0.9, -0.3, 1.2, -1,
                                      0.1, -0.4, -1,  0.6, -0.8, 1,   0};
  const std::vector<double> unit = {0, 0, 0, 0, 0.25, 0.5, 0.75, 1, 1, 1, 1};
  const auto view = [&](const std::vector<double>& knots) {
    return BSplineCurveView{
        .degree = 3,
        .control_points = {.dimension = 2, .coordinates = points},
        .knots = knots,
        .weights = {}};
  };
  const size_t unit_bound = BSplineCurvePointBound(view(unit), 1e-3);
  for (double scale : {1e-150, 1e-3, 1e100, 1e169}) {
    SCOPED_TRACE(testing::Message() << "scale " << scale);
    std::vector<double> knots = unit;
    const double offset = scale > 1e168 ? 8.8e168 : 0.0;
    for (double& knot : knots) knot = offset + scale * knot;
    EXPECT_EQ(BSplineCurvePointBound(view(knots), 1e-3), unit_bound);
    EXPECT_TRUE(ExpectBoundHolds(view(knots), 1e-3));
  }
}

// A tolerance double precision cannot resolve is refused before any work;
// a line is flat at any tolerance.
TEST(TessellationTest, UnresolvableToleranceIsRefusedAtOnce) {
  const std::vector<double> cubic = {0, 0, 1, 2, 3, 2, 4, 0};
  const BezierCurveView curve{
      .control_points = {.dimension = 2, .coordinates = cubic}, .weights = {}};
  for (double tolerance : {1e-300, 1e-15}) {
    const absl::StatusOr<Polyline> polyline =
        TessellateBezierCurve(curve, tolerance, 1 << 24);
    EXPECT_EQ(polyline.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_EQ(FieldPathOf(polyline.status()), "tolerance");
  }
  EXPECT_TRUE(TessellateBezierCurve(curve, 1e-8, 1 << 24).ok());
  const std::vector<double> knots = {0, 0, 0, 0, 1, 1, 1, 1};
  const BSplineCurveView bspline{
      .degree = 3,
      .control_points = {.dimension = 2, .coordinates = cubic},
      .knots = knots,
      .weights = {}};
  EXPECT_EQ(TessellateBSplineCurve(bspline, 1e-300, 1 << 24).status().code(),
            absl::StatusCode::kInvalidArgument);
  const std::vector<double> line = {0, 0, 4, 2};
  const absl::StatusOr<Polyline> segment = TessellateBezierCurve(
      {.control_points = {.dimension = 2, .coordinates = line}, .weights = {}},
      1e-300, 16);
  ASSERT_TRUE(segment.ok()) << segment.status();
  EXPECT_EQ(segment->parameters.size(), 2u);
}

// The quarter circle (1,0), (1,1), (0,1) with weights 1, sqrt(2)/2, 1:
// about the centre (1/2, 1/2) every |P_i - c| is sqrt(2)/2, the spatial
// homogeneous points w_i (P_i - c) have the second difference
// (-sqrt(2)/2, -sqrt(2)/2) of length 1 and the weights 2 - sqrt(2), so
// D = (1 + (sqrt(2)/2)(2 - sqrt(2))) / (sqrt(2)/2) = 2, the deviation
// bound n^2 D / 8 = 1, and 1 4^-d <= 0.0005 first at d = 6: 65 points.
TEST(TessellationTest, PointBoundOfARationalQuarterCircle) {
  const std::vector<double> points = {1, 0, 1, 1, 0, 1};
  const std::vector<double> weights = {1, std::sqrt(0.5), 1};
  const BezierCurveView curve{
      .control_points = {.dimension = 2, .coordinates = points},
      .weights = weights};
  EXPECT_EQ(BezierCurvePointBound(curve, 1e-3), 65u);
  const absl::StatusOr<Polyline> polyline =
      TessellateBezierCurve(curve, 1e-3, 1 << 10);
  ASSERT_TRUE(polyline.ok()) << polyline.status();
  EXPECT_LE(polyline->parameters.size(), 65u);
  // Every point is on the circle.
  for (size_t i = 0; i < polyline->parameters.size(); ++i) {
    EXPECT_NEAR(
        std::hypot(polyline->points[2 * i], polyline->points[2 * i + 1]), 1.0,
        1e-12);
  }
}

// Weights all equal change neither the curve nor its bound; a weight of 0
// leaves no bound.
TEST(TessellationTest, RationalPointBoundsOfEqualAndZeroWeights) {
  const std::vector<double> points = {0, 0, 1, 2, 3, 2, 4, 0};
  const std::vector<double> ones(4, 1.0), twos(4, 2.0);
  const std::vector<double> zero = {1, 0, 0, 1};
  const auto bound = [&](const std::vector<double>& weights) {
    return BezierCurvePointBound(
        {.control_points = {.dimension = 2, .coordinates = points},
         .weights = weights},
        1e-4);
  };
  const size_t polynomial = bound({});
  EXPECT_EQ(bound(ones), polynomial);
  EXPECT_EQ(bound(twos), polynomial);
  EXPECT_EQ(bound(zero), SIZE_MAX);
}

// Random rational curves and NURBS, weights from 1/20 to 20.
TEST(TessellationTest, RationalPointBoundsHoldForRandomCurves) {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> log_weight(-3.0, 3.0);
  const auto random_weights = [&](size_t count) {
    std::vector<double> weights(count);
    for (double& w : weights) w = std::exp(log_weight(rng));
    return weights;
  };
  int splines_checked = 0;
  for (int degree = 1; degree <= 7; ++degree) {
    for (int dimension : {1, 2, 3}) {
      for (double tolerance : {1e-1, 1e-3, 1e-5}) {
        SCOPED_TRACE(testing::Message() << "degree " << degree << " dim "
                                        << dimension << " tol " << tolerance);
        const std::vector<double> points =
            RandomValues(rng, static_cast<size_t>(degree + 1) * dimension);
        const std::vector<double> weights =
            random_weights(static_cast<size_t>(degree) + 1);
        const BezierCurveView bezier{
            .control_points = {.dimension = dimension, .coordinates = points},
            .weights = weights};
        ExpectBoundHolds(bezier, tolerance);

        const int count = degree + 1 + static_cast<int>(rng() % 8);
        const std::vector<double> knots =
            RandomKnots(rng, count, degree, /*clamped=*/true);
        const std::vector<double> control =
            RandomValues(rng, static_cast<size_t>(count) * dimension);
        const std::vector<double> spline_weights =
            random_weights(static_cast<size_t>(count));
        const BSplineCurveView bspline{
            .degree = degree,
            .control_points = {.dimension = dimension, .coordinates = control},
            .knots = knots,
            .weights = spline_weights};
        if (ExpectBoundHolds(bspline, tolerance)) ++splines_checked;
      }
    }
  }
  EXPECT_GT(splines_checked, 40);
}

// A rational curve does not change when all its weights are scaled, and
// neither may its point bound: subnormal weights (the fuzzer's 1e-310) once
// squared to 0 in the bound's norms and gave 2 points for a polyline of
// 178.
TEST(TessellationTest, RationalPointBoundIsScaleInvariant) {
  const std::vector<double> points = {1.00006103515625, 0, 0, 1, -1, 0};
  const std::vector<double> tiny = {
      7.87861249229048e-310, 1.65706651316478e-309, 3.42277921082698e-310};
  std::vector<double> normal;
  for (const double w : tiny) normal.push_back(std::ldexp(w, 1000));
  const double tolerance = 4.9591355495905987e-05;
  const BezierCurveView subnormal_curve{
      .control_points = {.dimension = 2, .coordinates = points},
      .weights = tiny};
  const BezierCurveView scaled_curve{
      .control_points = {.dimension = 2, .coordinates = points},
      .weights = normal};
  const size_t bound = BezierCurvePointBound(subnormal_curve, tolerance);
  EXPECT_EQ(bound, BezierCurvePointBound(scaled_curve, tolerance));
  const absl::StatusOr<Polyline> polyline =
      TessellateBezierCurve(subnormal_curve, tolerance, 1 << 20);
  ASSERT_TRUE(polyline.ok()) << polyline.status();
  EXPECT_GE(bound, polyline->parameters.size());
}

// Every curve kind tessellates: a Hermite curve with the values and slopes
// of (t, t^3) is y = x^3 and a Lagrange curve through (t, t^2) is y = x^2,
// so the distance to a point of it bounds each polyline point's distance; the
// point bound holds.
TEST(TessellationTest, HermiteAndLagrangeCurves) {
  constexpr double kTolerance = 1e-5;
  const std::vector<double> nodes = {-1.0, 0.0, 0.3, 1.0};
  std::vector<double> cubic_points, tangents, parabola_points;
  for (const double t : nodes) {
    cubic_points.insert(cubic_points.end(), {t, t * t * t});
    tangents.insert(tangents.end(), {1.0, 3 * t * t});
    parabola_points.insert(parabola_points.end(), {t, t * t});
  }
  const absl::StatusOr<HermiteCurve> hermite = HermiteCurve::Create(
      {.points = {.dimension = 2, .coordinates = cubic_points},
       .tangents = {.dimension = 2, .coordinates = tangents},
       .nodes = nodes});
  const absl::StatusOr<LagrangeCurve> lagrange = LagrangeCurve::Create(
      {.points = {.dimension = 2, .coordinates = parabola_points},
       .nodes = nodes});
  ASSERT_TRUE(hermite.ok() && lagrange.ok());
  const std::pair<Curve, int> cases[] = {{*hermite, 3}, {*lagrange, 2}};
  for (const auto& [curve, power] : cases) {
    const absl::StatusOr<Polyline> polyline =
        TessellateCurve(curve, kTolerance, 1 << 20);
    ASSERT_TRUE(polyline.ok()) << polyline.status();
    const std::vector<double>& t = polyline->parameters;
    const std::vector<double>& xy = polyline->points;
    EXPECT_GE(CurvePointBound(curve, kTolerance), t.size());
    EXPECT_EQ(t.front(), -1.0);
    EXPECT_EQ(t.back(), 1.0);
    for (size_t k = 0; k < t.size(); ++k) {
      EXPECT_NEAR(xy[2 * k], t[k], 1e-15);
      EXPECT_NEAR(xy[2 * k + 1], std::pow(t[k], power), 1e-14);
      if (k == 0) continue;
      EXPECT_LT(t[k - 1], t[k]);
      for (const double f : {0.25, 0.5, 0.75}) {
        const double x = (1 - f) * xy[2 * k - 2] + f * xy[2 * k];
        const double y = (1 - f) * xy[2 * k - 1] + f * xy[2 * k + 1];
        EXPECT_LE(testing_util::DistanceToPowerCurve(x, y, power), kTolerance);
      }
    }
    // The Hermite curve's nodes end its pieces: they are polyline points.
    for (const double node : power == 3 ? nodes : std::vector<double>{}) {
      EXPECT_TRUE(std::find(t.begin(), t.end(), node) != t.end()) << node;
    }
  }
}

TEST(TessellationTest, CurveErrors) {
  const std::vector<double> points = {0, 0, 1, 2, 2, 0, 3, 1};
  const BezierCurveView curve{
      .control_points = {.dimension = 2, .coordinates = points}, .weights = {}};
  for (double tolerance : {0.0, -1.0, std::nan(""), HUGE_VAL}) {
    EXPECT_EQ(
        FieldPathOf(TessellateBezierCurve(curve, tolerance, 100).status()),
        "tolerance");
  }
  EXPECT_EQ(TessellateBezierCurve(curve, 1e-4, 10).status().code(),
            absl::StatusCode::kResourceExhausted);
  const absl::StatusOr<Polyline> enough =
      TessellateBezierCurve(curve, 1e-4, 1000);
  ASSERT_TRUE(enough.ok());
  EXPECT_TRUE(
      TessellateBezierCurve(curve, 1e-4, enough->parameters.size()).ok());
  EXPECT_EQ(TessellateBezierCurve(curve, 1e-4, enough->parameters.size() - 1)
                .status()
                .code(),
            absl::StatusCode::kResourceExhausted);
  CancellationToken token;
  token.Cancel();
  EXPECT_EQ(TessellateBezierCurve(curve, 1e-9, 1 << 20, &token).status().code(),
            absl::StatusCode::kCancelled);
  const std::vector<double> point = {2, 5};
  const std::vector<double> knots = {1, 3};
  const BSplineCurveView constant{
      .degree = 0,
      .control_points = {.dimension = 2, .coordinates = point},
      .knots = knots,
      .weights = {}};
  const absl::StatusOr<Polyline> constant_polyline =
      TessellateBSplineCurve(constant, 1e-3, 100);
  ASSERT_TRUE(constant_polyline.ok()) << constant_polyline.status();
  EXPECT_EQ(constant_polyline->parameters, (std::vector<double>{1, 3}));
  EXPECT_EQ(constant_polyline->points, (std::vector<double>{2, 5, 2, 5}));
}

}  // namespace
}  // namespace freeform
