// The definitions behind reference.h: direct sums and recurrences.
#include "reference.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace freeform::reliability {
namespace {

// Derivative `order` at t of the polynomial sum_m c[m] t^m.
double Polynomial(Coordinates c, double t, int order) {
  double sum = 0;
  double power = 1;
  for (size_t m = static_cast<size_t>(order); m < c.size(); ++m) {
    double factor = 1;
    for (int f = 0; f < order; ++f) factor *= static_cast<double>(m) - f;
    sum += c[m] * factor * power;
    power *= t;
  }
  return sum;
}

// N_{i,p} (derivative `order`) on the non-empty span `span`.
double CoxDeBoor(int i, int p, Coordinates knots, double u, int span,
                 int order) {
  if (order > p) return 0;
  if (p == 0) return i == span ? 1 : 0;
  const auto at = [&](int k) { return knots[static_cast<size_t>(k)]; };
  const double left = at(i + p) - at(i);
  const double right = at(i + p + 1) - at(i + 1);
  if (order == 0) {
    const double a =
        left > 0 ? (u - at(i)) / left * CoxDeBoor(i, p - 1, knots, u, span, 0)
                 : 0;
    const double b = right > 0 ? (at(i + p + 1) - u) / right *
                                     CoxDeBoor(i + 1, p - 1, knots, u, span, 0)
                               : 0;
    return a + b;
  }
  const double a =
      left > 0 ? CoxDeBoor(i, p - 1, knots, u, span, order - 1) / left : 0;
  const double b =
      right > 0 ? CoxDeBoor(i + 1, p - 1, knots, u, span, order - 1) / right
                : 0;
  return p * (a - b);
}

double Factorial(int n) {
  double result = 1;
  for (int k = 2; k <= n; ++k) result *= k;
  return result;
}

}  // namespace

double Binomial(int n, int k) {
  if (k < 0 || k > n) return 0;
  double result = 1;
  for (int j = 1; j <= k; ++j) result = result * (n - k + j) / j;
  return result;
}

double Bernstein(int n, int i, double t, int order) {
  if (i < 0 || i > n) return 0;
  if (order > 0) {
    return n * (Bernstein(n - 1, i - 1, t, order - 1) -
                Bernstein(n - 1, i, t, order - 1));
  }
  return Binomial(n, i) * std::pow(1 - t, n - i) * std::pow(t, i);
}

int BSplineSpan(int p, Coordinates knots, double u) {
  const int n = static_cast<int>(knots.size()) - p - 2;
  const auto at = [&](int k) { return knots[static_cast<size_t>(k)]; };
  int m = p;
  while (m < n && at(m + 1) <= u) ++m;
  while (m > p && at(m) == at(m + 1)) --m;
  return m;
}

double BSpline(int i, int p, Coordinates knots, double u, int order) {
  return CoxDeBoor(i, p, knots, u, BSplineSpan(p, knots, u), order);
}

double Lagrange(Coordinates nodes, int i, double t, int order) {
  // prod_{j != i} (t - t_j) / (t_i - t_j), expanded into monomials.
  Values c = {1.0};
  const auto index = static_cast<size_t>(i);
  for (size_t j = 0; j < nodes.size(); ++j) {
    if (j == index) continue;
    const double scale = 1 / (nodes[index] - nodes[j]);
    Values next(c.size() + 1, 0.0);
    for (size_t m = 0; m < c.size(); ++m) {
      next[m + 1] += c[m] * scale;
      next[m] -= c[m] * nodes[j] * scale;
    }
    c = std::move(next);
  }
  return Polynomial(c, t, order);
}

double Hermite(int i, double t, int order) {
  static constexpr double kCoefficients[4][4] = {
      {1, 0, -3, 2}, {0, 0, 3, -2}, {0, 1, -2, 1}, {0, 0, -1, 1}};
  return Polynomial(kCoefficients[i], t, order);
}

BasisDerivatives BernsteinBasis(int n, double t, int orders) {
  BasisDerivatives result(static_cast<size_t>(orders) + 1,
                          Values(static_cast<size_t>(n) + 1));
  for (int k = 0; k <= orders; ++k) {
    for (int i = 0; i <= n; ++i) result[k][i] = Bernstein(n, i, t, k);
  }
  return result;
}

BasisDerivatives BSplineBasis(int p, Coordinates knots, double u, int orders) {
  const int count = static_cast<int>(knots.size()) - p - 1;
  const int span = BSplineSpan(p, knots, u);
  BasisDerivatives result(static_cast<size_t>(orders) + 1,
                          Values(static_cast<size_t>(count), 0.0));
  for (int k = 0; k <= orders; ++k) {
    for (int i = std::max(0, span - p); i <= std::min(span, count - 1); ++i) {
      result[k][i] = CoxDeBoor(i, p, knots, u, span, k);
    }
  }
  return result;
}

BasisDerivatives LagrangeBasis(Coordinates nodes, double t, int orders) {
  BasisDerivatives result(static_cast<size_t>(orders) + 1,
                          Values(nodes.size()));
  for (int k = 0; k <= orders; ++k) {
    for (size_t i = 0; i < nodes.size(); ++i) {
      result[k][i] = Lagrange(nodes, static_cast<int>(i), t, k);
    }
  }
  return result;
}

std::vector<Values> Combine(int dimension, Coordinates points,
                            Coordinates weights,
                            const BasisDerivatives& functions) {
  const auto d = static_cast<size_t>(dimension);
  const size_t orders = functions.size();
  const size_t count = points.size() / d;
  // Homogeneous sums: A^(k) (d values) and W^(k).
  std::vector<Values> a(orders, Values(d, 0.0));
  Values w(orders, 0.0);
  for (size_t k = 0; k < orders; ++k) {
    for (size_t i = 0; i < count; ++i) {
      const double f = functions[k][i];
      const double weight = weights.empty() ? 1.0 : weights[i];
      const double factor = weight != 0 ? weight : 1.0;  // a direction
      for (size_t j = 0; j < d; ++j) a[k][j] += f * factor * points[i * d + j];
      w[k] += f * weight;
    }
  }
  if (weights.empty()) return a;
  std::vector<Values> c(orders, Values(d));
  for (size_t k = 0; k < orders; ++k) {
    for (size_t j = 0; j < d; ++j) {
      double value = a[k][j];
      for (size_t i = 1; i <= k; ++i) {
        value -= Binomial(static_cast<int>(k), static_cast<int>(i)) * w[i] *
                 c[k - i][j];
      }
      c[k][j] = value / w[0];
    }
  }
  return c;
}

std::vector<Values> BezierCurveAt(int dimension, Coordinates points,
                                  Coordinates weights, double t, int orders) {
  const int n = static_cast<int>(points.size()) / dimension - 1;
  return Combine(dimension, points, weights, BernsteinBasis(n, t, orders));
}

std::vector<Values> BSplineCurveAt(int p, Coordinates knots, int dimension,
                                   Coordinates points, Coordinates weights,
                                   double u, int orders) {
  return Combine(dimension, points, weights, BSplineBasis(p, knots, u, orders));
}

std::vector<Values> LagrangeCurveAt(Coordinates nodes, int dimension,
                                    Coordinates points, double t, int orders) {
  return Combine(dimension, points, {}, LagrangeBasis(nodes, t, orders));
}

std::vector<Values> HermiteCurveAt(Coordinates nodes, int dimension,
                                   Coordinates points, Coordinates tangents,
                                   double t, int orders) {
  const auto d = static_cast<size_t>(dimension);
  size_t k = 0;  // the segment [nodes[k], nodes[k + 1]] holding t
  while (k + 2 < nodes.size() && nodes[k + 1] <= t) ++k;
  const double h = nodes[k + 1] - nodes[k];
  const double s = (t - nodes[k]) / h;
  std::vector<Values> result(static_cast<size_t>(orders) + 1, Values(d));
  for (int order = 0; order <= orders; ++order) {
    const double chain = std::pow(h, -order);
    for (size_t j = 0; j < d; ++j) {
      result[order][j] =
          chain * (Hermite(0, s, order) * points[k * d + j] +
                   Hermite(1, s, order) * points[(k + 1) * d + j] +
                   h * Hermite(2, s, order) * tangents[k * d + j] +
                   h * Hermite(3, s, order) * tangents[(k + 1) * d + j]);
    }
  }
  return result;
}

Values TensorAt(const BasisDerivatives& f, const BasisDerivatives& g,
                int dimension, Coordinates net, Coordinates weights,
                int order_u, int order_v) {
  const auto d = static_cast<size_t>(dimension);
  const size_t count_u = f[0].size();
  const size_t count_v = g[0].size();
  Values a(d, 0.0);
  double w = 0;
  for (size_t i = 0; i < count_u; ++i) {
    for (size_t j = 0; j < count_v; ++j) {
      const size_t r = i * count_v + j;
      const double b = f[order_u][i] * g[order_v][j];
      const double weight = weights.empty() ? 1.0 : weights[r];
      const double factor = weight != 0 ? weight : 1.0;
      for (size_t x = 0; x < d; ++x) a[x] += b * factor * net[r * d + x];
      w += b * weight;
    }
  }
  if (!weights.empty()) {
    for (double& value : a) value /= w;
  }
  return a;
}

Values TriangularBasis(int n, double u, double v) {
  const double w = 1 - u - v;
  Values basis;
  for (int i = n; i >= 0; --i) {
    for (int j = n - i; j >= 0; --j) {
      const int k = n - i - j;
      basis.push_back(Factorial(n) /
                      (Factorial(i) * Factorial(j) * Factorial(k)) *
                      std::pow(u, i) * std::pow(v, j) * std::pow(w, k));
    }
  }
  return basis;
}

Values TriangularAt(int n, int dimension, Coordinates points,
                    Coordinates weights, double u, double v) {
  return Combine(dimension, points, weights, {TriangularBasis(n, u, v)})[0];
}

double Dot(Coordinates a, Coordinates b) {
  double sum = 0;
  for (size_t j = 0; j < a.size(); ++j) sum += a[j] * b[j];
  return sum;
}

double Norm(Coordinates a) { return std::sqrt(Dot(a, a)); }

double Distance(Coordinates a, Coordinates b) {
  double sum = 0;
  for (size_t j = 0; j < a.size(); ++j) sum += (a[j] - b[j]) * (a[j] - b[j]);
  return std::sqrt(sum);
}

Values Cross(Coordinates a, Coordinates b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
          a[0] * b[1] - a[1] * b[0]};
}

double Scale(Coordinates values) {
  double scale = 0;
  for (const double value : values) scale = std::max(scale, std::abs(value));
  return scale;
}

double DistanceToSegment(Coordinates p, Coordinates a, Coordinates b) {
  double along = 0;
  double length2 = 0;
  for (size_t j = 0; j < p.size(); ++j) {
    along += (p[j] - a[j]) * (b[j] - a[j]);
    length2 += (b[j] - a[j]) * (b[j] - a[j]);
  }
  const double s = length2 > 0 ? std::clamp(along / length2, 0.0, 1.0) : 0.0;
  double sum = 0;
  for (size_t j = 0; j < p.size(); ++j) {
    const double x = a[j] + s * (b[j] - a[j]) - p[j];
    sum += x * x;
  }
  return std::sqrt(sum);
}

}  // namespace freeform::reliability
