#include "freeform/core/lagrange.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "freeform/core/cancellation.h"
#include "freeform/core/status.h"
#include "test_util.h"

namespace freeform {
namespace {

using ::freeform::testing_util::MaxAbs;
using ::freeform::testing_util::RandomValues;

using ::testing::DoubleNear;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::Pointwise;

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

std::vector<double> UniformNodes(int n, double a, double b) {
  std::vector<double> nodes(static_cast<size_t>(n + 1));
  for (int i = 0; i <= n; ++i) nodes[i] = a + (b - a) * i / n;
  return nodes;
}

// Chebyshev extreme points on [a, b]: clustered at the ends, where the
// Lebesgue constant stays O(log n).
std::vector<double> ChebyshevNodes(int n, double a, double b) {
  std::vector<double> nodes(static_cast<size_t>(n + 1));
  for (int i = 0; i <= n; ++i) {
    nodes[i] = a + (b - a) * (1 - std::cos(std::numbers::pi * i / n)) / 2;
  }
  return nodes;
}

// Strictly increasing nodes from `start` with random gaps in [0.2, 1].
std::vector<double> RandomNodes(std::mt19937_64& rng, int n, double start) {
  std::uniform_real_distribution<double> gap(0.2, 1.0);
  std::vector<double> nodes = {start};
  for (int i = 1; i <= n; ++i) nodes.push_back(nodes.back() + gap(rng));
  return nodes;
}

enum class NodeKind { kUniform, kChebyshev, kRandom };

std::vector<double> MakeNodes(NodeKind kind, std::mt19937_64& rng, int n) {
  switch (kind) {
    case NodeKind::kUniform:
      return UniformNodes(n, -1.0, 2.0);
    case NodeKind::kChebyshev:
      return ChebyshevNodes(n, -1.0, 2.0);
    case NodeKind::kRandom:
      break;
  }
  return RandomNodes(rng, n, -3.0);
}

// Random parameters in [t_0, t_n], the ends and every node.
std::vector<double> TestParameters(std::mt19937_64& rng,
                                   const std::vector<double>& nodes,
                                   int random_count) {
  std::uniform_real_distribution<double> uniform(nodes.front(), nodes.back());
  std::vector<double> params(nodes);
  for (int r = 0; r < random_count; ++r) params.push_back(uniform(rng));
  return params;
}

// The k-th derivatives of all L_i at t in long double, by Leibniz's rule on
// the product formula for L_i (docs/references.md, 'Lagrange basis and
// Neville's algorithm'): d^k/dt^k prod_{j != i} (t - t_j) is k! times the
// sum, over the ways to drop k factors, of the product of the others, i.e.
// k! times the coefficient of h^k in prod_{j != i} (t - t_j + h); divided by
// prod_{j != i} (t_i - t_j). `bound` is sum_i of the same with every
// t - t_j replaced by |t - t_j|: the size of the terms a product-sum
// evaluation rounds (for k = 0 the Lebesgue function sum_i |L_i(t)|), which
// bounds both sum_i |L_i^(k)(t)| and the rounding error of such evaluations
// in units of (number of operations) * u.
struct Reference {
  std::vector<long double> basis;
  double bound = 0;
};

Reference ReferenceDerivatives(const std::vector<double>& nodes, int k,
                               double t) {
  const size_t orders = static_cast<size_t>(k + 1);
  long double factorial = 1;
  for (int q = 2; q <= k; ++q) factorial *= q;
  Reference reference;
  long double bound = 0;
  for (size_t i = 0; i < nodes.size(); ++i) {
    // Coefficients of h^0..h^k of the product, with signed and absolute a.
    std::vector<long double> signed_series(orders, 0), absolute_series(orders);
    signed_series[0] = absolute_series[0] = 1;
    long double denominator = 1;
    for (size_t j = 0; j < nodes.size(); ++j) {
      if (j == i) continue;
      const long double a = static_cast<long double>(t) - nodes[j];
      for (size_t p = orders - 1; p > 0; --p) {
        signed_series[p] = a * signed_series[p] + signed_series[p - 1];
        absolute_series[p] =
            std::fabs(a) * absolute_series[p] + absolute_series[p - 1];
      }
      signed_series[0] *= a;
      absolute_series[0] *= std::fabs(a);
      denominator *= static_cast<long double>(nodes[i]) - nodes[j];
    }
    reference.basis.push_back(factorial * signed_series[k] / denominator);
    bound += factorial * absolute_series[k] / std::fabs(denominator);
  }
  reference.bound = static_cast<double>(bound);
  return reference;
}

LagrangeCurveView View(const std::vector<double>& coordinates, int dimension,
                       const std::vector<double>& nodes = {}) {
  return LagrangeCurveView{
      .points = {.dimension = dimension, .coordinates = coordinates},
      .nodes = nodes};
}

// Evaluates with `orders` derivative buffers and returns them.
std::vector<std::vector<double>> Evaluate(
    const LagrangeCurveView& curve, const std::vector<double>& params,
    int orders, const ExecutionContext& context = {}) {
  std::vector<std::vector<double>> buffers(
      static_cast<size_t>(orders),
      std::vector<double>(params.size() *
                          static_cast<size_t>(curve.points.dimension)));
  std::vector<absl::Span<double>> output(buffers.begin(), buffers.end());
  const absl::Status status =
      EvaluateLagrangeCurve(curve, params, output, context);
  EXPECT_TRUE(status.ok()) << status;
  return buffers;
}

// The dense basis, output[k][r * (n + 1) + i].
std::vector<std::vector<double>> EvaluateBasis(
    const std::vector<double>& nodes, const std::vector<double>& params,
    int orders, const ExecutionContext& context = {}) {
  std::vector<std::vector<double>> buffers(
      static_cast<size_t>(orders),
      std::vector<double>(params.size() * nodes.size()));
  std::vector<absl::Span<double>> output(buffers.begin(), buffers.end());
  const absl::Status status =
      EvaluateLagrangeBasis(nodes, params, output, context);
  EXPECT_TRUE(status.ok()) << status;
  return buffers;
}

// d^k/dt^k prod_j (t - roots_j) by the product rule: k! times the sum over
// k-element subsets S of prod_{j not in S} (t - roots_j).
double ProductDerivative(const std::vector<double>& roots, int k, double t) {
  double sum = 0;
  for (unsigned mask = 0; mask < (1u << roots.size()); ++mask) {
    if (std::popcount(mask) != k) continue;
    double product = 1;
    for (size_t j = 0; j < roots.size(); ++j) {
      if ((mask >> j & 1u) == 0) product *= t - roots[j];
    }
    sum += product;
  }
  return std::tgamma(k + 1.0) * sum;
}

// The cubic Lagrange basis with nodes 0, 1, 2, 3 is
// L_0 = -(t-1)(t-2)(t-3)/6, L_1 = t(t-2)(t-3)/2, L_2 = -t(t-1)(t-3)/2,
// L_3 = t(t-1)(t-2)/6 (docs/references.md,
// 'Worked example: the cubic Lagrange basis on the nodes 0, 1, 2, 3'); their
// derivatives by the product rule.
TEST(LagrangeBasisTest, CubicBasisIsTheNotesExample1) {
  const std::vector<double> nodes = {0, 1, 2, 3};
  const std::vector<std::vector<double>> roots = {
      {1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  const std::vector<double> scale = {-1.0 / 6, 1.0 / 2, -1.0 / 2, 1.0 / 6};
  std::vector<double> params;
  for (int r = 0; r <= 300; ++r) params.push_back(r / 100.0);
  const int orders = 5;
  const auto basis = EvaluateBasis(nodes, params, orders);
  for (int k = 0; k < orders; ++k) {
    for (size_t r = 0; r < params.size(); ++r) {
      for (size_t i = 0; i < 4; ++i) {
        const double expected =
            scale[i] * ProductDerivative(roots[i], k, params[r]);
        EXPECT_NEAR(basis[k][r * 4 + i], expected, 1e-14)
            << "k=" << k << " i=" << i << " t=" << params[r];
      }
    }
  }
  // The documented single-point example.
  const std::vector<double> weights = BarycentricWeights(nodes);
  std::vector<double> values(4);
  std::vector<double> scratch(1);
  LagrangeBasis(nodes, weights, 0.5, 0, absl::MakeSpan(scratch),
                absl::MakeSpan(values));
  EXPECT_THAT(values,
              Pointwise(DoubleNear(1e-16), {0.3125, 0.9375, -0.3125, 0.0625}));
}

// L_i(t_j) = delta_ij, sum_i L_i(t) = 1 and sum_i L_i^(k)(t) = 0 for k >= 1
// (the basis reproduces constants), for random nodes of degrees 1..20. The
// sums are checked to 4 (n + 1) units of rounding of the reference's bound,
// the size of the terms that cancel.
TEST(LagrangeBasisTest, CardinalConditionsAndPartitionOfUnity) {
  std::mt19937_64 rng(17);
  for (int n = 1; n <= 20; ++n) {
    const std::vector<double> nodes = RandomNodes(rng, n, -3.0);
    const std::vector<double> weights = BarycentricWeights(nodes);
    const size_t count = nodes.size();
    const int max_order = n + 1;
    std::vector<double> values(static_cast<size_t>(max_order + 1) * count);
    std::vector<double> scratch(static_cast<size_t>(max_order + 1));
    for (size_t j = 0; j < count; ++j) {
      LagrangeBasis(nodes, weights, nodes[j], 0, absl::MakeSpan(scratch),
                    absl::MakeSpan(values).first(count));
      for (size_t i = 0; i < count; ++i) {
        if (i == j) {
          EXPECT_EQ(values[i], 1.0) << n;
        } else {
          EXPECT_EQ(values[i], 0.0) << "n=" << n << " i=" << i << " j=" << j;
        }
      }
    }
    for (double t : TestParameters(rng, nodes, 10)) {
      LagrangeBasis(nodes, weights, t, max_order, absl::MakeSpan(scratch),
                    absl::MakeSpan(values));
      for (int k = 0; k <= max_order; ++k) {
        double sum = 0;
        for (size_t i = 0; i < count; ++i) {
          sum += values[k * count + i];
          if (k > n) {
            EXPECT_EQ(values[k * count + i], 0.0);
          }
        }
        EXPECT_NEAR(
            sum, k == 0 ? 1.0 : 0.0,
            4 * (n + 1) * kEpsilon * ReferenceDerivatives(nodes, k, t).bound)
            << "n=" << n << " k=" << k << " t=" << t;
      }
    }
  }
}

// Every derivative of every basis function matches the long double
// reference for uniform, Chebyshev and random nodes of degrees 1..20, to
// 4 (n + 1) units of rounding of the reference's bound: the ladder's
// products and sums have O(n) operations each.
TEST(LagrangeBasisTest, DerivativesMatchLongDoubleReference) {
  std::mt19937_64 rng(23);
  for (NodeKind kind :
       {NodeKind::kUniform, NodeKind::kChebyshev, NodeKind::kRandom}) {
    for (int n = 1; n <= 20; ++n) {
      const std::vector<double> nodes = MakeNodes(kind, rng, n);
      const std::vector<double> params = TestParameters(rng, nodes, 8);
      const int orders = n + 1;
      const auto basis = EvaluateBasis(nodes, params, orders);
      const size_t count = nodes.size();
      for (int k = 0; k < orders; ++k) {
        for (size_t r = 0; r < params.size(); ++r) {
          const Reference expected = ReferenceDerivatives(nodes, k, params[r]);
          const double tolerance = 4 * (n + 1) * kEpsilon * expected.bound;
          for (size_t i = 0; i < count; ++i) {
            EXPECT_NEAR(basis[k][r * count + i],
                        static_cast<double>(expected.basis[i]), tolerance)
                << "n=" << n << " k=" << k << " i=" << i << " t=" << params[r];
          }
        }
      }
    }
  }
}

// Neville, the ladder and the barycentric form each match the long double
// sum_i L_i(t) P_i (hence each other) for degrees 1..20 on uniform and
// Chebyshev nodes. Tolerance from Higham (IMA J. Numer. Anal. 24, 2004),
// with Lambda(t) = sum_i |L_i(t)|: the ladder (first form) errs by at most
// (5n + 5) u Lambda(t) max |P_i|, the second form by about
// (3n + 4) u Lambda(t) max |P_i| + (3n + 2) u Lambda(t) |C(t)|;
// 8 (n + 1) u Lambda(t) (max |P_i| + |C(t)|) covers both, and Neville stays
// within it too.
TEST(LagrangeCurveTest, NevilleLadderAndBarycentricMatchLongDouble) {
  std::mt19937_64 rng(29);
  for (NodeKind kind : {NodeKind::kUniform, NodeKind::kChebyshev}) {
    for (int n = 1; n <= 20; ++n) {
      const int dimension = 1 + n % 3;
      const size_t dim = static_cast<size_t>(dimension);
      const std::vector<double> nodes = MakeNodes(kind, rng, n);
      const std::vector<double> points =
          RandomValues(rng, static_cast<size_t>(n + 1) * dim);
      const PointsView view{.dimension = dimension, .coordinates = points};
      const std::vector<double> weights = BarycentricWeights(nodes);
      std::vector<double> scratch(points.size());
      std::vector<double> neville(dim), ladder(dim), barycentric(dim);
      for (double t : TestParameters(rng, nodes, 30)) {
        NevilleEvaluate(view, nodes, t, absl::MakeSpan(scratch),
                        absl::MakeSpan(neville));
        LadderEvaluate(view, nodes, weights, t, absl::MakeSpan(ladder));
        BarycentricEvaluate(view, nodes, weights, t,
                            absl::MakeSpan(barycentric));
        const Reference basis = ReferenceDerivatives(nodes, 0, t);
        for (size_t j = 0; j < dim; ++j) {
          long double expected = 0;
          for (size_t i = 0; i < nodes.size(); ++i) {
            expected += basis.basis[i] * points[i * dim + j];
          }
          const double reference = static_cast<double>(expected);
          const double tolerance = 8 * (n + 1) * kEpsilon * basis.bound *
                                   (MaxAbs(points) + std::fabs(reference));
          EXPECT_NEAR(neville[j], reference, tolerance) << n << " t=" << t;
          EXPECT_NEAR(ladder[j], reference, tolerance) << n << " t=" << t;
          EXPECT_NEAR(barycentric[j], reference, tolerance) << n << " t=" << t;
        }
      }
    }
  }
}

// C(t_i) = P_i exactly, for given and for uniform nodes.
TEST(LagrangeCurveTest, InterpolatesItsPointsExactlyAtTheNodes) {
  std::mt19937_64 rng(31);
  for (int n = 0; n <= 20; ++n) {
    const std::vector<double> points =
        RandomValues(rng, static_cast<size_t>(n + 1) * 3);
    const std::vector<double> nodes = RandomNodes(rng, n, 0.5);
    EXPECT_EQ(Evaluate(View(points, 3, nodes), nodes, 1)[0], points);
    const std::vector<double> uniform = LagrangeNodes(View(points, 3));
    EXPECT_EQ(Evaluate(View(points, 3), uniform, 1)[0], points);
  }
}

// Points sampled from a polynomial q of degree d <= n give back q and its
// derivatives at any t (orders above n are zero). The samples carry
// rounding, which the k-th derivative amplifies by up to the reference's
// bound; so does the evaluation. The tolerance is 8 (n + 1) u times that
// bound times max |P_i| (plus |C(t)| for positions: the second barycentric
// form's extra term, see above).
TEST(LagrangeCurveTest, ReproducesPolynomialsAndTheirDerivatives) {
  std::mt19937_64 rng(37);
  const int dimension = 2;
  for (NodeKind kind : {NodeKind::kUniform, NodeKind::kChebyshev}) {
    for (int n = 1; n <= 20; ++n) {
      for (int d : {n, n / 2}) {
        const std::vector<double> nodes = MakeNodes(kind, rng, n);
        // q(t) = sum_m c_m (t - 0.3)^m, per coordinate.
        const std::vector<double> c =
            RandomValues(rng, static_cast<size_t>((d + 1) * dimension));
        const auto q = [&](int k, double t, int j) {
          long double value = 0;
          for (int m = d; m >= k; --m) {
            long double falling = 1;
            for (int s = 0; s < k; ++s) falling *= m - s;
            value = value * (t - 0.3L) + falling * c[m * dimension + j];
          }
          return static_cast<double>(value);
        };
        std::vector<double> points;
        for (double node : nodes) {
          for (int j = 0; j < dimension; ++j) points.push_back(q(0, node, j));
        }
        const std::vector<double> params = TestParameters(rng, nodes, 12);
        const int orders = n + 2;
        const auto result =
            Evaluate(View(points, dimension, nodes), params, orders);
        for (int k = 0; k < orders; ++k) {
          for (size_t r = 0; r < params.size(); ++r) {
            const double bound =
                ReferenceDerivatives(nodes, k, params[r]).bound;
            for (int j = 0; j < dimension; ++j) {
              const double value = result[k][r * dimension + j];
              const double expected = q(k, params[r], j);
              const double size =
                  MaxAbs(points) + (k == 0 ? std::fabs(expected) : 0.0);
              if (k > n) {
                EXPECT_EQ(value, 0.0);
              } else {
                EXPECT_NEAR(value, expected,
                            8 * (n + 1) * kEpsilon * bound * size)
                    << "n=" << n << " d=" << d << " k=" << k
                    << " t=" << params[r];
              }
            }
          }
        }
      }
    }
  }
}

// Each coordinate of a curve in any dimension 1..16 is the 1-D curve through
// that coordinate of the points, bit for bit, at every derivative order.
TEST(LagrangeCurveTest, AnyDimensionActsCoordinatewise) {
  std::mt19937_64 rng(41);
  const int n = 7;
  const std::vector<double> nodes = ChebyshevNodes(n, 0.0, 1.0);
  const std::vector<double> params = TestParameters(rng, nodes, 20);
  for (int dimension = 1; dimension <= 16; ++dimension) {
    const size_t dim = static_cast<size_t>(dimension);
    const std::vector<double> points =
        RandomValues(rng, static_cast<size_t>(n + 1) * dim);
    const auto result = Evaluate(View(points, dimension, nodes), params, 3);
    for (size_t j = 0; j < dim; ++j) {
      std::vector<double> column;
      for (int i = 0; i <= n; ++i) column.push_back(points[i * dim + j]);
      const auto single = Evaluate(View(column, 1, nodes), params, 3);
      for (size_t k = 0; k < 3; ++k) {
        for (size_t r = 0; r < params.size(); ++r) {
          EXPECT_EQ(result[k][r * dim + j], single[k][r]) << dimension;
        }
      }
    }
  }
}

TEST(LagrangeCurveTest, SinglePointIsAConstantCurve) {
  const std::vector<double> point = {7, 8, 9};
  const auto uniform = Evaluate(View(point, 3), {0.0, 0.4, 1.0}, 3);
  EXPECT_THAT(uniform[0], ElementsAre(7, 8, 9, 7, 8, 9, 7, 8, 9));
  EXPECT_THAT(uniform[1], ElementsAre(0, 0, 0, 0, 0, 0, 0, 0, 0));
  EXPECT_THAT(uniform[2], ElementsAre(0, 0, 0, 0, 0, 0, 0, 0, 0));
  const std::vector<double> node = {2.5};
  EXPECT_THAT(Evaluate(View(point, 3, node), {2.5}, 1)[0],
              ElementsAre(7, 8, 9));
  EXPECT_THAT(EvaluateBasis(node, {2.5}, 2),
              ElementsAre(ElementsAre(1.0), ElementsAre(0.0)));
}

TEST(LagrangeCurveTest, NodesAndDomain) {
  const std::vector<double> points = {0, 1, 2, 3, 4};
  EXPECT_THAT(LagrangeNodes(View(points, 1)),
              ElementsAre(0.0, 0.25, 0.5, 0.75, 1.0));
  EXPECT_THAT(LagrangeNodes(View({5}, 1)), ElementsAre(0.0));
  EXPECT_EQ(LagrangeDomain(View(points, 1)), std::make_pair(0.0, 1.0));
  EXPECT_EQ(LagrangeDomain(View({5}, 1)), std::make_pair(0.0, 1.0));
  const std::vector<double> nodes = {-2, 0, 1, 5, 6};
  EXPECT_THAT(LagrangeNodes(View(points, 1, nodes)),
              ElementsAre(-2, 0, 1, 5, 6));
  EXPECT_EQ(LagrangeDomain(View(points, 1, nodes)), std::make_pair(-2.0, 6.0));
  const std::vector<double> node = {3};
  EXPECT_EQ(LagrangeDomain(View({5}, 1, node)), std::make_pair(3.0, 3.0));
}

// For uniform nodes the weights are proportional to (-1)^i binom(n, i)
// (Berrut & Trefethen 2004).
TEST(LagrangeBasisTest, UniformWeightsAreAlternatingBinomials) {
  for (int n = 1; n <= 30; ++n) {
    const std::vector<double> weights =
        BarycentricWeights(UniformNodes(n, -1.0, 2.0));
    double binomial = 1;
    for (int i = 0; i <= n; ++i) {
      const double expected = (i % 2 == 0 ? 1 : -1) * binomial;
      EXPECT_NEAR(weights[i] / weights[0], expected,
                  4 * n * kEpsilon * binomial)
          << "n=" << n << " i=" << i;
      binomial = binomial * (n - i) / (i + 1);
    }
  }
}

// For Chebyshev extreme points the weights are proportional to
// (-1)^i delta_i, delta_i = 1/2 at the ends and 1 inside (Berrut & Trefethen
// 2004), up to degree 2000, where partial products of the node differences
// leave the double range. The computed nodes carry rounding relative to
// their spacing, ~n^-2 at the ends; hence the n^2 u tolerance.
TEST(LagrangeBasisTest, ChebyshevWeightsAreAlternatingOnesToHighDegree) {
  for (int n : {1, 2, 5, 20, 100, 1000, 2000}) {
    const std::vector<double> weights =
        BarycentricWeights(ChebyshevNodes(n, -1.0, 2.0));
    for (int i = 0; i <= n; ++i) {
      const double expected =
          (i % 2 == 0 ? 1 : -1) * (i == 0 || i == n ? 1 : 2);
      EXPECT_NEAR(weights[i] / weights[0], expected,
                  static_cast<double>(n) * n * kEpsilon)
          << "n=" << n << " i=" << i;
    }
  }
}

// The weights are scaled by the interval's capacity, so degree 60 on an
// interval of length 2^-40 or 2^40 (whose unscaled weights, about
// (4 / length)^60, overflow or underflow) gives the unit interval's curve,
// with the k-th derivative scaled by length^-k; with power-of-two scales
// the arithmetic is the same bit for bit.
TEST(LagrangeCurveTest, WeightScalingSurvivesTinyAndHugeIntervals) {
  std::mt19937_64 rng(43);
  const int n = 60;
  const std::vector<double> points =
      RandomValues(rng, static_cast<size_t>(n + 1) * 2);
  const std::vector<double> unit = ChebyshevNodes(n, 0.0, 1.0);
  const std::vector<double> params = TestParameters(rng, unit, 20);
  const auto expected = Evaluate(View(points, 2, unit), params, 3);
  for (double length : {std::ldexp(1.0, -40), std::ldexp(1.0, 40)}) {
    std::vector<double> nodes, mapped;
    for (double node : unit) nodes.push_back(length * node);
    for (double t : params) mapped.push_back(length * t);
    const auto result = Evaluate(View(points, 2, nodes), mapped, 3);
    for (size_t k = 0; k < 3; ++k) {
      const double scale = std::pow(length, static_cast<double>(k));
      for (size_t x = 0; x < expected[k].size(); ++x) {
        EXPECT_EQ(result[k][x] * scale, expected[k][x])
            << "length=" << length << " k=" << k;
      }
    }
  }
}

TEST(LagrangeCurveTest, PoolResultsEqualSerialResults) {
  std::mt19937_64 rng(47);
  const std::vector<double> points = RandomValues(rng, 10 * 4);
  const std::vector<double> nodes = ChebyshevNodes(9, -1.0, 1.0);
  std::vector<double> params(50'003);
  for (size_t r = 0; r < params.size(); ++r) {
    params[r] = -1.0 + 2.0 * static_cast<double>(r) /
                           static_cast<double>(params.size() - 1);
  }
  ThreadPool pool(4);
  const ExecutionContext context{.pool = &pool, .grain = 1000};
  EXPECT_EQ(Evaluate(View(points, 4, nodes), params, 3),
            Evaluate(View(points, 4, nodes), params, 3, context));
  EXPECT_EQ(EvaluateBasis(nodes, params, 3),
            EvaluateBasis(nodes, params, 3, context));
}

TEST(LagrangeCurveTest, CancelledTokenStopsTheBatch) {
  const std::vector<double> points = {0, 0, 1, 1, 2, 0};
  const std::vector<double> nodes = {0, 1, 2};
  std::vector<double> params(50'000, 0.5);
  std::vector<double> curve_out(params.size() * 2);
  std::vector<double> basis_out(params.size() * 3);
  CancellationToken token;
  token.Cancel();
  ThreadPool pool(2);
  const ExecutionContext context{
      .pool = &pool, .cancellation = &token, .grain = 100};
  const absl::Span<double> curve_output[] = {absl::MakeSpan(curve_out)};
  const absl::Span<double> basis_output[] = {absl::MakeSpan(basis_out)};
  EXPECT_EQ(
      EvaluateLagrangeCurve(View(points, 2), params, curve_output, context)
          .code(),
      absl::StatusCode::kCancelled);
  EXPECT_EQ(EvaluateLagrangeBasis(nodes, params, basis_output, context).code(),
            absl::StatusCode::kCancelled);
}

struct InvalidCase {
  std::vector<double> coordinates;
  int dimension;
  std::vector<double> nodes;
  std::vector<double> params;
  std::string field;
};

TEST(LagrangeCurveTest, InvalidInputNamesTheField) {
  const double nan = std::nan("");
  const double inf = std::numeric_limits<double>::infinity();
  const double big = std::numeric_limits<double>::max();
  const std::vector<InvalidCase> cases = {
      {{0, 0, 1}, 2, {}, {0.5}, "points.coordinates"},
      {{}, 2, {}, {0.5}, "points.coordinates"},
      {{0, nan, 1, 1}, 2, {}, {0.5}, "points.coordinates[1]"},
      {{0, 0}, 0, {}, {0.5}, "points.dimension"},
      {{0, 0, 1, 1}, 2, {0, 1, 2}, {0.5}, "nodes"},
      {{0, 0, 1, 1}, 2, {0}, {0.5}, "nodes"},
      {{0, 1, 2}, 1, {0, nan, 2}, {0.5}, "nodes[1]"},
      {{0, 1, 2}, 1, {0, 1, inf}, {0.5}, "nodes[2]"},
      {{0, 1, 2}, 1, {0, 1, 1}, {0.5}, "nodes[2]"},
      {{0, 1, 2}, 1, {0, 2, 1}, {0.5}, "nodes[2]"},
      {{0, 1, 2, 3}, 1, {3, 2, nan, 1}, {0.5}, "nodes[1]"},
      {{0, 1}, 1, {-big, big}, {0.0}, "nodes"},
      {{0, 0, 1, 1}, 2, {}, {0.5, 1.5}, "parameters[1]"},
      {{0, 0, 1, 1}, 2, {}, {-0.1}, "parameters[0]"},
      {{0, 1, 2}, 1, {1, 2, 4}, {4, 0.5}, "parameters[1]"},
      {{0, 1, 2}, 1, {1, 2, 4}, {2, 4.5}, "parameters[1]"},
      {{0, 0, 1, 1}, 2, {}, {nan}, "parameters[0]"},
      {{0, 0, 1, 1}, 2, {}, {inf}, "parameters[0]"},
      {{5}, 1, {2}, {2.5}, "parameters[0]"},
  };
  for (const InvalidCase& c : cases) {
    std::vector<double> out(c.params.size() * std::max(c.dimension, 1));
    std::vector<absl::Span<double>> output = {absl::MakeSpan(out)};
    const absl::Status status = EvaluateLagrangeCurve(
        View(c.coordinates, c.dimension, c.nodes), c.params, output);
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << c.field;
    EXPECT_EQ(FieldPathOf(status).value_or(""), c.field) << status;
  }
}

TEST(LagrangeBasisTest, InvalidInputNamesTheField) {
  const double nan = std::nan("");
  const std::vector<std::pair<std::vector<double>, std::vector<double>>>
      inputs = {{{}, {0.5}},          {{0, nan, 1}, {0.5}},  {{0, 1, 1}, {0.5}},
                {{0, 1, 0.5}, {0.5}}, {{0, 1}, {0.5, 1.01}}, {{0, 1}, {nan}}};
  const std::vector<std::string> fields = {"nodes",         "nodes[1]",
                                           "nodes[2]",      "nodes[2]",
                                           "parameters[1]", "parameters[0]"};
  for (size_t c = 0; c < inputs.size(); ++c) {
    const auto& [nodes, params] = inputs[c];
    std::vector<double> out(params.size() * std::max<size_t>(nodes.size(), 1));
    std::vector<absl::Span<double>> output = {absl::MakeSpan(out)};
    const absl::Status status = EvaluateLagrangeBasis(nodes, params, output);
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << fields[c];
    EXPECT_EQ(FieldPathOf(status).value_or(""), fields[c]) << status;
  }
}

TEST(LagrangeCurveTest, WronglySizedOutputIsRejected) {
  const std::vector<double> points = {0, 0, 1, 1};
  const std::vector<double> params = {0.5};
  std::vector<double> good(2), bad(3);
  const std::vector<absl::Span<double>> output = {absl::MakeSpan(good),
                                                  absl::MakeSpan(bad)};
  absl::Status status = EvaluateLagrangeCurve(View(points, 2), params, output);
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(status.message(), HasSubstr("output[1]"));
  status = EvaluateLagrangeCurve(View(points, 2), params, {});
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  const std::vector<double> nodes = {0, 1, 2};
  status = EvaluateLagrangeBasis(nodes, params, output);  // needs 3 values
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(status.message(), HasSubstr("output[0]"));
}

}  // namespace
}  // namespace freeform

namespace freeform {
namespace {

// The parabola through (0, 0), (1, 1), (2, 4) at nodes 0, 1, 2 is the
// Bezier curve (0, 0), (1, 0), (2, 4): x = 2s, y = 4s^2.
TEST(LagrangeToBezierTest, ParabolaThroughThreePoints) {
  const std::vector<double> xy = {0, 0, 1, 1, 2, 4};
  const std::vector<double> nodes = {0, 1, 2};
  const LagrangeCurveView curve{.points = {.dimension = 2, .coordinates = xy},
                                .nodes = nodes};
  const absl::StatusOr<std::vector<double>> bezier = LagrangeToBezier(curve);
  ASSERT_TRUE(bezier.ok()) << bezier.status();
  EXPECT_THAT(*bezier,
              Pointwise(DoubleNear(1e-15), {0.0, 0.0, 1.0, 0.0, 2.0, 4.0}));
}

// Bezier evaluation of the converted points (de Casteljau) against the
// Lagrange ladder on the original, for degrees 1 to 12 on uneven nodes, to
// rounding relative to the Bezier points' size.
TEST(LagrangeToBezierTest, AgreesWithLagrangeEvaluation) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int degree = 1; degree <= 12; ++degree) {
    std::vector<double> points(3 * (degree + 1));
    for (double& value : points) value = uniform(random);
    std::vector<double> nodes = {-2.0};
    for (int i = 1; i <= degree; ++i) {
      nodes.push_back(nodes.back() + 0.5 + 0.5 * (uniform(random) + 1.0));
    }
    const LagrangeCurveView curve{
        .points = {.dimension = 3, .coordinates = points}, .nodes = nodes};
    const absl::StatusOr<std::vector<double>> converted =
        LagrangeToBezier(curve);
    ASSERT_TRUE(converted.ok()) << converted.status();
    const std::vector<double>& bezier = *converted;
    // The conversion is backward stable: its error scales with the size of
    // the Bezier points, which grows with the degree for random data.
    double scale = 1.0;
    for (double value : bezier) scale = std::max(scale, std::abs(value));
    std::vector<double> parameters, s;
    for (int k = 0; k <= 20; ++k) {
      s.push_back(k / 20.0);
      parameters.push_back(
          std::min(nodes.back(),
                   nodes.front() + s.back() * (nodes.back() - nodes.front())));
    }
    std::vector<double> expected(3 * parameters.size());
    const absl::Span<double> expected_output[] = {absl::MakeSpan(expected)};
    ASSERT_TRUE(EvaluateLagrangeCurve(curve, parameters, expected_output).ok());
    for (size_t k = 0; k < s.size(); ++k) {
      std::vector<double> work = bezier;  // de Casteljau in place
      for (int r = 1; r <= degree; ++r) {
        for (int i = 0; i <= degree - r; ++i) {
          for (int x = 0; x < 3; ++x) {
            work[3 * i + x] =
                (1 - s[k]) * work[3 * i + x] + s[k] * work[3 * (i + 1) + x];
          }
        }
      }
      for (int x = 0; x < 3; ++x) {
        EXPECT_NEAR(work[x], expected[3 * k + x], 1e-13 * scale)
            << "degree " << degree << " s " << s[k];
      }
    }
  }
}

// The Bernstein form of s^m of degree n is b_k = C(k, m) / C(n, m) (the
// power-to-Bernstein conversion). Sampled at uniform nodes i / n with n a
// power of two, the data are exact, so the conversion must give the
// binomial ratios to the rounding of the result, for condition numbers of
// 1e6 (17 nodes) to 7e12 (33 nodes), which double arithmetic turned into
// errors of 4e-10 and 4e-3.
TEST(LagrangeToBezierTest, MonomialsComeOutAsBinomialRatios) {
  for (int n : {4, 8, 16, 32}) {
    const std::vector<double> nodes = UniformNodes(n, 0.0, 1.0);
    for (int m : {1, 2, 5, 10}) {
      if (m > n) continue;
      std::vector<double> points;
      for (double t : nodes) points.push_back(std::pow(t, m));  // exact
      const LagrangeCurveView curve{
          .points = {.dimension = 1, .coordinates = points}, .nodes = nodes};
      const absl::StatusOr<std::vector<double>> bezier =
          LagrangeToBezier(curve);
      ASSERT_TRUE(bezier.ok()) << bezier.status() << " n=" << n;
      for (int k = 0; k <= n; ++k) {
        double expected = 0.0;
        if (k >= m) {
          expected = 1.0;
          for (int i = 0; i < m; ++i) {
            expected *= static_cast<double>(k - i) / (n - i);
          }
        }
        EXPECT_NEAR((*bezier)[k], expected, 4 * kEpsilon)
            << "n=" << n << " m=" << m << " k=" << k;
      }
    }
  }
}

// A straight line through 17 uniform nodes (like a fuzz finding of issue
// 30, whose Taylor-series conversion put the Bezier points 1.6e-8 off the
// interpolant) has its Bezier points evenly spaced on the line.
TEST(LagrangeToBezierTest, ALineOfDegreeSixteenStaysOnItsLine) {
  const int n = 16;
  std::vector<double> points;
  for (int i = 0; i <= n; ++i) {
    points.push_back(1.0 - 8.5 * i / n);  // exact
    points.push_back(1.0);
  }
  const LagrangeCurveView curve{
      .points = {.dimension = 2, .coordinates = points}, .nodes = {}};
  const absl::StatusOr<std::vector<double>> bezier = LagrangeToBezier(curve);
  ASSERT_TRUE(bezier.ok()) << bezier.status();
  for (int k = 0; k <= n; ++k) {
    EXPECT_NEAR((*bezier)[2 * k], 1.0 - 8.5 * k / n, 4 * 8.5 * kEpsilon);
    EXPECT_NEAR((*bezier)[2 * k + 1], 1.0, 4 * kEpsilon);
  }
}

// Where double-double arithmetic cannot reach double precision, the
// conversion refuses, naming the nodes, and CheckLagrangeBezierForm says
// the same without converting: 41 uniform nodes, and three nodes of which
// two are 1e-100 of the span apart (a constant curve whose Bezier points
// came out 1e15 off).
TEST(LagrangeToBezierTest, IllConditionedNodesAreRefused) {
  const std::vector<double> uniform_points(41, 1.0);
  const std::vector<double> clustered_points = {-1e15, -1e15, -1e15};
  const std::vector<double> clustered_nodes = {0.34281158056984895,
                                               1.3298537883676098, 1e100};
  const LagrangeCurveView curves[] = {
      {.points = {.dimension = 1, .coordinates = uniform_points}, .nodes = {}},
      {.points = {.dimension = 1, .coordinates = clustered_points},
       .nodes = clustered_nodes}};
  for (const LagrangeCurveView& curve : curves) {
    const absl::StatusOr<std::vector<double>> bezier = LagrangeToBezier(curve);
    ASSERT_FALSE(bezier.ok());
    EXPECT_EQ(bezier.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_EQ(FieldPathOf(bezier.status()), "nodes");
    EXPECT_THAT(bezier.status().message(), HasSubstr("ill-conditioned"));
    const absl::Status check = CheckLagrangeBezierForm(curve);
    EXPECT_EQ(check, bezier.status());
  }
  // Degree 31 on uniform nodes still passes, as does any degree 0 or 1.
  const std::vector<double> line = {0.0, 1.0};
  EXPECT_TRUE(
      CheckLagrangeBezierForm(
          {.points = {.dimension = 1, .coordinates = line}, .nodes = {}})
          .ok());
  const std::vector<double> points32(32, 1.0);
  EXPECT_TRUE(
      CheckLagrangeBezierForm(
          {.points = {.dimension = 1, .coordinates = points32}, .nodes = {}})
          .ok());
}

}  // namespace
}  // namespace freeform
