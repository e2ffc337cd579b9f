#include "freeform/core/patches.h"

namespace freeform {
namespace {

// Rows of the inverse collocation matrix of the cubic Bernstein basis at
// the nodes 0, 1/3, 2/3, 1.
constexpr double kInterpolationToBezier[4][4] = {
    {1.0, 0.0, 0.0, 0.0},
    {-5.0 / 6.0, 3.0, -1.5, 1.0 / 3.0},
    {1.0 / 3.0, -1.5, 3.0, -5.0 / 6.0},
    {0.0, 0.0, 0.0, 1.0}};

}  // namespace

std::vector<double> InterpolatingToBezierNet(int dimension,
                                             absl::Span<const double> points) {
  const size_t dim = static_cast<size_t>(dimension);
  // Rows first (along v, index j), then columns (along u, index i).
  std::vector<double> rows(16 * dim, 0.0);
  for (size_t i = 0; i < 4; ++i) {
    for (size_t j = 0; j < 4; ++j) {
      for (size_t m = 0; m < 4; ++m) {
        for (size_t x = 0; x < dim; ++x) {
          rows[(4 * i + j) * dim + x] +=
              kInterpolationToBezier[j][m] * points[(4 * i + m) * dim + x];
        }
      }
    }
  }
  std::vector<double> net(16 * dim, 0.0);
  for (size_t i = 0; i < 4; ++i) {
    for (size_t j = 0; j < 4; ++j) {
      for (size_t m = 0; m < 4; ++m) {
        for (size_t x = 0; x < dim; ++x) {
          net[(4 * i + j) * dim + x] +=
              kInterpolationToBezier[i][m] * rows[(4 * m + j) * dim + x];
        }
      }
    }
  }
  return net;
}

std::vector<double> HermiteToBezierNet(int dimension,
                                       absl::Span<const double> positions,
                                       absl::Span<const double> derivatives_u,
                                       absl::Span<const double> derivatives_v,
                                       absl::Span<const double> twists) {
  const size_t dim = static_cast<size_t>(dimension);
  std::vector<double> net(16 * dim, 0.0);
  for (int a = 0; a <= 1; ++a) {
    for (int b = 0; b <= 1; ++b) {
      const size_t corner = static_cast<size_t>(2 * a + b) * dim;
      const double su = a == 0 ? 1.0 : -1.0;
      const double sv = b == 0 ? 1.0 : -1.0;
      const int i = 3 * a;
      const int j = 3 * b;
      const int ni = i + static_cast<int>(su);
      const int nj = j + static_cast<int>(sv);
      for (size_t x = 0; x < dim; ++x) {
        const double p = positions[corner + x];
        const double du = derivatives_u[corner + x] / 3.0;
        const double dv = derivatives_v[corner + x] / 3.0;
        const double twist = twists.empty() ? 0.0 : twists[corner + x] / 9.0;
        net[(4 * i + j) * dim + x] = p;
        net[(4 * ni + j) * dim + x] = p + su * du;
        net[(4 * i + nj) * dim + x] = p + sv * dv;
        net[(4 * ni + nj) * dim + x] = p + su * du + sv * dv + su * sv * twist;
      }
    }
  }
  return net;
}

}  // namespace freeform
