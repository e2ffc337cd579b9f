// The exact predicates and expansions (core/src/triangulation/) against
// exact integer arithmetic: every coordinate is an integer multiple of a
// power of two, so that __int128 evaluates the determinants exactly.
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "gtest/gtest.h"
#include "triangulation/expansion.h"
#include "triangulation/insertion_order.h"
#include "triangulation/predicates.h"

namespace freeform::internal {
namespace {

__extension__ typedef __int128 Int;

int SignOf(Int value) { return value > 0 ? 1 : (value < 0 ? -1 : 0); }
int SignOf(double value) { return value > 0 ? 1 : (value < 0 ? -1 : 0); }

// A point of integer coordinates in units of 2^-53.
struct IntPoint {
  int64_t x;
  int64_t y;
  Point2 ToPoint() const {
    return {std::ldexp(static_cast<double>(x), -53),
            std::ldexp(static_cast<double>(y), -53)};
  }
};

Int ExactOrient(IntPoint a, IntPoint b, IntPoint c) {
  return Int{a.x - c.x} * (b.y - c.y) - Int{a.y - c.y} * (b.x - c.x);
}

Int ExactInCircle(IntPoint a, IntPoint b, IntPoint c, IntPoint d) {
  const Int adx = a.x - d.x, ady = a.y - d.y, bdx = b.x - d.x, bdy = b.y - d.y,
            cdx = c.x - d.x, cdy = c.y - d.y;
  return (adx * adx + ady * ady) * (bdx * cdy - bdy * cdx) +
         (bdx * bdx + bdy * bdy) * (cdx * ady - cdy * adx) +
         (cdx * cdx + cdy * cdy) * (adx * bdy - ady * bdx);
}

// Shewchuk's near-collinear case: a 256 x 256 grid of points an ulp apart
// at (0.5, 0.5), against the line through (12, 12) and (24, 24). The naive
// formula gets many signs wrong; the predicate none.
TEST(Orient2dTest, ExactOnUlpGridAgainstCollinearLine) {
  constexpr int64_t kHalf = int64_t{1} << 52;  // 0.5 in units of 2^-53
  const IntPoint b{12 * (kHalf * 2), 12 * (kHalf * 2)};
  const IntPoint c{24 * (kHalf * 2), 24 * (kHalf * 2)};
  int naive_wrong = 0, zeros = 0;
  for (int64_t i = 0; i < 256; ++i) {
    for (int64_t j = 0; j < 256; ++j) {
      const IntPoint a{kHalf + i, kHalf + j};
      const int exact = SignOf(ExactOrient(a, b, c));
      const Point2 pa = a.ToPoint(), pb = b.ToPoint(), pc = c.ToPoint();
      ASSERT_EQ(SignOf(Orient2d(pa, pb, pc)), exact) << i << ", " << j;
      ASSERT_EQ(SignOf(Orient2d(pb, pc, pa)), exact);
      ASSERT_EQ(SignOf(Orient2d(pb, pa, pc)), -exact);
      ASSERT_EQ(SignOf(Orient2dExact(pa, pb, pc)), exact);
      const double naive =
          (pa.x - pc.x) * (pb.y - pc.y) - (pa.y - pc.y) * (pb.x - pc.x);
      naive_wrong += SignOf(naive) != exact;
      zeros += exact == 0;
    }
  }
  EXPECT_EQ(zeros, 256);  // the diagonal i == j
  EXPECT_GT(naive_wrong, 1000);
}

// Twenty points exactly on the circle of radius 25 * 2^16 ulps around
// (0.5, 0.5) (Pythagorean triples), every quadruple with the fourth point
// moved by up to 2 ulps in x and y: zero exactly on the circle, else the
// sign of the exact determinant.
TEST(InCircleTest, ExactOnPerturbedCocircularPoints) {
  constexpr int64_t kCenter = int64_t{1} << 52;
  constexpr int64_t kScale = int64_t{1} << 16;
  const std::array<std::array<int64_t, 2>, 5> triples = {
      {{7, 24}, {15, 20}, {20, 15}, {24, 7}, {25, 0}}};
  std::vector<IntPoint> circle;
  for (const auto& [p, q] : triples) {
    for (const int sx : {1, -1}) {
      for (const int sy : {1, -1}) {
        if (q == 0 && sy < 0) continue;
        circle.push_back(
            {kCenter + sx * p * kScale, kCenter + sy * q * kScale});
        if (q == 0) circle.push_back({kCenter, kCenter + sx * p * kScale});
      }
    }
  }
  ASSERT_EQ(circle.size(), 20u);
  int64_t checked = 0, cocircular = 0;
  for (size_t i = 0; i < circle.size(); i += 3) {
    for (size_t j = i + 1; j < circle.size(); j += 2) {
      for (size_t k = j + 1; k < circle.size(); ++k) {
        for (size_t l = 0; l < circle.size(); l += 4) {
          if (l == i || l == j || l == k) continue;
          for (int64_t dx = -2; dx <= 2; ++dx) {
            for (int64_t dy = -2; dy <= 2; ++dy) {
              const IntPoint d{circle[l].x + dx, circle[l].y + dy};
              const int exact =
                  SignOf(ExactInCircle(circle[i], circle[j], circle[k], d));
              const Point2 a = circle[i].ToPoint(), b = circle[j].ToPoint(),
                           c = circle[k].ToPoint(), p = d.ToPoint();
              ASSERT_EQ(SignOf(InCircle(a, b, c, p)), exact);
              ASSERT_EQ(SignOf(InCircle(b, a, c, p)), -exact);
              ASSERT_EQ(SignOf(InCircleExact(a, b, c, p)), exact);
              if (dx == 0 && dy == 0) {
                ASSERT_EQ(exact, 0);
              }
              cocircular += exact == 0;
              ++checked;
            }
          }
        }
      }
    }
  }
  EXPECT_GT(checked, 10000);
  // No error bound certifies a zero: these took the exact evaluation.
  EXPECT_GT(cocircular, 500);
}

// Random points, integer multiples of 2^-53 below 2^-30 in magnitude: the
// predicates agree with the exact sign.
TEST(PredicatesTest, AgreeWithIntegersOnRandomPoints) {
  uint64_t state = 12345;
  const auto next = [&state]() {
    state = state * 6364136223846793005u + 1442695040888963407u;
    return static_cast<int64_t>(state >> 40) - (int64_t{1} << 23);
  };
  for (int trial = 0; trial < 20000; ++trial) {
    std::array<IntPoint, 4> p;
    for (IntPoint& q : p) q = {next(), next()};
    const Point2 a = p[0].ToPoint(), b = p[1].ToPoint(), c = p[2].ToPoint(),
                 d = p[3].ToPoint();
    ASSERT_EQ(SignOf(Orient2d(a, b, c)), SignOf(ExactOrient(p[0], p[1], p[2])));
    ASSERT_EQ(SignOf(InCircle(a, b, c, d)),
              SignOf(ExactInCircle(p[0], p[1], p[2], p[3])));
  }
}

// The extremes of the exact range: the sign of tiny and huge determinants.
TEST(PredicatesTest, ExactAtTheRangeLimits) {
  for (const double unit : {2 * kMinTriangulationMagnitude, 0x1p-100, 1.0,
                            0x1p100, kMaxTriangulationMagnitude / 4}) {
    const Point2 a{unit, unit}, b{2 * unit, 2 * unit}, c{3 * unit, 3 * unit};
    EXPECT_EQ(Orient2d(a, b, c), 0.0) << unit;
    const Point2 above{3 * unit, std::nextafter(3 * unit, 4 * unit)};
    EXPECT_GT(Orient2d(a, b, above), 0.0) << unit;
    const Point2 p0{unit, 0}, p1{0, unit}, p2{-unit, 0}, p3{0, -unit};
    EXPECT_EQ(InCircle(p0, p1, p2, p3), 0.0) << unit;
    EXPECT_GT(InCircle(p0, p1, p2, {0, std::nextafter(-unit, 0.0)}), 0.0);
    EXPECT_LT(InCircle(p0, p1, p2, {0, std::nextafter(-unit, -2 * unit)}), 0.0);
  }
  EXPECT_TRUE(InTriangulationRange(0.0));
  EXPECT_TRUE(InTriangulationRange(-kMaxTriangulationMagnitude));
  EXPECT_FALSE(InTriangulationRange(0x1p201));
  EXPECT_FALSE(InTriangulationRange(0x1p-181));
  EXPECT_FALSE(InTriangulationRange(std::nan("")));
}

TEST(ExpansionTest, SumsAndProductsAreExact) {
  // (1 + 2^-60) - 1 = 2^-60, which double arithmetic loses.
  const Expansion sum = Expansion::Of(1.0).Grown(0x1p-60).Grown(-1.0);
  ASSERT_EQ(sum.components().size(), 1u);
  EXPECT_EQ(sum.components()[0], 0x1p-60);
  // (2^30 + 1)^2 - 2^60 - 2^31 = 1.
  const Expansion x = Expansion::Of(0x1p30).Grown(1.0);
  const Expansion square =
      x * x - Expansion::Of(0x1p60) - Expansion::Of(0x1p31);
  EXPECT_EQ(square.Sign(), 1);
  EXPECT_EQ(square.Estimate(), 1.0);
  EXPECT_EQ((x - x).Sign(), 0);
  EXPECT_TRUE((x - x).components().empty());
  EXPECT_EQ(Expansion::Difference(1.0, 0x1p-80).Estimate(), 1.0);
  EXPECT_EQ(Expansion::Difference(1.0, 0x1p-80).components().size(), 2u);
  EXPECT_EQ(Expansion::Of(3.0).Scaled(0x1p-70).Estimate(), 3 * 0x1p-70);
}

// The Hilbert index visits the cells of the grid so that consecutive
// indices are neighbouring cells (checked on the 2^16 grid's corner 8 x 8:
// the curve of the full grid passes it in 64 consecutive indices).
TEST(InsertionOrderTest, HilbertCurveStepsBetweenNeighbours) {
  std::vector<std::array<int64_t, 2>> by_index(64);
  std::vector<uint64_t> indices;
  for (uint32_t x = 0; x < 8; ++x) {
    for (uint32_t y = 0; y < 8; ++y) indices.push_back(HilbertIndex(x, y));
  }
  std::sort(indices.begin(), indices.end());
  EXPECT_EQ(indices.front(), 0u);
  EXPECT_EQ(indices.back(), 63u);
  for (uint32_t x = 0; x < 8; ++x) {
    for (uint32_t y = 0; y < 8; ++y) by_index[HilbertIndex(x, y)] = {x, y};
  }
  for (size_t i = 1; i < by_index.size(); ++i) {
    EXPECT_EQ(std::abs(by_index[i][0] - by_index[i - 1][0]) +
                  std::abs(by_index[i][1] - by_index[i - 1][1]),
              1)
        << i;
  }
}

TEST(InsertionOrderTest, IsADeterministicPermutation) {
  std::vector<Point2> points;
  for (int i = 0; i < 5000; ++i) {
    points.push_back({std::sin(i * 1.7), std::cos(i * 0.31)});
  }
  const std::vector<int32_t> order = BiasedRandomizedOrder(points);
  EXPECT_EQ(order, BiasedRandomizedOrder(points));
  std::vector<int32_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (int i = 0; i < 5000; ++i) ASSERT_EQ(sorted[i], i);
}

}  // namespace
}  // namespace freeform::internal
