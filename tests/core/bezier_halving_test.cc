// The flat halvings of the bounding-box search
// (core/src/refine/bezier_halving.h) against the library's own splits, an
// independent algorithm each: HalveNet against SplitBezierSurface at 1/2 (de
// Casteljau per line of the lifted net), BisectTriangle (de Casteljau per row
// parallel to the split edge) against BisectTriangularPatch (the triangular de
// Casteljau pyramid), on random rational pieces of degrees 0 to 7 in 1 to 4
// dimensions; each half must also still be the same geometry (its corners where
// the whole's split points are).
#include "refine/bezier_halving.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <random>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "freeform/core/elevation.h"
#include "freeform/core/geometry_data.h"
#include "freeform/core/subdivision.h"
#include "freeform/core/triangular.h"

namespace freeform::internal {
namespace {

// Lifted values of points with weights: (w x, w) per point.
std::vector<double> Lifted(const std::vector<double>& coordinates,
                           const std::vector<double>& weights, int d) {
  std::vector<double> lifted;
  for (size_t k = 0; k < weights.size(); ++k) {
    for (int c = 0; c < d; ++c) {
      lifted.push_back(
          weights[k] *
          coordinates[k * static_cast<size_t>(d) + static_cast<size_t>(c)]);
    }
    lifted.push_back(weights[k]);
  }
  return lifted;
}

// Expects the lifted `halved` to project onto `coordinates` and `weights`.
void ExpectSamePoints(const std::vector<double>& halved,
                      const std::vector<double>& coordinates,
                      const std::vector<double>& weights, int d,
                      const std::string& what) {
  ASSERT_EQ(halved.size(), weights.size() * static_cast<size_t>(d + 1));
  for (size_t k = 0; k < weights.size(); ++k) {
    const double* point = &halved[k * static_cast<size_t>(d + 1)];
    EXPECT_NEAR(point[d], weights[k], 1e-14 * std::abs(weights[k]))
        << what << " weight " << k;
    for (int c = 0; c < d; ++c) {
      const double expected =
          coordinates[k * static_cast<size_t>(d) + static_cast<size_t>(c)];
      EXPECT_NEAR(point[c] / point[d], expected, 1e-13)
          << what << " point " << k << " coordinate " << c;
    }
  }
}

// Expects the lifted halves `first` and `second` to be the library's
// halves `expected` (SurfaceData or TriangularPatchData, two of them).
template <typename Piece>
void ExpectHalves(const std::vector<double>& first,
                  const std::vector<double>& second,
                  const absl::StatusOr<std::vector<Piece>>& expected, int d,
                  const std::string& what) {
  ASSERT_TRUE(expected.ok()) << expected.status();
  ASSERT_EQ(expected->size(), 2u);
  ExpectSamePoints(first, (*expected)[0].coordinates, (*expected)[0].weights, d,
                   what + " first");
  ExpectSamePoints(second, (*expected)[1].coordinates, (*expected)[1].weights,
                   d, what + " second");
}

std::vector<double> Uniform(std::mt19937_64& random, size_t count, double lo,
                            double hi) {
  std::uniform_real_distribution<double> value(lo, hi);
  std::vector<double> values(count);
  for (double& v : values) v = value(random);
  return values;
}

// RandomRational fills `coordinates` (in [-1, 1]) and `weights` (in
// [0.25, 4]) of `points` points in d dimensions and returns them lifted.
std::vector<double> RandomRational(std::mt19937_64& random, size_t points,
                                   int d, std::vector<double>& coordinates,
                                   std::vector<double>& weights) {
  coordinates = Uniform(random, points * static_cast<size_t>(d), -1.0, 1.0);
  weights = Uniform(random, points, 0.25, 4.0);
  return Lifted(coordinates, weights, d);
}

TEST(BezierHalving, HalveNetMatchesSplitBezierSurfaceAtOneHalf) {
  std::mt19937_64 random(7);
  for (int count_u = 1; count_u <= 8; ++count_u) {
    for (int count_v = 1; count_v <= 5; ++count_v) {
      for (int d = 1; d <= 4; ++d) {
        const size_t points =
            static_cast<size_t>(count_u) * static_cast<size_t>(count_v);
        SurfaceData net;
        net.dimension = d;
        net.count_u = count_u;
        net.count_v = count_v;
        const std::vector<double> lifted =
            RandomRational(random, points, d, net.coordinates, net.weights);
        for (const bool in_u : {true, false}) {
          const std::string what = absl::StrCat(count_u, "x", count_v, " in ",
                                                d, "-D, in ", in_u ? "u" : "v");
          std::vector<double> first(lifted.size()), second(lifted.size());
          HalveNet(lifted.data(), count_u, count_v, d + 1, in_u, first.data(),
                   second.data());
          ExpectHalves(first, second,
                       SplitBezierSurface(net.bezier_view(), in_u, 0.5), d,
                       what);
        }
      }
    }
  }
}

TEST(BezierHalving, BisectTriangleMatchesBisectTriangularPatch) {
  std::mt19937_64 random(11);
  std::vector<double> scratch;
  for (int n = 0; n <= 7; ++n) {
    for (int d = 1; d <= 4; ++d) {
      const size_t points = TriangularPointCount(n);
      TriangularPatchData patch;
      patch.degree = n;
      patch.dimension = d;
      const std::vector<double> lifted =
          RandomRational(random, points, d, patch.coordinates, patch.weights);
      for (int edge = 0; edge < 3; ++edge) {
        const std::string what =
            absl::StrCat("degree ", n, " in ", d, "-D, edge ", edge);
        std::vector<double> first(lifted.size()), second(lifted.size());
        BisectTriangle(lifted.data(), n, d + 1, edge, first.data(),
                       second.data(), scratch);
        ExpectHalves(first, second, BisectTriangularPatch(patch.view(), edge),
                     d, what);
      }
    }
  }
}

TEST(BezierHalving, MidpointsOfHugeCoordinatesDoNotOverflow) {
  // Two points near the largest double: (a + b) / 2 would overflow.
  const double big = 1.5e308;
  const std::vector<double> line = {big, big};
  std::vector<double> first(2), second(2);
  HalveNet(line.data(), 2, 1, 1, true, first.data(), second.data());
  EXPECT_EQ(first[1], big);
  EXPECT_EQ(second[0], big);
}

}  // namespace
}  // namespace freeform::internal
