// The kernels across parameters and grid columns (core/src/kinds/simd/) against
// the scalar reference evaluators, bit for bit, on every instruction set
// Highway compiled them for and this CPU runs (forced one at a time).
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "freeform/core/bezier.h"
#include "freeform/core/bspline.h"
#include "freeform/core/points.h"
#include "freeform/core/status.h"
#include "freeform/core/surface_output.h"
#include "freeform/core/tensor_surface.h"
#include "hwy/targets.h"
#include "kinds/scalar_reference.h"
#include "kinds/simd/curve_simd.h"
#include "test_util.h"

namespace freeform {
namespace {

using ::freeform::testing_util::EvenlySpaced;
using ::freeform::testing_util::LongDoubleDeCasteljau;
using ::freeform::testing_util::RandomKnots;
using ::freeform::testing_util::RandomValues;

// Output buffers for `orders` derivative orders and the spans over them.
struct Output {
  Output(int orders, size_t count, int dimension)
      : buffers(static_cast<size_t>(orders),
                std::vector<double>(count * static_cast<size_t>(dimension))),
        spans(buffers.begin(), buffers.end()) {}
  std::vector<std::vector<double>> buffers;
  std::vector<absl::Span<double>> spans;
};

// Makes the kernels dispatch to one target while in scope.
class ForcedTarget {
 public:
  explicit ForcedTarget(int64_t target) {
    hwy::SetSupportedTargetsForTest(target);
  }
  ~ForcedTarget() { hwy::SetSupportedTargetsForTest(0); }
  ForcedTarget(const ForcedTarget&) = delete;
  ForcedTarget& operator=(const ForcedTarget&) = delete;
};

// Every target compiled into the kernels that this CPU runs.
std::vector<int64_t> Targets() { return hwy::SupportedAndGeneratedTargets(); }

// Runs `check` once per target, with the kernels forced onto it.
template <typename Check>
void OnEveryTarget(Check check) {
  for (const int64_t target : Targets()) {
    SCOPED_TRACE(hwy::TargetName(target));
    const ForcedTarget forced(target);
    ASSERT_EQ(simd::DispatchedTarget(), target);
    check();
  }
}

// Expects the same bits in `actual` and `expected`, naming the first
// difference.
void ExpectSameBits(const std::vector<std::vector<double>>& actual,
                    const std::vector<std::vector<double>>& expected,
                    const std::string& what) {
  ASSERT_EQ(actual.size(), expected.size()) << what;
  for (size_t k = 0; k < actual.size(); ++k) {
    ASSERT_EQ(actual[k].size(), expected[k].size()) << what;
    for (size_t i = 0; i < actual[k].size(); ++i) {
      ASSERT_EQ(std::bit_cast<uint64_t>(actual[k][i]),
                std::bit_cast<uint64_t>(expected[k][i]))
          << what << ": order " << k << ", value " << i << ": " << actual[k][i]
          << " vs scalar " << expected[k][i];
    }
  }
}

// `count` parameters in [start, end]: every knot inside the domain and both
// ends first, then sorted evenly spaced values, then random unsorted ones.
std::vector<double> MixedParameters(std::mt19937_64& rng, double start,
                                    double end,
                                    const std::vector<double>& knots,
                                    size_t count) {
  std::vector<double> parameters = {start, end};
  for (const double knot : knots) {
    if (start <= knot && knot <= end) parameters.push_back(knot);
  }
  const size_t sorted = count / 2;
  if (sorted >= 2) {
    for (const double u : EvenlySpaced(start, end, sorted)) {
      parameters.push_back(u);
    }
  }
  for (const double u : RandomValues(rng, count, start, end)) {
    parameters.push_back(u);
  }
  parameters.resize(count);
  return parameters;
}

// A random non-rational B-spline curve; `points` and `knots` own its data.
struct RandomBSpline {
  RandomBSpline(std::mt19937_64& rng, int p, int dimension) {
    const int n = p + std::uniform_int_distribution<int>(0, 12)(rng);
    knots = RandomKnots(rng, p, n, rng() % 2 == 0);
    points = RandomValues(rng, static_cast<size_t>((n + 1) * dimension));
    view = {.degree = p,
            .control_points = {.dimension = dimension, .coordinates = points},
            .knots = knots};
  }
  std::vector<double> points;
  std::vector<double> knots;
  BSplineCurveView view;
};

// `lanes` (a public evaluator, which uses the kernels) and `scalar` (its
// scalar reference) give the same bits for `orders` derivative orders of a
// curve of `dimension` at `parameters`. Both are called as
// f(parameters, output spans) and return a status.
template <typename Lanes, typename Scalar>
void ExpectSameAsScalar(int dimension, const std::vector<double>& parameters,
                        int orders, Lanes lanes, Scalar scalar,
                        const std::string& what) {
  Output simd_out(orders, parameters.size(), dimension);
  Output scalar_out(orders, parameters.size(), dimension);
  ASSERT_TRUE(lanes(parameters, simd_out.spans).ok()) << what;
  ASSERT_TRUE(scalar(parameters, scalar_out.spans).ok()) << what;
  ExpectSameBits(simd_out.buffers, scalar_out.buffers, what);
}

void ExpectBSplineMatchesScalar(const BSplineCurveView& curve,
                                const std::vector<double>& parameters,
                                int orders, const std::string& what) {
  ExpectSameAsScalar(
      curve.control_points.dimension, parameters, orders,
      [&](const std::vector<double>& u, CurveOutput output) {
        return EvaluateBSplineCurve(curve, u, output);
      },
      [&](const std::vector<double>& u, CurveOutput output) {
        return internal::EvaluateBSplineCurveScalar(curve, u, output);
      },
      what);
}

// For the kernels' two schemes: the ladder (kAuto) and Horner.
void ExpectBezierMatchesScalar(const BezierCurveView& curve,
                               const std::vector<double>& parameters,
                               int orders, const std::string& what) {
  for (const BezierAlgorithm algorithm :
       {BezierAlgorithm::kAuto, BezierAlgorithm::kHorner}) {
    ExpectSameAsScalar(
        curve.control_points.dimension, parameters, orders,
        [&](const std::vector<double>& t, CurveOutput output) {
          return EvaluateBezierCurve(curve, t, output, {}, algorithm);
        },
        [&](const std::vector<double>& t, CurveOutput output) {
          return internal::EvaluateBezierCurveScalar(curve, t, output,
                                                     algorithm);
        },
        what +
            (algorithm == BezierAlgorithm::kAuto ? " (ladder)" : " (Horner)"));
  }
}

std::string Case(int degree, int dimension, int orders) {
  return "degree " + std::to_string(degree) + ", dimension " +
         std::to_string(dimension) + ", orders " + std::to_string(orders);
}

// The baseline (scalar or SSE) and AVX2 targets are among those tested when
// the CPU has AVX2, and forcing a target really switches the kernels.
TEST(CurveSimdTest, ForcesBaselineAndAvx2Targets) {
  const std::vector<int64_t> targets = Targets();
  ASSERT_FALSE(targets.empty());
  if ((hwy::SupportedTargets() & HWY_AVX2) != 0) {
    EXPECT_NE(std::find(targets.begin(), targets.end(), HWY_AVX2),
              targets.end());
    EXPECT_GE(targets.size(), 2u);
  }
  for (const int64_t target : targets) {
    std::printf("kernels tested on %s\n", hwy::TargetName(target));
  }
  OnEveryTarget([] {});
}

// Degrees 1..20, dimensions 1..16, 1..4 derivative orders (orders above the
// degree included), on random knot vectors with repeated knots, at knots,
// domain ends, sorted and unsorted parameters.
TEST(CurveSimdTest, BSplineMatchesScalarBitForBit) {
  OnEveryTarget([] {
    std::mt19937_64 rng(14);
    for (int p = 1; p <= 20; ++p) {
      for (int dimension = 1; dimension <= 16; ++dimension) {
        const RandomBSpline curve(rng, p, dimension);
        const int orders = 1 + (p + dimension) % 4;
        const std::vector<double> parameters = MixedParameters(
            rng, curve.knots[static_cast<size_t>(p)],
            curve.knots[curve.knots.size() - static_cast<size_t>(p) - 1],
            curve.knots, 61);
        ExpectBSplineMatchesScalar(curve.view, parameters, orders,
                                   Case(p, dimension, orders));
      }
    }
  });
}

// Batches of 1, 3, 7 and 4097 parameters (not multiples of any vector
// length; 4097 spans two chunks), sorted and unsorted.
TEST(CurveSimdTest, BSplineBatchSizesNotMultiplesOfTheLanes) {
  OnEveryTarget([] {
    std::mt19937_64 rng(7);
    for (const int p : {1, 3, 5, 7}) {
      for (const int dimension : {1, 3, 5}) {
        const RandomBSpline curve(rng, p, dimension);
        const double start = curve.knots[static_cast<size_t>(p)];
        const double end =
            curve.knots[curve.knots.size() - static_cast<size_t>(p) - 1];
        for (const size_t count : {1u, 3u, 7u, 4097u}) {
          const std::string what =
              Case(p, dimension, 2) + ", count " + std::to_string(count);
          ExpectBSplineMatchesScalar(curve.view,
                                     count == 1
                                         ? std::vector<double>{end}
                                         : EvenlySpaced(start, end, count),
                                     2, what + " sorted");
          ExpectBSplineMatchesScalar(curve.view,
                                     RandomValues(rng, count, start, end), 2,
                                     what + " unsorted");
        }
      }
    }
  });
}

// Degrees 1..20, dimensions 1..16, 1..4 orders, at 0, 1/2, 1, values around
// 1/2 (where Horner changes form) and random ones; batches of 1, 3, 7, 4097.
TEST(CurveSimdTest, BezierMatchesScalarBitForBit) {
  OnEveryTarget([] {
    std::mt19937_64 rng(4);
    for (int n = 1; n <= 20; ++n) {
      for (int dimension = 1; dimension <= 16; ++dimension) {
        const std::vector<double> points =
            RandomValues(rng, static_cast<size_t>((n + 1) * dimension));
        const BezierCurveView curve{
            .control_points = {.dimension = dimension, .coordinates = points}};
        const int orders = 1 + (n + dimension) % 4;
        std::vector<double> parameters = {
            0.0, 1.0, 0.5, std::nextafter(0.5, 0.0), std::nextafter(0.5, 1.0)};
        for (const double t : RandomValues(rng, 40, 0.0, 1.0)) {
          parameters.push_back(t);
        }
        ExpectBezierMatchesScalar(curve, parameters, orders,
                                  Case(n, dimension, orders));
      }
    }
    const std::vector<double> points = RandomValues(rng, 4 * 3);
    const BezierCurveView cubic{
        .control_points = {.dimension = 3, .coordinates = points}};
    for (const size_t count : {1u, 3u, 7u, 4097u}) {
      ExpectBezierMatchesScalar(cubic, RandomValues(rng, count, 0.0, 1.0), 2,
                                "count " + std::to_string(count));
    }
  });
}

// The range check of every batch (vectorized) names the first value that is
// NaN, infinite or outside the bounds, wherever it stands in a batch of any
// length, and accepts the bounds themselves.
TEST(CurveSimdTest, RangeCheckNamesTheFirstOffender) {
  OnEveryTarget([] {
    const double bad[] = {std::nan(""), HUGE_VAL, -HUGE_VAL, -0.5, 1.5};
    for (size_t count = 1; count <= 19; ++count) {
      std::vector<double> values = EvenlySpaced(0.0, 1.0, count + 1);
      values.pop_back();
      values.back() = 1.0;
      EXPECT_TRUE(ValidateInRange(values, 0.0, 1.0, "t").ok()) << count;
      for (size_t i = 0; i < count; ++i) {
        for (const double value : bad) {
          std::vector<double> with_bad = values;
          with_bad[i] = value;
          if (i + 1 < count) with_bad[count - 1] = value;
          const absl::Status status = ValidateInRange(with_bad, 0.0, 1.0, "t");
          EXPECT_EQ(FieldPathOf(status), "t[" + std::to_string(i) + "]")
              << count << " " << value;
        }
      }
    }
  });
}

// A degree-20 Bezier curve stays within 1e-13 (relative to the largest
// control point coordinate) of the long-double de Casteljau reference.
TEST(CurveSimdTest, DegreeTwentyBezierMatchesLongDoubleDeCasteljau) {
  OnEveryTarget([] {
    std::mt19937_64 rng(20);
    const int n = 20;
    const int dimension = 3;
    const std::vector<double> points =
        RandomValues(rng, static_cast<size_t>((n + 1) * dimension));
    const BezierCurveView curve{
        .control_points = {.dimension = dimension, .coordinates = points}};
    std::vector<double> parameters = EvenlySpaced(0.0, 1.0, 10'001);
    for (const double t : RandomValues(rng, 1000, 0.0, 1.0)) {
      parameters.push_back(t);
    }
    Output out(1, parameters.size(), dimension);
    ASSERT_TRUE(EvaluateBezierCurve(curve, parameters, out.spans).ok());
    double scale = 0;
    for (const double value : points) scale = std::max(scale, std::abs(value));
    double worst = 0;
    for (size_t r = 0; r < parameters.size(); ++r) {
      const std::vector<long double> exact =
          LongDoubleDeCasteljau(points, dimension, parameters[r]);
      for (int j = 0; j < dimension; ++j) {
        const long double error =
            std::fabs(out.buffers[0][r * dimension + j] - exact[j]);
        worst = std::max(worst, static_cast<double>(error) / scale);
      }
    }
    EXPECT_LT(worst, 1e-13);
  });
}

// A random non-rational B-spline surface of degrees p x q; the vectors own
// its data.
struct RandomSurface {
  RandomSurface(std::mt19937_64& rng, int p, int q, int dimension) {
    const int n = p + std::uniform_int_distribution<int>(0, 6)(rng);
    const int m = q + std::uniform_int_distribution<int>(0, 12)(rng);
    knots_u = RandomKnots(rng, p, n, rng() % 2 == 0);
    knots_v = RandomKnots(rng, q, m, rng() % 2 == 0);
    points =
        RandomValues(rng, static_cast<size_t>((n + 1) * (m + 1) * dimension));
    view = {.degree_u = p,
            .degree_v = q,
            .control_net = {.dimension = dimension,
                            .count_u = n + 1,
                            .count_v = m + 1,
                            .coordinates = points},
            .knots_u = knots_u,
            .knots_v = knots_v};
  }
  std::vector<double> points;
  std::vector<double> knots_u;
  std::vector<double> knots_v;
  BSplineSurfaceView view;
};

// The grid kernel and the scalar grid give the same bits for every partial
// with k + l <= max_order.
void ExpectGridMatchesScalar(const BSplineSurfaceView& surface,
                             const std::vector<double>& u,
                             const std::vector<double>& v, int max_order,
                             const std::string& what) {
  const int partials = static_cast<int>(PartialCount(max_order));
  const int dimension = surface.control_net.dimension;
  const size_t count = u.size() * v.size();
  Output simd_out(partials, count, dimension);
  Output scalar_out(partials, count, dimension);
  const SurfaceSamples samples = SurfaceSamples::Grid(u, v);
  ASSERT_TRUE(EvaluateBSplineSurface(surface, samples, simd_out.spans).ok())
      << what;
  ASSERT_TRUE(
      internal::EvaluateBSplineSurfaceScalar(surface, samples, scalar_out.spans)
          .ok())
      << what;
  ExpectSameBits(simd_out.buffers, scalar_out.buffers, what);
}

// u degrees 1..20 against v degrees 1..20 (in a rotating pairing),
// dimensions 1..16, partials up to order 0..3 (orders above the degree
// included), on random knot vectors with repeated knots; the columns hold
// every knot, both ends, sorted runs and unsorted values, 37 of them (no
// multiple of any vector length).
TEST(SurfaceSimdTest, GridMatchesScalarBitForBit) {
  OnEveryTarget([] {
    std::mt19937_64 rng(33);
    for (int p = 1; p <= 20; ++p) {
      for (int dimension = 1; dimension <= 16; ++dimension) {
        const int q = 1 + (p * 7 + dimension) % 20;
        const RandomSurface surface(rng, p, q, dimension);
        const auto domain = BSplineSurfaceDomain(surface.view);
        const std::vector<double> u = MixedParameters(
            rng, domain.u_start, domain.u_end, surface.knots_u, 5);
        const std::vector<double> v = MixedParameters(
            rng, domain.v_start, domain.v_end, surface.knots_v, 37);
        const int max_order = (p + dimension) % 4;
        ExpectGridMatchesScalar(surface.view, u, v, max_order,
                                "degrees " + std::to_string(p) + " x " +
                                    Case(q, dimension, max_order + 1));
      }
    }
  });
}

// Rows of 1, 3, 7 and 4097 sorted columns (long runs on one span, and runs
// that end inside a vector), and unsorted ones (runs of one column).
TEST(SurfaceSimdTest, GridRowsOfEveryLength) {
  OnEveryTarget([] {
    std::mt19937_64 rng(8);
    for (const int q : {1, 3, 6}) {
      for (const int dimension : {1, 3, 5}) {
        const RandomSurface surface(rng, 3, q, dimension);
        const auto domain = BSplineSurfaceDomain(surface.view);
        const std::vector<double> u =
            EvenlySpaced(domain.u_start, domain.u_end, 3);
        for (const size_t count : {1u, 3u, 7u, 4097u}) {
          const std::string what =
              Case(q, dimension, 2) + ", columns " + std::to_string(count);
          ExpectGridMatchesScalar(
              surface.view, u,
              count == 1 ? std::vector<double>{domain.v_end}
                         : EvenlySpaced(domain.v_start, domain.v_end, count),
              1, what + " sorted");
          ExpectGridMatchesScalar(
              surface.view, u,
              RandomValues(rng, count, domain.v_start, domain.v_end), 1,
              what + " unsorted");
        }
      }
    }
  });
}

}  // namespace
}  // namespace freeform
