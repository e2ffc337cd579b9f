#include "freeform/core/subdivision.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "freeform/core/status.h"
#include "test_util.h"

namespace freeform {
namespace {

using ::freeform::testing_util::MaxDifference;

using ::freeform::testing_util::EvenlySpaced;
using ::freeform::testing_util::RandomValues;

using ::testing::Optional;

constexpr double kTolerance = 1e-12;
constexpr size_t kSamples = 10000;

std::vector<double> EvaluateBezier(const BezierCurveView& curve,
                                   const std::vector<double>& params) {
  std::vector<double> values(params.size() * curve.control_points.dimension);
  const std::vector<absl::Span<double>> output = {absl::MakeSpan(values)};
  const absl::Status status = EvaluateBezierCurve(curve, params, output);
  EXPECT_TRUE(status.ok()) << status;
  return values;
}

std::vector<double> EvaluateBSpline(const BSplineCurveView& curve,
                                    const std::vector<double>& params) {
  std::vector<double> values(params.size() * curve.control_points.dimension);
  const std::vector<absl::Span<double>> output = {absl::MakeSpan(values)};
  const absl::Status status = EvaluateBSplineCurve(curve, params, output);
  EXPECT_TRUE(status.ok()) << status;
  return values;
}

void ExpectFieldError(const absl::Status& status, const std::string& field) {
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << status;
  EXPECT_THAT(FieldPathOf(status), Optional(field)) << status;
}

// A random B-spline of degree p with `points` control points: clamped or
// with random knots before and after the domain, some interior knots
// repeated up to p times; weights in [0.5, 2] when rational.
BSplineCurveData RandomBSpline(std::mt19937_64& rng, int p, int points,
                               int dimension, bool clamped, bool rational) {
  BSplineCurveData curve;
  curve.degree = p;
  curve.dimension = dimension;
  curve.coordinates =
      RandomValues(rng, static_cast<size_t>(points) * dimension);
  if (rational) curve.weights = RandomValues(rng, points, 0.5, 2.0);
  const int total = points + p + 1;
  std::vector<double> knots = RandomValues(rng, total, 0.0, 1.0);
  std::sort(knots.begin(), knots.end());
  // Repeat a few interior knots (never beyond p).
  for (int i = p + 1; i + 1 < points && p > 1; i += 3) knots[i + 1] = knots[i];
  if (clamped) {
    for (int i = 0; i <= p; ++i) knots[i] = 0.0;
    for (int i = points; i < total; ++i) knots[i] = 1.0;
  }
  curve.knots = knots;
  EXPECT_TRUE(ValidateBSplineCurve(curve.view()).ok());
  return curve;
}

// The half circle (1,0,1), (0,1,0), (-1,0,1) on 0,0,0,1,1,1; see
// 'Worked example: the half circle with a point at infinity' in
// docs/references.md.
BSplineCurveData HalfCircle() {
  return {.degree = 2,
          .dimension = 2,
          .coordinates = {1, 0, 0, 1, -1, 0},
          .knots = {0, 0, 0, 1, 1, 1},
          .weights = {1, 0, 1}};
}

// ---------------------------------------------------------------------------
// SplitBezierCurve

TEST(SplitBezierCurve, DeCasteljauTriangleAtOneHalf) {
  const std::vector<double> points = {0, 0, 1, 2, 3, 2, 4, 0};
  const BezierCurveView curve{.control_points = {2, points}};
  const std::vector<double> t = {0.5};
  auto pieces = SplitBezierCurve(curve, t);
  ASSERT_TRUE(pieces.ok()) << pieces.status();
  ASSERT_EQ(pieces->size(), 2u);
  EXPECT_EQ((*pieces)[0].coordinates,
            (std::vector<double>{0, 0, 0.5, 1, 1.25, 1.5, 2, 1.5}));
  EXPECT_EQ((*pieces)[1].coordinates,
            (std::vector<double>{2, 1.5, 2.75, 1.5, 3.5, 1, 4, 0}));
}

TEST(SplitBezierCurve, PiecesEvaluateToOriginalForAllDegrees) {
  std::mt19937_64 rng(11);
  for (int n = 1; n <= 15; ++n) {
    for (bool rational : {false, true}) {
      const std::vector<double> points = RandomValues(rng, 3 * (n + 1));
      const std::vector<double> weights =
          rational ? RandomValues(rng, n + 1, 0.5, 2.0) : std::vector<double>{};
      const BezierCurveView curve{.control_points = {3, points},
                                  .weights = weights};
      const std::vector<double> cuts = {0.1, 0.35, 0.36, 0.8};
      auto pieces = SplitBezierCurve(curve, cuts);
      ASSERT_TRUE(pieces.ok()) << pieces.status();
      ASSERT_EQ(pieces->size(), cuts.size() + 1);
      for (size_t k = 0; k < pieces->size(); ++k) {
        const double a = k == 0 ? 0.0 : cuts[k - 1];
        const double b = k == cuts.size() ? 1.0 : cuts[k];
        const std::vector<double> local =
            EvenlySpaced(0.0, 1.0, kSamples / pieces->size());
        std::vector<double> global(local.size());
        for (size_t i = 0; i < local.size(); ++i) {
          global[i] = a + (b - a) * local[i];
        }
        EXPECT_LT(MaxDifference(EvaluateBezier((*pieces)[k].view(), local),
                                EvaluateBezier(curve, global)),
                  kTolerance)
            << "degree " << n << " rational " << rational << " piece " << k;
      }
    }
  }
}

TEST(SplitBezierCurve, HalfCircleWithPointAtInfinity) {
  const std::vector<double> points = {1, 0, 0, 1, -1, 0};
  const std::vector<double> weights = {1, 0, 1};
  const BezierCurveView curve{.control_points = {2, points},
                              .weights = weights};
  const std::vector<double> t = {0.5};
  auto pieces = SplitBezierCurve(curve, t);
  ASSERT_TRUE(pieces.ok()) << pieces.status();
  // Quarter circles: (1,0) w 1, (1,1) w 1/2, (0,1) w 1/2, then mirrored.
  EXPECT_LT(MaxDifference((*pieces)[0].coordinates, {1, 0, 1, 1, 0, 1}), 1e-15);
  EXPECT_LT(MaxDifference((*pieces)[0].weights, {1, 0.5, 0.5}), 1e-15);
  for (const BezierCurveData& piece : *pieces) {
    const std::vector<double> xy =
        EvaluateBezier(piece.view(), EvenlySpaced(0, 1, 101));
    for (size_t i = 0; i < xy.size(); i += 2) {
      EXPECT_NEAR(std::hypot(xy[i], xy[i + 1]), 1.0, 1e-15);
    }
  }
}

TEST(SplitBezierCurve, RejectsParametersOutsideOrNotIncreasing) {
  const std::vector<double> points = {0, 0, 1, 1};
  const BezierCurveView curve{.control_points = {2, points}};
  ExpectFieldError(SplitBezierCurve(curve, std::vector<double>{0.0}).status(),
                   "parameters[0]");
  ExpectFieldError(
      SplitBezierCurve(curve, std::vector<double>{0.2, 1.0}).status(),
      "parameters[1]");
  ExpectFieldError(
      SplitBezierCurve(curve, std::vector<double>{0.2, 0.5, 0.5}).status(),
      "parameters[2]");
  ExpectFieldError(
      SplitBezierCurve(curve, std::vector<double>{std::nan("")}).status(),
      "parameters[0]");
  auto whole = SplitBezierCurve(curve, {});
  ASSERT_TRUE(whole.ok());
  EXPECT_EQ(whole->size(), 1u);
}

// ---------------------------------------------------------------------------
// InsertKnots

TEST(KnotInsertion, HalfCircleSeedExample) {
  // (1,0,1), (0,1,0), (-1,0,1) on 0,0,0,1,1,1 with 1/2 inserted gives
  // (1,0), (1,1), (-1,1), (-1,0) with weights 1, 1/2, 1/2, 1: Q_0^w = P_0^w
  // keeps the weight 1 (docs/references.md,
  // 'Worked example: the half circle with a point at infinity').
  const BSplineCurveData half = HalfCircle();
  const BSplineCurveView curve = half.view();
  auto refined = InsertKnots(curve, std::vector<double>{0.5});
  ASSERT_TRUE(refined.ok()) << refined.status();
  EXPECT_EQ(refined->knots, (std::vector<double>{0, 0, 0, 0.5, 1, 1, 1}));
  EXPECT_LT(MaxDifference(refined->coordinates, {1, 0, 1, 1, -1, 1, -1, 0}),
            1e-15);
  EXPECT_LT(MaxDifference(refined->weights, {1, 0.5, 0.5, 1}), 1e-15);
  const std::vector<double> params = EvenlySpaced(0, 1, 1001);
  EXPECT_LT(MaxDifference(EvaluateBSpline(refined->view(), params),
                          EvaluateBSpline(curve, params)),
            1e-15);
}

TEST(KnotInsertion, RandomCurvesUnchangedForAllDegrees) {
  std::mt19937_64 rng(7);
  for (int p = 1; p <= 15; ++p) {
    for (bool clamped : {true, false}) {
      for (bool rational : {false, true}) {
        const BSplineCurveData curve =
            RandomBSpline(rng, p, p + 6, 3, clamped, rational);
        const double lo = curve.knots[p];
        const double hi = curve.knots[curve.knots.size() - p - 1];
        // Random values, an existing interior knot (multiplicity 2 for
        // p > 1) once more, and for unclamped curves the domain ends p times
        // each, which clamps the curve there (multiplicity p + 1).
        std::vector<double> x = RandomValues(rng, 2 * p + 3, lo, hi);
        if (p >= 3) x.push_back(curve.knots[p + 1]);
        if (!clamped) {
          x.insert(x.end(), static_cast<size_t>(p), lo);
          x.insert(x.end(), static_cast<size_t>(p), hi);
        }
        std::sort(x.begin(), x.end());
        auto refined = InsertKnots(curve.view(), x);
        ASSERT_TRUE(refined.ok()) << refined.status() << " degree " << p;
        ASSERT_TRUE(ValidateBSplineCurve(refined->view()).ok());
        EXPECT_EQ(refined->coordinates.size(),
                  curve.coordinates.size() + 3 * x.size());
        const std::vector<double> params = EvenlySpaced(lo, hi, kSamples);
        EXPECT_LT(MaxDifference(EvaluateBSpline(refined->view(), params),
                                EvaluateBSpline(curve.view(), params)),
                  kTolerance)
            << "degree " << p << " clamped " << clamped << " rational "
            << rational;
      }
    }
  }
}

TEST(KnotInsertion, UnclampedWithRepeatedKnotAtDomainEnd) {
  // Degree 3, 6 points, domain [u_3, u_6] = [3, 5] with u_5 = u_6 = 5.
  std::mt19937_64 rng(31);
  const std::vector<double> points = RandomValues(rng, 12);
  const std::vector<double> weights = RandomValues(rng, 6, 0.5, 2.0);
  const std::vector<double> knots = {0, 1, 2, 3, 4, 5, 5, 6, 7, 8};
  const BSplineCurveView curve{.degree = 3,
                               .control_points = {2, points},
                               .knots = knots,
                               .weights = weights};
  ASSERT_TRUE(ValidateBSplineCurve(curve).ok());
  const std::vector<double> params = EvenlySpaced(3, 5, kSamples);
  const std::vector<std::vector<double>> insertions = {
      {5}, {5, 5}, {3, 3, 3, 5, 5}, {4, 4, 5}, {3, 4.5, 5}};
  for (const std::vector<double>& x : insertions) {
    auto refined = InsertKnots(curve, x);
    ASSERT_TRUE(refined.ok()) << refined.status();
    ASSERT_TRUE(ValidateBSplineCurve(refined->view()).ok());
    EXPECT_LT(MaxDifference(EvaluateBSpline(refined->view(), params),
                            EvaluateBSpline(curve, params)),
              kTolerance);
  }
  ExpectFieldError(InsertKnots(curve, std::vector<double>{5, 5, 5}).status(),
                   "knots[2]");
  auto pieces = DecomposeBSplineCurve(curve);
  ASSERT_TRUE(pieces.ok());
  EXPECT_EQ(pieces->breakpoints, (std::vector<double>{3, 4, 5}));
  for (size_t k = 0; k < 2; ++k) {
    const std::vector<double> local = EvenlySpaced(0, 1, 1000);
    std::vector<double> global(local.size());
    for (size_t i = 0; i < local.size(); ++i)
      global[i] = 3.0 + static_cast<double>(k) + local[i];
    EXPECT_LT(MaxDifference(EvaluateBezier(pieces->segments[k].view(), local),
                            EvaluateBSpline(curve, global)),
              kTolerance);
  }
}

TEST(KnotInsertion, RefinementEqualsRepeatedSingleInsertion) {
  std::mt19937_64 rng(3);
  const BSplineCurveData curve = RandomBSpline(rng, 4, 9, 2, true, false);
  std::vector<double> x = RandomValues(rng, 6, 0.0, 1.0);
  std::sort(x.begin(), x.end());
  auto all = InsertKnots(curve.view(), x);
  ASSERT_TRUE(all.ok());
  BSplineCurveData one = curve;
  for (double u : x) {
    auto next = InsertKnots(one.view(), std::vector<double>{u});
    ASSERT_TRUE(next.ok());
    one = *next;
  }
  EXPECT_EQ(all->knots, one.knots);
  EXPECT_LT(MaxDifference(all->coordinates, one.coordinates), 1e-14);
}

TEST(KnotInsertion, RejectsOutsideDomainDecreasingAndOverflow) {
  const std::vector<double> points = {0, 0, 1, 2, 2, 0, 3, 2, 4, 0};
  const std::vector<double> knots = {0, 0, 0, 0, 1, 2, 2, 2, 2};
  const BSplineCurveView curve{
      .degree = 3, .control_points = {2, points}, .knots = knots};
  ExpectFieldError(InsertKnots(curve, std::vector<double>{-0.1}).status(),
                   "knots[0]");
  ExpectFieldError(InsertKnots(curve, std::vector<double>{0.5, 2.5}).status(),
                   "knots[1]");
  ExpectFieldError(InsertKnots(curve, std::vector<double>{1.5, 0.5}).status(),
                   "knots[1]");
  // 1 already once: two more reach the degree, a third exceeds it.
  EXPECT_TRUE(InsertKnots(curve, std::vector<double>{1, 1}).ok());
  ExpectFieldError(
      InsertKnots(curve, std::vector<double>{0.5, 1, 1, 1}).status(),
      "knots[3]");
  // The clamped ends already have multiplicity p + 1.
  ExpectFieldError(InsertKnots(curve, std::vector<double>{0.5, 2}).status(),
                   "knots[1]");
  ExpectFieldError(
      InsertKnots(curve, std::vector<double>{std::nan("")}).status(),
      "knots[0]");
}

TEST(KnotInsertion, SurfaceUnchangedOnGrid) {
  std::mt19937_64 rng(5);
  for (bool rational : {false, true}) {
    for (bool in_u : {true, false}) {
      SurfaceData surface;
      surface.degree_u = 3;
      surface.degree_v = 2;
      surface.dimension = 3;
      surface.count_u = 6;
      surface.count_v = 5;
      surface.coordinates = RandomValues(rng, 6 * 5 * 3);
      if (rational) surface.weights = RandomValues(rng, 30, 0.5, 2.0);
      surface.knots_u = {0, 0, 0, 0, 0.3, 0.6, 1, 1, 1, 1};
      surface.knots_v = {-1, -0.5, 0, 0.2, 0.7, 1, 1.5, 2};
      ASSERT_TRUE(ValidateBSplineSurface(surface.bspline_view()).ok());
      const std::vector<double> x =
          in_u ? std::vector<double>{0.1, 0.3, 0.3, 0.95}
               : std::vector<double>{0, 0.2, 0.5, 1};
      auto refined = InsertSurfaceKnots(surface.bspline_view(), in_u, x);
      ASSERT_TRUE(refined.ok()) << refined.status();
      ASSERT_TRUE(ValidateBSplineSurface(refined->bspline_view()).ok());
      EXPECT_EQ(refined->count_u, in_u ? 10 : 6);
      EXPECT_EQ(refined->count_v, in_u ? 5 : 9);
      const std::vector<double> us = EvenlySpaced(0, 1, 101);
      const std::vector<double> vs = EvenlySpaced(0, 1, 99);
      const SurfaceSamples grid = SurfaceSamples::Grid(us, vs);
      std::vector<double> before(grid.size() * 3), after(grid.size() * 3);
      const std::vector<absl::Span<double>> out_before = {
          absl::MakeSpan(before)};
      const std::vector<absl::Span<double>> out_after = {absl::MakeSpan(after)};
      ASSERT_TRUE(
          EvaluateBSplineSurface(surface.bspline_view(), grid, out_before)
              .ok());
      ASSERT_TRUE(
          EvaluateBSplineSurface(refined->bspline_view(), grid, out_after)
              .ok());
      EXPECT_LT(MaxDifference(before, after), kTolerance);
    }
  }
}

// Every Bezier patch of the decomposition is the surface on its span
// rectangle, clamped in u and unclamped in v.
TEST(DecomposeBSplineSurface, PatchesAreTheSurfaceOnTheirSpans) {
  std::mt19937_64 rng(6);
  for (bool rational : {false, true}) {
    SurfaceData surface{.degree_u = 3,
                        .degree_v = 2,
                        .dimension = 3,
                        .count_u = 6,
                        .count_v = 5,
                        .coordinates = RandomValues(rng, 6 * 5 * 3),
                        .knots_u = {0, 0, 0, 0, 0.3, 0.3, 1, 1, 1, 1},
                        .knots_v = {-1, -0.5, 0, 0.2, 0.7, 1, 1.5, 2}};
    if (rational) surface.weights = RandomValues(rng, 30, 0.5, 2.0);
    auto pieces = DecomposeBSplineSurface(surface.bspline_view());
    ASSERT_TRUE(pieces.ok()) << pieces.status();
    EXPECT_EQ(pieces->breakpoints_u, (std::vector<double>{0, 0.3, 1}));
    EXPECT_EQ(pieces->breakpoints_v, (std::vector<double>{0, 0.2, 0.7, 1}));
    ASSERT_EQ(pieces->patches.size(), 2u * 3u);
    const std::vector<double> st = EvenlySpaced(0, 1, 7);
    for (size_t i = 0; i < 2; ++i) {
      for (size_t j = 0; j < 3; ++j) {
        const SurfaceData& patch = pieces->patches[i * 3 + j];
        EXPECT_EQ(patch.count_u, 4);
        EXPECT_EQ(patch.count_v, 3);
        std::vector<double> us, vs;
        for (const double x : st) {
          us.push_back(
              pieces->breakpoints_u[i] +
              x * (pieces->breakpoints_u[i + 1] - pieces->breakpoints_u[i]));
          vs.push_back(
              pieces->breakpoints_v[j] +
              x * (pieces->breakpoints_v[j + 1] - pieces->breakpoints_v[j]));
        }
        std::vector<double> expected(st.size() * st.size() * 3);
        std::vector<double> got(expected.size());
        const std::vector<absl::Span<double>> out_expected = {
            absl::MakeSpan(expected)};
        const std::vector<absl::Span<double>> out_got = {absl::MakeSpan(got)};
        ASSERT_TRUE(EvaluateBSplineSurface(surface.bspline_view(),
                                           SurfaceSamples::Grid(us, vs),
                                           out_expected)
                        .ok());
        ASSERT_TRUE(EvaluateBezierSurface(patch.bezier_view(),
                                          SurfaceSamples::Grid(st, st), out_got)
                        .ok());
        EXPECT_LT(MaxDifference(expected, got), kTolerance);
      }
    }
  }
}

TEST(KnotInsertion, SurfaceRejectsOverflowInThatDirection) {
  const std::vector<double> net(2 * 3 * 3, 0.0);
  const std::vector<double> knots_u = {0, 0, 1, 1};
  const std::vector<double> knots_v = {0, 0, 0, 1, 1, 1};
  const BSplineSurfaceView surface{.degree_u = 1,
                                   .degree_v = 2,
                                   .control_net = {3, 2, 3, net},
                                   .knots_u = knots_u,
                                   .knots_v = knots_v};
  ExpectFieldError(
      InsertSurfaceKnots(surface, true, std::vector<double>{0.5, 0.5}).status(),
      "knots[1]");
  EXPECT_TRUE(
      InsertSurfaceKnots(surface, false, std::vector<double>{0.5, 0.5}).ok());
}

// ---------------------------------------------------------------------------
// DecomposeBSplineCurve

TEST(DecomposeBSplineCurve, SegmentsEvaluateToOriginalForAllDegrees) {
  std::mt19937_64 rng(13);
  for (int p = 1; p <= 15; ++p) {
    for (bool clamped : {true, false}) {
      for (bool rational : {false, true}) {
        const BSplineCurveData curve =
            RandomBSpline(rng, p, p + 5, 2, clamped, rational);
        auto pieces = DecomposeBSplineCurve(curve.view());
        ASSERT_TRUE(pieces.ok()) << pieces.status();
        const std::vector<double>& breaks = pieces->breakpoints;
        ASSERT_EQ(breaks.size(), pieces->segments.size() + 1);
        std::vector<double> distinct;
        for (int i = p; i <= static_cast<int>(curve.knots.size()) - p - 1;
             ++i) {
          if (distinct.empty() || distinct.back() != curve.knots[i]) {
            distinct.push_back(curve.knots[i]);
          }
        }
        EXPECT_EQ(breaks, distinct);
        for (size_t k = 0; k < pieces->segments.size(); ++k) {
          const BezierCurveData& segment = pieces->segments[k];
          EXPECT_EQ(segment.view().degree(), p);
          EXPECT_EQ(segment.weights.empty(), !rational);
          const std::vector<double> local =
              EvenlySpaced(0, 1, kSamples / pieces->segments.size());
          std::vector<double> global(local.size());
          for (size_t i = 0; i < local.size(); ++i) {
            global[i] = breaks[k] + (breaks[k + 1] - breaks[k]) * local[i];
          }
          EXPECT_LT(MaxDifference(EvaluateBezier(segment.view(), local),
                                  EvaluateBSpline(curve.view(), global)),
                    kTolerance)
              << "degree " << p << " segment " << k;
        }
      }
    }
  }
}

TEST(DecomposeBSplineCurve, HalfCircleIsOneRationalSegment) {
  const BSplineCurveData half = HalfCircle();
  const BSplineCurveView curve = half.view();
  auto pieces = DecomposeBSplineCurve(curve);
  ASSERT_TRUE(pieces.ok());
  ASSERT_EQ(pieces->segments.size(), 1u);
  EXPECT_EQ(pieces->segments[0].coordinates, half.coordinates);
  EXPECT_EQ(pieces->segments[0].weights, half.weights);
  EXPECT_EQ(pieces->breakpoints, (std::vector<double>{0, 1}));
}

// ---------------------------------------------------------------------------
// SubdividePolygon

// The uniform B-spline of degree d on integer knots with control points
// `polygon` (wrapped when closed), evaluated at t (taken modulo m when
// closed).
std::vector<double> UniformLimit(const std::vector<double>& polygon,
                                 int dimension, int d, bool closed,
                                 const std::vector<double>& t) {
  const int m = static_cast<int>(polygon.size()) / dimension;
  std::vector<double> points = polygon;
  for (int i = 0; closed && i < d; ++i) {
    for (int x = 0; x < dimension; ++x) {
      points.push_back(polygon[(i % m) * dimension + x]);
    }
  }
  const int count = static_cast<int>(points.size()) / dimension;
  std::vector<double> knots(count + d + 1);
  for (size_t i = 0; i < knots.size(); ++i) knots[i] = static_cast<double>(i);
  std::vector<double> params = t;
  for (double& u : params) {
    if (closed) u = d + std::fmod(std::fmod(u - d, m) + m, m);
  }
  const BSplineCurveView curve{
      .degree = d, .control_points = {dimension, points}, .knots = knots};
  return EvaluateBSpline(curve, params);
}

// The largest distance between the points of level k (1-based) and the
// limit at their Greville abscissae (r + d (2^k - 1) + (d + 1) / 2) / 2^k,
// open polygons counting only the abscissae in the domain [d, m].
double DistanceToLimit(const std::vector<double>& polygon,
                       const std::vector<double>& level, int dimension, int d,
                       int k, bool closed) {
  const int m = static_cast<int>(polygon.size()) / dimension;
  const double scale = std::ldexp(1.0, k);
  std::vector<double> t;
  std::vector<double> points;
  for (size_t r = 0; r < level.size() / dimension; ++r) {
    const double u =
        (static_cast<double>(r) + d * (scale - 1) + (d + 1) / 2.0) / scale;
    if (!closed && (u < d || u > m)) continue;
    t.push_back(u);
    points.insert(points.end(), level.begin() + r * dimension,
                  level.begin() + (r + 1) * dimension);
  }
  EXPECT_FALSE(t.empty());
  return MaxDifference(points, UniformLimit(polygon, dimension, d, closed, t));
}

void ExpectConvergence(SubdivisionScheme scheme, int d, bool closed) {
  std::mt19937_64 rng(17 + d);
  const int m = std::max(d + 4, 6);
  const std::vector<double> polygon = RandomValues(rng, 2 * m);
  constexpr int kLevels = 7;
  auto levels = SubdividePolygon({2, polygon}, closed, scheme, d, kLevels);
  ASSERT_TRUE(levels.ok()) << levels.status();
  ASSERT_EQ(levels->size(), static_cast<size_t>(kLevels));
  size_t count = m;
  std::vector<double> distance;
  for (int k = 1; k <= kLevels; ++k) {
    count = closed ? 2 * count : 2 * count - d;
    EXPECT_EQ((*levels)[k - 1].size(), 2 * count);
    distance.push_back(
        DistanceToLimit(polygon, (*levels)[k - 1], 2, d, k, closed));
  }
  if (d == 1) {  // The polygon is its own limit.
    EXPECT_LT(distance.back(), 1e-14);
    return;
  }
  for (int k = 3; k < kLevels; ++k) {
    const double ratio = distance[k - 1] / distance[k];
    EXPECT_GT(ratio, 3.5) << "degree " << d << " level " << k;
    EXPECT_LT(ratio, 4.5) << "degree " << d << " level " << k;
  }
  EXPECT_LT(distance.back(), 1e-3);
}

TEST(ChaikinSubdivision, CutsEveryEdgeAtQuarterAndThreeQuarters) {
  const std::vector<double> polygon = {0, 0, 4, 0, 4, 8};
  auto open =
      SubdividePolygon({2, polygon}, false, SubdivisionScheme::kChaikin, 0, 1);
  ASSERT_TRUE(open.ok()) << open.status();
  EXPECT_EQ(open->back(), (std::vector<double>{1, 0, 3, 0, 4, 2, 4, 6}));
  auto closed =
      SubdividePolygon({2, polygon}, true, SubdivisionScheme::kChaikin, 0, 1);
  ASSERT_TRUE(closed.ok()) << closed.status();
  EXPECT_EQ(closed->back(),
            (std::vector<double>{1, 0, 3, 0, 4, 2, 4, 6, 3, 6, 1, 2}));
}

TEST(ChaikinSubdivision, ConvergesToQuadraticUniformBSpline) {
  for (bool closed : {false, true}) {
    ExpectConvergence(SubdivisionScheme::kChaikin, 2, closed);
  }
}

TEST(UniformSubdivision, MatchesChaikinAtDegreeTwo) {
  const std::vector<double> polygon = {0, 0, 1, 3, 4, 1, 6, 5, 7, 0};
  for (bool closed : {false, true}) {
    auto chaikin = SubdividePolygon({2, polygon}, closed,
                                    SubdivisionScheme::kChaikin, 0, 3);
    auto uniform = SubdividePolygon({2, polygon}, closed,
                                    SubdivisionScheme::kUniformBSpline, 2, 3);
    ASSERT_TRUE(chaikin.ok() && uniform.ok());
    EXPECT_EQ(*chaikin, *uniform);
  }
}

TEST(UniformSubdivision, CubicMaskAndMidpoints) {
  const std::vector<double> polygon = {0, 8, 16, 24, 32};  // 1D
  auto cubic = SubdividePolygon({1, polygon}, false,
                                SubdivisionScheme::kUniformBSpline, 3, 1);
  ASSERT_TRUE(cubic.ok());
  // Q_3 = (4 P_0 + 4 P_1) / 8, Q_4 = (P_0 + 6 P_1 + P_2) / 8, ...
  EXPECT_EQ(cubic->back(), (std::vector<double>{4, 8, 12, 16, 20, 24, 28}));
  auto linear = SubdividePolygon({1, polygon}, false,
                                 SubdivisionScheme::kUniformBSpline, 1, 1);
  ASSERT_TRUE(linear.ok());
  EXPECT_EQ(linear->back(),
            (std::vector<double>{0, 4, 8, 12, 16, 20, 24, 28, 32}));
}

TEST(UniformSubdivision, ConvergesToUniformBSplineOfItsDegree) {
  for (int d = 1; d <= 7; ++d) {
    for (bool closed : {false, true}) {
      ExpectConvergence(SubdivisionScheme::kUniformBSpline, d, closed);
    }
  }
}

TEST(UniformSubdivision, RejectsBadArguments) {
  const std::vector<double> polygon = {0, 0, 1, 0, 1, 1};
  const PointsView view{2, polygon};
  const auto uniform = SubdivisionScheme::kUniformBSpline;
  ExpectFieldError(SubdividePolygon(view, false, uniform, 2, 0).status(),
                   "levels");
  ExpectFieldError(SubdividePolygon(view, false, uniform, 0, 1).status(),
                   "degree");
  ExpectFieldError(SubdividePolygon(view, false, uniform, 3, 1).status(),
                   "polygon.coordinates");
  EXPECT_TRUE(SubdividePolygon(view, true, uniform, 3, 1).ok());
  const std::vector<double> two = {0, 0, 1, 0};
  ExpectFieldError(
      SubdividePolygon({2, two}, true, SubdivisionScheme::kChaikin, 0, 1)
          .status(),
      "polygon.coordinates");
}

// ---------------------------------------------------------------------------
// SplitBezierSurface, SplitTriangularPatch

TEST(PatchSplit, BezierSurfacePiecesEvaluateToOriginal) {
  std::mt19937_64 rng(19);
  for (bool rational : {false, true}) {
    for (bool in_u : {true, false}) {
      const std::vector<double> net = RandomValues(rng, 4 * 6 * 3);
      const std::vector<double> weights =
          rational ? RandomValues(rng, 24, 0.5, 2.0) : std::vector<double>{};
      const BezierSurfaceView surface{.control_net = {3, 4, 6, net},
                                      .weights = weights};
      const double t = 0.3;
      auto pieces = SplitBezierSurface(surface, in_u, t);
      ASSERT_TRUE(pieces.ok()) << pieces.status();
      ASSERT_EQ(pieces->size(), 2u);
      const std::vector<double> uv = RandomValues(rng, 2 * kSamples, 0, 1);
      for (int h = 0; h < 2; ++h) {
        const SurfaceData& piece = (*pieces)[h];
        EXPECT_EQ(piece.count_u, 4);
        EXPECT_EQ(piece.count_v, 6);
        std::vector<double> mapped = uv;
        for (size_t i = in_u ? 0 : 1; i < mapped.size(); i += 2) {
          mapped[i] = h == 0 ? t * uv[i] : t + (1 - t) * uv[i];
        }
        std::vector<double> expected(kSamples * 3), actual(kSamples * 3);
        const std::vector<absl::Span<double>> out_expected = {
            absl::MakeSpan(expected)};
        const std::vector<absl::Span<double>> out_actual = {
            absl::MakeSpan(actual)};
        ASSERT_TRUE(EvaluateBezierSurface(
                        surface, SurfaceSamples::Pairs(mapped), out_expected)
                        .ok());
        ASSERT_TRUE(EvaluateBezierSurface(piece.bezier_view(),
                                          SurfaceSamples::Pairs(uv), out_actual)
                        .ok());
        EXPECT_LT(MaxDifference(expected, actual), kTolerance);
      }
    }
  }
  const std::vector<double> net(12, 0.0);
  ExpectFieldError(
      SplitBezierSurface({.control_net = {3, 2, 2, net}}, true, 1.0).status(),
      "parameter");
}

std::vector<double> EvaluateTriangle(const TriangularPatchView& patch,
                                     const std::vector<double>& uv) {
  std::vector<double> values(uv.size() / 2 * patch.control_points.dimension);
  const std::vector<absl::Span<double>> output = {absl::MakeSpan(values)};
  const absl::Status status = EvaluateTriangularPatch(patch, uv, output);
  EXPECT_TRUE(status.ok()) << status;
  return values;
}

TEST(PatchSplit, TriangularPiecesMatchOriginalAtMappedPoints) {
  std::mt19937_64 rng(23);
  const double u = 0.2, v = 0.3, w = 0.5;
  for (int n = 1; n <= 8; ++n) {
    for (bool rational : {false, true}) {
      const size_t count = TriangularPointCount(n);
      const std::vector<double> points = RandomValues(rng, 3 * count);
      const std::vector<double> weights =
          rational ? RandomValues(rng, count, 0.5, 2.0) : std::vector<double>{};
      const TriangularPatchView patch{
          .degree = n, .control_points = {3, points}, .weights = weights};
      auto pieces = SplitTriangularPatch(patch, u, v);
      ASSERT_TRUE(pieces.ok()) << pieces.status();
      ASSERT_EQ(pieces->size(), 3u);
      // Random barycentric points (a, b, c) of the pieces.
      std::vector<double> ab;
      while (ab.size() < 2000) {
        const std::vector<double> pair = RandomValues(rng, 2, 0, 1);
        if (pair[0] + pair[1] <= 1)
          ab.insert(ab.end(), pair.begin(), pair.end());
      }
      for (int i = 0; i < 3; ++i) {
        std::vector<double> mapped(ab.size());
        for (size_t r = 0; r < ab.size(); r += 2) {
          // The piece's vertex i is X = (u, v, w); the others stay.
          double bary[3] = {ab[r], ab[r + 1], 1 - ab[r] - ab[r + 1]};
          const double x = bary[i];
          bary[i] = 0;
          mapped[r] = bary[0] + x * u;
          mapped[r + 1] = bary[1] + x * v;
        }
        EXPECT_LT(MaxDifference(EvaluateTriangle((*pieces)[i].view(), ab),
                                EvaluateTriangle(patch, mapped)),
                  kTolerance)
            << "degree " << n << " piece " << i + 1;
      }
      (void)w;
    }
  }
}

// Bisection at an edge midpoint X: half h is the piece of the vertex
// kOthers[edge][h], with X in that vertex's place.
TEST(PatchSplit, TriangularBisectionHalvesMatchOriginal) {
  std::mt19937_64 rng(31);
  constexpr double kMidpoints[3][2] = {{0.0, 0.5}, {0.5, 0.0}, {0.5, 0.5}};
  constexpr int kOthers[3][2] = {{1, 2}, {0, 2}, {0, 1}};
  for (int n = 1; n <= 6; ++n) {
    const size_t count = TriangularPointCount(n);
    const std::vector<double> points = RandomValues(rng, 3 * count);
    const std::vector<double> weights = RandomValues(rng, count, 0.5, 2.0);
    const TriangularPatchView patch{
        .degree = n, .control_points = {3, points}, .weights = weights};
    std::vector<double> ab;
    while (ab.size() < 400) {
      const std::vector<double> pair = RandomValues(rng, 2, 0, 1);
      if (pair[0] + pair[1] <= 1) ab.insert(ab.end(), pair.begin(), pair.end());
    }
    for (int edge = 0; edge < 3; ++edge) {
      auto halves = BisectTriangularPatch(patch, edge);
      ASSERT_TRUE(halves.ok()) << halves.status();
      ASSERT_EQ(halves->size(), 2u);
      for (int h = 0; h < 2; ++h) {
        const int vertex = kOthers[edge][h];
        std::vector<double> mapped(ab.size());
        for (size_t r = 0; r < ab.size(); r += 2) {
          double bary[3] = {ab[r], ab[r + 1], 1 - ab[r] - ab[r + 1]};
          const double x = bary[vertex];
          bary[vertex] = 0;
          mapped[r] = bary[0] + x * kMidpoints[edge][0];
          mapped[r + 1] = bary[1] + x * kMidpoints[edge][1];
        }
        EXPECT_LT(MaxDifference(EvaluateTriangle((*halves)[h].view(), ab),
                                EvaluateTriangle(patch, mapped)),
                  kTolerance)
            << "degree " << n << " edge " << edge << " half " << h;
      }
    }
  }
  ExpectFieldError(BisectTriangularPatch(
                       {.degree = 0, .control_points = {3, {0.0, 0.0, 0.0}}}, 3)
                       .status(),
                   "edge");
}

TEST(PatchSplit, TriangularPiecesKeepCartesianDomain) {
  std::mt19937_64 rng(29);
  const int n = 3;
  const std::vector<double> points = RandomValues(rng, 3 * 10);
  const std::vector<double> triangle = {0, 0, 4, 0, 1, 3};
  const TriangularPatchView patch{
      .degree = n, .control_points = {3, points}, .domain_triangle = triangle};
  auto pieces = SplitTriangularPatch(patch, 0.25, 0.25);
  ASSERT_TRUE(pieces.ok());
  // X = 0.25 A + 0.25 B + 0.5 C = (1.5, 1.5).
  EXPECT_EQ((*pieces)[0].domain_triangle,
            (std::vector<double>{1.5, 1.5, 4, 0, 1, 3}));
  // Points inside piece 1's triangle (X, B, C) by convex combination.
  std::vector<double> xy;
  for (int r = 0; r < 100; ++r) {
    std::vector<double> b = RandomValues(rng, 3, 0, 1);
    const double sum = b[0] + b[1] + b[2];
    xy.push_back((b[0] * 1.5 + b[1] * 4 + b[2] * 1) / sum);
    xy.push_back((b[0] * 1.5 + b[1] * 0 + b[2] * 3) / sum);
  }
  EXPECT_LT(MaxDifference(EvaluateTriangle((*pieces)[0].view(), xy),
                          EvaluateTriangle(patch, xy)),
            kTolerance);
}

TEST(PatchSplit, TriangularRejectsPointsNotStrictlyInside) {
  const std::vector<double> points(9, 0.0);
  const TriangularPatchView patch{.degree = 1, .control_points = {3, points}};
  ExpectFieldError(SplitTriangularPatch(patch, 0.0, 0.5).status(), "u");
  ExpectFieldError(SplitTriangularPatch(patch, 0.5, -0.1).status(), "v");
  ExpectFieldError(SplitTriangularPatch(patch, 0.5, 0.5).status(), "v");
  ExpectFieldError(SplitTriangularPatch(patch, std::nan(""), 0.2).status(),
                   "u");
}

}  // namespace
}  // namespace freeform
