#include "freeform/core/arc_length.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "freeform/core/elevation.h"
#include "freeform/core/status.h"
#include "freeform/core/thread_pool.h"
#include "shapes.h"
#include "test_util.h"

namespace freeform {
namespace {

constexpr auto Distance = testing_util::PointDistance;

using testing_util::CornerLength;
using testing_util::EvenlySpaced;
using testing_util::NurbsCircle;
using testing_util::RandomKnots;
using testing_util::RandomValues;
using testing_util::RationalCorner;

std::vector<double> Points(const Curve& curve,
                           const std::vector<double>& parameters) {
  std::vector<double> points(parameters.size() * DimensionOf(curve));
  const absl::Span<double> output[] = {absl::MakeSpan(points)};
  EXPECT_TRUE(EvaluateCurve(curve, parameters, output).ok());
  return points;
}

// PolylineLength returns the length of the polyline through `segments` + 1
// evenly spaced parameters of every piece between consecutive `cuts`.
double PolylineLength(const Curve& curve, const std::vector<double>& cuts,
                      int segments) {
  const int d = DimensionOf(curve);
  double length = 0.0;
  for (size_t k = 0; k + 1 < cuts.size(); ++k) {
    const std::vector<double> points =
        Points(curve, EvenlySpaced(cuts[k], cuts[k + 1], segments + 1));
    for (int i = 0; i < segments; ++i) {
      length += Distance(&points[i * d], &points[(i + 1) * d], d);
    }
  }
  return length;
}

// ReferenceLength is the polyline length with Richardson extrapolation: a
// chord of a smooth piece falls short of its arc by O(h^2), so
// (4 L(2N) - L(N)) / 3 removes the leading term.
double ReferenceLength(const Curve& curve, const std::vector<double>& cuts) {
  const double coarse = PolylineLength(curve, cuts, 2048);
  const double fine = PolylineLength(curve, cuts, 4096);
  return (4.0 * fine - coarse) / 3.0;
}

TEST(GaussLegendreRule, IntegratesPolynomialsOfDegreeBelowTwiceItsPoints) {
  for (const int n : {1, 2, 5, 16}) {
    std::vector<double> nodes(n), weights(n);
    GaussLegendreRule(n, absl::MakeSpan(nodes), absl::MakeSpan(weights));
    for (int k = 0; k < 2 * n; ++k) {
      double sum = 0.0;
      for (int i = 0; i < n; ++i) sum += weights[i] * std::pow(nodes[i], k);
      EXPECT_NEAR(sum, k % 2 == 1 ? 0.0 : 2.0 / (k + 1), 1e-14)
          << "n = " << n << ", x^" << k;
    }
  }
  std::vector<double> nodes(2), weights(2);
  GaussLegendreRule(2, absl::MakeSpan(nodes), absl::MakeSpan(weights));
  EXPECT_NEAR(nodes[0], -1.0 / std::sqrt(3.0), 2e-16);
  EXPECT_NEAR(nodes[1], 1.0 / std::sqrt(3.0), 2e-16);
  EXPECT_NEAR(weights[0], 1.0, 1e-15);
}

TEST(ArcLength, NurbsCircleHasLengthTwoPiR) {
  for (const double radius : {1.0, 2.5}) {
    const BSplineCurveData data = NurbsCircle(radius, 3.0, -1.0);
    const Curve circle = *BSplineCurve::Create(data.view());
    absl::StatusOr<double> length = ArcLength(circle, 0.0, 1.0, 1e-13);
    ASSERT_TRUE(length.ok()) << length.status();
    EXPECT_NEAR(*length, 2.0 * std::numbers::pi * radius, 1e-12 * radius);
    // Half the domain is half the circle (the quarters are symmetric).
    EXPECT_NEAR(*ArcLength(circle, 0.0, 0.5, 1e-13), std::numbers::pi * radius,
                1e-12 * radius);
    EXPECT_EQ(*ArcLength(circle, 0.3, 0.3, 1e-13), 0.0);
  }
}

// Arcs of the circle of radius 2: length 2 pi r times the fraction of the
// turn, in a batch large enough to run in chunks on a pool.
TEST(ArcLengths, BatchOfCircleArcs) {
  const BSplineCurveData data = NurbsCircle(2.0, 1.0, 1.0);
  const Curve circle = *BSplineCurve::Create(data.view());
  std::vector<double> intervals;
  const int count = 300;
  for (int i = 0; i < count; ++i) {
    // Quarter-turn pieces are exact in the NURBS parameter: [k/4, m/4].
    const int k = i % 4, m = k + 1 + (i / 4) % (4 - k);
    intervals.push_back(k / 4.0);
    intervals.push_back(m / 4.0);
  }
  ThreadPool pool(2);
  std::vector<double> lengths(count);
  ASSERT_TRUE(ArcLengths(circle, intervals, 1e-12, absl::MakeSpan(lengths),
                         {.pool = &pool, .grain = 16})
                  .ok());
  for (int i = 0; i < count; ++i) {
    const double turns = intervals[2 * i + 1] - intervals[2 * i];
    EXPECT_NEAR(lengths[i], 2.0 * std::numbers::pi * 2.0 * turns, 1e-11)
        << "interval " << i;
  }
  const std::vector<double> odd = {0.0, 0.5, 0.2};
  EXPECT_EQ(FieldPathOf(ArcLengths(circle, odd, 1e-9,
                                   absl::MakeSpan(lengths).subspan(0, 1))),
            "intervals");
  const std::vector<double> reversed = {0.0, 0.5, 0.7, 0.6};
  EXPECT_EQ(FieldPathOf(ArcLengths(circle, reversed, 1e-9,
                                   absl::MakeSpan(lengths).subspan(0, 2))),
            "intervals[1].end");
  const std::vector<double> outside = {-0.5, 0.5};
  EXPECT_EQ(FieldPathOf(ArcLengths(circle, outside, 1e-9,
                                   absl::MakeSpan(lengths).subspan(0, 1))),
            "intervals[0].start");
  EXPECT_EQ(FieldPathOf(ArcLengths(circle, outside, -1.0,
                                   absl::MakeSpan(lengths).subspan(0, 1))),
            "tolerance");
}

TEST(ArcLength, StraightLineElevatedToDegreeSevenHasItsChordsLength) {
  // A quadratic along a line with uneven control points (so the speed
  // varies), raised to degree 7.
  const BezierCurveData quadratic{
      .dimension = 3, .coordinates = {1, 2, 3, 3.7, -1.6, 12.9, 4, -2, 14}};
  absl::StatusOr<BezierCurveData> line =
      ElevateBezierCurve(quadratic.view(), 5);
  ASSERT_TRUE(line.ok());
  ASSERT_EQ(line->coordinates.size(), 8u * 3);
  const Curve curve = *BezierCurve::Create(line->view());
  const double chord = std::sqrt(9.0 + 16.0 + 121.0);
  EXPECT_NEAR(*ArcLength(curve, 0.0, 1.0, 1e-12), chord, 1e-12 * chord);
  const std::vector<double> ends = Points(curve, {0.2, 0.7});
  EXPECT_NEAR(*ArcLength(curve, 0.2, 0.7, 1e-12),
              Distance(&ends[0], &ends[3], 3), 1e-12 * chord);
}

// Every curve kind against the extrapolated polyline, over the whole domain
// and over an interval that starts and ends inside pieces.
TEST(ArcLength, EveryKindMatchesExtrapolatedPolyline) {
  std::mt19937_64 rng(12);
  const std::vector<double> bezier_points = RandomValues(rng, 6 * 4);
  const std::vector<double> weights = RandomValues(rng, 6, 0.5, 2.0);
  const std::vector<double> spline_points = RandomValues(rng, 9 * 3);
  const std::vector<double> knots = RandomKnots(rng, 3, 8, false);
  const std::vector<double> lagrange_points = RandomValues(rng, 5 * 2);
  const std::vector<double> hermite_points = RandomValues(rng, 4 * 2);
  const std::vector<double> tangents = RandomValues(rng, 4 * 2);
  const std::vector<double> nodes = {0.0, 0.5, 1.75, 2.0};
  const std::vector<double> power = RandomValues(rng, 4 * 2);
  const std::vector<double> direction_points = {0, 0, 1, 1, 2, 0, 3, 1};
  const std::vector<double> direction_weights = {1, 0, 3, 1};
  struct Case {
    const char* name;
    Curve curve;
    std::vector<double> cuts;
  };
  std::vector<Case> cases = {
      {"rational Bezier",
       *BezierCurve::Create(
           {.control_points = {4, bezier_points}, .weights = weights}),
       {0.0, 1.0}},
      {"B-spline",
       *BSplineCurve::Create(
           {.degree = 3, .control_points = {3, spline_points}, .knots = knots}),
       {}},
      {"Lagrange",
       *LagrangeCurve::Create({.points = {2, lagrange_points}}),
       {0.0, 1.0}},
      {"Hermite",
       *HermiteCurve::Create({.points = {2, hermite_points},
                              .tangents = {2, tangents},
                              .nodes = nodes}),
       nodes},
      {"power form", *BezierCurve::FromPowerForm({2, power}), {0.0, 1.0}},
      // The second control point is the direction (1, 1) (weight 0): the
      // length runs on a copy whose weights are divided by 4.
      {"rational Bezier with a direction",
       *BezierCurve::Create({.control_points = {2, direction_points},
                             .weights = direction_weights}),
       {0.0, 1.0}}};
  for (int s = 3; s <= 9; ++s) {
    if (cases[1].cuts.empty() || knots[s] != cases[1].cuts.back()) {
      cases[1].cuts.push_back(knots[s]);
    }
  }
  for (const Case& c : cases) {
    const double start = c.cuts.front();
    const double end = c.cuts.back();
    const double reference = ReferenceLength(c.curve, c.cuts);
    absl::StatusOr<double> length = ArcLength(c.curve, start, end, 1e-12);
    ASSERT_TRUE(length.ok()) << c.name << ": " << length.status();
    EXPECT_NEAR(*length, reference, 1e-10 * reference) << c.name;
    // An interval inside: the cuts clipped to it.
    const double a = start + 0.13 * (end - start);
    const double b = start + 0.81 * (end - start);
    std::vector<double> inner = {a};
    for (const double cut : c.cuts) {
      if (cut > a && cut < b) inner.push_back(cut);
    }
    inner.push_back(b);
    const double inner_reference = ReferenceLength(c.curve, inner);
    EXPECT_NEAR(*ArcLength(c.curve, a, b, 1e-12), inner_reference,
                1e-10 * reference)
        << c.name;
  }
}

// On a circle of radius r the point at length s from angle 0 is at angle
// s / r.
TEST(ParametersAtArcLengths, CirclePointsAtTheirAngle) {
  const double radius = 2.0;
  const BSplineCurveData data = NurbsCircle(radius);
  const Curve circle = *BSplineCurve::Create(data.view());
  const std::vector<double> lengths = {
      0.0, 0.1, 1.0, 3.0, 7.5, 12.0, 4.0 * std::numbers::pi};
  std::vector<double> parameters(lengths.size());
  ThreadPool pool(2);
  const absl::Status status = ParametersAtArcLengths(
      circle, 0.0, lengths, 1e-12, absl::MakeSpan(parameters),
      {.pool = &pool, .cancellation = nullptr, .grain = 2});
  ASSERT_TRUE(status.ok()) << status;
  const std::vector<double> points = Points(circle, parameters);
  for (size_t i = 0; i < lengths.size(); ++i) {
    const double angle = lengths[i] / radius;
    EXPECT_NEAR(points[2 * i], radius * std::cos(angle), 1e-11) << i;
    EXPECT_NEAR(points[2 * i + 1], radius * std::sin(angle), 1e-11) << i;
  }
  EXPECT_EQ(parameters.front(), 0.0);
  EXPECT_NEAR(parameters.back(), 1.0, 1e-12);
}

TEST(ParametersAtArcLengths, FromAStartInsideTheDomain) {
  const BSplineCurveData data = NurbsCircle(1.0);
  const Curve circle = *BSplineCurve::Create(data.view());
  // The circle's parameter 0.25 is the angle pi / 2.
  const std::vector<double> lengths = {1.0};
  std::vector<double> parameter(1);
  ASSERT_TRUE(ParametersAtArcLengths(circle, 0.25, lengths, 1e-12,
                                     absl::MakeSpan(parameter))
                  .ok());
  const std::vector<double> point = Points(circle, parameter);
  EXPECT_NEAR(point[0], std::cos(std::numbers::pi / 2 + 1.0), 1e-11);
  EXPECT_NEAR(point[1], std::sin(std::numbers::pi / 2 + 1.0), 1e-11);
}

// Length 0 from a start inside a piece is the start itself, never before
// it: the fuzzer's Hermite curve from 1e-6 got 9.99999999918e-07 (the
// piece's parameter, breakpoint + u width, rounded below the start).
// ParametersOfShortLengths returns the parameters at the lengths 0, 0.1
// and 0.2 from `start` (tolerance 1e-8), empty when the call fails.
std::vector<double> ParametersOfShortLengths(const Curve& curve, double start) {
  const std::vector<double> lengths = {0, 0.1, 0.2};
  std::vector<double> parameters(lengths.size());
  const absl::Status status = ParametersAtArcLengths(
      curve, start, lengths, 1e-8, absl::MakeSpan(parameters));
  EXPECT_TRUE(status.ok()) << status;
  if (!status.ok()) return {};
  return parameters;
}

TEST(ParametersAtArcLengths, NeverBeforeTheStart) {
  const std::vector<double> points = {0, 0, 1, 1, 2, 0};
  const std::vector<double> tangents = {1, 0, 0, 0, -1, 0};
  const std::vector<double> nodes = {-1, 1, 3};
  const Curve curve = *HermiteCurve::Create(
      {.points = {2, points}, .tangents = {2, tangents}, .nodes = nodes});
  const std::vector<double> parameters = ParametersOfShortLengths(curve, 1e-6);
  ASSERT_EQ(parameters.size(), 3u);
  EXPECT_EQ(parameters[0], 1e-6);
  EXPECT_GT(parameters[1], 1e-6);
  EXPECT_GT(parameters[2], parameters[1]);
}

// A fuzzer's request: a start of 1e-300 on a domain of 1e170 came back as
// the parameter 0 for the length 0, mapped back from the scaled copy.
TEST(ParametersAtArcLengths, NeverBeforeATinyStartOnAHugeDomain) {
  const std::vector<double> points = {0, 0, 1, 2, 1, 2, 1, 2};
  const std::vector<double> knots = {0, 0, 2.5e169, 5e169, 1e170, 1e170};
  const Curve curve = *BSplineCurve::Create(
      {.degree = 1, .control_points = {2, points}, .knots = knots});
  const std::vector<double> parameters =
      ParametersOfShortLengths(curve, 1e-300);
  ASSERT_EQ(parameters.size(), 3u);
  EXPECT_EQ(parameters[0], 1e-300);
  // Along the first leg (length sqrt(5) over 2.5e169) the lengths 0.1 and
  // 0.2 are at t = L 2.5e169 / sqrt(5).
  EXPECT_NEAR(parameters[1], 0.1 * 2.5e169 / std::sqrt(5.0), 1e-7 * 2.5e169);
  EXPECT_NEAR(parameters[2], 0.2 * 2.5e169 / std::sqrt(5.0), 1e-7 * 2.5e169);
}

// Equal arc-length samples of the circle have equal chords
// 2 r sin(pi / (n - 1)).
TEST(EqualArcLengthParameters, CircleSamplesHaveEqualChords) {
  const double radius = 1.5;
  const BSplineCurveData data = NurbsCircle(radius, -1.0, 2.0);
  const Curve circle = *BSplineCurve::Create(data.view());
  constexpr size_t kCount = 13;
  std::vector<double> parameters(kCount);
  ASSERT_TRUE(EqualArcLengthParameters(circle, 0.0, 1.0, kCount, 1e-12,
                                       absl::MakeSpan(parameters))
                  .ok());
  const std::vector<double> points = Points(circle, parameters);
  const double chord = 2.0 * radius * std::sin(std::numbers::pi / (kCount - 1));
  for (size_t k = 0; k + 1 < kCount; ++k) {
    EXPECT_LT(parameters[k], parameters[k + 1]);
    EXPECT_NEAR(Distance(&points[2 * k], &points[2 * k + 2], 2), chord, 1e-11);
  }
}

// On a free-form B-spline each arc between consecutive samples, measured
// by the extrapolated polyline, is the total over count - 1.
TEST(EqualArcLengthParameters, ArcsAreEqualOnAFreeFormSpline) {
  std::mt19937_64 rng(5);
  const std::vector<double> points = RandomValues(rng, 7 * 2);
  const std::vector<double> knots = RandomKnots(rng, 3, 6, true);
  const Curve curve = *BSplineCurve::Create(
      {.degree = 3, .control_points = {2, points}, .knots = knots});
  constexpr size_t kCount = 6;
  constexpr double kTolerance = 1e-9;
  std::vector<double> parameters(kCount);
  ASSERT_TRUE(EqualArcLengthParameters(curve, 0.0, 1.0, kCount, kTolerance,
                                       absl::MakeSpan(parameters))
                  .ok());
  EXPECT_EQ(parameters.front(), 0.0);
  EXPECT_EQ(parameters.back(), 1.0);
  std::vector<double> arcs;
  double total = 0.0;
  for (size_t k = 0; k + 1 < kCount; ++k) {
    std::vector<double> cuts = {parameters[k]};
    for (const double knot : knots) {
      if (knot > parameters[k] && knot < parameters[k + 1] &&
          knot != cuts.back()) {
        cuts.push_back(knot);
      }
    }
    cuts.push_back(parameters[k + 1]);
    arcs.push_back(ReferenceLength(curve, cuts));
    total += arcs.back();
  }
  for (const double arc : arcs) {
    EXPECT_NEAR(arc, total / (kCount - 1), 2 * kTolerance + 1e-11);
  }
}

TEST(EqualArcLengthParameters, ZeroLengthGivesEvenlySpacedParameters) {
  const std::vector<double> point = {1.0, 2.0, 1.0, 2.0, 1.0, 2.0};
  const Curve curve = *BezierCurve::Create({.control_points = {2, point}});
  std::vector<double> parameters(5);
  ASSERT_TRUE(EqualArcLengthParameters(curve, 0.0, 1.0, 5, 1e-9,
                                       absl::MakeSpan(parameters))
                  .ok());
  EXPECT_EQ(parameters, (std::vector<double>{0.0, 0.25, 0.5, 0.75, 1.0}));
}

TEST(ArcLength, ErrorsNameTheirField) {
  const BSplineCurveData data = NurbsCircle(1.0);
  const Curve circle = *BSplineCurve::Create(data.view());
  EXPECT_EQ(FieldPathOf(ArcLength(circle, 0.0, 1.0, 0.0).status()),
            "tolerance");
  EXPECT_EQ(FieldPathOf(ArcLength(circle, 0.0, 1.0, NAN).status()),
            "tolerance");
  EXPECT_EQ(FieldPathOf(ArcLength(circle, -0.1, 1.0, 1e-9).status()), "start");
  EXPECT_EQ(FieldPathOf(ArcLength(circle, 0.0, 1.5, 1e-9).status()), "end");
  EXPECT_EQ(FieldPathOf(ArcLength(circle, 0.6, 0.5, 1e-9).status()), "end");
  EXPECT_TRUE(ValidateArcLengthInterval(circle, 0.0, 1.0).ok());
  EXPECT_TRUE(ValidateArcLengthInterval(circle, 0.5, 0.5).ok());
  EXPECT_EQ(FieldPathOf(ValidateArcLengthInterval(circle, NAN, 1.0)), "start");
  EXPECT_EQ(FieldPathOf(ValidateArcLengthInterval(circle, 0.0, INFINITY)),
            "end");
  EXPECT_EQ(FieldPathOf(ValidateArcLengthInterval(circle, 0.6, 0.5)), "end");
  std::vector<double> parameters(2);
  const std::vector<double> too_long = {1.0, 7.0};
  EXPECT_EQ(FieldPathOf(ParametersAtArcLengths(circle, 0.0, too_long, 1e-9,
                                               absl::MakeSpan(parameters))),
            "lengths[1]");
  const std::vector<double> negative = {-1.0, 1.0};
  EXPECT_EQ(FieldPathOf(ParametersAtArcLengths(circle, 0.0, negative, 1e-9,
                                               absl::MakeSpan(parameters))),
            "lengths[0]");
  EXPECT_EQ(FieldPathOf(EqualArcLengthParameters(circle, 0.0, 1.0, 1, 1e-9,
                                                 absl::MakeSpan(parameters))),
            "count");
  EXPECT_EQ(EqualArcLengthParameters(circle, 0.0, 1.0, 3, 1e-9,
                                     absl::MakeSpan(parameters))
                .code(),
            absl::StatusCode::kInvalidArgument);
}

// The corner with weights 1, w, 1 (shapes.h) runs from (1, 0) to near (1, 1)
// for t < 1/w and on to (0, 1) for t > 1 - 1/w: between the quadrature's
// nodes for large w. Its length, below 2 and tending to 2, is the closed
// form of its speed integrated independently in long double (CornerLength),
// over the whole curve and over stretches of the first leg, which doubles
// near t = 0 resolve at any weight. It is at most the control polygon's 2
// to rounding (for w = 1e15 it is 2 - 9e-16, four units in the last place
// below 2, and the sum of its intervals, each settled at the rounding of
// its speed, may land a few units above: 2.2e-15 above for w = 1e300,
// whose halvings for the weights give about a thousand stretches).
// A tolerance below what double precision resolves on the curve (2^-48 of
// its largest coordinate) is refused at once, as Tessellate refuses it; a
// straight segment, whose rule is exact, meets any tolerance.
TEST(ArcLength, ToleranceBelowTheResolutionIsRefused) {
  const BSplineCurveData data = NurbsCircle(1.0);
  const Curve circle = *BSplineCurve::Create(data.view());
  for (const double tolerance : {5e-324, 1e-20, 1e-15}) {
    EXPECT_EQ(FieldPathOf(ArcLength(circle, 0.0, 1.0, tolerance).status()),
              "tolerance")
        << tolerance;
    std::vector<double> parameters(3);
    EXPECT_EQ(FieldPathOf(EqualArcLengthParameters(
                  circle, 0.0, 1.0, 3, tolerance, absl::MakeSpan(parameters))),
              "tolerance")
        << tolerance;
  }
  EXPECT_NEAR(*ArcLength(circle, 0.0, 1.0, 1e-14), 2.0 * std::numbers::pi,
              1e-14);
  const std::vector<double> segment = {0.0, 0.0, 3.0, 4.0};
  const Curve line = *BezierCurve::Create({.control_points = {2, segment}});
  EXPECT_DOUBLE_EQ(*ArcLength(line, 0.0, 1.0, 5e-324), 5.0);
}

// The quartic through (0, 0), (0.75, 0.75), (1.5, 0.5), (2.25, 0.25) and
// (5.5340232221128655e19, 1) at nodes 0..4 (a fuzz finding): x' crosses 0
// near t = 0.38, 1.5 and 2.62 while y' is about 1, so the speed has three
// kinks, where the 16-point rule on [0, 4] and on its halves agreed to
// 3.3e14 and both were 2.2e16 short. Its length, by mpmath's tanh-sinh
// quadrature at 50 digits split at those crossings (the roots of x', from
// the power form), is 67157677643348836533.568; the answer must be within
// the tolerance 2^53 = 9.0e15 (and at 1e-3 of that tolerance, within it).
TEST(ArcLength, SpeedKinksMeetTheTolerance) {
  const std::vector<double> points = {
      0, 0, 0.75, 0.75, 1.5, 0.5, 2.25, 0.25, 5.5340232221128655e19, 1};
  const std::vector<double> nodes = {0, 1, 2, 3, 4};
  const Curve quartic =
      *LagrangeCurve::Create({.points = {2, points}, .nodes = nodes});
  const double exact = 67157677643348836533.568;
  for (const double tolerance : {0x1p53, 0x1p53 * 1e-3}) {
    const absl::StatusOr<double> length =
        ArcLength(quartic, 0.0, 4.0, tolerance);
    ASSERT_TRUE(length.ok()) << length.status();
    EXPECT_NEAR(*length, exact, tolerance) << "tolerance " << tolerance;
  }
}

// A curve that stands still has length 0, however its weights swing: its
// speed's slope is 0 but for the rounding of the products it is made of
// (weights 1 and 1e15 alternating, a campaign finding whose search for the
// speed's minima halved noise for 2^32 steps until the deadline).
TEST(ArcLength, ACurveStandingStillHasLengthZero) {
  const int count = 17;
  std::vector<double> points;
  std::vector<double> weights;
  for (int i = 0; i < count; ++i) {
    points.insert(points.end(), {-3.7647058823529411, 1, 0});
    weights.push_back(i % 2 == 0 ? 1.0 : 1e15);
  }
  const Curve still =
      *BezierCurve::Create({.control_points = {3, points}, .weights = weights});
  for (const auto& [from, to] : {std::pair{0.0, 1.0}, std::pair{1e-300, 0.5}}) {
    const absl::StatusOr<double> length = ArcLength(still, from, to, 1e-8);
    ASSERT_TRUE(length.ok()) << length.status();
    EXPECT_NEAR(*length, 0.0, 1e-8) << "[" << from << ", " << to << "]";
  }
}

TEST(ArcLength, RationalCornerWithExtremeWeightsHasItsLength) {
  for (const double w : {1.0, 1e5, 1e10, 1e15, 1e50, 1e150, 1e300}) {
    const BezierCurveData data = RationalCorner(w);
    const Curve corner = *BezierCurve::Create(data.view());
    const absl::StatusOr<double> length = ArcLength(corner, 0.0, 1.0, 1e-10);
    ASSERT_TRUE(length.ok()) << length.status();
    EXPECT_NEAR(*length, static_cast<double>(CornerLength(w, 1.0)), 2e-10)
        << "w = " << w;
    EXPECT_LE(*length, 2.0 + 1e-14) << "w = " << w << ": " << *length - 2.0;
    for (const double t : {0.3 / w, 1.0 / w, 4.0 / w, 0.25}) {
      if (t > 0.25) continue;
      const absl::StatusOr<double> part = ArcLength(corner, 0.0, t, 1e-10);
      ASSERT_TRUE(part.ok()) << part.status();
      EXPECT_NEAR(*part, static_cast<double>(CornerLength(w, t)), 2e-10)
          << "w = " << w << ", t = " << t;
    }
  }
}

// Lengths on the first leg of the corner with weight 1e10 have parameters
// near t = 0, where doubles are dense: each is met within the tolerance.
// On the second leg, within 1e-10 of t = 1, adjacent doubles of t are 1e-8
// apart along the curve: no parameter meets a tolerance of 1e-9, which is
// refused naming the weights; a tolerance of 1e-7 is met.
TEST(ParametersAtArcLengths, RationalCornerMeetsTheToleranceOrNamesTheWeights) {
  const double w = 1e10;
  const BezierCurveData data = RationalCorner(w);
  const Curve corner = *BezierCurve::Create(data.view());
  const std::vector<double> first_leg = {0.1, 0.5, 0.9, 0.99};
  std::vector<double> parameters(first_leg.size());
  ASSERT_TRUE(ParametersAtArcLengths(corner, 0.0, first_leg, 1e-9,
                                     absl::MakeSpan(parameters))
                  .ok());
  for (size_t i = 0; i < first_leg.size(); ++i) {
    EXPECT_NEAR(static_cast<double>(CornerLength(w, parameters[i])),
                first_leg[i], 1e-9 + 1e-11)
        << i;
  }
  const std::vector<double> second_leg = {1.5};
  std::vector<double> one(1);
  const absl::Status refused = ParametersAtArcLengths(
      corner, 0.0, second_leg, 1e-9, absl::MakeSpan(one));
  EXPECT_EQ(refused.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(FieldPathOf(refused), "weights") << refused;
  ASSERT_TRUE(
      ParametersAtArcLengths(corner, 0.0, second_leg, 1e-7, absl::MakeSpan(one))
          .ok());
  EXPECT_NEAR(static_cast<double>(CornerLength(w, one[0])), 1.5, 1e-7 + 1e-11);
}

// Samples of the corner with weight 1e10 are equally far apart along it (the
// independent CornerLength between consecutive ones), within twice the
// tolerance, on both legs and across the corner.
TEST(EqualArcLengthParameters, RationalCornerSamplesAreEquallySpaced) {
  const double w = 1e10;
  const BezierCurveData data = RationalCorner(w);
  const Curve corner = *BezierCurve::Create(data.view());
  const double tolerance = 1e-7;
  std::vector<double> parameters(11);
  ASSERT_TRUE(EqualArcLengthParameters(corner, 0.0, 1.0, parameters.size(),
                                       tolerance, absl::MakeSpan(parameters))
                  .ok());
  const double spacing = static_cast<double>(CornerLength(w, 1.0)) / 10;
  for (size_t k = 0; k + 1 < parameters.size(); ++k) {
    EXPECT_NEAR(static_cast<double>(CornerLength(w, parameters[k + 1]) -
                                    CornerLength(w, parameters[k])),
                spacing, 2 * tolerance + 1e-11)
        << k;
  }
}

// Lengths are the same at every scale of the coordinates (S) and of the
// knots (K), where double precision represents the curve: the unit segment
// on knots [0, 0, K, K] has length 1 and its point at length 1/4 is at
// t = K/4; the quadratic (0,0), (S,0), (S,S), congruent to the corner with
// weight 1 scaled by S, has S times its length. Squared speeds of 1e-170
// underflowed, and on knots 1e300 apart with S = 1e-300 the speed itself is
// below the double range.
TEST(ArcLength, EveryScaleOfCoordinatesAndKnots) {
  const double unit_corner = static_cast<double>(CornerLength(1.0, 1.0));
  for (int k = -300; k <= 300; k += 30) {
    const double scale = std::pow(10.0, k);
    const std::vector<double> segment = {0, 0, 1, 0};
    const std::vector<double> knots = {0, 0, scale, scale};
    const Curve line = *BSplineCurve::Create(
        {.degree = 1, .control_points = {2, segment}, .knots = knots});
    const absl::StatusOr<double> length = ArcLength(line, 0.0, scale, 1e-12);
    ASSERT_TRUE(length.ok()) << length.status();
    EXPECT_NEAR(*length, 1.0, 1e-12) << "K = " << scale;
    const std::vector<double> quarter = {0.25};
    std::vector<double> t(1);
    ASSERT_TRUE(
        ParametersAtArcLengths(line, 0.0, quarter, 1e-12, absl::MakeSpan(t))
            .ok());
    EXPECT_NEAR(t[0] / scale, 0.25, 1e-12) << "K = " << scale;
    for (const double knot_scale : {1e-300, 1.0, 1e300}) {
      const std::vector<double> points = {0, 0, scale, 0, scale, scale};
      const std::vector<double> quadratic_knots = {
          0, 0, 0, knot_scale, knot_scale, knot_scale};
      const Curve curve = *BSplineCurve::Create({.degree = 2,
                                                 .control_points = {2, points},
                                                 .knots = quadratic_knots});
      const absl::StatusOr<double> scaled =
          ArcLength(curve, 0.0, knot_scale, 1e-12 * scale);
      ASSERT_TRUE(scaled.ok()) << scaled.status();
      EXPECT_NEAR(*scaled / scale, unit_corner, 1e-11)
          << "S = " << scale << ", K = " << knot_scale;
    }
  }
}

// A spline of 200 spans needs far more quadrature steps than one poll's
// worth, so a cancelled token stops the integration.
TEST(ArcLength, StopsWhenCancelled) {
  std::mt19937_64 rng(9);
  const std::vector<double> points = RandomValues(rng, 202 * 2);
  const std::vector<double> knots = RandomKnots(rng, 2, 201, true);
  const Curve curve = *BSplineCurve::Create(
      {.degree = 2, .control_points = {2, points}, .knots = knots});
  CancellationToken token;
  token.Cancel();
  EXPECT_EQ(ArcLength(curve, 0.0, 1.0, 1e-9, &token).status().code(),
            absl::StatusCode::kCancelled);
  EXPECT_TRUE(ArcLength(curve, 0.0, 1.0, 1e-9).ok());
}

TEST(ParametersAtArcLengths, StopsWhenCancelled) {
  const BSplineCurveData data = NurbsCircle(1.0);
  const Curve circle = *BSplineCurve::Create(data.view());
  CancellationToken token;
  token.Cancel();
  const std::vector<double> lengths(100, 1.0);
  std::vector<double> parameters(lengths.size());
  EXPECT_EQ(ParametersAtArcLengths(circle, 0.0, lengths, 1e-9,
                                   absl::MakeSpan(parameters),
                                   {.pool = nullptr, .cancellation = &token})
                .code(),
            absl::StatusCode::kCancelled);
}

}  // namespace
}  // namespace freeform
