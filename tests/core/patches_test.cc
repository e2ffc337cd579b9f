#include "freeform/core/patches.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "freeform/core/bezier.h"

namespace freeform {
namespace {

// Independent reference: a bicubic Bezier net evaluated as curves in v for
// every row, then one curve in u through the results (derivative orders
// `order_u`, `order_v`).
std::vector<double> TensorPoint(const std::vector<double>& net, int dimension,
                                double u, double v, int order_u, int order_v) {
  const size_t dim = static_cast<size_t>(dimension);
  std::vector<double> column(4 * dim);
  for (size_t i = 0; i < 4; ++i) {
    const std::vector<double> row(net.begin() + 4 * i * dim,
                                  net.begin() + 4 * (i + 1) * dim);
    std::vector<std::vector<double>> buffers(order_v + 1,
                                             std::vector<double>(dim));
    std::vector<absl::Span<double>> output(buffers.begin(), buffers.end());
    EXPECT_TRUE(EvaluateBezierCurve({{dimension, row}, {}},
                                    std::vector<double>{v}, output)
                    .ok());
    std::copy(buffers[order_v].begin(), buffers[order_v].end(),
              column.begin() + i * dim);
  }
  std::vector<std::vector<double>> buffers(order_u + 1,
                                           std::vector<double>(dim));
  std::vector<absl::Span<double>> output(buffers.begin(), buffers.end());
  EXPECT_TRUE(EvaluateBezierCurve({{dimension, column}, {}},
                                  std::vector<double>{u}, output)
                  .ok());
  return buffers[order_u];
}

TEST(PatchesTest, InterpolatingPatchPassesThroughItsSixteenPoints) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> uniform(-5, 5);
  std::vector<double> points(16 * 3);
  for (double& value : points) value = uniform(rng);
  const std::vector<double> net = InterpolatingToBezierNet(3, points);
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const std::vector<double> at =
          TensorPoint(net, 3, i / 3.0, j / 3.0, 0, 0);
      for (int x = 0; x < 3; ++x) {
        EXPECT_NEAR(at[x], points[(4 * i + j) * 3 + x], 1e-13) << i << "," << j;
      }
    }
  }
}

// f(u, v) = sum_{a,b <= 3} c_ab u^a v^b: its corner data make a Ferguson
// patch that is f itself.
TEST(PatchesTest, HermitePatchReproducesBicubicPolynomials) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> uniform(-1, 1);
  double c[4][4][2];
  for (auto& row : c) {
    for (auto& entry : row) {
      for (double& value : entry) value = uniform(rng);
    }
  }
  auto f = [&](double u, double v, int du, int dv, int x) {
    double sum = 0;
    for (int a = du; a < 4; ++a) {
      for (int b = dv; b < 4; ++b) {
        double factor = 1;
        for (int q = 0; q < du; ++q) factor *= a - q;
        for (int q = 0; q < dv; ++q) factor *= b - q;
        sum += factor * c[a][b][x] * std::pow(u, a - du) * std::pow(v, b - dv);
      }
    }
    return sum;
  };
  std::vector<double> positions, su, sv, twists;
  for (int a = 0; a <= 1; ++a) {
    for (int b = 0; b <= 1; ++b) {
      for (int x = 0; x < 2; ++x) {
        positions.push_back(f(a, b, 0, 0, x));
        su.push_back(f(a, b, 1, 0, x));
        sv.push_back(f(a, b, 0, 1, x));
        twists.push_back(f(a, b, 1, 1, x));
      }
    }
  }
  const std::vector<double> net =
      HermiteToBezierNet(2, positions, su, sv, twists);
  for (double u : {0.0, 0.2, 0.5, 0.9, 1.0}) {
    for (double v : {0.0, 0.3, 0.6, 1.0}) {
      for (auto [du, dv] : {std::pair{0, 0}, {1, 0}, {0, 1}, {1, 1}, {2, 1}}) {
        const std::vector<double> at = TensorPoint(net, 2, u, v, du, dv);
        for (int x = 0; x < 2; ++x) {
          EXPECT_NEAR(at[x], f(u, v, du, dv, x), 1e-12)
              << u << "," << v << " d" << du << dv;
        }
      }
    }
  }
}

}  // namespace
}  // namespace freeform
