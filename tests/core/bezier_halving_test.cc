// The flat halvings of the bounding-box search (core/src/bezier_halving.h)
// against the library's own splits, an independent algorithm each:
// HalveNet against SplitBezierSurface at 1/2 (de Casteljau per line of the
// lifted net), BisectTriangle (de Casteljau per row parallel to the split
// edge) against BisectTriangularPatch (the triangular de Casteljau pyramid),
// on random rational pieces of degrees 0 to 7 in 1 to 4 dimensions; each
// half must also still be the same geometry (its corners where the whole's
// split points are).
#include "bezier_halving.h"

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
      lifted.push_back(weights[k] * coordinates[k * static_cast<size_t>(d) +
                                                static_cast<size_t>(c)]);
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

std::vector<double> Uniform(std::mt19937_64& random, size_t count, double lo,
                            double hi) {
  std::uniform_real_distribution<double> value(lo, hi);
  std::vector<double> values(count);
  for (double& v : values) v = value(random);
  return values;
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
        net.coordinates =
            Uniform(random, points * static_cast<size_t>(d), -1.0, 1.0);
        net.weights = Uniform(random, points, 0.25, 4.0);
        const std::vector<double> lifted =
            Lifted(net.coordinates, net.weights, d);
        for (const bool in_u : {true, false}) {
          const std::string what =
              absl::StrCat(count_u, "x", count_v, " in ", d, "-D, in ",
                           in_u ? "u" : "v");
          std::vector<double> first(lifted.size()), second(lifted.size());
          HalveNet(lifted.data(), count_u, count_v, d + 1, in_u,
                   first.data(), second.data());
          absl::StatusOr<std::vector<SurfaceData>> expected =
              SplitBezierSurface(net.bezier_view(), in_u, 0.5);
          ASSERT_TRUE(expected.ok()) << expected.status();
          ExpectSamePoints(first, (*expected)[0].coordinates,
                           (*expected)[0].weights, d, what + " first");
          ExpectSamePoints(second, (*expected)[1].coordinates,
                           (*expected)[1].weights, d, what + " second");
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
      patch.coordinates =
          Uniform(random, points * static_cast<size_t>(d), -1.0, 1.0);
      patch.weights = Uniform(random, points, 0.25, 4.0);
      const std::vector<double> lifted =
          Lifted(patch.coordinates, patch.weights, d);
      for (int edge = 0; edge < 3; ++edge) {
        const std::string what =
            absl::StrCat("degree ", n, " in ", d, "-D, edge ", edge);
        std::vector<double> first(lifted.size()), second(lifted.size());
        BisectTriangle(lifted.data(), n, d + 1, edge, first.data(),
                       second.data(), scratch);
        absl::StatusOr<std::vector<TriangularPatchData>> expected =
            BisectTriangularPatch(patch.view(), edge);
        ASSERT_TRUE(expected.ok()) << expected.status();
        ExpectSamePoints(first, (*expected)[0].coordinates,
                         (*expected)[0].weights, d, what + " first");
        ExpectSamePoints(second, (*expected)[1].coordinates,
                         (*expected)[1].weights, d, what + " second");
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
