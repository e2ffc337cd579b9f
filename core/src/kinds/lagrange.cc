#include "freeform/core/lagrange.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "absl/strings/str_cat.h"
#include "base/double_double.h"
#include "base/scaled.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "kinds/validated_lagrange.h"

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

// LagrangeBasisWorkspace holds one chunk's LagrangeBasis storage for orders
// 0..top.
class LagrangeBasisWorkspace {
 public:
  LagrangeBasisWorkspace(absl::Span<const double> nodes,
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
void CombinePoints(const PointsView& points, absl::Span<const double> basis,
                   absl::Span<double> out) {
  std::fill(out.begin(), out.end(), 0.0);
  for (size_t i = 0; i < basis.size(); ++i) {
    const double* point = points.point(i);
    for (size_t j = 0; j < out.size(); ++j) out[j] += basis[i] * point[j];
  }
}

}  // namespace

absl::Status ValidateLagrangeCurve(const LagrangeCurveView& curve) {
  RETURN_IF_ERROR(ValidatePoints(curve.points, "points"));
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

using internal::DoubleDouble;
using internal::TwoSum;

// The bound on the conversion's rounding, relative to the magnitudes of
// BernsteinBasisOfLagrange (below): each factor's two coefficients come from
// exact node differences and one division, each step of the product and of
// the final sum costs a few double-double operations of relative error
// 4 * 2^-106 (double_double.h), and n steps and a sum of n + 1 terms
// accumulate n of them, to first order.
double RelativeRounding(int n) { return 8.0 * (n + 2) * 0x1p-104; }

// Below this size, a double-double product loses its low word (underflow):
// its error is absolute, at most 2^-1074 per operation.
constexpr double kUnderflowFloor = 0x1p-968;

// Rule of the conversion: its error bound is at most 2^-53 of the largest
// point coordinate, half an ulp of it, as much as the result's own
// rounding.
constexpr double kAllowedError = 0x1p-53;

// BernsteinBasisOfLagrange computes, for each i, the scaled Bernstein
// coefficients C(n, k) [B_k] L_i of the Lagrange basis polynomial L_i on
// [t_0, t_n] mapped to [0, 1], as the product over j != i of the linear
// factors (t - t_j) / (t_i - t_j), whose Bernstein coefficients are
// -(t_j - t_0) / (t_i - t_j) and (t_n - t_j) / (t_i - t_j). In the scaled
// (homogeneous) basis a product by a linear factor is a convolution:
// h_k = g_0 f_k + g_1 f_(k-1). Alongside, in double, the same product of
// the factors' absolute values: an upper bound of the magnitude each
// rounding error is relative to (Farouki & Rajan, "On the numerical
// condition of polynomials in Bernstein form", 1987: Bernstein arithmetic
// is componentwise stable), so that the error of the result is known.
class BernsteinBasisOfLagrange {
 public:
  BernsteinBasisOfLagrange(absl::Span<const double> nodes, bool exact)
      : nodes_(nodes), exact_(exact), n_(nodes.size() - 1) {}

  // Compute sets Coefficients() (when exact) and Magnitudes() for L_i.
  void Compute(size_t i) {
    coefficients_.assign(n_ + 1, DoubleDouble{});
    magnitudes_.assign(n_ + 1, 0.0);
    coefficients_[0] = {1.0, 0.0};
    magnitudes_[0] = 1.0;
    size_t degree = 0;
    for (size_t j = 0; j <= n_; ++j) {
      if (j == i) continue;
      const DoubleDouble width = TwoSum(nodes_[i], -nodes_[j]);
      const DoubleDouble low = -TwoSum(nodes_[j], -nodes_[0]) / width;
      const DoubleDouble high = TwoSum(nodes_[n_], -nodes_[j]) / width;
      ++degree;
      Multiply(degree, low, high);
    }
  }

  absl::Span<const DoubleDouble> Coefficients() const { return coefficients_; }
  absl::Span<const double> Magnitudes() const { return magnitudes_; }

 private:
  // Multiply by the linear factor (low, high), the product being of
  // `degree`.
  void Multiply(size_t degree, const DoubleDouble& low,
                const DoubleDouble& high) {
    const double low_size = std::abs(low.hi);
    const double high_size = std::abs(high.hi);
    for (size_t k = degree; k > 0; --k) {
      magnitudes_[k] =
          low_size * magnitudes_[k] + high_size * magnitudes_[k - 1];
      if (exact_) {
        coefficients_[k] = low * coefficients_[k] + high * coefficients_[k - 1];
      }
    }
    magnitudes_[0] *= low_size;
    if (exact_) coefficients_[0] = low * coefficients_[0];
  }

  absl::Span<const double> nodes_;
  bool exact_;
  size_t n_;
  std::vector<DoubleDouble> coefficients_;
  std::vector<double> magnitudes_;
};

// ScaledBinomials returns C(n, k), k = 0..n, exactly (Pascal's rule, in
// double-double: exact below 2^106).
std::vector<DoubleDouble> ScaledBinomials(size_t n) {
  std::vector<DoubleDouble> row(n + 1);
  row[0] = {1.0, 0.0};
  for (size_t m = 1; m <= n; ++m) {
    row[m] = {1.0, 0.0};
    for (size_t k = m - 1; k > 0; --k) row[k] = row[k] + row[k - 1];
  }
  return row;
}

// PointSizes returns max_x |P_i,x| for each point and, last, the largest.
std::vector<double> PointSizes(const PointsView& points) {
  std::vector<double> sizes(points.size() + 1, 0.0);
  for (size_t i = 0; i < points.size(); ++i) {
    const double* point = points.point(i);
    for (int x = 0; x < points.dimension; ++x) {
      sizes[i] = std::max(sizes[i], std::abs(point[x]));
    }
    sizes.back() = std::max(sizes.back(), sizes[i]);
  }
  return sizes;
}

// ConversionErrorBound returns an upper bound, relative to the largest
// point coordinate, of the rounding of the Bezier points: for each k,
// sum_i (magnitude_ik / C(n, k)) |P_i| times RelativeRounding, plus the
// absolute errors of underflow.
class ConversionErrorBound {
 public:
  ConversionErrorBound(const PointsView& points,
                       absl::Span<const DoubleDouble> binomials)
      : sizes_(PointSizes(points)),
        binomials_(binomials),
        sums_(binomials.size(), 0.0) {}

  void Add(size_t i, absl::Span<const double> magnitudes) {
    const double size = Relative(sizes_[i]);
    for (size_t k = 0; k < sums_.size(); ++k) {
      sums_[k] += magnitudes[k] / binomials_[k].hi * size;
      largest_magnitude_ = std::max(largest_magnitude_, magnitudes[k]);
    }
  }

  double Relative() const {
    const int n = static_cast<int>(sums_.size()) - 1;
    const double largest = *std::max_element(sums_.begin(), sums_.end());
    // 2 covers the rounding of the bound's own double arithmetic.
    return 2.0 * (RelativeRounding(n) * largest +
                  (n + 1.0) * (n + 1.0) * kUnderflowFloor *
                      std::max(1.0, largest_magnitude_));
  }

 private:
  double Relative(double size) const {
    return sizes_.back() > 0.0 ? size / sizes_.back() : 0.0;
  }

  std::vector<double> sizes_;
  absl::Span<const DoubleDouble> binomials_;
  std::vector<double> sums_;
  double largest_magnitude_ = 0.0;
};

absl::Status BezierFormError(double relative, int degree) {
  return InvalidFieldError(
      "nodes",
      absl::StrCat(
          "the Bezier form of this degree-", degree,
          " interpolant cannot be computed to double precision from these "
          "nodes: the conversion's error bound is ",
          relative,
          " of the largest point coordinate, above 2^-53; the interpolation "
          "is too ill-conditioned: use fewer nodes, or nodes clustered "
          "toward the ends like Chebyshev points"));
}

}  // namespace

absl::Status CheckLagrangeBezierForm(const LagrangeCurveView& curve) {
  const int n = curve.degree();
  if (n <= 0) return absl::OkStatus();
  const std::vector<double> nodes = LagrangeNodes(curve);
  const std::vector<DoubleDouble> binomials =
      ScaledBinomials(static_cast<size_t>(n));
  BernsteinBasisOfLagrange basis(nodes, /*exact=*/false);
  ConversionErrorBound bound(curve.points, binomials);
  for (size_t i = 0; i < nodes.size(); ++i) {
    basis.Compute(i);
    bound.Add(i, basis.Magnitudes());
  }
  if (!(bound.Relative() <= kAllowedError)) {
    return BezierFormError(bound.Relative(), n);
  }
  return absl::OkStatus();
}

absl::StatusOr<std::vector<double>> LagrangeToBezier(
    const LagrangeCurveView& curve) {
  const int n = curve.degree();
  if (n <= 0) {
    return std::vector<double>(curve.points.coordinates.begin(),
                               curve.points.coordinates.end());
  }
  const std::vector<double> nodes = LagrangeNodes(curve);
  const size_t d = static_cast<size_t>(curve.points.dimension);
  const std::vector<DoubleDouble> binomials =
      ScaledBinomials(static_cast<size_t>(n));
  BernsteinBasisOfLagrange basis(nodes, /*exact=*/true);
  ConversionErrorBound bound(curve.points, binomials);
  // The points scaled by a power of two to at most 1 (exactly, but for
  // coordinates 2^-1022 below the largest), so that no sum overflows.
  const double scale =
      std::ldexp(1.0, internal::ExponentAbove(PointSizes(curve.points).back()));
  std::vector<DoubleDouble> sums(nodes.size() * d);
  for (size_t i = 0; i < nodes.size(); ++i) {
    basis.Compute(i);
    bound.Add(i, basis.Magnitudes());
    const absl::Span<const DoubleDouble> coefficients = basis.Coefficients();
    const double* point = curve.points.point(i);
    for (size_t x = 0; x < d; ++x) {
      const DoubleDouble coordinate{point[x] / scale, 0.0};
      for (size_t k = 0; k < nodes.size(); ++k) {
        sums[k * d + x] = sums[k * d + x] + coefficients[k] * coordinate;
      }
    }
  }
  if (!(bound.Relative() <= kAllowedError)) {
    return BezierFormError(bound.Relative(), n);
  }
  std::vector<double> out(sums.size());
  for (size_t k = 0; k < nodes.size(); ++k) {
    for (size_t x = 0; x < d; ++x) {
      out[k * d + x] = (sums[k * d + x] / binomials[k]).ToDouble() * scale;
      if (!std::isfinite(out[k * d + x])) {
        return InvalidFieldError(
            "points",
            "the Bezier points of this interpolant overflow double "
            "precision: scale the points");
      }
    }
  }
  // The ends are the end points, exactly.
  std::copy_n(curve.points.point(0), d, out.begin());
  std::copy_n(curve.points.point(static_cast<size_t>(n)), d,
              out.begin() + static_cast<std::ptrdiff_t>(n * d));
  return out;
}

absl::Status EvaluateLagrangeCurve(const LagrangeCurveView& curve,
                                   absl::Span<const double> parameters,
                                   CurveOutput output,
                                   const ExecutionContext& context) {
  RETURN_IF_ERROR(ValidateLagrangeCurve(curve));
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
  RETURN_IF_ERROR(ValidateBatch(parameters, domain.first, domain.second, output,
                                dimension));
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
    LagrangeBasisWorkspace basis(nodes, weights, top);
    for (size_t r = begin; r < end; ++r) {
      basis.Evaluate(parameters[r]);
      for (size_t k = 0; k < output.size(); ++k) {
        const absl::Span<double> out = output[k].subspan(r * dim, dim);
        if (k <= top) {
          CombinePoints(curve.points, basis.Row(k), out);
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
  RETURN_IF_ERROR(ValidateNodes(nodes));
  return internal::EvaluateValidLagrangeBasis(nodes, parameters, output,
                                              context);
}

namespace internal {

absl::Status EvaluateValidLagrangeBasis(absl::Span<const double> nodes,
                                        absl::Span<const double> parameters,
                                        CurveOutput output,
                                        const ExecutionContext& context) {
  const size_t count = nodes.size();
  RETURN_IF_ERROR(ValidateBatch(parameters, nodes.front(), nodes.back(), output,
                                static_cast<int>(count)));
  const std::vector<double> weights = BarycentricWeights(nodes);
  const size_t orders = output.size();

  return ParallelFor(parameters.size(), context, [&](size_t begin, size_t end) {
    LagrangeBasisWorkspace basis(nodes, weights, orders - 1);
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
