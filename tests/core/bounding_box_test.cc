#include "freeform/core/bounding_box.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "freeform/core/status.h"
#include "shapes.h"
#include "test_util.h"

namespace freeform {
namespace {

using testing_util::CurvePoints;
using testing_util::EvenlySpaced;
using testing_util::NurbsCircle;
using testing_util::RandomKnots;
using testing_util::RandomValues;
using testing_util::SpherePatch;
using testing_util::SurfacePoints;

constexpr double kTolerance = 1e-10;

// GoldenMaximum returns the largest value of f on [a, b] near its single
// local maximum there, by golden-section search.
double GoldenMaximum(const std::function<double(double)>& f, double a,
                     double b) {
  const double g = (std::sqrt(5.0) - 1) / 2;
  double best = std::max(f(a), f(b));
  for (int step = 0; step < 80; ++step) {
    const double x1 = b - g * (b - a), x2 = a + g * (b - a);
    const double f1 = f(x1), f2 = f(x2);
    best = std::max({best, f1, f2});
    (f1 < f2 ? a : b) = (f1 < f2 ? x1 : x2);
  }
  return best;
}

// PatternMaximum climbs from (u, v) by a shrinking compass search over the
// points `inside` accepts and returns the largest value of f met.
double PatternMaximum(const std::function<double(double, double)>& f,
                      const std::function<bool(double, double)>& inside,
                      double u, double v, double step) {
  double best = f(u, v);
  while (step > 1e-13) {
    bool moved = false;
    // Along the axes, and along the hypotenuse of a triangle.
    for (const auto& [du, dv] :
         {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, -1}, {-1, 1}}) {
      const double nu = u + du * step, nv = v + dv * step;
      if (!inside(nu, nv)) continue;
      const double value = f(nu, nv);
      if (value > best) {
        best = value, u = nu, v = nv, moved = true;
      }
    }
    if (!moved) step *= 0.5;
  }
  return best;
}

// A local search from sample `best` for the largest value of `sign` times
// coordinate j.
using Refine = std::function<double(int j, double sign, size_t best)>;

// CheckSides checks `box` against the sampled `points` of dimension d:
// every sample lies in the box, and each side is within 1e-9 of the sampled
// extreme refined by `refine` (and not inside it).
void CheckSides(const BoundingBox& box, const std::vector<double>& points,
                int d, const Refine& refine, const std::string& name) {
  const size_t count = points.size() / d;
  for (int j = 0; j < d; ++j) {
    for (const double sign : {1.0, -1.0}) {
      const double side = sign > 0 ? box.upper[j] : -box.lower[j];
      size_t best = 0;
      for (size_t r = 0; r < count; ++r) {
        ASSERT_LE(sign * points[r * d + j], side) << name << " sample " << r;
        if (sign * points[r * d + j] > sign * points[best * d + j]) best = r;
      }
      const double refined = refine(j, sign, best);
      EXPECT_LE(side - refined, 1e-9) << name << " coordinate " << j;
      EXPECT_GE(side - refined, -1e-13) << name << " coordinate " << j;
    }
  }
}

// CheckCurveBox samples the curve at 10^5 parameters and refines the
// extremes by golden-section search between the neighbours of the best
// sample.
void CheckCurveBox(const Curve& curve, const std::string& name) {
  absl::StatusOr<BoundingBox> box = CurveBoundingBox(curve, kTolerance);
  ASSERT_TRUE(box.ok()) << name << ": " << box.status();
  const ParameterDomain domain = DomainOf(curve);
  const std::vector<double> t = EvenlySpaced(domain.start, domain.end, 100000);
  CheckSides(
      *box, CurvePoints(curve, t), DimensionOf(curve),
      [&](int j, double sign, size_t best) {
        return GoldenMaximum(
            [&](double s) { return sign * CurvePoints(curve, {s})[j]; },
            t[best == 0 ? 0 : best - 1], t[std::min(best + 1, t.size() - 1)]);
      },
      name);
}

TEST(CurveBoundingBox, WorkedCubicIsTighterThanItsHull) {
  // (0,0), (1,2), (3,2), (4,0): y peaks at C(1/2) = (2, 1.5), the control
  // points reach 2.
  const std::vector<double> net = {0, 0, 1, 2, 3, 2, 4, 0};
  const Curve cubic = *BezierCurve::Create({.control_points = {2, net}});
  absl::StatusOr<BoundingBox> box = CurveBoundingBox(cubic, kTolerance);
  ASSERT_TRUE(box.ok());
  // Within the rounding margin, 2^-44 of the largest coordinate 4.
  EXPECT_NEAR(box->lower[0], 0.0, 1e-12);
  EXPECT_NEAR(box->upper[0], 4.0, 1e-12);
  EXPECT_NEAR(box->lower[1], 0.0, 1e-12);
  EXPECT_GE(box->upper[1], 1.5);
  EXPECT_LE(box->upper[1], 1.5 + kTolerance + 1e-12);
}

TEST(CurveBoundingBox, NurbsCircleIsItsSquare) {
  const BSplineCurveData data = NurbsCircle(2.0, 1.0, -3.0);
  const Curve circle = *BSplineCurve::Create(data.view());
  absl::StatusOr<BoundingBox> box = CurveBoundingBox(circle, kTolerance);
  ASSERT_TRUE(box.ok());
  EXPECT_GE(box->upper[0], 3.0);
  EXPECT_LE(box->upper[0], 3.0 + kTolerance + 1e-12);
  EXPECT_LE(box->lower[0], -1.0);
  EXPECT_GE(box->lower[0], -1.0 - kTolerance - 1e-12);
  EXPECT_GE(box->upper[1], -1.0);
  EXPECT_LE(box->upper[1], -1.0 + kTolerance + 1e-12);
  EXPECT_LE(box->lower[1], -5.0);
  EXPECT_GE(box->lower[1], -5.0 - kTolerance - 1e-12);
}

// A tolerance below rounding is met as the rounding margin, without
// splitting forever.
TEST(CurveBoundingBox, ToleranceBelowRoundingEnds) {
  const BSplineCurveData data = NurbsCircle(1.0);
  const Curve circle = *BSplineCurve::Create(data.view());
  absl::StatusOr<BoundingBox> box = CurveBoundingBox(circle, 1e-300);
  ASSERT_TRUE(box.ok());
  for (int j = 0; j < 2; ++j) {
    EXPECT_GE(box->upper[j], 1.0);
    EXPECT_LE(box->upper[j], 1.0 + 1e-12);
    EXPECT_LE(box->lower[j], -1.0);
    EXPECT_GE(box->lower[j], -1.0 - 1e-12);
  }
}

// The box is computed on the geometry rescaled by a power of two
// (scaled_geometry.h), so a copy scaled by 2^k has the box scaled by 2^k
// exactly. The Bezier form of a Lagrange curve of degree 14 through points
// up to 4e300 (the fuzzer's) overflowed: its box missed the curve's points
// at 3e301 by a factor of 10.
TEST(CurveBoundingBox, EveryScaleHasTheScaledBox) {
  std::mt19937_64 rng(5);
  const std::vector<double> points = RandomValues(rng, 15 * 3);
  const Curve unit = *LagrangeCurve::Create({.points = {3, points}});
  const absl::StatusOr<BoundingBox> box = CurveBoundingBox(unit, kTolerance);
  ASSERT_TRUE(box.ok()) << box.status();
  for (const int k : {-1000, -500, 500, 1000}) {
    std::vector<double> scaled = points;
    for (double& c : scaled) c = std::ldexp(c, k);
    const Curve curve = *LagrangeCurve::Create({.points = {3, scaled}});
    const absl::StatusOr<BoundingBox> big =
        CurveBoundingBox(curve, std::ldexp(kTolerance, k));
    ASSERT_TRUE(big.ok()) << k << ": " << big.status();
    for (int j = 0; j < 3; ++j) {
      EXPECT_EQ(big->lower[j], std::ldexp(box->lower[j], k)) << k;
      EXPECT_EQ(big->upper[j], std::ldexp(box->upper[j], k)) << k;
    }
  }
  std::vector<double> fuzzed(15 * 3, 0.0);
  const double tail[] = {1.0000000020372682e300,
                         1e300,
                         0,
                         2e300,
                         0,
                         1e300,
                         2e300,
                         0,
                         1e300,
                         3e300,
                         1e300,
                         1e300,
                         3e300,
                         1e300,
                         1e300,
                         3e300,
                         1e300,
                         1e300,
                         3e300,
                         1e300,
                         1e300,
                         3e300,
                         1e300,
                         1e300,
                         4e300,
                         2.172923689948439e-11,
                         0,
                         4e300,
                         2.172923689948439e-11,
                         0};
  std::copy(std::begin(tail), std::end(tail), fuzzed.begin() + 15);
  const Curve huge = *LagrangeCurve::Create({.points = {3, fuzzed}});
  const absl::StatusOr<BoundingBox> huge_box = CurveBoundingBox(huge, 1e-9);
  ASSERT_TRUE(huge_box.ok()) << huge_box.status();
  const ParameterDomain domain = DomainOf(huge);
  const std::vector<double> samples =
      CurvePoints(huge, EvenlySpaced(domain.start, domain.end, 20001));
  for (size_t r = 0; r < samples.size(); r += 3) {
    for (int j = 0; j < 3; ++j) {
      ASSERT_LE(samples[r + j], huge_box->upper[j]) << r / 3 << " " << j;
      ASSERT_GE(samples[r + j], huge_box->lower[j]) << r / 3 << " " << j;
    }
  }
}

TEST(CurveBoundingBox, EveryKindContainsDenseSamplesAndIsTight) {
  std::mt19937_64 rng(21);
  const std::vector<double> bezier_points = RandomValues(rng, 7 * 3);
  std::vector<double> weights = RandomValues(rng, 7, 0.3, 3.0);
  weights[3] = 0.0;  // a point at infinity inside
  const std::vector<double> spline_points = RandomValues(rng, 12 * 3, -5, 5);
  const std::vector<double> spline_weights = RandomValues(rng, 12, 0.2, 4.0);
  const std::vector<double> knots = RandomKnots(rng, 3, 11, false);
  const std::vector<double> lagrange_points = RandomValues(rng, 6 * 2);
  const std::vector<double> hermite_points = RandomValues(rng, 5 * 4);
  const std::vector<double> tangents = RandomValues(rng, 5 * 4, -3, 3);
  const std::vector<double> power = RandomValues(rng, 5 * 2);
  CheckCurveBox(*BezierCurve::Create(
                    {.control_points = {3, bezier_points}, .weights = weights}),
                "rational Bezier");
  CheckCurveBox(*BSplineCurve::Create({.degree = 3,
                                       .control_points = {3, spline_points},
                                       .knots = knots,
                                       .weights = spline_weights}),
                "NURBS");
  CheckCurveBox(*LagrangeCurve::Create({.points = {2, lagrange_points}}),
                "Lagrange");
  CheckCurveBox(*HermiteCurve::Create(
                    {.points = {4, hermite_points}, .tangents = {4, tangents}}),
                "Hermite");
  CheckCurveBox(*BezierCurve::FromPowerForm({2, power}), "power form");
}

// CheckSurfaceBox is CheckCurveBox on about 10^5 (u, v) points of the
// domain (a 317 x 317 grid, or the points (i, j) / 446 of the triangle),
// refined by compass search from the best sample.
void CheckSurfaceBox(const Surface& surface, const std::string& name) {
  absl::StatusOr<BoundingBox> box = SurfaceBoundingBox(surface, kTolerance);
  ASSERT_TRUE(box.ok()) << name << ": " << box.status();
  const SurfaceDomain domain = DomainOf(surface);
  const bool triangle = IsTriangular(surface);
  const int steps = triangle ? 446 : 316;
  const auto inside = [&](double u, double v) {
    return u >= domain.u_start && u <= domain.u_end && v >= domain.v_start &&
           v <= domain.v_end && (!triangle || u + v <= 1.0);
  };
  std::vector<double> uv;
  for (int i = 0; i <= steps; ++i) {
    for (int j = 0; j <= steps; ++j) {
      const double u =
          domain.u_start + (domain.u_end - domain.u_start) * i / steps;
      const double v =
          domain.v_start + (domain.v_end - domain.v_start) * j / steps;
      if (inside(u, v)) uv.insert(uv.end(), {u, v});
    }
  }
  CheckSides(
      *box, SurfacePoints(surface, SurfaceSamples::Pairs(uv)),
      DimensionOf(surface),
      [&](int j, double sign, size_t best) {
        return PatternMaximum(
            [&](double a, double b) {
              const std::vector<double> point = {a, b};
              return sign *
                     SurfacePoints(surface, SurfaceSamples::Pairs(point))[j];
            },
            inside, uv[2 * best], uv[2 * best + 1],
            (domain.u_end - domain.u_start) / steps);
      },
      name);
}

TEST(SurfaceBoundingBox, SpherePatchIsItsOctantCube) {
  const SurfaceData data = SpherePatch(1.5);
  const Surface sphere = *BezierSurface::Create(data.bezier_view());
  absl::StatusOr<BoundingBox> box = SurfaceBoundingBox(sphere, kTolerance);
  ASSERT_TRUE(box.ok());
  for (int j = 0; j < 3; ++j) {
    EXPECT_NEAR(box->lower[j], 0.0, 1e-12);
    EXPECT_GE(box->upper[j], 1.5);
    EXPECT_LE(box->upper[j], 1.5 + kTolerance + 1e-12);
  }
  CheckSurfaceBox(sphere, "sphere patch");
}

TEST(SurfaceBoundingBox, NurbsSurfaceContainsDenseSamplesAndIsTight) {
  std::mt19937_64 rng(8);
  const std::vector<double> net = RandomValues(rng, 6 * 5 * 3);
  const std::vector<double> weights = RandomValues(rng, 6 * 5, 0.5, 2.0);
  const std::vector<double> knots_u = RandomKnots(rng, 3, 5, true);
  const std::vector<double> knots_v = RandomKnots(rng, 2, 4, false);
  const Surface surface =
      *BSplineSurface::Create({.degree_u = 3,
                               .degree_v = 2,
                               .control_net = {.dimension = 3,
                                               .count_u = 6,
                                               .count_v = 5,
                                               .coordinates = net},
                               .knots_u = knots_u,
                               .knots_v = knots_v,
                               .weights = weights});
  CheckSurfaceBox(surface, "NURBS surface");
}

// z = 1 - (u - v)^2 on the biquadratic patch (u / 2, v / 2 net spacing):
// its largest z, 1, is attained along the diagonal u = v, a ridge that the
// halvings cross, so the search for that side needs about
// sqrt(size / tolerance) pieces along it. Within a reachable tolerance the
// side is tight; below it (the margin) the budget of kMaxBoxHalvings ends the
// search with a bound still above the surface, within 4 size / budget^2
// (2.2e-8 here; 1.49e-8 measured). Before the budget, the 1e-14 box took
// minutes (4 million pieces).
TEST(SurfaceBoundingBox, RidgeExtremeEndsWithinTheHalvingBudget) {
  // z_ij = 1 - a_i - a_j + 2 b_i b_j: the Bernstein coefficients of 1, u^2
  // (a = 0, 0, 1) and u (b = 0, 1/2, 1).
  const double z[3][3] = {{1, 1, 0}, {1, 1.5, 1}, {0, 1, 1}};
  std::vector<double> net;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j)
      net.insert(net.end(), {i / 2.0, j / 2.0, z[i][j]});
  }
  const Surface ridge = *BezierSurface::Create(
      {.control_net = {
           .dimension = 3, .count_u = 3, .count_v = 3, .coordinates = net}});
  for (const double tolerance : {1e-6, 1e-14}) {
    SCOPED_TRACE(tolerance);
    absl::StatusOr<BoundingBox> box = SurfaceBoundingBox(ridge, tolerance);
    ASSERT_TRUE(box.ok()) << box.status();
    EXPECT_NEAR(box->lower[0], 0.0, 1e-12);
    EXPECT_NEAR(box->upper[0], 1.0, 1e-12);
    EXPECT_NEAR(box->lower[1], 0.0, 1e-12);
    EXPECT_NEAR(box->upper[1], 1.0, 1e-12);
    EXPECT_NEAR(box->lower[2], 0.0, 1e-12);  // at the corners (0, 1), (1, 0)
    EXPECT_GE(box->upper[2], 1.0);
    EXPECT_LE(box->upper[2], 1.0 + std::max(tolerance, 4 * 1.5 / (1 << 28)))
        << box->upper[2] - 1.0;
  }
}

// A token that never stops and counts how often it is asked: the work of a
// search, in polls (one per 2^16 units of CancellationPoll).
struct PollCounter {
  PollCounter() {
    token.SetPoll([this] {
      ++polls;
      return false;
    });
  }
  PollCounter(const PollCounter&) = delete;
  PollCounter& operator=(const PollCounter&) = delete;

  int polls = 0;
  CancellationToken token;
};

// A rational patch whose halvings round corner weights to zero (weights of
// 1e-317 next to zeros, coordinates up to 7e252; found by the BoundingBox
// fuzzer) has a corner at infinity: the search reports a side that is not
// finite at once instead of halving 16,384 pieces for each of the six sides,
// each one unbounded. The token's poll counts the work: one poll per 2^16
// units, about 600 halvings of this 3 x 3 net.
TEST(SurfaceBoundingBox, CornerAtInfinityEndsTheSearchAtOnce) {
  const std::vector<double> net = {0,
                                   8.28904605845809e-317,
                                   0,
                                   2,
                                   0,
                                   0,
                                   4,
                                   0,
                                   4.34584737989688e-311,
                                   0,
                                   2,
                                   0,
                                   2,
                                   2,
                                   1.2015398835938887e-306,
                                   4,
                                   2,
                                   2,
                                   0,
                                   4,
                                   0,
                                   1.5778922151280042e+214,
                                   1.4490884972206536e+166,
                                   5.5560354281809549e+180,
                                   4,
                                   7.2048658145058678e+252,
                                   4.0000000000116946};
  const std::vector<double> weights = {
      5.31017013119972e-315, 0, 5.30498947741318e-315, 0, 5.32577027372978e-315,
      2.07226151461452e-317, 2.07226151461452e-317, 1.3481685079097897e-225,
      // 1e-06 in the fuzz input, whose
      // smallest weights are now refused
      // (below 2^-1021 of the largest,
      // rational.h); the same ratios
      // otherwise
      1e-10};
  absl::StatusOr<Surface> surface =
      BezierSurface::Create({.control_net = {.dimension = 3,
                                             .count_u = 3,
                                             .count_v = 3,
                                             .coordinates = net},
                             .weights = weights});
  ASSERT_TRUE(surface.ok()) << surface.status();
  PollCounter counter;
  absl::StatusOr<BoundingBox> box =
      SurfaceBoundingBox(*surface, kTolerance, &counter.token);
  ASSERT_TRUE(box.ok()) << box.status();
  bool finite = true;
  for (int j = 0; j < 3; ++j) {
    finite =
        finite && std::isfinite(box->lower[j]) && std::isfinite(box->upper[j]);
  }
  EXPECT_FALSE(finite);
  EXPECT_LE(counter.polls, 6);
}

// The search for one side stops once its halvings have cost
// kMaxBoxHalvingWork: on a degree-40 patch in 8-D (41 x 41 random control
// points) the box still holds every sample of the surface, and the work,
// counted by the token's polls (one per 2^16 units, a halving reporting 4
// units per control value), stays within what the budget allows: for each
// of the 16 sides, budget / halving cost + 1 halvings.
TEST(SurfaceBoundingBox, HighDegreeSearchStopsAtTheWorkBudget) {
  constexpr int kCount = 41, kDimension = 8;
  std::mt19937_64 rng(41);
  const std::vector<double> net =
      RandomValues(rng, kCount * kCount * kDimension);
  const Surface surface =
      *BezierSurface::Create({.control_net = {.dimension = kDimension,
                                              .count_u = kCount,
                                              .count_v = kCount,
                                              .coordinates = net}});
  PollCounter counter;
  absl::StatusOr<BoundingBox> box =
      SurfaceBoundingBox(surface, kTolerance, &counter.token);
  ASSERT_TRUE(box.ok()) << box.status();
  const std::vector<double> uv = EvenlySpaced(0.0, 1.0, 201);
  const std::vector<double> points =
      SurfacePoints(surface, SurfaceSamples::Grid(uv, uv));
  for (size_t r = 0; r < points.size() / kDimension; ++r) {
    for (int j = 0; j < kDimension; ++j) {
      ASSERT_LE(points[r * kDimension + j], box->upper[j]) << r;
      ASSERT_GE(points[r * kDimension + j], box->lower[j]) << r;
    }
  }
  const size_t values = size_t{kCount} * kCount * kDimension;
  const size_t halvings_per_side = kMaxBoxHalvingWork / (values * kCount) + 1;
  const size_t units = 2 * kDimension * halvings_per_side * 4 * values;
  EXPECT_LE(static_cast<size_t>(counter.polls), units / (size_t{1} << 16) + 1);
}

// A rational quadratic triangular patch with weights from 1e-300 to 2
// (found by the BoundingBox fuzzer with 1.3e-321: 1.2 s under ASan). The
// control point of weight 1e-300 keeps its hull far from the surface, so the
// search for that side halves until its budget; the answer must still hold
// every sample, and the whole search must stay within the budget of its six
// sides: 16,384 halvings each, a halving reporting 4 units per control
// value (18), one poll per 2^16 units.
TEST(SurfaceBoundingBox, NearZeroWeightSearchHoldsTheSurfaceWithinBudget) {
  const std::vector<double> points = {0,
                                      0,
                                      3.0517578125e-05,
                                      1.0000000000000557,
                                      0,
                                      1,
                                      0,
                                      1,
                                      1,
                                      3.0517578125e-05,
                                      2.05568342200354e-314,
                                      0,
                                      1.0000000036670613,
                                      1,
                                      0,
                                      0,
                                      -131072,
                                      1.06099789548264e-313};
  const std::vector<double> weights = {1, 1.4693679385278594e-39,
                                       2.0000000000291007, 4.57763671875e-05,
                                       // 1.3e-321 in the fuzz input: now
                                       // refused (below 2^-1021 of the
                                       // largest, rational.h), and 1e-300
                                       // keeps its hull as far
                                       1e-300, 1};
  const Surface patch = *TriangularPatch::Create(
      {.degree = 2, .control_points = {3, points}, .weights = weights});
  PollCounter counter;
  absl::StatusOr<BoundingBox> box =
      SurfaceBoundingBox(patch, 1e-6, &counter.token);
  ASSERT_TRUE(box.ok()) << box.status();
  std::vector<double> uv;
  constexpr int kSteps = 400;
  for (int i = 0; i <= kSteps; ++i) {
    for (int j = 0; i + j <= kSteps; ++j) {
      uv.insert(uv.end(), {static_cast<double>(i) / kSteps,
                           static_cast<double>(j) / kSteps});
    }
  }
  const std::vector<double> samples =
      SurfacePoints(patch, SurfaceSamples::Pairs(uv));
  for (size_t r = 0; r < samples.size() / 3; ++r) {
    for (int j = 0; j < 3; ++j) {
      ASSERT_LE(samples[r * 3 + j], box->upper[j]) << r;
      ASSERT_GE(samples[r * 3 + j], box->lower[j]) << r;
    }
  }
  const size_t units = 6 * size_t{kMaxBoxHalvings} * 4 * 18;
  EXPECT_LE(static_cast<size_t>(counter.polls), units / (size_t{1} << 16) + 6);
}

// A rational cubic triangular patch with random positive weights, and the
// flat triangle, whose box is its vertices' box.
TEST(SurfaceBoundingBox, TriangularPatches) {
  std::mt19937_64 rng(30);
  const std::vector<double> points = RandomValues(rng, 10 * 3);
  const std::vector<double> weights = RandomValues(rng, 10, 0.3, 3.0);
  CheckSurfaceBox(
      *TriangularPatch::Create(
          {.degree = 3, .control_points = {3, points}, .weights = weights}),
      "triangular patch");
  const std::vector<double> flat = {1, 5, 0, -2, 1, 3, 0, -1, 2};
  absl::StatusOr<BoundingBox> box = SurfaceBoundingBox(
      *TriangularPatch::Create({.degree = 1, .control_points = {3, flat}}),
      kTolerance);
  ASSERT_TRUE(box.ok());
  const double lower[3] = {-2, -1, 0}, upper[3] = {1, 5, 3};
  for (int j = 0; j < 3; ++j) {
    EXPECT_NEAR(box->lower[j], lower[j], 1e-12);
    EXPECT_NEAR(box->upper[j], upper[j], 1e-12);
  }
}

// A rational curve and surface whose x reaches -2.5e304 at weight 1e103
// while y stays in [1e25, 1e25 + 1e10], next to weights of 1e203 (the
// fuzz finding's ranges). With positive weights every y of the geometry is
// a convex combination of the control points' y, so the box's y sides lie
// within that range widened by twice the margin 2^-44 of 1e25 (and the
// tolerance), and hold the ends, which the geometry attains. Scaled by one
// power of two for x, y became 2e-280 and w y (weight 8e-101 then)
// underflowed to 0: the lower y side was -5.7e11 = -2^-44 1e25.
constexpr double kHugeX = -2.5e304;
constexpr double kBaseY = 1e25;
constexpr double kRiseY = 1e10;

void ExpectYWithinItsHull(const BoundingBox& box, const std::string& name) {
  const double slack = 2 * 0x1p-44 * (kBaseY + kRiseY) + 1e-6;
  EXPECT_GE(box.lower[1], kBaseY - slack) << name;
  EXPECT_LE(box.lower[1], kBaseY) << name;
  EXPECT_GE(box.upper[1], kBaseY) << name;
  EXPECT_LE(box.upper[1], kBaseY + kRiseY + slack) << name;
}

TEST(CurveBoundingBox, HugeAxisKeepsTheDigitsOfAnother) {
  const std::vector<double> points = {0, kBaseY, kHugeX, kBaseY + kRiseY,
                                      1, kBaseY};
  const std::vector<double> weights = {1e103, 1e103, 1e203};
  absl::StatusOr<Curve> curve = BezierCurve::Create(
      {.control_points = {.dimension = 2, .coordinates = points},
       .weights = weights});
  ASSERT_TRUE(curve.ok()) << curve.status();
  absl::StatusOr<BoundingBox> box = CurveBoundingBox(*curve, 1e-6);
  ASSERT_TRUE(box.ok()) << box.status();
  ExpectYWithinItsHull(*box, "curve");
}

TEST(SurfaceBoundingBox, HugeAxisKeepsTheDigitsOfAnother) {
  const std::vector<double> net = {0, kBaseY, kHugeX, kBaseY + kRiseY,
                                   1, kBaseY, 2,      kBaseY};
  const std::vector<double> weights = {1e103, 1e103, 1e203, 1e103};
  absl::StatusOr<Surface> surface =
      BezierSurface::Create({.control_net = {.dimension = 2,
                                             .count_u = 2,
                                             .count_v = 2,
                                             .coordinates = net},
                             .weights = weights});
  ASSERT_TRUE(surface.ok()) << surface.status();
  absl::StatusOr<BoundingBox> box = SurfaceBoundingBox(*surface, 1e-6);
  ASSERT_TRUE(box.ok()) << box.status();
  ExpectYWithinItsHull(*box, "surface");
}

TEST(BoundingBox, Errors) {
  const BSplineCurveData data = NurbsCircle(1.0);
  const Curve circle = *BSplineCurve::Create(data.view());
  EXPECT_EQ(FieldPathOf(CurveBoundingBox(circle, 0.0).status()), "tolerance");
  const SurfaceData sphere = SpherePatch(1.0);
  EXPECT_EQ(FieldPathOf(SurfaceBoundingBox(
                            *BezierSurface::Create(sphere.bezier_view()), -1.0)
                            .status()),
            "tolerance");
  CancellationToken token;
  token.Cancel();
  std::vector<double> wiggle;
  for (int i = 0; i < 200; ++i) {
    // The ends at y = 1/2, so the hull's 0 and 1 are far from the curve.
    const double y = i == 0 || i == 199 ? 0.5 : (i % 2) * 1.0;
    wiggle.insert(wiggle.end(), {i * 0.01, y});
  }
  const Curve curve = *BezierCurve::Create({.control_points = {2, wiggle}});
  EXPECT_EQ(CurveBoundingBox(curve, 1e-12, &token).status().code(),
            absl::StatusCode::kCancelled);
}

// The pieces of DecomposeCurve evaluate to the curve on their intervals.
TEST(DecomposeCurve, PiecesAreTheCurveOnTheirIntervals) {
  std::mt19937_64 rng(4);
  const std::vector<double> points = RandomValues(rng, 6 * 2);
  const std::vector<double> tangents = RandomValues(rng, 6 * 2);
  const std::vector<double> nodes = {0.0, 0.5, 0.7, 1.5, 2.0, 4.0};
  const Curve hermite = *HermiteCurve::Create(
      {.points = {2, points}, .tangents = {2, tangents}, .nodes = nodes});
  const Curve lagrange =
      *LagrangeCurve::Create({.points = {2, points}, .nodes = nodes});
  for (const Curve& curve : {hermite, lagrange}) {
    absl::StatusOr<BezierDecomposition> pieces = DecomposeCurve(curve);
    ASSERT_TRUE(pieces.ok());
    EXPECT_EQ(pieces->breakpoints, CurveBreakpoints(curve));
    for (size_t k = 0; k < pieces->segments.size(); ++k) {
      const double a = pieces->breakpoints[k], b = pieces->breakpoints[k + 1];
      const Curve piece = *BezierCurve::Create(pieces->segments[k].view());
      for (const double s : {0.0, 0.3, 1.0}) {
        const std::vector<double> expected =
            CurvePoints(curve, {a + s * (b - a)});
        const std::vector<double> got = CurvePoints(piece, {s});
        EXPECT_NEAR(got[0], expected[0], 1e-10);
        EXPECT_NEAR(got[1], expected[1], 1e-10);
      }
    }
  }
}

}  // namespace
}  // namespace freeform
