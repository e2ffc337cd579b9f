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

#include "freeform/core/status.h"
#include "freeform/core/surface_output.h"
#include "teapot.h"
#include "test_util.h"

namespace freeform {
namespace {

using testing_util::Patches;
using testing_util::RandomValues;
using testing_util::ReadTeapot;

double Distance(const double* a, const double* b, int dimension) {
  double d2 = 0.0;
  for (int j = 0; j < dimension; ++j) d2 += (a[j] - b[j]) * (a[j] - b[j]);
  return std::sqrt(d2);
}

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

// ------------------------------------------------------------ surfaces --

// SurfacePoint evaluates patch at (u, v), with S_u x S_v in `normal`.
std::array<double, 3> SurfacePoint(const BezierSurfaceView& patch, double u,
                                   double v,
                                   std::array<double, 3>* normal = nullptr) {
  const std::vector<double> uv = {u, v};
  std::vector<std::vector<double>> buffers(3, std::vector<double>(3));
  std::vector<absl::Span<double>> output(buffers.begin(), buffers.end());
  EXPECT_TRUE(
      EvaluateBezierSurface(patch, SurfaceSamples::Pairs(uv), output).ok());
  if (normal != nullptr) {
    const std::vector<double>& a = buffers[1];
    const std::vector<double>& b = buffers[2];
    *normal = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
               a[0] * b[1] - a[1] * b[0]};
  }
  return {buffers[0][0], buffers[0][1], buffers[0][2]};
}

// The sides of every patch whose control points no other patch side has
// (in either direction): (patch, side) with side 0..3 = v=0, u=1, v=1, u=0.
std::map<std::pair<uint32_t, int>, bool> UnsharedSides(const Patches& patches) {
  std::map<std::vector<double>, int> uses;
  std::map<std::pair<uint32_t, int>, std::vector<double>> keys;
  for (uint32_t i = 0; i < patches.nets.size(); ++i) {
    const int nu = patches.counts[i][0], nv = patches.counts[i][1];
    for (int side = 0; side < 4; ++side) {
      std::vector<std::array<double, 3>> points;
      const int count = side % 2 == 0 ? nu : nv;
      for (int k = 0; k < count; ++k) {
        const int row = side == 0 || side == 2 ? k : side == 1 ? nu - 1 : 0;
        const int col = side == 1 || side == 3 ? k : side == 2 ? nv - 1 : 0;
        const double* p = &patches.nets[i][3 * (row * nv + col)];
        points.push_back({p[0], p[1], p[2]});
      }
      std::vector<std::array<double, 3>> reversed(points.rbegin(),
                                                  points.rend());
      const auto& key = std::min(points, reversed);
      std::vector<double> flat;
      for (const auto& p : key) flat.insert(flat.end(), p.begin(), p.end());
      ++uses[flat];
      keys[{i, side}] = flat;
    }
  }
  std::map<std::pair<uint32_t, int>, bool> unshared;
  for (const auto& [side, key] : keys) unshared[side] = uses[key] == 1;
  return unshared;
}

// SideOf returns the patch side both (u, v) lie on, or -1.
int SideOf(const double* a, const double* b) {
  if (a[1] == 0 && b[1] == 0) return 0;
  if (a[0] == 1 && b[0] == 1) return 1;
  if (a[1] == 1 && b[1] == 1) return 2;
  if (a[0] == 0 && b[0] == 0) return 3;
  return -1;
}

struct MeshFigures {
  size_t boundary_edges = 0;
  size_t misoriented_edges = 0;
  double worst_error = 0.0;
};

// CheckMesh checks the mathematics of a mesh of `patches`: vertices and
// triangle corners on their patches, the surface within `tolerance` of
// every triangle (at its centroid, edge midpoints and three inner points,
// through the corners' (u, v)), unit normals, triangles counter-clockwise
// about S_u x S_v, every edge used by at most two triangles, edges used
// once only on patch sides no other patch shares, and no vertex inside a
// boundary edge (no T-junction).
MeshFigures CheckMesh(const Patches& patches, const Mesh& mesh,
                      double tolerance) {
  const std::vector<BezierSurfaceView> views = patches.Views();
  const size_t vertex_count = mesh.vertices.size() / 3;
  EXPECT_EQ(mesh.normals.size(), 3 * vertex_count);
  EXPECT_EQ(mesh.patch.size(), vertex_count);
  EXPECT_EQ(mesh.uv.size(), 2 * vertex_count);
  const size_t triangle_count = mesh.triangles.size() / 3;
  EXPECT_EQ(mesh.triangle_patch.size(), triangle_count);
  EXPECT_EQ(mesh.corner_uv.size(), 6 * triangle_count);
  for (size_t r = 0; r < vertex_count; ++r) {
    const auto p =
        SurfacePoint(views[mesh.patch[r]], mesh.uv[2 * r], mesh.uv[2 * r + 1]);
    EXPECT_LE(Distance(p.data(), &mesh.vertices[3 * r], 3), 1e-12) << r;
    EXPECT_NEAR(std::hypot(mesh.normals[3 * r], mesh.normals[3 * r + 1],
                           mesh.normals[3 * r + 2]),
                1.0, 1e-12)
        << r;
  }
  MeshFigures figures;
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  std::map<std::pair<uint32_t, uint32_t>, std::vector<size_t>> edges;
  const std::vector<std::array<double, 3>> weights = {
      {1 / 3.0, 1 / 3.0, 1 / 3.0},
      {0.5, 0.5, 0},
      {0, 0.5, 0.5},
      {0.5, 0, 0.5},
      {2 / 3.0, 1 / 6.0, 1 / 6.0},
      {1 / 6.0, 2 / 3.0, 1 / 6.0},
      {1 / 6.0, 1 / 6.0, 2 / 3.0}};
  for (size_t t = 0; t < triangle_count; ++t) {
    const BezierSurfaceView& patch = views[mesh.triangle_patch[t]];
    const uint32_t* corner = &mesh.triangles[3 * t];
    const double* uv = &mesh.corner_uv[6 * t];
    for (int k = 0; k < 3; ++k) {
      const auto p = SurfacePoint(patch, uv[2 * k], uv[2 * k + 1]);
      EXPECT_LE(Distance(p.data(), &mesh.vertices[3 * corner[k]], 3), 1e-12);
      ++directed[{corner[k], corner[(k + 1) % 3]}];
      edges[std::minmax(corner[k], corner[(k + 1) % 3])].push_back(t);
    }
    for (const auto& w : weights) {
      double mesh_point[3] = {0, 0, 0};
      double u = 0, v = 0;
      for (int k = 0; k < 3; ++k) {
        for (int x = 0; x < 3; ++x) {
          mesh_point[x] += w[k] * mesh.vertices[3 * corner[k] + x];
        }
        u += w[k] * uv[2 * k];
        v += w[k] * uv[2 * k + 1];
      }
      const auto p = SurfacePoint(patch, u, v);
      const double error = Distance(p.data(), mesh_point, 3);
      figures.worst_error = std::max(figures.worst_error, error);
    }
    // Orientation: the parameter triangle is counter-clockwise, which makes
    // the space triangle turn about S_u x S_v.
    const double area_uv =
        (uv[2] - uv[0]) * (uv[5] - uv[1]) - (uv[4] - uv[0]) * (uv[3] - uv[1]);
    EXPECT_GT(area_uv, 0.0) << t;
    std::array<double, 3> n;
    SurfacePoint(patch, (uv[0] + uv[2] + uv[4]) / 3,
                 (uv[1] + uv[3] + uv[5]) / 3, &n);
    const double* a = &mesh.vertices[3 * corner[0]];
    const double* b = &mesh.vertices[3 * corner[1]];
    const double* c = &mesh.vertices[3 * corner[2]];
    const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double g[3] = {e1[1] * e2[2] - e1[2] * e2[1],
                         e1[2] * e2[0] - e1[0] * e2[2],
                         e1[0] * e2[1] - e1[1] * e2[0]};
    EXPECT_GT(g[0] * n[0] + g[1] * n[1] + g[2] * n[2], 0.0) << t;
  }
  EXPECT_LE(figures.worst_error, tolerance * (1 + 1e-9));
  const std::map<std::pair<uint32_t, int>, bool> unshared =
      UnsharedSides(patches);
  for (const auto& [edge, triangles] : edges) {
    EXPECT_LE(triangles.size(), 2u);
    if (triangles.size() == 2 && directed[edge] != 1) {
      ++figures.misoriented_edges;
    }
    if (triangles.size() != 1) continue;
    ++figures.boundary_edges;
    // A boundary edge lies on an unshared side of its triangle's patch.
    const size_t t = triangles[0];
    const double* uv = &mesh.corner_uv[6 * t];
    int ka = 0, kb = 0;
    for (int k = 0; k < 3; ++k) {
      if (mesh.triangles[3 * t + k] == edge.first) ka = k;
      if (mesh.triangles[3 * t + k] == edge.second) kb = k;
    }
    const int side = SideOf(uv + 2 * ka, uv + 2 * kb);
    EXPECT_NE(side, -1) << "boundary edge inside patch " << t;
    if (side == -1) continue;
    EXPECT_TRUE(unshared.at({mesh.triangle_patch[t], side}))
        << "crack along a shared side, triangle " << t;
    // No T-junction: no vertex strictly inside a boundary edge.
    const double* a = &mesh.vertices[3 * edge.first];
    const double* b = &mesh.vertices[3 * edge.second];
    const double length = Distance(a, b, 3);
    for (size_t r = 0; r < vertex_count; ++r) {
      const double* p = &mesh.vertices[3 * r];
      const double da = Distance(p, a, 3), db = Distance(p, b, 3);
      if (da < 1e-9 * length || db < 1e-9 * length) continue;
      EXPECT_GT(DistanceToSegment(p, a, b, 3), 1e-9 * length) << r;
    }
  }
  // Welded: no two vertices coincide.
  std::vector<std::array<double, 3>> sorted;
  for (size_t r = 0; r < vertex_count; ++r) {
    sorted.push_back({mesh.vertices[3 * r], mesh.vertices[3 * r + 1],
                      mesh.vertices[3 * r + 2]});
  }
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end());
  return figures;
}

TEST(TessellationTest, UtahTeapotIsWatertightAndWithinTolerance) {
  const Patches teapot = ReadTeapot();
  ASSERT_EQ(teapot.nets.size(), 32u);
  const std::vector<BezierSurfaceView> views = teapot.Views();
  constexpr double kTolerance = 1e-3;
  const auto start = std::chrono::steady_clock::now();
  const absl::StatusOr<Mesh> mesh =
      TessellateBezierPatches(views, kTolerance, 1 << 22);
  const double ms = std::chrono::duration<double, std::milli>(
                        std::chrono::steady_clock::now() - start)
                        .count();
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  const MeshFigures figures = CheckMesh(teapot, *mesh, kTolerance);
  std::printf(
      "teapot at %g: %zu vertices, %zu triangles, %.2f ms; worst sampled "
      "error %.3g, %zu boundary edges, %zu edges not oriented "
      "consistently\n",
      kTolerance, mesh->vertices.size() / 3, mesh->triangles.size() / 3, ms,
      figures.worst_error, figures.boundary_edges, figures.misoriented_edges);
  EXPECT_GT(figures.boundary_edges, 0u);  // rim, spout and handle ends
  // Coarser tolerance, fewer vertices; finer, more.
  const size_t coarse =
      TessellateBezierPatches(views, 1e-2, 1 << 22)->vertices.size();
  EXPECT_LT(coarse, mesh->vertices.size());
  // The planned size bounds the mesh, and not loosely: welding only merges
  // the vertices of the few patch sides that meet without sharing control
  // points.
  const absl::StatusOr<MeshSize> bound =
      BezierPatchesMeshBound(views, kTolerance, 1 << 22);
  ASSERT_TRUE(bound.ok()) << bound.status();
  EXPECT_GE(bound->vertices, mesh->vertices.size() / 3);
  EXPECT_LE(bound->vertices, 2 * mesh->vertices.size() / 3);
  EXPECT_GE(bound->triangles, mesh->triangles.size() / 3);
  EXPECT_LE(bound->triangles, 2 * mesh->triangles.size() / 3);
  EXPECT_EQ(BezierPatchesMeshBound(views, kTolerance, 100).status().code(),
            absl::StatusCode::kResourceExhausted);
}

// Two patches of different degrees sharing a side in opposite directions:
// A's side v = 1 is B's side u = 0 reversed.
Patches TwoPatches() {
  Patches patches;
  std::vector<double> a;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      a.insert(a.end(), {static_cast<double>(i), static_cast<double>(j),
                         0.3 * std::sin(i * 1.3 + j * 0.7)});
    }
  }
  std::vector<double> b;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 4; ++j) {
      if (i == 0) {
        const double* p = &a[3 * ((3 - j) * 4 + 3)];
        b.insert(b.end(), p, p + 3);
      } else {
        b.insert(b.end(), {3.0 - j, 3.0 + 1.5 * i, 0.8 * std::cos(i + j)});
      }
    }
  }
  patches.nets = {a, b};
  patches.counts = {{4, 4}, {3, 4}};
  return patches;
}

TEST(TessellationTest, SharedReversedSideIsWelded) {
  const Patches patches = TwoPatches();
  for (double tolerance : {1e-1, 1e-3, 1e-4}) {
    const absl::StatusOr<Mesh> mesh =
        TessellateBezierPatches(patches.Views(), tolerance, 1 << 22);
    ASSERT_TRUE(mesh.ok()) << mesh.status();
    const MeshFigures figures = CheckMesh(patches, *mesh, tolerance);
    EXPECT_EQ(figures.misoriented_edges, 0u);
    // Vertices on the shared curve appear once and are used by both.
    std::map<uint32_t, std::array<bool, 2>> on_shared;
    for (size_t t = 0; t < mesh->triangle_patch.size(); ++t) {
      const uint32_t patch = mesh->triangle_patch[t];
      for (int k = 0; k < 3; ++k) {
        const double* uv = &mesh->corner_uv[6 * t + 2 * k];
        if ((patch == 0 && uv[1] == 1) || (patch == 1 && uv[0] == 0)) {
          on_shared[mesh->triangles[3 * t + k]][patch] = true;
        }
      }
    }
    ASSERT_GE(on_shared.size(), 2u);
    for (const auto& [vertex, used] : on_shared) {
      EXPECT_TRUE(used[0] && used[1]) << vertex;
    }
  }
}

TEST(TessellationTest, PatchErrors) {
  Patches patches = TwoPatches();
  std::vector<BezierSurfaceView> views = patches.Views();
  EXPECT_EQ(TessellateBezierPatches(views, 1e-4, 10).status().code(),
            absl::StatusCode::kResourceExhausted);
  EXPECT_EQ(FieldPathOf(TessellateBezierPatches(views, 0.0, 100).status()),
            "tolerance");
  const std::vector<double> weights(12, 1.0);
  views[1].weights = weights;
  EXPECT_EQ(FieldPathOf(TessellateBezierPatches(views, 1e-3, 1000).status()),
            "surfaces[1].bezier.weights");
  views[1].weights = {};
  views[0].control_net.dimension = 2;
  views[0].control_net.count_v = 6;
  EXPECT_EQ(FieldPathOf(TessellateBezierPatches(views, 1e-3, 1000).status()),
            "surfaces[0].bezier.control_net.dimension");
  CancellationToken token;
  token.Cancel();
  EXPECT_EQ(TessellateBezierPatches(patches.Views(), 1e-3, 1 << 20, &token)
                .status()
                .code(),
            absl::StatusCode::kCancelled);
}

}  // namespace
}  // namespace freeform
