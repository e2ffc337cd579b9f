#include "linalg/symmetric_eigen.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numeric>
#include <vector>

namespace freeform::internal {
namespace {

constexpr int kMaxSweeps = 64;

// Rotate applies the Jacobi rotation J (J_pp = J_qq = c, J_pq = s,
// J_qp = -s) as a <- J^T a J and v <- v J.
void Rotate(size_t n, size_t p, size_t q, double c, double s,
            std::vector<double>& a, std::vector<double>& v) {
  for (size_t k = 0; k < n; ++k) {
    const double kp = a[k * n + p], kq = a[k * n + q];
    a[k * n + p] = c * kp - s * kq;
    a[k * n + q] = s * kp + c * kq;
  }
  for (size_t k = 0; k < n; ++k) {
    const double pk = a[p * n + k], qk = a[q * n + k];
    a[p * n + k] = c * pk - s * qk;
    a[q * n + k] = s * pk + c * qk;
  }
  for (size_t k = 0; k < n; ++k) {
    const double kp = v[k * n + p], kq = v[k * n + q];
    v[k * n + p] = c * kp - s * kq;
    v[k * n + q] = s * kp + c * kq;
  }
}

// Annihilate zeroes a_pq by the rotation with tan = t, the smaller root of
// t^2 + 2 theta t - 1 = 0, theta = (a_qq - a_pp) / (2 a_pq).
void Annihilate(size_t n, size_t p, size_t q, std::vector<double>& a,
                std::vector<double>& v) {
  const double apq = a[p * n + q];
  if (apq == 0.0) return;
  const double theta = (a[q * n + q] - a[p * n + p]) / (2 * apq);
  const double t = std::abs(theta) > 1e150
                       ? 0.5 / theta
                       : std::copysign(1.0, theta) /
                             (std::abs(theta) + std::sqrt(theta * theta + 1));
  const double c = 1 / std::sqrt(t * t + 1);
  Rotate(n, p, q, c, t * c, a, v);
  a[p * n + q] = a[q * n + p] = 0.0;
}

}  // namespace

SymmetricEigenSystem SymmetricEigen(size_t n, std::vector<double> a) {
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = 0; j < i; ++j) a[i * n + j] = a[j * n + i];
  }
  std::vector<double> v(n * n, 0.0);
  for (size_t i = 0; i < n; ++i) v[i * n + i] = 1.0;
  double norm = 0;
  for (double value : a) norm += value * value;
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    double off = 0;
    for (size_t p = 0; p < n; ++p) {
      for (size_t q = p + 1; q < n; ++q) off += a[p * n + q] * a[p * n + q];
    }
    if (!(off > 1e-30 * norm)) break;
    for (size_t p = 0; p < n; ++p) {
      for (size_t q = p + 1; q < n; ++q) Annihilate(n, p, q, a, v);
    }
  }
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t x, size_t y) {
    return a[x * n + x] > a[y * n + y];
  });
  SymmetricEigenSystem system;
  system.values.resize(n);
  system.vectors.resize(n * n);
  for (size_t k = 0; k < n; ++k) {
    system.values[k] = a[order[k] * n + order[k]];
    for (size_t c = 0; c < n; ++c) {
      system.vectors[k * n + c] = v[c * n + order[k]];
    }
  }
  return system;
}

}  // namespace freeform::internal
