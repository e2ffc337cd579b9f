#include "freeform/core/lagrange.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "absl/strings/str_cat.h"
#include "freeform/core/status.h"
#include "validated.h"

namespace freeform {
namespace {

// The scale c of BarycentricWeights: the capacity (t_n - t_0) / 4.
double NodeScale(absl::Span<const double> nodes) {
  return nodes.size() > 1 ? (nodes.back() - nodes.front()) / 4 : 1.0;
}

// ValidateNodes checks that `nodes` are finite and strictly increasing, with
// a finite span so that every difference t - t_j is finite too.
absl::Status ValidateNodes(absl::Span<const double> nodes) {
  for (size_t i = 0; i < nodes.size(); ++i) {
    if (!std::isfinite(nodes[i])) {
      return InvalidFieldError(IndexedField("nodes", i),
                               absl::StrCat("must be finite, got ", nodes[i]));
    }
    if (i > 0 && !(nodes[i] > nodes[i - 1])) {
      return InvalidFieldError(
          IndexedField("nodes", i),
          absl::StrCat("nodes must be strictly increasing, got ", nodes[i],
                       " after ", nodes[i - 1]));
    }
  }
  if (!nodes.empty() && !std::isfinite(nodes.back() - nodes.front())) {
    return InvalidFieldError("nodes", "the span t_n - t_0 overflows");
  }
  return absl::OkStatus();
}

// MultiplyByLinear sets out = in * (a + u) for the truncated Taylor series
// in[k * stride], out[k * stride], k = 0..top, in u; `out` may be `in`.
void MultiplyByLinear(const double* in, double a, size_t top, size_t stride,
                      double* out) {
  for (size_t k = top; k > 0; --k) {
    out[k * stride] = a * in[k * stride] + in[(k - 1) * stride];
  }
  out[0] = a * in[0];
}

// BasisWorkspace holds one chunk's LagrangeBasis storage for orders 0..top.
class BasisWorkspace {
 public:
  BasisWorkspace(absl::Span<const double> nodes,
                 absl::Span<const double> weights, size_t top)
      : nodes_(nodes),
        weights_(weights),
        top_(top),
        storage_((top + 1) * (nodes.size() + 1)) {}

  // Evaluate computes every L_i^(k)(t).
  void Evaluate(double t) {
    const absl::Span<double> all = absl::MakeSpan(storage_);
    const size_t values = (top_ + 1) * nodes_.size();
    LagrangeBasis(nodes_, weights_, t, static_cast<int>(top_),
                  all.subspan(values), all.first(values));
  }

  // Row returns L_i^(k)(t), i = 0..n, of the last Evaluate.
  absl::Span<const double> Row(size_t k) const {
    return absl::MakeConstSpan(storage_).subspan(k * nodes_.size(),
                                                 nodes_.size());
  }

 private:
  absl::Span<const double> nodes_;
  absl::Span<const double> weights_;
  size_t top_;
  std::vector<double> storage_;
};

// Combine writes out = sum_i basis[i] P_i.
void Combine(const PointsView& points, absl::Span<const double> basis,
             absl::Span<double> out) {
  std::fill(out.begin(), out.end(), 0.0);
  for (size_t i = 0; i < basis.size(); ++i) {
    const double* point = points.point(i);
    for (size_t j = 0; j < out.size(); ++j) out[j] += basis[i] * point[j];
  }
}

}  // namespace

absl::Status ValidateLagrangeCurve(const LagrangeCurveView& curve) {
  if (absl::Status status = ValidatePoints(curve.points, "points");
      !status.ok()) {
    return status;
  }
  if (curve.nodes.empty()) return absl::OkStatus();
  if (curve.nodes.size() != curve.points.size()) {
    return InvalidFieldError(
        "nodes", absl::StrCat("has ", curve.nodes.size(), " nodes for ",
                              curve.points.size(), " points"));
  }
  return ValidateNodes(curve.nodes);
}

std::vector<double> LagrangeNodes(const LagrangeCurveView& curve) {
  if (!curve.nodes.empty()) {
    return std::vector<double>(curve.nodes.begin(), curve.nodes.end());
  }
  const size_t count = curve.points.size();
  std::vector<double> nodes(count, 0.0);
  for (size_t i = 1; i < count; ++i) {
    nodes[i] = static_cast<double>(i) / static_cast<double>(count - 1);
  }
  return nodes;
}

std::pair<double, double> LagrangeDomain(const LagrangeCurveView& curve) {
  if (curve.nodes.empty()) return {0.0, 1.0};
  return {curve.nodes.front(), curve.nodes.back()};
}

std::vector<double> BarycentricWeights(absl::Span<const double> nodes) {
  const double scale = NodeScale(nodes);
  std::vector<double> weights(nodes.size());
  for (size_t i = 0; i < nodes.size(); ++i) {
    // The product as mantissa * 2^exponent: a partial product may leave the
    // double range even when the whole one does not (clustered nodes).
    double mantissa = 1.0;
    int exponent = 0;
    for (size_t j = 0; j < nodes.size(); ++j) {
      if (j == i) continue;
      int shift = 0;
      mantissa = std::frexp(mantissa * ((nodes[i] - nodes[j]) / scale), &shift);
      exponent += shift;
    }
    weights[i] = std::ldexp(1.0 / mantissa, -exponent);
  }
  return weights;
}

void NevilleEvaluate(const PointsView& points, absl::Span<const double> nodes,
                     double t, absl::Span<double> scratch,
                     absl::Span<double> point) {
  const size_t dim = static_cast<size_t>(points.dimension);
  const size_t count = nodes.size();
  std::copy_n(points.coordinates.begin(), count * dim, scratch.begin());
  // After level m, scratch point i holds P_{i..i+m}(t).
  for (size_t m = 1; m < count; ++m) {
    for (size_t i = 0; i + m < count; ++i) {
      const double left = t - nodes[i];
      const double right = t - nodes[i + m];
      const double width = nodes[i + m] - nodes[i];
      double* q = &scratch[i * dim];
      for (size_t j = 0; j < dim; ++j) {
        q[j] = (left * q[j + dim] - right * q[j]) / width;
      }
    }
  }
  std::copy_n(scratch.begin(), dim, point.begin());
}

void LadderEvaluate(const PointsView& points, absl::Span<const double> nodes,
                    absl::Span<const double> weights, double t,
                    absl::Span<double> point) {
  const double scale = NodeScale(nodes);
  std::fill(point.begin(), point.end(), 0.0);
  double left = 1.0;  // The left rail: prod_{j<k} (t - t_j) / c.
  for (size_t k = 0; k < nodes.size(); ++k) {
    const double factor = (t - nodes[k]) / scale;
    const double rung = weights[k] * left;
    const double* p = points.point(k);
    for (size_t j = 0; j < point.size(); ++j) {
      point[j] = factor * point[j] + rung * p[j];
    }
    left *= factor;
  }
}

void BarycentricEvaluate(const PointsView& points,
                         absl::Span<const double> nodes,
                         absl::Span<const double> weights, double t,
                         absl::Span<double> point) {
  std::fill(point.begin(), point.end(), 0.0);
  double denominator = 0.0;
  for (size_t i = 0; i < nodes.size(); ++i) {
    const double difference = t - nodes[i];
    const double coefficient = weights[i] / difference;
    const double* p = points.point(i);
    // At a node, or so close to it that the quotient overflows (|t - t_i|
    // below ~1e-290), the interpolant is P_i to rounding.
    if (difference == 0.0 || std::isinf(coefficient)) {
      std::copy_n(p, point.size(), point.begin());
      return;
    }
    denominator += coefficient;
    for (size_t j = 0; j < point.size(); ++j) point[j] += coefficient * p[j];
  }
  for (double& coordinate : point) coordinate /= denominator;
}

// Warren's ladder (docs/references.md, 'Warren's ladder for Lagrange
// curves') in truncated Taylor series arithmetic: with a_j = (t - t_j) / c
// and s = t + c u, L_i(s) = w_i A_i(u) B_i(u), where the left rail
// A_i = prod_{j<i} (a_j + u) and the right rail B_i = prod_{j>i} (a_j + u)
// are series in u truncated after u^top, and
// L_i^(k)(t) = k! / c^k [u^k] A_i B_i.
//
// Why this and not the alternatives for derivatives: it never divides by
// t - t_i, so unlike the differentiated barycentric formulas (Schneider &
// Werner 1986) it does not cancel catastrophically near the nodes, and it
// builds no sub-interpolants P_{i..j} extrapolated far outside [t_i, t_j],
// whose growth the differentiated Neville recurrence must cancel. Every
// coefficient is a sum of products of the O(1) scaled a_j, so its rounding
// error is a few n units in the last place of the same sum taken with
// |a_j|: the backward stability of the modified Lagrange formula (Higham,
// "The numerical stability of barycentric Lagrange interpolation", IMA J.
// Numer. Anal. 24, 2004), carried over to each Taylor coefficient. Exact
// zeros L_i(t_j) = 0 at the nodes come for free. O(n top^2) per point.
void LagrangeBasis(absl::Span<const double> nodes,
                   absl::Span<const double> weights, double t, int max_order,
                   absl::Span<double> scratch, absl::Span<double> values) {
  const size_t count = nodes.size();
  const size_t top = std::min(static_cast<size_t>(max_order), count - 1);
  const double scale = NodeScale(nodes);
  // Column i of `values` (stride `count`) first holds the left rail A_i.
  values[0] = 1.0;
  for (size_t k = 1; k <= top; ++k) values[k * count] = 0.0;
  for (size_t i = 1; i < count; ++i) {
    MultiplyByLinear(&values[i - 1], (t - nodes[i - 1]) / scale, top, count,
                     &values[i]);
  }
  // Then, right to left, column i becomes w_i [u^k] A_i B_i; descending k
  // reads only the A_i coefficients not yet overwritten.
  double* right = scratch.data();
  right[0] = 1.0;
  std::fill(right + 1, right + top + 1, 0.0);
  for (size_t i = count; i-- > 0;) {
    for (size_t k = top + 1; k-- > 0;) {
      double sum = 0.0;
      for (size_t m = 0; m <= k; ++m) {
        sum += values[m * count + i] * right[k - m];
      }
      values[k * count + i] = weights[i] * sum;
    }
    if (t == nodes[i]) values[i] = 1.0;  // exactly, not 1 + rounding
    MultiplyByLinear(right, (t - nodes[i]) / scale, top, 1, right);
  }
  double factor = 1.0;  // k! / c^k
  for (size_t k = 1; k <= top; ++k) {
    factor *= static_cast<double>(k) / scale;
    for (size_t i = 0; i < count; ++i) values[k * count + i] *= factor;
  }
  const absl::Span<double> above = values.subspan((top + 1) * count);
  std::fill(above.begin(), above.end(), 0.0);
}

namespace {

// BezierHalfFromTaylor writes control points b_0..b_top of the curve seen
// from one end of its domain: `from` = t_0 with `step` = h gives b_j, and
// `from` = t_n with `step` = -h gives b_{n-j} (the reversed curve), at
// out[index(j)].
template <typename Index>
void BezierHalfFromTaylor(const LagrangeCurveView& curve,
                          absl::Span<const double> nodes,
                          absl::Span<const double> weights, double from,
                          double step, int top, Index index,
                          std::vector<double>& out) {
  const size_t count = nodes.size();
  const int n = static_cast<int>(count) - 1;
  const size_t d = static_cast<size_t>(curve.points.dimension);
  std::vector<double> basis((static_cast<size_t>(top) + 1) * count);
  std::vector<double> scratch(static_cast<size_t>(top) + 1);
  LagrangeBasis(nodes, weights, from, top, absl::MakeSpan(scratch),
                absl::MakeSpan(basis));
  // a_k = C^(k)(from) step^k / k!.
  std::vector<double> taylor((static_cast<size_t>(top) + 1) * d, 0.0);
  double factor = 1.0;
  for (int k = 0; k <= top; ++k) {
    double* a = &taylor[static_cast<size_t>(k) * d];
    for (size_t i = 0; i < count; ++i) {
      const double weight = factor * basis[static_cast<size_t>(k) * count + i];
      const double* point = curve.points.point(i);
      for (size_t x = 0; x < d; ++x) a[x] += weight * point[x];
    }
    factor *= step / (k + 1);
  }
  // b_j = sum_{k<=j} (C(j, k) / C(n, k)) a_k; the ratio is
  // prod_{i<k} (j - i) / (n - i).
  for (int j = 0; j <= top; ++j) {
    double* b = &out[index(j) * d];
    double ratio = 1.0;
    for (int k = 0; k <= j; ++k) {
      const double* a = &taylor[static_cast<size_t>(k) * d];
      for (size_t x = 0; x < d; ++x) b[x] += ratio * a[x];
      ratio *= static_cast<double>(j - k) / (n - k);
    }
  }
}

}  // namespace

std::vector<double> LagrangeToBezier(const LagrangeCurveView& curve) {
  const std::vector<double> nodes = LagrangeNodes(curve);
  const int n = curve.degree();
  std::vector<double> out(curve.points.coordinates.size(), 0.0);
  if (n == 0)
    return {curve.points.coordinates.begin(), curve.points.coordinates.end()};
  const std::vector<double> weights = BarycentricWeights(nodes);
  const double h = nodes.back() - nodes.front();
  const int front = n / 2;  // b_0..b_front from t_0, the rest from t_n
  BezierHalfFromTaylor(
      curve, nodes, weights, nodes.front(), h, front,
      [](int j) { return static_cast<size_t>(j); }, out);
  BezierHalfFromTaylor(
      curve, nodes, weights, nodes.back(), -h, n - front - 1,
      [n](int j) { return static_cast<size_t>(n - j); }, out);
  return out;
}

absl::Status EvaluateLagrangeCurve(const LagrangeCurveView& curve,
                                   absl::Span<const double> parameters,
                                   CurveOutput output,
                                   const ExecutionContext& context) {
  if (absl::Status status = ValidateLagrangeCurve(curve); !status.ok()) {
    return status;
  }
  return internal::EvaluateValidLagrangeCurve(curve, parameters, output,
                                              context);
}

namespace internal {

absl::Status EvaluateValidLagrangeCurve(const LagrangeCurveView& curve,
                                        absl::Span<const double> parameters,
                                        CurveOutput output,
                                        const ExecutionContext& context) {
  const std::pair<double, double> domain = LagrangeDomain(curve);
  const int dimension = curve.points.dimension;
  if (absl::Status status = ValidateBatch(parameters, domain.first,
                                          domain.second, output, dimension);
      !status.ok()) {
    return status;
  }
  const std::vector<double> nodes = LagrangeNodes(curve);
  const std::vector<double> weights = BarycentricWeights(nodes);
  const size_t dim = static_cast<size_t>(dimension);
  const size_t count = nodes.size();
  // Derivatives of order above the degree are zero.
  const size_t top = std::min(output.size() - 1, count - 1);

  // Positions too come from the basis, i.e. the first barycentric form: it
  // is backward stable for any nodes (Higham 2004), while the second form
  // errs by up to the Lebesgue constant times |C(t)| more: 1000 times the
  // ladder's error on uniform nodes of degree 20.
  return ParallelFor(parameters.size(), context, [&](size_t begin, size_t end) {
    BasisWorkspace basis(nodes, weights, top);
    for (size_t r = begin; r < end; ++r) {
      basis.Evaluate(parameters[r]);
      for (size_t k = 0; k < output.size(); ++k) {
        const absl::Span<double> out = output[k].subspan(r * dim, dim);
        if (k <= top) {
          Combine(curve.points, basis.Row(k), out);
        } else {
          std::fill(out.begin(), out.end(), 0.0);
        }
      }
    }
  });
}

}  // namespace internal

absl::Status EvaluateLagrangeBasis(absl::Span<const double> nodes,
                                   absl::Span<const double> parameters,
                                   CurveOutput output,
                                   const ExecutionContext& context) {
  if (nodes.empty()) {
    return InvalidFieldError("nodes", "needs at least one node");
  }
  if (absl::Status status = ValidateNodes(nodes); !status.ok()) return status;
  return internal::EvaluateValidLagrangeBasis(nodes, parameters, output,
                                              context);
}

namespace internal {

absl::Status EvaluateValidLagrangeBasis(absl::Span<const double> nodes,
                                        absl::Span<const double> parameters,
                                        CurveOutput output,
                                        const ExecutionContext& context) {
  const size_t count = nodes.size();
  if (absl::Status status =
          ValidateBatch(parameters, nodes.front(), nodes.back(), output,
                        static_cast<int>(count));
      !status.ok()) {
    return status;
  }
  const std::vector<double> weights = BarycentricWeights(nodes);
  const size_t orders = output.size();

  return ParallelFor(parameters.size(), context, [&](size_t begin, size_t end) {
    BasisWorkspace basis(nodes, weights, orders - 1);
    for (size_t r = begin; r < end; ++r) {
      basis.Evaluate(parameters[r]);
      for (size_t k = 0; k < orders; ++k) {
        const absl::Span<const double> row = basis.Row(k);
        std::copy(row.begin(), row.end(), output[k].begin() + r * count);
      }
    }
  });
}

}  // namespace internal

}  // namespace freeform
