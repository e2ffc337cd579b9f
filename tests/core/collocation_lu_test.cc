// The streaming collocation solver of global interpolation
// (core/src/construct/collocation_lu.h, open_interpolation.cc) against the
// general banded LU it replaces (banded_lu.h): the same solution bit for bit on
// random totally positive collocation systems with and without derivative
// rows, the same largest residual as EvaluateBSplineCurve measures, and the
// W5 interpolation of 10^5 points through its points.
#include "construct/collocation_lu.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "construct/interpolation_knots.h"
#include "construct/interpolation_result.h"
#include "construct/open_interpolation.h"
#include "freeform/core/bspline.h"
#include "freeform/core/interpolation.h"
#include "kinds/bspline_spans.h"
#include "linalg/banded_lu.h"

namespace freeform::internal {
namespace {

// Sorted random parameters in [0, 1] with both ends, strictly increasing.
std::vector<double> RandomParameters(std::mt19937_64& rng, int count) {
  std::uniform_real_distribution<double> gap(0.05, 1.0);
  std::vector<double> t(static_cast<size_t>(count), 0.0);
  for (size_t k = 1; k < t.size(); ++k) t[k] = t[k - 1] + gap(rng);
  const double total = t.back();
  for (double& value : t) value /= total;
  t.back() = 1.0;
  return t;
}

std::vector<double> RandomValues(std::mt19937_64& rng, size_t count) {
  std::uniform_real_distribution<double> value(-10.0, 10.0);
  std::vector<double> values(count);
  for (double& v : values) v = value(rng);
  return values;
}

// The solution of the open system by the general path: BuildOpenRows,
// FactorOpenSystem and BandedLu::Solve; empty when singular.
Matrix GeneralSolution(const PointsView& points, int p,
                       const std::vector<double>& knots,
                       const std::vector<double>& t, EndCondition start,
                       EndCondition end) {
  absl::StatusOr<BandedLu> lu = FactorOpenSystem(
      p, BuildOpenRows(p, knots, t, start, end, nullptr), nullptr);
  if (!lu.ok()) return {};
  Matrix rhs;
  const size_t d = static_cast<size_t>(points.dimension);
  for (size_t k = 0; k < points.size(); ++k) {
    if (k + 1 == points.size() && end.order > 0) {
      rhs.insert(rhs.end(), end.value.begin(), end.value.end());
    }
    rhs.insert(rhs.end(), points.point(k), points.point(k) + d);
    if (k == 0 && start.order > 0) {
      rhs.insert(rhs.end(), start.value.begin(), start.value.end());
    }
  }
  EXPECT_TRUE(lu->Solve(rhs.data(), points.dimension).ok());
  return rhs;
}

TEST(CollocationLu, MatchesBandedLuBitForBit) {
  std::mt19937_64 rng(14);
  for (int p = 1; p <= 7; ++p) {
    for (int dimension = 1; dimension <= 4; ++dimension) {
      for (int ends = 0; ends < 4; ++ends) {
        if (ends != 0 && p < 2) continue;
        const bool has_start = (ends & 1) != 0, has_end = (ends & 2) != 0;
        const int count = p + 1 + static_cast<int>(rng() % 60);
        const std::vector<double> t = RandomParameters(rng, count);
        std::vector<double> sites;
        if (has_start) sites.push_back(t.front());
        sites.insert(sites.end(), t.begin(), t.end());
        if (has_end) sites.push_back(t.back());
        const std::vector<double> knots =
            KnotsFor(sites, p, Parameterization::kChordLength,
                     rng() % 2 == 0 ? KnotRule::kAveraging : KnotRule::kUniform,
                     nullptr)
                .value();
        const std::vector<double> coordinates =
            RandomValues(rng, static_cast<size_t>(count * dimension));
        const std::vector<double> start_value =
            RandomValues(rng, static_cast<size_t>(dimension));
        const std::vector<double> end_value =
            RandomValues(rng, static_cast<size_t>(dimension));
        const PointsView points{.dimension = dimension,
                                .coordinates = coordinates};
        const EndCondition start{.order = has_start ? 1 : 0,
                                 .value = start_value};
        const EndCondition end{.order = has_end ? 1 : 0, .value = end_value};
        const std::string label = "p=" + std::to_string(p) +
                                  " d=" + std::to_string(dimension) +
                                  " ends=" + std::to_string(ends);
        const Matrix expected =
            GeneralSolution(points, p, knots, t, start, end);
        absl::StatusOr<Matrix> general =
            SolveOpen(points, p, knots, t, start, end, nullptr);
        // The uniform knot rule may break Schoenberg-Whitney; then both fail.
        if (expected.empty()) {
          EXPECT_FALSE(general.ok()) << label;
          continue;
        }
        ASSERT_TRUE(general.ok()) << label << " " << general.status();
        ASSERT_EQ(general->size(), expected.size()) << label;
        for (size_t i = 0; i < expected.size(); ++i) {
          ASSERT_EQ((*general)[i], expected[i]) << label << " at " << i;
        }
        absl::StatusOr<OpenSolution> measured =
            SolveOpenMeasured(points, p, knots, t, start, end, true, nullptr);
        ASSERT_TRUE(measured.ok()) << label;
        EXPECT_EQ(measured->control, *general) << label;
        absl::StatusOr<std::pair<double, double>> residuals =
            CurveResiduals(MakeCurve(p, dimension, measured->control, knots), t,
                           points, nullptr);
        ASSERT_TRUE(residuals.ok()) << label;
        EXPECT_EQ(measured->max_residual, residuals->first) << label;
      }
    }
  }
}

TEST(CollocationLu, SolvesRandomTotallyPositiveBandSystems) {
  // Collocation matrices of random knots at parameters that satisfy the
  // Schoenberg-Whitney condition, straight through the class.
  std::mt19937_64 rng(15);
  for (int p = 1; p <= 8; ++p) {
    const int count = 3 * p + 20;
    const std::vector<double> t = RandomParameters(rng, count);
    const std::vector<double> knots =
        KnotsFor(t, p, Parameterization::kChordLength, KnotRule::kAveraging,
                 nullptr)
            .value();
    absl::StatusOr<OpenRows> rows = BuildOpenRows(p, knots, t, {}, {}, nullptr);
    ASSERT_TRUE(rows.ok());
    const std::vector<double> x = RandomValues(rng, 2 * count);
    // b = A x.
    std::vector<double> b(x.size(), 0.0);
    const size_t w = static_cast<size_t>(p) + 1;
    for (size_t r = 0; r < static_cast<size_t>(count); ++r) {
      for (size_t j = 0; j < w; ++j) {
        const size_t column = static_cast<size_t>(rows->first[r]) + j;
        for (size_t c = 0; c < 2; ++c) {
          b[2 * r + c] += rows->values[r * w + j] * x[2 * column + c];
        }
      }
    }
    auto solve = [&]<int kDegree, int kDimension>() {
      std::vector<double> solution = b;
      CollocationLu<kDegree, kDimension> lu(count, p, 2, solution.data());
      for (size_t r = 0; r < static_cast<size_t>(count); ++r) {
        EXPECT_TRUE(lu.AddRow(rows->first[r], rows->values.data() + r * w));
      }
      lu.BackSubstitute();
      return solution;
    };
    const std::vector<double> any = solve.template operator()<kAnyDegree, 0>();
    for (size_t i = 0; i < x.size(); ++i) {
      EXPECT_NEAR(any[i], x[i], 1e-10) << "p=" << p << " at " << i;
    }
    if (p == 3) {
      EXPECT_EQ((solve.template operator()<3, 2>()), any);
    }
  }
}

TEST(CollocationLu, ReportsASingularRow) {
  // Row 1 is a copy of row 0: its pivot vanishes.
  std::vector<double> rhs(3, 1.0);
  CollocationLu<kAnyDegree, 0> lu(3, 1, 1, rhs.data());
  const double row[] = {1.0, 0.5};
  EXPECT_TRUE(lu.AddRow(0, row));
  EXPECT_FALSE(lu.AddRow(0, row));
  // A row whose band misses the diagonal.
  CollocationLu<1, 1> shifted(3, 1, 1, rhs.data());
  EXPECT_FALSE(shifted.AddRow(1, row));
}

// W5 of the benchmarks (bench/construction_bench.cc): 10^5 points on a
// noisy helix, LCG seed 4.
std::vector<double> W5Points(size_t count) {
  uint64_t state = 4;
  auto next = [&state] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return 2.0 * (static_cast<double>(state >> 11) * 0x1.0p-53) - 1.0;
  };
  std::vector<double> points;
  for (size_t i = 0; i < count; ++i) {
    const double t = 0.01 * static_cast<double>(i);
    const double r1 = next(), r2 = next(), r3 = next();
    points.push_back(10 * std::cos(t) + 0.1 * r1);
    points.push_back(10 * std::sin(t) + 0.1 * r2);
    points.push_back(t + 0.1 * r3);
  }
  return points;
}

TEST(CollocationLu, W5PassesThroughTheHundredThousandPoints) {
  const std::vector<double> points = W5Points(100'000);
  CurveInterpolationOptions options;
  options.degree = 3;
  const absl::StatusOr<CurveInterpolation> result =
      InterpolateCurve({3, points}, options);
  ASSERT_TRUE(result.ok()) << result.status();
  double largest = 0;
  for (double value : points) largest = std::max(largest, std::abs(value));
  EXPECT_LT(result->max_residual, 1e-12 * largest);
  // The reported residual is EvaluateBSplineCurve's, exactly.
  std::vector<double> values(points.size());
  const std::vector<absl::Span<double>> output = {absl::MakeSpan(values)};
  ASSERT_TRUE(
      EvaluateBSplineCurve(result->curve.view(), result->parameters, output)
          .ok());
  double max = 0;
  for (size_t k = 0; k < points.size() / 3; ++k) {
    max = std::max(max, PointDistance(&values[3 * k], &points[3 * k], 3));
  }
  EXPECT_EQ(result->max_residual, max);
  EXPECT_LT(max, 1e-12 * largest);
}

}  // namespace
}  // namespace freeform::internal
