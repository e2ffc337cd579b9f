#include "freeform/core/triangular.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "freeform/core/bezier.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/status.h"

namespace freeform {
namespace {

using ::testing::HasSubstr;

using Buffers = std::vector<std::vector<double>>;

// Evaluates with all partials up to `max_order` and returns the buffers.
Buffers Evaluate(const TriangularPatchView& patch,
                 const std::vector<double>& uv, int max_order,
                 const ExecutionContext& context = {}) {
  Buffers buffers(
      PartialCount(max_order),
      std::vector<double>(uv.size() / 2 *
                          static_cast<size_t>(patch.control_points.dimension)));
  std::vector<absl::Span<double>> output(buffers.begin(), buffers.end());
  const absl::Status status =
      EvaluateTriangularPatch(patch, uv, output, context);
  EXPECT_TRUE(status.ok()) << status;
  return buffers;
}

absl::Status EvaluateStatus(const TriangularPatchView& patch,
                            const std::vector<double>& uv, int buffers = 1) {
  std::vector<std::vector<double>> storage(
      static_cast<size_t>(buffers),
      std::vector<double>(
          uv.size() / 2 *
          static_cast<size_t>(std::max(patch.control_points.dimension, 0))));
  std::vector<absl::Span<double>> output(storage.begin(), storage.end());
  return EvaluateTriangularPatch(patch, uv, output);
}

TriangularPatchView View(int degree, const std::vector<double>& coordinates,
                         int dimension, const std::vector<double>& weights = {},
                         const std::vector<double>& triangle = {}) {
  return TriangularPatchView{
      .degree = degree,
      .control_points = {.dimension = dimension, .coordinates = coordinates},
      .weights = weights,
      .domain_triangle = triangle};
}

std::vector<double> RandomValues(std::mt19937_64& rng, size_t count,
                                 double lo = -1.0, double hi = 1.0) {
  std::uniform_real_distribution<double> uniform(lo, hi);
  std::vector<double> values(count);
  for (double& value : values) value = uniform(rng);
  return values;
}

// Random barycentric (u, v) pairs inside the triangle, corners and edges
// included.
std::vector<double> RandomPairs(std::mt19937_64& rng, size_t count) {
  std::vector<double> uv = {1, 0, 0, 1, 0, 0, 0.5, 0.5, 0, 0.25, 0.75, 0};
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  while (uv.size() < 2 * count) {
    double u = uniform(rng), v = uniform(rng);
    if (u + v > 1) {
      u = 1 - u;
      v = 1 - v;
    }
    uv.push_back(u);
    uv.push_back(v);
  }
  uv.resize(2 * count);
  return uv;
}

long double Factorial(int n) {
  long double result = 1;
  for (int i = 2; i <= n; ++i) result *= i;
  return result;
}

long double FallingFactorial(int n, int k) {
  long double result = 1;
  for (int i = 0; i < k; ++i) result *= n - i;
  return result;
}

// d^(a+b) / du^a dv^b of u^i v^j w^k with w = 1 - u - v, by the product
// rule in long double.
long double MonomialPartial(int i, int j, int k, int a, int b, long double u,
                            long double v) {
  const long double w = 1.0L - u - v;
  long double sum = 0;
  for (int p = 0; p <= std::min(a, i); ++p) {
    for (int q = 0; q <= std::min(b, j); ++q) {
      const int s = (a - p) + (b - q);  // derivatives falling on w
      if (s > k) continue;
      const long double sign = s % 2 == 0 ? 1.0L : -1.0L;
      sum += FallingFactorial(a, p) / Factorial(p) *
             (FallingFactorial(b, q) / Factorial(q)) * FallingFactorial(i, p) *
             std::pow(u, i - p) * FallingFactorial(j, q) * std::pow(v, j - q) *
             sign * FallingFactorial(k, s) * std::pow(w, k - s);
    }
  }
  return sum;
}

// Reference partial d^(a+b) S / du^a dv^b: the explicit Bernstein sum with
// multinomial coefficients, independent of de Casteljau.
std::vector<long double> ReferencePartial(const std::vector<double>& control,
                                          int dimension, int n, int a, int b,
                                          double u, double v) {
  std::vector<long double> result(static_cast<size_t>(dimension), 0.0L);
  for (int i = n; i >= 0; --i) {
    for (int j = n - i; j >= 0; --j) {
      const int k = n - i - j;
      const long double basis = Factorial(n) /
                                (Factorial(i) * Factorial(j) * Factorial(k)) *
                                MonomialPartial(i, j, k, a, b, u, v);
      const double* p = control.data() + TriangularIndex(n, i, j) * dimension;
      for (int x = 0; x < dimension; ++x) result[x] += basis * p[x];
    }
  }
  return result;
}

TEST(TriangularIndexTest, FollowsTheDocumentedOrder) {
  // n = 2: P200, P110, P101, P020, P011, P002.
  EXPECT_EQ(TriangularIndex(2, 2, 0), 0u);
  EXPECT_EQ(TriangularIndex(2, 1, 1), 1u);
  EXPECT_EQ(TriangularIndex(2, 1, 0), 2u);
  EXPECT_EQ(TriangularIndex(2, 0, 2), 3u);
  EXPECT_EQ(TriangularIndex(2, 0, 1), 4u);
  EXPECT_EQ(TriangularIndex(2, 0, 0), 5u);
  for (int n = 0; n <= 12; ++n) {
    EXPECT_EQ(TriangularPointCount(n),
              static_cast<size_t>((n + 1) * (n + 2) / 2));
    size_t expected = 0;
    for (int i = n; i >= 0; --i) {
      for (int j = n - i; j >= 0; --j) {
        EXPECT_EQ(TriangularIndex(n, i, j), expected++);
      }
    }
  }
}

// S(1/3, 1/3, 1/3) of the quadratic patch below (docs/references.md,
// 'Worked example: the quadratic triangular patch at the centroid'). It is
// (2, 2, 3), not the (2, 2, 7/3) that two slipped level-1 de Casteljau
// points give: P^1_010 = (P020 + P110 + P011) / 3
// = (0+3+0, 6+3+3, 0+6+3) / 3 = (1, 4, 3), not (1, 4, 2), and P^1_001 =
// (P002 + P101 + P011) / 3 = (0+3+0, 0+0+3, 0+0+3) / 3 = (1, 1, 1), not
// (1, 1, 0). With P^1_100 = (4, 1, 5) the point is (6, 6, 9) / 3 = (2, 2, 3).
TEST(TriangularPatchTest, SeedWorkedExample) {
  // P200, P110, P101, P020, P011, P002.
  const std::vector<double> control = {6, 0, 9, 3, 3, 6, 3, 0, 0,
                                       0, 6, 0, 0, 3, 3, 0, 0, 0};
  const std::vector<double> uv = {1.0 / 3, 1.0 / 3};
  const Buffers result = Evaluate(View(2, control, 3), uv, 1);
  EXPECT_NEAR(result[0][0], 2.0, 1e-15);
  EXPECT_NEAR(result[0][1], 2.0, 1e-15);
  EXPECT_NEAR(result[0][2], 3.0, 1e-15);
  // Independently: the Bernstein sum at the centroid is (corners + 2 edge
  // points) / 9 = ((6,6,9) + 2 (6,6,9)) / 9.
  const std::vector<long double> reference =
      ReferencePartial(control, 3, 2, 0, 0, 1.0 / 3, 1.0 / 3);
  EXPECT_NEAR(static_cast<double>(reference[2]), 3.0, 1e-15);
  // The first partials expose the level-1 points: D_(1,0,-1) S =
  // 2 (P^1_100 - P^1_001) = (6, 0, 8), D_(0,1,-1) S = 2 (P^1_010 - P^1_001)
  // = (0, 6, 4); the slipped points would give (6, 0, 10), (0, 6, 4).
  const std::vector<double> du = {6, 0, 8}, dv = {0, 6, 4};
  for (int x = 0; x < 3; ++x) {
    EXPECT_NEAR(result[PartialIndex(1, 0)][x], du[x], 1e-14);
    EXPECT_NEAR(result[PartialIndex(0, 1)][x], dv[x], 1e-14);
  }
}

TEST(TriangularPatchTest, InterpolatesCorners) {
  std::mt19937_64 rng(1);
  for (int n = 1; n <= 10; ++n) {
    const std::vector<double> control =
        RandomValues(rng, TriangularPointCount(n) * 3);
    const Buffers result = Evaluate(View(n, control, 3), {1, 0, 0, 1, 0, 0}, 0);
    const size_t corners[] = {TriangularIndex(n, n, 0),
                              TriangularIndex(n, 0, n),
                              TriangularIndex(n, 0, 0)};
    for (size_t c = 0; c < 3; ++c) {
      for (size_t x = 0; x < 3; ++x) {
        EXPECT_NEAR(result[0][c * 3 + x], control[corners[c] * 3 + x], 1e-15)
            << "degree " << n << " corner " << c;
      }
    }
  }
}

// Each edge is the Bezier curve of its control points: along
// (u, v) = (1-t, t), (1-t, 0) and (0, 1-t), with d/dt = -S_u + S_v, -S_u
// and -S_v respectively. Polynomial and rational.
TEST(TriangularPatchTest, EdgesAreBezierCurves) {
  std::mt19937_64 rng(2);
  const std::vector<double> t = {0.0, 0.1, 0.37, 0.5, 0.81, 1.0};
  for (int n = 1; n <= 10; ++n) {
    for (const bool rational : {false, true}) {
      const size_t count = TriangularPointCount(n);
      const std::vector<double> control = RandomValues(rng, count * 2);
      const std::vector<double> weights =
          rational ? RandomValues(rng, count, 0.2, 3.0) : std::vector<double>{};
      for (int edge = 0; edge < 3; ++edge) {
        std::vector<double> edge_points, edge_weights, uv;
        for (int q = 0; q <= n; ++q) {
          const size_t index = edge == 0   ? TriangularIndex(n, n - q, q)
                               : edge == 1 ? TriangularIndex(n, n - q, 0)
                                           : TriangularIndex(n, 0, n - q);
          edge_points.insert(edge_points.end(), control.begin() + index * 2,
                             control.begin() + index * 2 + 2);
          if (rational) edge_weights.push_back(weights[index]);
        }
        for (const double s : t) {
          const double pair[3][2] = {{1 - s, s}, {1 - s, 0}, {0, 1 - s}};
          uv.push_back(pair[edge][0]);
          uv.push_back(pair[edge][1]);
        }
        const Buffers patch = Evaluate(View(n, control, 2, weights), uv, 1);
        std::vector<std::vector<double>> curve(
            2, std::vector<double>(t.size() * 2));
        std::vector<absl::Span<double>> output(curve.begin(), curve.end());
        ASSERT_TRUE(
            EvaluateBezierCurve(
                {.control_points = {.dimension = 2, .coordinates = edge_points},
                 .weights = edge_weights},
                t, output)
                .ok());
        const double du = edge == 2 ? 0.0 : -1.0;
        const double dv = edge == 0 ? 1.0 : edge == 2 ? -1.0 : 0.0;
        for (size_t x = 0; x < curve[0].size(); ++x) {
          EXPECT_NEAR(patch[0][x], curve[0][x], 1e-14)
              << "degree " << n << " edge " << edge;
          const double tangent = du * patch[PartialIndex(1, 0)][x] +
                                 dv * patch[PartialIndex(0, 1)][x];
          EXPECT_NEAR(tangent, curve[1][x], 1e-12 * n * n)
              << "degree " << n << " edge " << edge;
        }
      }
    }
  }
}

TEST(TriangularBasisTest, PartitionOfUnityNonnegativeAndMultinomial) {
  std::mt19937_64 rng(3);
  const std::vector<double> uv = RandomPairs(rng, 40);
  for (int n = 0; n <= 10; ++n) {
    const size_t count = TriangularPointCount(n);
    std::vector<double> values(uv.size() / 2 * count);
    ASSERT_TRUE(EvaluateTriangularBasis(n, uv, absl::MakeSpan(values)).ok());
    for (size_t r = 0; r < uv.size() / 2; ++r) {
      const long double u = uv[2 * r], v = uv[2 * r + 1], w = 1.0L - u - v;
      double sum = 0;
      for (int i = n; i >= 0; --i) {
        for (int j = n - i; j >= 0; --j) {
          const int k = n - i - j;
          const double value = values[r * count + TriangularIndex(n, i, j)];
          const long double expected =
              Factorial(n) / (Factorial(i) * Factorial(j) * Factorial(k)) *
              std::pow(u, i) * std::pow(v, j) * std::pow(w, k);
          EXPECT_GE(value, 0.0);
          EXPECT_NEAR(value, static_cast<double>(expected), 1e-14);
          sum += value;
        }
      }
      EXPECT_NEAR(sum, 1.0, 1e-14) << "degree " << n;
    }
  }
}

TEST(TriangularBasisTest, PatchIsTheBasisCombination) {
  std::mt19937_64 rng(4);
  const int n = 6;
  const size_t count = TriangularPointCount(n);
  const std::vector<double> control = RandomValues(rng, count * 3);
  const std::vector<double> uv = RandomPairs(rng, 20);
  std::vector<double> values(uv.size() / 2 * count);
  ASSERT_TRUE(EvaluateTriangularBasis(n, uv, absl::MakeSpan(values)).ok());
  const Buffers patch = Evaluate(View(n, control, 3), uv, 0);
  for (size_t r = 0; r < uv.size() / 2; ++r) {
    for (size_t x = 0; x < 3; ++x) {
      double sum = 0;
      for (size_t f = 0; f < count; ++f) {
        sum += values[r * count + f] * control[f * 3 + x];
      }
      EXPECT_NEAR(patch[0][r * 3 + x], sum, 1e-14);
    }
  }
}

// With P'(i,j,k) = P(j,k,i), S'(a,b,c) = S(b,c,a); with P'(i,j,k) =
// P(j,i,k), S'(a,b,c) = S(b,a,c).
TEST(TriangularPatchTest, SymmetricUnderPermutingCoordinatesAndPoints) {
  std::mt19937_64 rng(5);
  for (int n = 1; n <= 10; ++n) {
    const size_t count = TriangularPointCount(n);
    const std::vector<double> control = RandomValues(rng, count * 3);
    std::vector<double> cyclic(control.size()), swapped(control.size());
    for (int i = n; i >= 0; --i) {
      for (int j = n - i; j >= 0; --j) {
        const int k = n - i - j;
        for (size_t x = 0; x < 3; ++x) {
          cyclic[TriangularIndex(n, i, j) * 3 + x] =
              control[TriangularIndex(n, j, k) * 3 + x];
          swapped[TriangularIndex(n, i, j) * 3 + x] =
              control[TriangularIndex(n, j, i) * 3 + x];
        }
      }
    }
    const std::vector<double> uv = RandomPairs(rng, 10);
    std::vector<double> uv_cyclic, uv_swapped;
    for (size_t r = 0; r < uv.size() / 2; ++r) {
      const double a = uv[2 * r], b = uv[2 * r + 1], c = 1 - a - b;
      uv_cyclic.insert(uv_cyclic.end(), {b, c});
      uv_swapped.insert(uv_swapped.end(), {b, a});
    }
    const Buffers base_cyclic = Evaluate(View(n, control, 3), uv_cyclic, 0);
    const Buffers base_swapped = Evaluate(View(n, control, 3), uv_swapped, 0);
    const Buffers permuted_cyclic = Evaluate(View(n, cyclic, 3), uv, 0);
    const Buffers permuted_swapped = Evaluate(View(n, swapped, 3), uv, 0);
    for (size_t x = 0; x < base_cyclic[0].size(); ++x) {
      EXPECT_NEAR(permuted_cyclic[0][x], base_cyclic[0][x], 1e-14);
      EXPECT_NEAR(permuted_swapped[0][x], base_swapped[0][x], 1e-14);
    }
  }
}

TEST(TriangularPatchTest, PartialsMatchLongDoubleReference) {
  std::mt19937_64 rng(6);
  const int max_order = 4;
  for (int n = 1; n <= 10; ++n) {
    const std::vector<double> control =
        RandomValues(rng, TriangularPointCount(n) * 2);
    const std::vector<double> uv = RandomPairs(rng, 12);
    const Buffers result = Evaluate(View(n, control, 2), uv, max_order);
    for (int total = 0; total <= max_order; ++total) {
      const double tolerance = 2e-15 * std::pow(2.0 * n + 2, total + 1);
      for (int b = 0; b <= total; ++b) {
        const int a = total - b;
        for (size_t r = 0; r < uv.size() / 2; ++r) {
          const std::vector<long double> expected =
              ReferencePartial(control, 2, n, a, b, uv[2 * r], uv[2 * r + 1]);
          for (size_t x = 0; x < 2; ++x) {
            EXPECT_NEAR(result[PartialIndex(a, b)][r * 2 + x],
                        static_cast<double>(expected[x]), tolerance)
                << "degree " << n << " partial (" << a << ", " << b << ")";
          }
        }
      }
    }
  }
}

// P(i,j,k) = (i/n, j/n, i(i-1)/(n(n-1)) + 3 ij/(n(n-1))) are the Bernstein
// coefficients of (u, v, u^2 + 3uv) (the blossoms of u and u^2, uv are
// averages of the arguments' coordinates), so every partial is known.
TEST(TriangularPatchTest, ReproducesPolynomials) {
  std::mt19937_64 rng(7);
  for (int n = 2; n <= 10; ++n) {
    std::vector<double> control(TriangularPointCount(n) * 3);
    const double scale = 1.0 / (n * (n - 1.0));
    for (int i = n; i >= 0; --i) {
      for (int j = n - i; j >= 0; --j) {
        double* p = control.data() + TriangularIndex(n, i, j) * 3;
        p[0] = static_cast<double>(i) / n;
        p[1] = static_cast<double>(j) / n;
        p[2] = (i * (i - 1.0) + 3.0 * i * j) * scale;
      }
    }
    const std::vector<double> uv = RandomPairs(rng, 10);
    const Buffers result = Evaluate(View(n, control, 3), uv, 3);
    for (size_t r = 0; r < uv.size() / 2; ++r) {
      const double u = uv[2 * r], v = uv[2 * r + 1];
      const double expected[10][3] = {{u, v, u * u + 3 * u * v},  // (0,0)
                                      {1, 0, 2 * u + 3 * v},      // (1,0)
                                      {0, 1, 3 * u},              // (0,1)
                                      {0, 0, 2},                  // (2,0)
                                      {0, 0, 3},                  // (1,1)
                                      {0, 0, 0},
                                      {0, 0, 0},
                                      {0, 0, 0},
                                      {0, 0, 0},
                                      {0, 0, 0}};
      for (size_t p = 0; p < PartialCount(3); ++p) {
        for (size_t x = 0; x < 3; ++x) {
          EXPECT_NEAR(result[p][r * 3 + x], expected[p][x], 1e-12)
              << "degree " << n << " partial " << p;
        }
      }
    }
  }
}

TEST(TriangularPatchTest, OrdersAboveTheDegreeAreZero) {
  const std::vector<double> control = {1, 2, 3};  // degree 1, dimension 1
  const Buffers result = Evaluate(View(1, control, 1), {0.2, 0.3}, 2);
  EXPECT_NEAR(result[0][0], 0.2 * 1 + 0.3 * 2 + 0.5 * 3, 1e-15);
  EXPECT_NEAR(result[PartialIndex(1, 0)][0], 1 - 3, 1e-15);
  EXPECT_NEAR(result[PartialIndex(0, 1)][0], 2 - 3, 1e-15);
  for (size_t p = PartialIndex(2, 0); p < PartialCount(2); ++p) {
    EXPECT_EQ(result[p][0], 0.0);
  }
}

TEST(TriangularPatchTest, DomainTriangleFollowsTheChainRule) {
  std::mt19937_64 rng(8);
  const std::vector<double> triangle = {0.3, -0.2, 2.1, 0.4, 0.9, 1.7};
  const double ax = triangle[0], ay = triangle[1], bx = triangle[2],
               by = triangle[3], cx = triangle[4], cy = triangle[5];
  // Signed double area and the gradients of u = area(X,B,C) / area and
  // v = area(A,X,C) / area (Cramer).
  const double d = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
  const double ux = (by - cy) / d, uy = (cx - bx) / d;
  const double vx = (cy - ay) / d, vy = (ax - cx) / d;
  for (int n = 1; n <= 6; ++n) {
    const std::vector<double> control =
        RandomValues(rng, TriangularPointCount(n) * 3);
    const std::vector<double> uv = RandomPairs(rng, 12);
    std::vector<double> xy;
    for (size_t r = 0; r < uv.size() / 2; ++r) {
      const double u = uv[2 * r], v = uv[2 * r + 1], w = 1 - u - v;
      xy.push_back(u * ax + v * bx + w * cx);
      xy.push_back(u * ay + v * by + w * cy);
    }
    const Buffers base = Evaluate(View(n, control, 3), uv, 2);
    const Buffers mapped = Evaluate(View(n, control, 3, {}, triangle), xy, 2);
    for (size_t x = 0; x < base[0].size(); ++x) {
      const double su = base[1][x], sv = base[2][x];
      const double suu = base[3][x], suv = base[4][x], svv = base[5][x];
      const double tolerance = 1e-12 * n * n;
      EXPECT_NEAR(mapped[0][x], base[0][x], 1e-13);
      EXPECT_NEAR(mapped[1][x], ux * su + vx * sv, tolerance);
      EXPECT_NEAR(mapped[2][x], uy * su + vy * sv, tolerance);
      EXPECT_NEAR(mapped[3][x],
                  ux * ux * suu + 2 * ux * vx * suv + vx * vx * svv, tolerance);
      EXPECT_NEAR(mapped[4][x],
                  ux * uy * suu + (ux * vy + vx * uy) * suv + vx * vy * svv,
                  tolerance);
      EXPECT_NEAR(mapped[5][x],
                  uy * uy * suu + 2 * uy * vy * suv + vy * vy * svv, tolerance);
    }
  }
}

TEST(TriangularPatchTest, DomainTriangleVerticesAndOutsidePoints) {
  const std::vector<double> control = {1, 2, 3};  // P100, P010, P001
  // Clockwise triangle A, B, C.
  const std::vector<double> triangle = {0, 0, 0, 1, 1, 0};
  const TriangularPatchView patch = View(1, control, 1, {}, triangle);
  const Buffers result = Evaluate(patch, {0, 0, 0, 1, 1, 0, 0.5, 0.5}, 0);
  EXPECT_NEAR(result[0][0], 1, 1e-15);
  EXPECT_NEAR(result[0][1], 2, 1e-15);
  EXPECT_NEAR(result[0][2], 3, 1e-15);
  EXPECT_NEAR(result[0][3], 2.5, 1e-15);
  // A tiny excursion is clamped; a real one names the pair's first value.
  EXPECT_TRUE(EvaluateStatus(patch, {-1e-13, 0.5}).ok());
  const absl::Status outside = EvaluateStatus(patch, {0.2, 0.2, 0.6, 0.6});
  EXPECT_EQ(outside.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(FieldPathOf(outside), "uv[2]");
  EXPECT_EQ(FieldPathOf(EvaluateStatus(patch, {0.2, NAN})), "uv[1]");
}

TEST(TriangularPatchTest, EqualWeightsGiveThePolynomialPatch) {
  std::mt19937_64 rng(9);
  for (int n = 1; n <= 10; ++n) {
    const size_t count = TriangularPointCount(n);
    const std::vector<double> control = RandomValues(rng, count * 3);
    const std::vector<double> weights(count, 2.5);
    const std::vector<double> uv = RandomPairs(rng, 10);
    const Buffers polynomial = Evaluate(View(n, control, 3), uv, 2);
    const Buffers rational = Evaluate(View(n, control, 3, weights), uv, 2);
    for (size_t p = 0; p < polynomial.size(); ++p) {
      for (size_t x = 0; x < polynomial[p].size(); ++x) {
        EXPECT_NEAR(rational[p][x], polynomial[p][x],
                    1e-13 * std::pow(n + 1.0, 2));
      }
    }
  }
}

// Random weights: value and first partials against the long-double
// homogeneous reference and the quotient rule S' = (A' - w' S) / w.
TEST(TriangularPatchTest, RationalMatchesHomogeneousReference) {
  std::mt19937_64 rng(10);
  for (int n = 1; n <= 8; ++n) {
    const size_t count = TriangularPointCount(n);
    const std::vector<double> control = RandomValues(rng, count * 2);
    std::vector<double> weights = RandomValues(rng, count, 0.0, 2.0);
    weights[TriangularIndex(n, n, 0)] = 0.7;
    weights[TriangularIndex(n, 0, n)] = 1.3;
    weights[TriangularIndex(n, 0, 0)] = 0.4;
    std::vector<double> homogeneous;
    for (size_t f = 0; f < count; ++f) {
      homogeneous.insert(homogeneous.end(),
                         {weights[f] * control[2 * f],
                          weights[f] * control[2 * f + 1], weights[f]});
    }
    const std::vector<double> uv = RandomPairs(rng, 10);
    const Buffers result = Evaluate(View(n, control, 2, weights), uv, 1);
    for (size_t r = 0; r < uv.size() / 2; ++r) {
      const auto h = [&](int a, int b) {
        return ReferencePartial(homogeneous, 3, n, a, b, uv[2 * r],
                                uv[2 * r + 1]);
      };
      const std::vector<long double> value = h(0, 0), du = h(1, 0),
                                     dv = h(0, 1);
      for (size_t x = 0; x < 2; ++x) {
        const long double s = value[x] / value[2];
        EXPECT_NEAR(result[0][r * 2 + x], static_cast<double>(s), 1e-13);
        EXPECT_NEAR(result[1][r * 2 + x],
                    static_cast<double>((du[x] - du[2] * s) / value[2]),
                    1e-11 * n);
        EXPECT_NEAR(result[2][r * 2 + x],
                    static_cast<double>((dv[x] - dv[2] * s) / value[2]),
                    1e-11 * n);
      }
    }
  }
}

// The rational quadratic octant: corners (1,0,0), (0,1,0), (0,0,1), edge
// points (1,1,0), (0,1,1), (1,0,1) with weights sqrt(2)/2. Its edges are
// quarter circles; the inside is not on the sphere (at the centroid
// |S| = sqrt(3) (1 + 4s) / (3 (1 + 2s)) ~ 0.916 with s = sqrt(2)/2).
TEST(TriangularPatchTest, RationalOctantHasCircularEdges) {
  const double s = std::sqrt(2.0) / 2;
  // P200, P110, P101, P020, P011, P002.
  const std::vector<double> control = {1, 0, 0, 1, 1, 0, 1, 0, 1,
                                       0, 1, 0, 0, 1, 1, 0, 0, 1};
  const std::vector<double> weights = {1, s, s, 1, s, 1};
  const TriangularPatchView patch = View(2, control, 3, weights);
  std::vector<double> uv;
  for (int q = 0; q <= 20; ++q) {
    const double t = q / 20.0;
    uv.insert(uv.end(), {1 - t, t, 1 - t, 0, 0, 1 - t});
  }
  const Buffers edges = Evaluate(patch, uv, 0);
  for (size_t r = 0; r < uv.size() / 2; ++r) {
    const double* p = edges[0].data() + r * 3;
    EXPECT_NEAR(std::hypot(p[0], p[1], p[2]), 1.0, 1e-14) << r;
    const size_t zero = r % 3 == 0 ? 2 : r % 3 == 1 ? 1 : 0;
    EXPECT_NEAR(p[zero], 0.0, 1e-15);
  }
  const Buffers center = Evaluate(patch, {1.0 / 3, 1.0 / 3}, 0);
  const double norm = std::hypot(center[0][0], center[0][1], center[0][2]);
  EXPECT_NEAR(norm, std::sqrt(3.0) * (1 + 4 * s) / (3 * (1 + 2 * s)), 1e-15);
  EXPECT_GT(std::abs(norm - 1.0), 0.05);
}

TEST(TriangularPatchTest, RationalPartialsMatchFiniteDifferences) {
  const double s = std::sqrt(2.0) / 2;
  const std::vector<double> control = {1, 0, 0, 1, 1, 0, 1, 0, 1,
                                       0, 1, 0, 0, 1, 1, 0, 0, 1};
  const std::vector<double> weights = {1, s, s, 1, s, 1};
  const TriangularPatchView patch = View(2, control, 3, weights);
  const double h = 1e-5;
  for (const auto& [u, v] : {std::pair{0.3, 0.2}, std::pair{0.1, 0.6}}) {
    const Buffers at = Evaluate(patch, {u, v}, 2);
    const Buffers around =
        Evaluate(patch, {u + h, v, u - h, v, u, v + h, u, v - h}, 1);
    for (size_t x = 0; x < 3; ++x) {
      const double* value = around[0].data();
      EXPECT_NEAR(at[1][x], (value[x] - value[3 + x]) / (2 * h), 1e-9);
      EXPECT_NEAR(at[2][x], (value[6 + x] - value[9 + x]) / (2 * h), 1e-9);
      const double* du = around[1].data();
      const double* dv = around[2].data();
      EXPECT_NEAR(at[3][x], (du[x] - du[3 + x]) / (2 * h), 1e-8);      // uu
      EXPECT_NEAR(at[4][x], (du[6 + x] - du[9 + x]) / (2 * h), 1e-8);  // uv
      EXPECT_NEAR(at[4][x], (dv[x] - dv[3 + x]) / (2 * h), 1e-8);      // vu
      EXPECT_NEAR(at[5][x], (dv[6 + x] - dv[9 + x]) / (2 * h), 1e-8);  // vv
    }
  }
}

TEST(TriangularPatchTest, ZeroWeightInsideIsAPointAtInfinity) {
  // Degree 2 with the edge point P110 a direction D = (0, 1) (weight 0): on
  // the edge w = 0, S = (u^2 P200 + 2uv D + v^2 P020) / (u^2 + v^2) with
  // P200 = (1, 0), P020 = (0, 0).
  const std::vector<double> control = {1, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 1};
  const std::vector<double> weights = {1, 0, 1, 1, 1, 1};
  const Buffers result = Evaluate(View(2, control, 2, weights), {0.5, 0.5}, 0);
  EXPECT_NEAR(result[0][0], (0.25 * 1 + 0.5 * 0) / 0.5, 1e-15);
  EXPECT_NEAR(result[0][1], (0.25 * 0 + 0.5 * 1) / 0.5, 1e-15);
}

TEST(TriangularPatchTest, PoolMatchesSerial) {
  std::mt19937_64 rng(11);
  const int n = 5;
  const size_t count = TriangularPointCount(n);
  const std::vector<double> control = RandomValues(rng, count * 3);
  const std::vector<double> weights = RandomValues(rng, count, 0.5, 2.0);
  const std::vector<double> uv = RandomPairs(rng, 1000);
  ThreadPool pool(2);
  const ExecutionContext parallel{.pool = &pool, .grain = 37};
  const TriangularPatchView patch = View(n, control, 3, weights);
  EXPECT_EQ(Evaluate(patch, uv, 2, parallel), Evaluate(patch, uv, 2));
  std::vector<double> serial(uv.size() / 2 * count), pooled(serial.size());
  ASSERT_TRUE(EvaluateTriangularBasis(n, uv, absl::MakeSpan(serial)).ok());
  ASSERT_TRUE(
      EvaluateTriangularBasis(n, uv, absl::MakeSpan(pooled), parallel).ok());
  EXPECT_EQ(serial, pooled);
}

TEST(TriangularPatchTest, CancelledTokenStopsTheBatch) {
  CancellationToken token;
  token.Cancel();
  const ExecutionContext context{.cancellation = &token};
  const std::vector<double> control = {1, 2, 3};
  const std::vector<double> uv = {0.2, 0.3, 0.1, 0.1};
  std::vector<double> buffer(2);
  const absl::Span<double> output[] = {absl::MakeSpan(buffer)};
  EXPECT_EQ(
      EvaluateTriangularPatch(View(1, control, 1), uv, output, context).code(),
      absl::StatusCode::kCancelled);
  std::vector<double> values(6);
  EXPECT_EQ(
      EvaluateTriangularBasis(1, uv, absl::MakeSpan(values), context).code(),
      absl::StatusCode::kCancelled);
}

struct InvalidCase {
  std::string name;
  TriangularPatchView patch;
  std::string field;
};

TEST(TriangularPatchTest, ValidationNamesTheField) {
  const std::vector<double> quadratic = {6, 0, 9, 3, 3, 6, 3, 0, 0,
                                         0, 6, 0, 0, 3, 3, 0, 0, 0};
  const std::vector<double> bad_point = {6, 0, 9, 3, NAN, 6, 3, 0, 0,
                                         0, 6, 0, 0, 3,   3, 0, 0, 0};
  const std::vector<double> five_points(15, 1.0);
  const std::vector<double> ones(6, 1.0), five_weights(5, 1.0);
  const std::vector<double> negative = {1, 1, -1, 1, 1, 1};
  const std::vector<double> infinite = {1, 1, 1, INFINITY, 1, 1};
  const std::vector<double> corner0 = {0, 1, 1, 1, 1, 1};
  const std::vector<double> corner3 = {1, 1, 1, 0, 1, 1};
  const std::vector<double> corner5 = {1, 1, 1, 1, 1, 0};
  const std::vector<double> short_triangle = {0, 0, 1, 0, 0};
  const std::vector<double> nan_triangle = {0, 0, 1, NAN, 0, 1};
  const std::vector<double> collinear = {0, 0, 1, 1, 2, 2};
  const std::vector<double> coincident = {3, 3, 3, 3, 3, 3};
  const std::vector<InvalidCase> cases = {
      {"negative degree", View(-1, quadratic, 3), "degree"},
      {"bad dimension", View(2, quadratic, 0), "control_points.dimension"},
      {"non-finite point", View(2, bad_point, 3),
       "control_points.coordinates[4]"},
      {"wrong count", View(2, five_points, 3), "control_points.coordinates"},
      {"weight count", View(2, quadratic, 3, five_weights), "weights"},
      {"negative weight", View(2, quadratic, 3, negative), "weights[2]"},
      {"infinite weight", View(2, quadratic, 3, infinite), "weights[3]"},
      {"corner P200", View(2, quadratic, 3, corner0), "weights[0]"},
      {"corner P020", View(2, quadratic, 3, corner3), "weights[3]"},
      {"corner P002", View(2, quadratic, 3, corner5), "weights[5]"},
      {"triangle size", View(2, quadratic, 3, {}, short_triangle),
       "domain_triangle"},
      {"triangle value", View(2, quadratic, 3, {}, nan_triangle),
       "domain_triangle[3]"},
      {"collinear", View(2, quadratic, 3, {}, collinear), "domain_triangle"},
      {"coincident", View(2, quadratic, 3, {}, coincident), "domain_triangle"},
  };
  for (const InvalidCase& c : cases) {
    const absl::Status status = ValidateTriangularPatch(c.patch);
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << c.name;
    EXPECT_EQ(FieldPathOf(status), c.field) << c.name;
    EXPECT_EQ(FieldPathOf(EvaluateStatus(c.patch, {0.2, 0.2})), c.field)
        << c.name;
  }
  EXPECT_THAT(
      std::string(ValidateTriangularPatch(View(2, five_points, 3)).message()),
      HasSubstr("6"));
}

TEST(TriangularPatchTest, ZeroEdgeAndInteriorWeightsAreValid) {
  // Degree 3: every non-corner weight zero still leaves the denominator
  // positive on the closed triangle (only the corners matter). With the
  // directions of the zero-weight points 0 and corner points 1, S = 1.
  std::vector<double> weights(10, 0.0), control(10, 0.0);
  for (const auto& [i, j, weight] :
       {std::tuple{3, 0, 1.0}, std::tuple{0, 3, 2.0}, std::tuple{0, 0, 3.0}}) {
    weights[TriangularIndex(3, i, j)] = weight;
    control[TriangularIndex(3, i, j)] = 1.0;
  }
  EXPECT_TRUE(ValidateTriangularPatch(View(3, control, 1, weights)).ok());
  const Buffers result =
      Evaluate(View(3, control, 1, weights), {0.5, 0.5, 0.2, 0.3, 0.0, 0.4}, 1);
  for (size_t r = 0; r < 3; ++r) {
    EXPECT_NEAR(result[0][r], 1.0, 1e-15);
    EXPECT_NEAR(result[1][r], 0.0, 1e-14);
    EXPECT_NEAR(result[2][r], 0.0, 1e-14);
  }
  // A degenerate-looking but tiny triangle is fine: the test is relative.
  const std::vector<double> tiny = {0, 0, 1e-9, 0, 0, 1e-9};
  EXPECT_TRUE(ValidateTriangularPatch(View(3, control, 1, {}, tiny)).ok());
}

TEST(TriangularPatchTest, ParametersMustLieInTheTriangle) {
  const std::vector<double> control = {1, 2, 3};
  const TriangularPatchView patch = View(1, control, 1);
  EXPECT_EQ(FieldPathOf(EvaluateStatus(patch, {0.2, 0.3, 0.1})), "uv");
  EXPECT_EQ(FieldPathOf(EvaluateStatus(patch, {0.2, 0.3, -1e-9, 0.5})),
            "uv[2]");
  EXPECT_EQ(FieldPathOf(EvaluateStatus(patch, {0.2, 0.3, 0.5, -1e-9})),
            "uv[3]");
  EXPECT_EQ(FieldPathOf(EvaluateStatus(patch, {0.6, 0.5})), "uv[0]");
  EXPECT_EQ(FieldPathOf(EvaluateStatus(patch, {NAN, 0.5})), "uv[0]");
  EXPECT_EQ(FieldPathOf(EvaluateStatus(patch, {0.5, INFINITY})), "uv[1]");
  // Excursions within 1e-12 are clamped onto the triangle.
  const Buffers clamped =
      Evaluate(patch, {-1e-13, 1 + 1e-13, 1 + 5e-13, -5e-13}, 0);
  EXPECT_EQ(clamped[0][0], 2.0);
  EXPECT_EQ(clamped[0][1], 1.0);
}

TEST(TriangularPatchTest, RejectsWrongOutput) {
  const std::vector<double> control = {1, 2, 3};
  const TriangularPatchView patch = View(1, control, 1);
  EXPECT_EQ(EvaluateStatus(patch, {0.2, 0.3}, 2).code(),
            absl::StatusCode::kInvalidArgument);
  std::vector<double> small(0);
  const absl::Span<double> output[] = {absl::MakeSpan(small)};
  EXPECT_EQ(
      EvaluateTriangularPatch(patch, std::vector<double>{0.2, 0.3}, output)
          .code(),
      absl::StatusCode::kInvalidArgument);
  EXPECT_TRUE(EvaluateStatus(patch, {}, 3).ok());
}

TEST(TriangularBasisTest, ValidatesItsArguments) {
  std::vector<double> values(3);
  const std::vector<double> uv = {0.2, 0.3};
  EXPECT_EQ(
      FieldPathOf(EvaluateTriangularBasis(-1, uv, absl::MakeSpan(values))),
      "degree");
  EXPECT_EQ(FieldPathOf(EvaluateTriangularBasis(2, uv, absl::MakeSpan(values))),
            "values");
  EXPECT_EQ(FieldPathOf(EvaluateTriangularBasis(
                1, std::vector<double>{0.2, 0.9}, absl::MakeSpan(values))),
            "uv[0]");
  EXPECT_TRUE(EvaluateTriangularBasis(1, uv, absl::MakeSpan(values)).ok());
}

}  // namespace
}  // namespace freeform
