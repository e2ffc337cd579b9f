#include "freeform/core/knot_removal.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "freeform/core/cancellation.h"
#include "freeform/core/interpolation.h"
#include "freeform/core/status.h"
#include "freeform/core/subdivision.h"
#include "shapes.h"
#include "test_util.h"
#include "workloads.h"

namespace freeform {
namespace {

using ::freeform::testing_util::EvenlySpaced;
using ::freeform::testing_util::NurbsCircle;
using ::freeform::testing_util::RandomKnots;
using ::freeform::testing_util::RandomValues;
using ::testing::ElementsAreArray;
using ::testing::Optional;

constexpr size_t kSamples = 10000;

void ExpectFieldError(const absl::Status& status, const std::string& field) {
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << status;
  EXPECT_THAT(FieldPathOf(status), Optional(field)) << status;
}

// MaxPointDistance returns the largest |a_k - b_k| over points of
// `dimension` coordinates (with 1, the largest difference of two arrays).
double MaxPointDistance(const std::vector<double>& a,
                        const std::vector<double>& b, int dimension) {
  EXPECT_EQ(a.size(), b.size());
  double largest = 0.0;
  for (size_t k = 0; k + dimension <= std::min(a.size(), b.size());
       k += static_cast<size_t>(dimension)) {
    largest =
        std::max(largest, testing_util::PointDistance(&a[k], &b[k], dimension));
  }
  return largest;
}

std::vector<double> CurveValues(const BSplineCurveView& curve,
                                const std::vector<double>& parameters) {
  std::vector<double> values(parameters.size() *
                             curve.control_points.dimension);
  const std::vector<absl::Span<double>> output = {absl::MakeSpan(values)};
  const absl::Status status = EvaluateBSplineCurve(curve, parameters, output);
  EXPECT_TRUE(status.ok()) << status;
  return values;
}

// CurveDistance returns the largest distance between two curves on the
// same domain at kSamples evenly spaced parameters.
double CurveDistance(const BSplineCurveView& a, const BSplineCurveView& b) {
  const ParameterDomain domain = BSplineDomain(a);
  const std::vector<double> parameters =
      EvenlySpaced(domain.start, domain.end, kSamples);
  return MaxPointDistance(CurveValues(a, parameters),
                          CurveValues(b, parameters),
                          a.control_points.dimension);
}

// SurfaceDistance does the same on a 100 x 100 grid.
double SurfaceDistance(const BSplineSurfaceView& a,
                       const BSplineSurfaceView& b) {
  const SurfaceDomain domain = BSplineSurfaceDomain(a);
  const std::vector<double> us =
      EvenlySpaced(domain.u_start, domain.u_end, 100);
  const std::vector<double> vs =
      EvenlySpaced(domain.v_start, domain.v_end, 100);
  const SurfaceSamples samples{.grid = true, .u = us, .v = vs};
  const int dim = a.control_net.dimension;
  std::vector<double> values[2];
  const BSplineSurfaceView* surfaces[2] = {&a, &b};
  for (int s = 0; s < 2; ++s) {
    values[s].resize(samples.size() * dim);
    const std::vector<absl::Span<double>> output = {absl::MakeSpan(values[s])};
    const absl::Status status =
        EvaluateBSplineSurface(*surfaces[s], samples, output);
    EXPECT_TRUE(status.ok()) << status;
  }
  return MaxPointDistance(values[0], values[1], dim);
}

// A random curve of degree p with `count` control points in `dimension`
// coordinates on random (clamped or not) knots with some interior knots
// repeated; weights in [0.5, 2] when rational.
BSplineCurveData RandomCurve(std::mt19937_64& rng, int p, int count,
                             int dimension, bool clamped, bool rational) {
  BSplineCurveData curve{.degree = p, .dimension = dimension};
  curve.coordinates = RandomValues(rng, static_cast<size_t>(count) * dimension);
  curve.knots = RandomKnots(rng, p, count - 1, clamped);
  if (rational) curve.weights = RandomValues(rng, count, 0.5, 2.0);
  EXPECT_TRUE(ValidateBSplineCurve(curve.view()).ok());
  return curve;
}

// SpanMidpoint returns the midpoint of the k-th non-empty span inside the
// domain of degree p `knots` (wrapping around).
double SpanMidpoint(const std::vector<double>& knots, int p, int k) {
  std::vector<double> midpoints;
  for (size_t i = p; i + p + 1 < knots.size(); ++i) {
    if (knots[i] < knots[i + 1]) {
      midpoints.push_back(0.5 * (knots[i] + knots[i + 1]));
    }
  }
  return midpoints[static_cast<size_t>(k) % midpoints.size()];
}

BSplineCurveData Inserted(const BSplineCurveData& curve,
                          const std::vector<double>& knots) {
  absl::StatusOr<BSplineCurveData> refined = InsertKnots(curve.view(), knots);
  EXPECT_TRUE(refined.ok()) << refined.status();
  return *refined;
}

// ---------------------------------------------------------------------------
// The worked example of docs/references.md, 'Knot removal'.

// The quadratic on knots 0,0,0,1,2,2,2 with points (0,0), (1,2.5), (3,2),
// (4,0): removing u = 1 solves Q_1 = 2 P_2 - P_3 = (2,4) from the right;
// re-inserting u = 1 gives (Q_0 + Q_1) / 2 = (1,2) in place of P_1, so the
// certificate is |(1,2.5) - (1,2)| = 0.5. The true distance is
// 0.5 N_{1,2}(t), largest at t = 2/3 where N_{1,2} = 2t - 1.5t^2 = 2/3.
BSplineCurveData WorkedExample() {
  return {.degree = 2,
          .dimension = 2,
          .coordinates = {0, 0, 1, 2.5, 3, 2, 4, 0},
          .knots = {0, 0, 0, 1, 2, 2, 2}};
}

TEST(KnotRemoval, WorkedExampleGivesTheBezierCurveAndItsBound) {
  const BSplineCurveData curve = WorkedExample();
  absl::StatusOr<CurveKnotRemoval> removed =
      RemoveCurveKnot(curve.view(), 1.0, 1, 1.0);
  ASSERT_TRUE(removed.ok()) << removed.status();
  EXPECT_EQ(removed->removals, 1);
  EXPECT_THAT(removed->curve.knots, ElementsAreArray({0, 0, 0, 2, 2, 2}));
  EXPECT_LT(MaxPointDistance(removed->curve.coordinates, {0, 0, 2, 4, 4, 0}, 1),
            1e-15);
  EXPECT_NEAR(removed->error_bound, 0.5, 1e-15);
  // The true distance: 1/3 at t = 2/3, below the bound.
  const std::vector<double> at = {2.0 / 3.0};
  EXPECT_NEAR(MaxPointDistance(CurveValues(curve.view(), at),
                               CurveValues(removed->curve.view(), at), 2),
              1.0 / 3.0, 1e-15);
  EXPECT_NEAR(CurveDistance(curve.view(), removed->curve.view()), 1.0 / 3.0,
              1e-8);
}

TEST(KnotRemoval, WorkedExampleStaysWhenTheBoundExceedsTheTolerance) {
  // The true distance 1/3 would fit 0.4, but the certificate (0.5) does not.
  const BSplineCurveData curve = WorkedExample();
  absl::StatusOr<CurveKnotRemoval> removed =
      RemoveCurveKnot(curve.view(), 1.0, 1, 0.4);
  ASSERT_TRUE(removed.ok()) << removed.status();
  EXPECT_EQ(removed->removals, 0);
  EXPECT_EQ(removed->error_bound, 0.0);
  EXPECT_EQ(removed->curve.knots, curve.knots);
  EXPECT_EQ(removed->curve.coordinates, curve.coordinates);
}

TEST(KnotRemoval, RationalWorkedExampleBound) {
  // The example with weight 1.5 on P_1: homogeneous (1.5, 3, 1.5) against
  // the re-inserted (1, 2, 1); centre c = (2, 1), rho = sqrt(5);
  // e_s = |(0.5, 1) - 0.5 (2, 1)| = sqrt(1/2), e_w = 0.5, refined weights
  // all 1: bound sqrt(1/2) + sqrt(5) / 2.
  BSplineCurveData curve = WorkedExample();
  curve.coordinates = {0, 0, 1, 2, 3, 2, 4, 0};
  curve.weights = {1, 1.5, 1, 1};
  absl::StatusOr<CurveKnotRemoval> removed =
      RemoveCurveKnot(curve.view(), 1.0, 1, 10.0);
  ASSERT_TRUE(removed.ok()) << removed.status();
  EXPECT_EQ(removed->removals, 1);
  EXPECT_LT(MaxPointDistance(removed->curve.coordinates, {0, 0, 2, 4, 4, 0}, 1),
            1e-15);
  EXPECT_LT(MaxPointDistance(removed->curve.weights, {1, 1, 1}, 1), 1e-15);
  EXPECT_NEAR(removed->error_bound, std::sqrt(0.5) + std::sqrt(5.0) / 2, 1e-15);
  // The true distance, about 0.2084 near t = 0.235 (a 20001-point scan of
  // the closed forms N_{i,2} in docs/references.md), is far below it.
  const double sampled = CurveDistance(curve.view(), removed->curve.view());
  EXPECT_NEAR(sampled, 0.2084, 1e-3);
  EXPECT_LE(sampled, removed->error_bound);
}

// ---------------------------------------------------------------------------
// Inserted knots come out exactly.

struct RoundTripCase {
  int degree;
  bool clamped;
  bool rational;
};

class CurveRoundTrip : public ::testing::TestWithParam<RoundTripCase> {};

TEST_P(CurveRoundTrip, InsertedKnotsAreRemovedExactly) {
  const RoundTripCase c = GetParam();
  std::mt19937_64 rng(17 + c.degree);
  for (int trial = 0; trial < 20; ++trial) {
    const BSplineCurveData curve =
        RandomCurve(rng, c.degree, 12, 3, c.clamped, c.rational);
    // Once, and as many times as the degree allows.
    for (const int times : {1, c.degree}) {
      const double u = SpanMidpoint(curve.knots, c.degree, trial);
      const BSplineCurveData refined =
          Inserted(curve, std::vector<double>(static_cast<size_t>(times), u));
      absl::StatusOr<CurveKnotRemoval> removed =
          RemoveCurveKnot(refined.view(), u, times + 2, 1e-9);
      ASSERT_TRUE(removed.ok()) << removed.status();
      EXPECT_EQ(removed->removals, times);
      EXPECT_EQ(removed->curve.knots, curve.knots);
      EXPECT_LT(
          MaxPointDistance(removed->curve.coordinates, curve.coordinates, 1),
          1e-12);
      EXPECT_LT(MaxPointDistance(removed->curve.weights, curve.weights, 1),
                1e-12);
      EXPECT_LT(removed->error_bound, 1e-12);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Curves, CurveRoundTrip,
                         ::testing::Values(RoundTripCase{1, true, false},
                                           RoundTripCase{2, true, false},
                                           RoundTripCase{3, true, false},
                                           RoundTripCase{3, false, false},
                                           RoundTripCase{5, true, false},
                                           RoundTripCase{2, true, true},
                                           RoundTripCase{3, true, true},
                                           RoundTripCase{3, false, true},
                                           RoundTripCase{4, false, true}));

TEST(KnotRemoval, ExtraCopiesOfAnExistingKnotGoAndTheOriginalStays) {
  // The circle with 0.1 inserted twice (the most a quadratic allows) and
  // 0.6 once: asked for three removals of 0.1, two are possible.
  const BSplineCurveData circle = NurbsCircle(2.0);
  const BSplineCurveData refined = Inserted(circle, {0.1, 0.1, 0.6});
  absl::StatusOr<CurveKnotRemoval> removed =
      RemoveCurveKnot(refined.view(), 0.1, 3, 1e-9);
  ASSERT_TRUE(removed.ok()) << removed.status();
  EXPECT_EQ(removed->removals, 2);
  const BSplineCurveData expected = Inserted(circle, {0.6});
  EXPECT_EQ(removed->curve.knots, expected.knots);
  EXPECT_LT(
      MaxPointDistance(removed->curve.coordinates, expected.coordinates, 1),
      1e-12);
  EXPECT_LT(MaxPointDistance(removed->curve.weights, expected.weights, 1),
            1e-12);
  // The circle's own double knot 1/2 is a corner of the homogeneous curve:
  // it stays at a small tolerance.
  absl::StatusOr<CurveKnotRemoval> kept =
      RemoveCurveKnot(circle.view(), 0.5, 2, 1e-6);
  ASSERT_TRUE(kept.ok()) << kept.status();
  EXPECT_EQ(kept->removals, 0);
  EXPECT_EQ(kept->curve.knots, circle.knots);
}

TEST(KnotRemoval, CubicExistingKnotRaisedIsLoweredBackExactly) {
  std::mt19937_64 rng(5);
  BSplineCurveData curve = RandomCurve(rng, 3, 10, 2, true, false);
  curve.knots = {0, 0, 0, 0, 0.2, 0.3, 0.5, 0.6, 0.8, 0.9, 1, 1, 1, 1};
  const BSplineCurveData refined = Inserted(curve, {0.5, 0.5});
  absl::StatusOr<CurveKnotRemoval> removed =
      RemoveCurveKnot(refined.view(), 0.5, 3, 1e-9);
  ASSERT_TRUE(removed.ok()) << removed.status();
  // The two inserted copies go; the original one carries a jump of the
  // third derivative and stays.
  EXPECT_EQ(removed->removals, 2);
  EXPECT_EQ(removed->curve.knots, curve.knots);
  EXPECT_LT(MaxPointDistance(removed->curve.coordinates, curve.coordinates, 1),
            1e-12);
}

// ---------------------------------------------------------------------------
// Removal within a tolerance.

TEST(KnotRemoval, ApproximateRemovalStaysWithinTheCertifiedBound) {
  std::mt19937_64 rng(23);
  for (const bool rational : {false, true}) {
    for (int trial = 0; trial < 10; ++trial) {
      const BSplineCurveData curve = RandomCurve(rng, 3, 10, 3, true, rational);
      const double u = SpanMidpoint(curve.knots, 3, trial);
      BSplineCurveData refined = Inserted(curve, {u});
      // Move every point by up to 1e-3: u no longer goes exactly.
      for (double& x : refined.coordinates) x += 1e-3 * RandomValues(rng, 1)[0];
      absl::StatusOr<CurveKnotRemoval> removed =
          RemoveCurveKnot(refined.view(), u, 1, 0.1);
      ASSERT_TRUE(removed.ok()) << removed.status();
      ASSERT_EQ(removed->removals, 1);
      const double sampled =
          CurveDistance(refined.view(), removed->curve.view());
      EXPECT_GT(sampled, 1e-6);
      EXPECT_LE(sampled, removed->error_bound);
      EXPECT_LE(removed->error_bound, 0.1);
      // Below the bound the knot stays and nothing changes.
      absl::StatusOr<CurveKnotRemoval> kept =
          RemoveCurveKnot(refined.view(), u, 1, 0.999 * removed->error_bound);
      ASSERT_TRUE(kept.ok()) << kept.status();
      EXPECT_EQ(kept->removals, 0);
      EXPECT_EQ(kept->curve.coordinates, refined.coordinates);
    }
  }
}

TEST(KnotRemoval, SimplifyWithinToleranceOfNoisyRefinedCurve) {
  // A refined curve with noise of 1e-6 on every point simplifies at
  // 1e-4 to about the original knots, every removal certified against the
  // noisy input: the bound is within the tolerance and above the sampled
  // distance.
  std::mt19937_64 rng(31);
  for (const bool rational : {false, true}) {
    const BSplineCurveData curve = RandomCurve(rng, 3, 20, 2, true, rational);
    std::vector<double> extra;
    for (int k = 0; k < 60; ++k) extra.push_back((k + 0.5) / 60.0);
    std::vector<double> sorted_extra = extra;
    std::sort(sorted_extra.begin(), sorted_extra.end());
    BSplineCurveData noisy = Inserted(curve, sorted_extra);
    for (double& x : noisy.coordinates) x += 1e-6 * RandomValues(rng, 1)[0];
    const double tolerance = 1e-4;
    absl::StatusOr<CurveKnotRemoval> simplified =
        SimplifyCurveKnots(noisy.view(), tolerance);
    ASSERT_TRUE(simplified.ok()) << simplified.status();
    EXPECT_GE(simplified->removals, 50);
    EXPECT_LE(simplified->error_bound, tolerance);
    const double sampled =
        CurveDistance(noisy.view(), simplified->curve.view());
    EXPECT_LE(sampled, simplified->error_bound);
    EXPECT_EQ(simplified->curve.knots.size(),
              noisy.knots.size() - simplified->removals);
  }
}

TEST(KnotRemoval, CertificateHoldsForEveryKnotOfRandomCurves) {
  // Knots that carry shape, removed as often as the degree allows with a
  // loose tolerance from random
  // curves (clamped or not, rational or not, interior knots repeated): the
  // sampled distance never exceeds the certified bound. Then everything
  // simplified at once, against the same check.
  std::mt19937_64 rng(29);
  int checked = 0;
  for (const int p : {1, 2, 3, 4}) {
    for (const bool clamped : {true, false}) {
      for (const bool rational : {false, true}) {
        const BSplineCurveData curve =
            RandomCurve(rng, p, 9, 2, clamped, rational);
        const double end = curve.knots[curve.knots.size() - p - 1];
        for (size_t i = p + 1; curve.knots[i] < end; ++i) {
          if (curve.knots[i] == curve.knots[i - 1]) continue;
          absl::StatusOr<CurveKnotRemoval> removed =
              RemoveCurveKnot(curve.view(), curve.knots[i], p, 1e6);
          ASSERT_TRUE(removed.ok()) << removed.status();
          // A rational removal may refuse: its new weights would not all
          // be positive.
          if (!rational) {
            EXPECT_GE(removed->removals, 1);
          }
          if (removed->removals == 0) continue;
          EXPECT_TRUE(ValidateBSplineCurve(removed->curve.view()).ok());
          EXPECT_LE(CurveDistance(curve.view(), removed->curve.view()),
                    removed->error_bound * (1 + 1e-12));
          ++checked;
        }
        absl::StatusOr<CurveKnotRemoval> simplified =
            SimplifyCurveKnots(curve.view(), 0.5);
        ASSERT_TRUE(simplified.ok()) << simplified.status();
        EXPECT_LE(simplified->error_bound, 0.5);
        EXPECT_LE(CurveDistance(curve.view(), simplified->curve.view()),
                  simplified->error_bound * (1 + 1e-12));
      }
    }
  }
  EXPECT_GT(checked, 50);
}

// ---------------------------------------------------------------------------
// W1 refined tenfold and simplified back.

TEST(KnotRemoval, W1RefinedToAThousandKnotsSimplifiesBackToItsKnots) {
  const bench::SplineData w1 = bench::RandomSpline(1, 100, 3);
  const BSplineCurveData curve{.degree = w1.degree,
                               .dimension = w1.dimension,
                               .coordinates = w1.points,
                               .knots = w1.knots};
  ASSERT_EQ(curve.knots.size(), 104u);
  // Nine knots inside each of the 97 spans: 977 knots in all.
  std::vector<double> extra;
  for (size_t i = 3; i + 4 < curve.knots.size(); ++i) {
    for (int k = 1; k <= 9; ++k) {
      extra.push_back(curve.knots[i] +
                      (curve.knots[i + 1] - curve.knots[i]) * k / 10.0);
    }
  }
  const BSplineCurveData refined = Inserted(curve, extra);
  ASSERT_EQ(refined.knots.size(), 977u);
  absl::StatusOr<CurveKnotRemoval> simplified =
      SimplifyCurveKnots(refined.view(), 1e-9);
  ASSERT_TRUE(simplified.ok()) << simplified.status();
  // Every inserted knot goes, none of W1's own (random points: each carries
  // a jump of the third derivative far above 1e-9).
  EXPECT_EQ(simplified->removals, 873);
  EXPECT_EQ(simplified->curve.knots, curve.knots);
  EXPECT_LT(
      MaxPointDistance(simplified->curve.coordinates, curve.coordinates, 1),
      1e-12);
  EXPECT_LT(simplified->error_bound, 1e-12);
  EXPECT_LT(CurveDistance(refined.view(), simplified->curve.view()), 1e-12);
}

// ---------------------------------------------------------------------------
// Knots that carry shape stay.

TEST(KnotRemoval, CuspKnotStays) {
  // A cubic with a triple knot at 1/2 and a right-angle corner at (3, 0).
  const BSplineCurveData corner{
      .degree = 3,
      .dimension = 2,
      .coordinates = {0, 0, 1, 0, 2, 0, 3, 0, 3, 1, 3, 2, 3, 3},
      .knots = {0, 0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1, 1}};
  absl::StatusOr<CurveKnotRemoval> removed =
      RemoveCurveKnot(corner.view(), 0.5, 3, 1e-3);
  ASSERT_TRUE(removed.ok()) << removed.status();
  EXPECT_EQ(removed->removals, 0);
  EXPECT_EQ(removed->curve.knots, corner.knots);
  EXPECT_EQ(removed->curve.coordinates, corner.coordinates);
  absl::StatusOr<CurveKnotRemoval> simplified =
      SimplifyCurveKnots(corner.view(), 1e-3);
  ASSERT_TRUE(simplified.ok()) << simplified.status();
  EXPECT_EQ(simplified->removals, 0);
}

// A degree-0 B-spline is a step function: its interior knot u_r separates
// the constant pieces P_{r-1} and P_r, and removing it joins them into one
// piece. Within tolerance only when they agree: the joined value is their
// midpoint, |P_r - P_{r-1}| / 2 from each, which is also the true distance.
BSplineCurveData StepCurve() {
  return {.degree = 0,
          .dimension = 1,
          .coordinates = {1, 1, 2},
          .knots = {0, 1, 2, 3}};
}

TEST(KnotRemoval, DegreeZeroEqualStepsJoin) {
  const BSplineCurveData step = StepCurve();
  absl::StatusOr<CurveKnotRemoval> simplified =
      SimplifyCurveKnots(step.view(), 1e-9);
  ASSERT_TRUE(simplified.ok()) << simplified.status();
  EXPECT_EQ(simplified->removals, 1);
  EXPECT_THAT(simplified->curve.knots, ElementsAreArray({0, 2, 3}));
  EXPECT_THAT(simplified->curve.coordinates, ElementsAreArray({1, 2}));
  EXPECT_EQ(simplified->error_bound, 0.0);
  EXPECT_EQ(CurveDistance(step.view(), simplified->curve.view()), 0.0);
  absl::StatusOr<CurveKnotRemoval> removed =
      RemoveCurveKnot(step.view(), 1.0, 1, 1e-9);
  ASSERT_TRUE(removed.ok()) << removed.status();
  EXPECT_EQ(removed->removals, 1);
  EXPECT_THAT(removed->curve.coordinates, ElementsAreArray({1, 2}));
}

TEST(KnotRemoval, DegreeZeroStepJoinsAtItsMidpointWithinHalfItsJump) {
  const BSplineCurveData step = StepCurve();
  absl::StatusOr<CurveKnotRemoval> kept =
      RemoveCurveKnot(step.view(), 2.0, 1, 0.49);
  ASSERT_TRUE(kept.ok()) << kept.status();
  EXPECT_EQ(kept->removals, 0);
  EXPECT_EQ(kept->curve.coordinates, step.coordinates);
  absl::StatusOr<CurveKnotRemoval> joined =
      RemoveCurveKnot(step.view(), 2.0, 1, 0.5);
  ASSERT_TRUE(joined.ok()) << joined.status();
  EXPECT_EQ(joined->removals, 1);
  EXPECT_THAT(joined->curve.knots, ElementsAreArray({0, 1, 3}));
  EXPECT_THAT(joined->curve.coordinates, ElementsAreArray({1.0, 1.5}));
  EXPECT_EQ(joined->error_bound, 0.5);
  EXPECT_EQ(CurveDistance(step.view(), joined->curve.view()), 0.5);
}

TEST(KnotRemoval, DegreeZeroSimplifyKeepsOnePieceForEachRunOfEqualValues) {
  // Runs of equal 2D values on random knots, rational too (a weight per
  // run: the certificate bounds the homogeneous points, so pieces of equal
  // values but other weights, though the same curve, are not certified
  // equal): simplifying
  // within 1e-9 leaves one piece per run, with the run's value, and the
  // same step function.
  std::mt19937_64 rng(7);
  for (const bool rational : {false, true}) {
    SCOPED_TRACE(rational ? "rational" : "polynomial");
    BSplineCurveData curve{.degree = 0, .dimension = 2};
    std::vector<double> expected;
    std::uniform_int_distribution<int> run_length(1, 4);
    for (int run = 0; run < 12; ++run) {
      const std::vector<double> value = RandomValues(rng, 2);
      const double weight = RandomValues(rng, 1, 0.5, 2.0)[0];
      expected.insert(expected.end(), value.begin(), value.end());
      for (int k = run_length(rng); k > 0; --k) {
        curve.coordinates.insert(curve.coordinates.end(), value.begin(),
                                 value.end());
        if (rational) curve.weights.push_back(weight);
      }
    }
    const int count = static_cast<int>(curve.coordinates.size() / 2);
    curve.knots = RandomKnots(rng, 0, count - 1, true);
    ASSERT_TRUE(ValidateBSplineCurve(curve.view()).ok());
    absl::StatusOr<CurveKnotRemoval> simplified =
        SimplifyCurveKnots(curve.view(), 1e-9);
    ASSERT_TRUE(simplified.ok()) << simplified.status();
    EXPECT_EQ(simplified->removals, count - 12);
    EXPECT_LT(MaxPointDistance(simplified->curve.coordinates, expected, 1),
              1e-15);
    EXPECT_LT(simplified->error_bound, 1e-15);
    EXPECT_LT(CurveDistance(curve.view(), simplified->curve.view()), 1e-15);
  }
}

TEST(KnotRemoval, InterpolatingSplineJointsStay) {
  // A cubic through 8 points on a circle of radius 1: every interior knot
  // is a C2 joint with a jump of the third derivative of order 1.
  std::vector<double> points;
  for (int k = 0; k < 8; ++k) {
    points.push_back(std::cos(0.7 * k));
    points.push_back(std::sin(0.7 * k));
  }
  absl::StatusOr<CurveInterpolation> interpolated =
      InterpolateCurve({.dimension = 2, .coordinates = points}, {});
  ASSERT_TRUE(interpolated.ok()) << interpolated.status();
  const BSplineCurveView curve = interpolated->curve.view();
  ASSERT_EQ(curve.knots.size(), 12u);  // 4 interior knots
  absl::StatusOr<CurveKnotRemoval> simplified = SimplifyCurveKnots(curve, 1e-6);
  ASSERT_TRUE(simplified.ok()) << simplified.status();
  EXPECT_EQ(simplified->removals, 0);
  EXPECT_EQ(simplified->curve.knots, interpolated->curve.knots);
  // Each joint alone, too.
  for (size_t i = 4; i < 8; ++i) {
    absl::StatusOr<CurveKnotRemoval> removed =
        RemoveCurveKnot(curve, curve.knots[i], 1, 1e-6);
    ASSERT_TRUE(removed.ok()) << removed.status();
    EXPECT_EQ(removed->removals, 0);
  }
}

// ---------------------------------------------------------------------------
// Surfaces.

// A random B-spline surface of degrees (p, q) on clamped random knots, with
// count_u x count_v points in 3D; weights in [0.5, 2] when rational.
SurfaceData RandomSurface(std::mt19937_64& rng, int p, int q, int count_u,
                          int count_v, bool rational) {
  SurfaceData surface{.degree_u = p,
                      .degree_v = q,
                      .dimension = 3,
                      .count_u = count_u,
                      .count_v = count_v};
  surface.coordinates =
      RandomValues(rng, static_cast<size_t>(count_u) * count_v * 3);
  surface.knots_u = RandomKnots(rng, p, count_u - 1, true);
  surface.knots_v = RandomKnots(rng, q, count_v - 1, true);
  if (rational) {
    surface.weights =
        RandomValues(rng, static_cast<size_t>(count_u) * count_v, 0.5, 2.0);
  }
  EXPECT_TRUE(ValidateBSplineSurface(surface.bspline_view()).ok());
  return surface;
}

SurfaceData InsertedSurface(const SurfaceData& surface, bool in_u,
                            const std::vector<double>& knots) {
  absl::StatusOr<SurfaceData> refined =
      InsertSurfaceKnots(surface.bspline_view(), in_u, knots);
  EXPECT_TRUE(refined.ok()) << refined.status();
  return *refined;
}

void ExpectSameSurface(const SurfaceData& actual, const SurfaceData& expected) {
  EXPECT_EQ(actual.count_u, expected.count_u);
  EXPECT_EQ(actual.count_v, expected.count_v);
  EXPECT_EQ(actual.knots_u, expected.knots_u);
  EXPECT_EQ(actual.knots_v, expected.knots_v);
  EXPECT_LT(MaxPointDistance(actual.coordinates, expected.coordinates, 1),
            1e-12);
  EXPECT_LT(MaxPointDistance(actual.weights, expected.weights, 1), 1e-12);
}

TEST(SurfaceKnotRemoval, InsertedKnotsAreRemovedExactlyInEitherDirection) {
  std::mt19937_64 rng(41);
  for (const bool rational : {false, true}) {
    for (const bool in_u : {true, false}) {
      const SurfaceData surface = RandomSurface(rng, 3, 2, 7, 6, rational);
      const std::vector<double>& knots =
          in_u ? surface.knots_u : surface.knots_v;
      const int degree = in_u ? 3 : 2;
      for (const int times : {1, degree}) {
        const double u = SpanMidpoint(knots, degree, 1);
        const SurfaceData refined = InsertedSurface(
            surface, in_u, std::vector<double>(static_cast<size_t>(times), u));
        absl::StatusOr<SurfaceKnotRemoval> removed =
            RemoveSurfaceKnot(refined.bspline_view(), in_u, u, times, 1e-9);
        ASSERT_TRUE(removed.ok()) << removed.status();
        EXPECT_EQ(in_u ? removed->removals_u : removed->removals_v, times);
        EXPECT_EQ(in_u ? removed->removals_v : removed->removals_u, 0);
        ExpectSameSurface(removed->surface, surface);
        EXPECT_LT(removed->error_bound, 1e-12);
      }
    }
  }
}

TEST(SurfaceKnotRemoval, DegreeZeroEqualStepsJoinInEitherDirection) {
  // Degree 0 in u, 1 in v: three columns of u-steps, the first two equal.
  SurfaceData surface{.degree_u = 0,
                      .degree_v = 1,
                      .dimension = 1,
                      .count_u = 3,
                      .count_v = 2,
                      .coordinates = {1, 5, 1, 5, 2, 7},
                      .knots_u = {0, 1, 2, 3},
                      .knots_v = {0, 0, 1, 1}};
  for (const KnotDirections directions :
       {KnotDirections::kU, KnotDirections::kBoth}) {
    absl::StatusOr<SurfaceKnotRemoval> simplified =
        SimplifySurfaceKnots(surface.bspline_view(), directions, 1e-9);
    ASSERT_TRUE(simplified.ok()) << simplified.status();
    EXPECT_EQ(simplified->removals_u, 1);
    EXPECT_EQ(simplified->removals_v, 0);
    EXPECT_THAT(simplified->surface.knots_u, ElementsAreArray({0, 2, 3}));
    EXPECT_THAT(simplified->surface.coordinates,
                ElementsAreArray({1, 5, 2, 7}));
  }
  absl::StatusOr<SurfaceKnotRemoval> removed =
      RemoveSurfaceKnot(surface.bspline_view(), true, 2.0, 1, 1e-9);
  ASSERT_TRUE(removed.ok()) << removed.status();
  EXPECT_EQ(removed->removals_u, 0);
  // Transposed: degree 0 in v.
  SurfaceData transposed{.degree_u = 1,
                         .degree_v = 0,
                         .dimension = 1,
                         .count_u = 2,
                         .count_v = 3,
                         .coordinates = {1, 1, 2, 5, 5, 7},
                         .knots_u = {0, 0, 1, 1},
                         .knots_v = {0, 1, 2, 3}};
  absl::StatusOr<SurfaceKnotRemoval> in_v =
      RemoveSurfaceKnot(transposed.bspline_view(), false, 1.0, 1, 1e-9);
  ASSERT_TRUE(in_v.ok()) << in_v.status();
  EXPECT_EQ(in_v->removals_v, 1);
  EXPECT_THAT(in_v->surface.coordinates, ElementsAreArray({1, 2, 5, 7}));
}

TEST(SurfaceKnotRemoval, SimplifyBothDirectionsGivesBackTheOriginal) {
  std::mt19937_64 rng(43);
  for (const bool rational : {false, true}) {
    const SurfaceData surface = RandomSurface(rng, 3, 3, 8, 7, rational);
    const SurfaceData in_u =
        InsertedSurface(surface, true,
                        {SpanMidpoint(surface.knots_u, 3, 0),
                         SpanMidpoint(surface.knots_u, 3, 2),
                         SpanMidpoint(surface.knots_u, 3, 3)});
    const SurfaceData refined =
        InsertedSurface(in_u, false,
                        {SpanMidpoint(surface.knots_v, 3, 1),
                         SpanMidpoint(surface.knots_v, 3, 1)});
    absl::StatusOr<SurfaceKnotRemoval> simplified = SimplifySurfaceKnots(
        refined.bspline_view(), KnotDirections::kBoth, 1e-9);
    ASSERT_TRUE(simplified.ok()) << simplified.status();
    EXPECT_EQ(simplified->removals_u, 3);
    EXPECT_EQ(simplified->removals_v, 2);
    ExpectSameSurface(simplified->surface, surface);
    EXPECT_LT(simplified->error_bound, 1e-12);
    // One direction only leaves the other alone.
    absl::StatusOr<SurfaceKnotRemoval> only_v =
        SimplifySurfaceKnots(refined.bspline_view(), KnotDirections::kV, 1e-9);
    ASSERT_TRUE(only_v.ok()) << only_v.status();
    EXPECT_EQ(only_v->removals_u, 0);
    EXPECT_EQ(only_v->removals_v, 2);
    ExpectSameSurface(only_v->surface, in_u);
  }
}

TEST(SurfaceKnotRemoval, KnotGoesOnlyIfItGoesFromEveryLine) {
  std::mt19937_64 rng(47);
  const SurfaceData surface = RandomSurface(rng, 2, 2, 6, 5, false);
  const double u = SpanMidpoint(surface.knots_u, 2, 1);
  SurfaceData refined = InsertedSurface(surface, true, {u});
  // Move one point of one column (the curve in u at v index 3) by 1e-3.
  const int count_v = refined.count_v;
  refined.coordinates[(3 * static_cast<size_t>(count_v) + 3) * 3 + 2] += 1e-3;
  absl::StatusOr<SurfaceKnotRemoval> removed =
      RemoveSurfaceKnot(refined.bspline_view(), true, u, 1, 1e-6);
  ASSERT_TRUE(removed.ok()) << removed.status();
  EXPECT_EQ(removed->removals_u, 0);
  EXPECT_EQ(removed->surface.coordinates, refined.coordinates);
  // With a tolerance above the change it goes, within its bound.
  absl::StatusOr<SurfaceKnotRemoval> loose =
      RemoveSurfaceKnot(refined.bspline_view(), true, u, 1, 1e-2);
  ASSERT_TRUE(loose.ok()) << loose.status();
  EXPECT_EQ(loose->removals_u, 1);
  const double sampled =
      SurfaceDistance(refined.bspline_view(), loose->surface.bspline_view());
  EXPECT_GT(sampled, 1e-5);
  EXPECT_LE(sampled, loose->error_bound);
  EXPECT_LE(loose->error_bound, 1e-2);
}

TEST(SurfaceKnotRemoval, SimplifyNoisySurfaceWithinTheBound) {
  // Both directions refined and disturbed by 1e-6, simplified at 1e-4: the
  // v pass is certified against the original after the u pass changed it.
  std::mt19937_64 rng(53);
  for (const bool rational : {false, true}) {
    const SurfaceData surface = RandomSurface(rng, 3, 2, 6, 5, rational);
    std::vector<double> extra_u;
    std::vector<double> extra_v;
    for (int k = 1; k < 10; ++k) {
      extra_u.push_back(k / 10.0 + 0.013);
      extra_v.push_back(k / 10.0 - 0.017);
    }
    SurfaceData noisy = InsertedSurface(InsertedSurface(surface, true, extra_u),
                                        false, extra_v);
    for (double& x : noisy.coordinates) x += 1e-6 * RandomValues(rng, 1)[0];
    const double tolerance = 1e-4;
    absl::StatusOr<SurfaceKnotRemoval> simplified = SimplifySurfaceKnots(
        noisy.bspline_view(), KnotDirections::kBoth, tolerance);
    ASSERT_TRUE(simplified.ok()) << simplified.status();
    EXPECT_GE(simplified->removals_u, 5);
    EXPECT_GE(simplified->removals_v, 5);
    EXPECT_LE(simplified->error_bound, tolerance);
    const double sampled = SurfaceDistance(noisy.bspline_view(),
                                           simplified->surface.bspline_view());
    EXPECT_LE(sampled, simplified->error_bound);
  }
}

// ---------------------------------------------------------------------------
// Errors.

TEST(KnotRemovalErrors, TolerancesTimesAndKnots) {
  const BSplineCurveData curve = WorkedExample();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const double tolerance : {0.0, -1.0, nan, inf}) {
    ExpectFieldError(RemoveCurveKnot(curve.view(), 1.0, 1, tolerance).status(),
                     "tolerance");
    ExpectFieldError(SimplifyCurveKnots(curve.view(), tolerance).status(),
                     "tolerance");
  }
  ExpectFieldError(RemoveCurveKnot(curve.view(), 1.0, 0, 1.0).status(),
                   "times");
  // Not a knot, a domain end, outside, not finite.
  for (const double knot : {0.5, 0.0, 2.0, 3.0, nan, inf}) {
    const absl::Status status =
        RemoveCurveKnot(curve.view(), knot, 1, 1.0).status();
    ExpectFieldError(status, "knot");
    EXPECT_THAT(std::string(status.message()),
                ::testing::HasSubstr("is not there"));
  }
}

TEST(KnotRemovalErrors, InvalidGeometryAndWeights) {
  BSplineCurveData decreasing = WorkedExample();
  decreasing.knots[4] = 0.5;
  ExpectFieldError(RemoveCurveKnot(decreasing.view(), 1.0, 1, 1.0).status(),
                   "knots[4]");
  ExpectFieldError(SimplifyCurveKnots(decreasing.view(), 1.0).status(),
                   "knots[4]");
  BSplineCurveData zero_weight = WorkedExample();
  zero_weight.weights = {1, 0, 1, 1};
  ExpectFieldError(RemoveCurveKnot(zero_weight.view(), 1.0, 1, 1.0).status(),
                   "weights[1]");
  BSplineCurveData negative = WorkedExample();
  negative.weights = {1, 1, 1, -1};
  ExpectFieldError(SimplifyCurveKnots(negative.view(), 1.0).status(),
                   "weights[3]");

  std::mt19937_64 rng(59);
  SurfaceData surface = RandomSurface(rng, 2, 2, 4, 4, true);
  const double v = surface.knots_v[3];
  ExpectFieldError(
      RemoveSurfaceKnot(surface.bspline_view(), true, v, 1, 1.0).status(),
      "knot");
  ExpectFieldError(
      RemoveSurfaceKnot(surface.bspline_view(), false, v, 0, 1.0).status(),
      "times");
  ExpectFieldError(
      SimplifySurfaceKnots(surface.bspline_view(), KnotDirections::kBoth, -1.0)
          .status(),
      "tolerance");
  surface.weights[5] = 0.0;
  ExpectFieldError(
      SimplifySurfaceKnots(surface.bspline_view(), KnotDirections::kU, 1.0)
          .status(),
      "weights[5]");
  surface.coordinates.pop_back();
  ExpectFieldError(
      SimplifySurfaceKnots(surface.bspline_view(), KnotDirections::kU, 1.0)
          .status(),
      "control_net.coordinates");
}

TEST(KnotRemovalErrors, CancelledTokenStops) {
  const bench::SplineData w1 = bench::RandomSpline(1, 100, 3);
  const BSplineCurveData original{.degree = w1.degree,
                                  .dimension = w1.dimension,
                                  .coordinates = w1.points,
                                  .knots = w1.knots};
  std::vector<double> extra;
  for (int k = 1; k < 1000; ++k) extra.push_back(k / 1000.0 + 1e-4);
  const BSplineCurveData curve = Inserted(original, extra);
  CancellationToken token;
  token.Cancel();
  EXPECT_EQ(SimplifyCurveKnots(curve.view(), 1e-9, &token).status().code(),
            absl::StatusCode::kCancelled);
}

}  // namespace
}  // namespace freeform
