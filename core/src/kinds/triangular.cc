#include "freeform/core/triangular.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "absl/strings/str_cat.h"
#include "base/homogeneous.h"
#include "freeform/core/rational.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "freeform/core/tensor_surface.h"
#include "kinds/validated_triangular.h"

namespace freeform {
namespace {

// Relative area below which a domain triangle counts as degenerate.
constexpr double kDegenerateAreaRatio = 1e-14;

// Which value of a parameter pair breaks the triangle rule.
enum class PairFault { kNone, kFirst, kSecond };

// Maps parameter pairs to barycentric (u, v): the identity, or the inverse
// of the affine map (u, v) -> C + u (A - C) + v (B - C) of a domain
// triangle. `directions` are the barycentric directions (du, dv, dw) of the
// two parameter axes, along which the partials are taken.
class ParameterMap {
 public:
  explicit ParameterMap(absl::Span<const double> triangle) {
    if (triangle.empty()) return;
    cartesian_ = true;
    origin_ = {triangle[4], triangle[5]};
    const double ax = triangle[0] - origin_[0], ay = triangle[1] - origin_[1];
    const double bx = triangle[2] - origin_[0], by = triangle[3] - origin_[1];
    const double det = ax * by - bx * ay;
    // inverse_ = [A - C | B - C]^-1, rows (du/dx, du/dy), (dv/dx, dv/dy).
    inverse_ = {by / det, -bx / det, -ay / det, ax / det};
    directions_[0] = {inverse_[0], inverse_[2], -inverse_[0] - inverse_[2]};
    directions_[1] = {inverse_[1], inverse_[3], -inverse_[1] - inverse_[3]};
  }

  // Check returns which value of the pair (a, b) lies outside the triangle
  // by more than kTriangleTolerance or is not finite.
  PairFault Check(double a, double b) const {
    if (!std::isfinite(a)) return PairFault::kFirst;
    if (!std::isfinite(b)) return PairFault::kSecond;
    double u, v;
    ToBarycentric(a, b, &u, &v);
    if (!cartesian_) {
      if (u < -kTriangleTolerance) return PairFault::kFirst;
      if (v < -kTriangleTolerance) return PairFault::kSecond;
    } else if (u < -kTriangleTolerance || v < -kTriangleTolerance) {
      return PairFault::kFirst;
    }
    if (u + v > 1 + kTriangleTolerance) return PairFault::kFirst;
    return PairFault::kNone;
  }

  // Clamped writes the barycentric coordinates of a checked pair, moved
  // onto the closed triangle.
  void Clamped(double a, double b, double* u, double* v, double* w) const {
    ToBarycentric(a, b, u, v);
    *u = std::max(*u, 0.0);
    *v = std::max(*v, 0.0);
    const double sum = *u + *v;
    if (sum > 1) {
      *u /= sum;
      *v /= sum;
    }
    *w = std::max(1.0 - *u - *v, 0.0);
  }

  const std::array<double, 3>& direction(int axis) const {
    return directions_[static_cast<size_t>(axis)];
  }

 private:
  void ToBarycentric(double a, double b, double* u, double* v) const {
    if (!cartesian_) {
      *u = a;
      *v = b;
      return;
    }
    const double x = a - origin_[0], y = b - origin_[1];
    *u = inverse_[0] * x + inverse_[1] * y;
    *v = inverse_[2] * x + inverse_[3] * y;
  }

  bool cartesian_ = false;
  std::array<double, 2> origin_{};
  std::array<double, 4> inverse_{};
  // D_u = D_(1,0,-1) and D_v = D_(0,1,-1) without a domain triangle.
  std::array<std::array<double, 3>, 2> directions_{
      {{1.0, 0.0, -1.0}, {0.0, 1.0, -1.0}}};
};

// ValidatePairs checks an even number of values, each pair inside the
// triangle ("uv", "uv[i]").
absl::Status ValidatePairs(absl::Span<const double> uv,
                           const ParameterMap& map) {
  if (uv.size() % 2 != 0) {
    return InvalidFieldError(
        "uv", absl::StrCat("holds ", uv.size(), " values, not (u, v) pairs"));
  }
  for (size_t r = 0; r < uv.size() / 2; ++r) {
    const PairFault fault = map.Check(uv[2 * r], uv[2 * r + 1]);
    if (fault == PairFault::kNone) continue;
    return InvalidFieldError(
        IndexedField("uv", fault == PairFault::kFirst ? 2 * r : 2 * r + 1),
        absl::StrCat("the point (", uv[2 * r], ", ", uv[2 * r + 1],
                     ") must be finite and inside the domain triangle"));
  }
  return absl::OkStatus();
}

absl::Status ValidateWeights(absl::Span<const double> weights, int degree,
                             size_t count) {
  if (weights.size() != count) {
    return InvalidFieldError(
        "weights", absl::StrCat("has ", weights.size(), " weights for ", count,
                                " control points"));
  }
  RETURN_IF_ERROR(ValidateWeightValues(weights));
  // See ValidateTriangularPatch: the corners decide positivity.
  for (const size_t corner :
       {TriangularIndex(degree, degree, 0), TriangularIndex(degree, 0, degree),
        TriangularIndex(degree, 0, 0)}) {
    if (weights[corner] == 0) {
      return InvalidFieldError(
          IndexedField("weights", corner),
          "a corner weight must be positive: with weight 0 the patch is "
          "infinite at that corner");
    }
  }
  return absl::OkStatus();
}

absl::Status ValidateDomainTriangle(absl::Span<const double> triangle) {
  if (triangle.empty()) return absl::OkStatus();
  if (triangle.size() != 6) {
    return InvalidFieldError(
        "domain_triangle",
        absl::StrCat("holds ", triangle.size(),
                     " values, expected 6 (vertices A, B, C in 2D)"));
  }
  RETURN_IF_ERROR(ValidateFinite(triangle, "domain_triangle"));
  const double abx = triangle[2] - triangle[0], aby = triangle[3] - triangle[1];
  const double acx = triangle[4] - triangle[0], acy = triangle[5] - triangle[1];
  const double bcx = acx - abx, bcy = acy - aby;
  const double area = 0.5 * std::abs(abx * acy - aby * acx);
  const double longest = std::max(
      {abx * abx + aby * aby, acx * acx + acy * acy, bcx * bcx + bcy * bcy});
  if (area <= kDegenerateAreaRatio * longest) {
    return InvalidFieldError("domain_triangle",
                             "the triangle is degenerate (zero area)");
  }
  return absl::OkStatus();
}

// DeCasteljauStep replaces the degree-m net at `net` (work values per point)
// by the degree m-1 net Q(i,j,k) = a Q(i+1,j,k) + b Q(i,j+1,k) +
// c Q(i,j,k+1): a de Casteljau step at (a, b, c) when a + b + c = 1, a
// directional difference when a + b + c = 0 (Farin 1986, eq. 3.2 and 3.5).
// In storage order the target of (i, j) is the slot of (i+1, j), and every
// other read lies further on, so the step runs in place.
void DeCasteljauStep(double* net, int m, size_t work, double a, double b,
                     double c) {
  size_t out = 0;
  for (int i = m - 1; i >= 0; --i) {
    const size_t row = TriangularIndex(m, i, m - i);
    for (int j = m - 1 - i; j >= 0; --j, ++out) {
      double* target = net + out * work;
      const double* next_j = net + (row + static_cast<size_t>(m - 1 - i - j)) *
                                       work;  // (i, j+1, k)
      const double* next_k = next_j + work;   // (i, j, k+1)
      for (size_t x = 0; x < work; ++x) {
        target[x] = a * target[x] + b * next_j[x] + c * next_k[x];
      }
    }
  }
}

// PatchEvaluator evaluates one valid patch point by point with partials up
// to max_order; Evaluate() is const, each thread passes its own scratch.
class PatchEvaluator {
 public:
  PatchEvaluator(const TriangularPatchView& patch, int max_order,
                 const ParameterMap& map)
      : degree_(patch.degree),
        dimension_(patch.control_points.dimension),
        work_(static_cast<size_t>(dimension_) + (patch.rational() ? 1 : 0)),
        max_order_(max_order),
        top_(std::min(max_order, patch.degree)),
        rational_(patch.rational()),
        map_(map),
        control_(internal::LiftedValues(patch.control_points, patch.weights)) {}

  size_t partials_size() const {
    return PartialCount(max_order_) * static_cast<size_t>(dimension_);
  }
  size_t scratch_size() const {
    return (TriangularPointCount(degree_) + TriangularPointCount(top_) +
            (rational_ ? PartialCount(max_order_) : 0)) *
           work_;
  }

  // Evaluate writes the partials at barycentric (u, v, w) into
  // partials[PartialIndex(k, l) * dimension + x].
  void Evaluate(double u, double v, double w, double* scratch,
                double* partials) const {
    double* net = scratch;
    double* differences = net + TriangularPointCount(degree_) * work_;
    double* raw =
        rational_ ? differences + TriangularPointCount(top_) * work_ : partials;
    std::copy(control_.begin(), control_.end(), net);
    std::fill(raw, raw + PartialCount(max_order_) * work_, 0.0);
    for (int m = degree_; m > top_; --m)
      DeCasteljauStep(net, m, work_, u, v, w);
    for (int r = top_;; --r) {
      // `net` holds the degree-r net of de Casteljau level n - r.
      Differentiate(net, r, differences, raw);
      if (r == 0) break;
      DeCasteljauStep(net, r, work_, u, v, w);
    }
    if (rational_) {
      ProjectHomogeneousSurfaceDerivatives(raw, dimension_, max_order_,
                                           partials);
    }
  }

 private:
  // Differentiate writes the order-r partials n!/(n-r)! D1^a D2^b of the
  // level n - r net (Farin 1986, eq. 3.6).
  void Differentiate(const double* net, int r, double* differences,
                     double* raw) const {
    double factor = 1.0;
    for (int q = 0; q < r; ++q) factor *= degree_ - q;
    const size_t values = TriangularPointCount(r) * work_;
    for (int a = 0; a <= r; ++a) {
      std::copy(net, net + values, differences);
      for (int m = r; m > 0; --m) {
        const auto& d = map_.direction(m > r - a ? 0 : 1);
        DeCasteljauStep(differences, m, work_, d[0], d[1], d[2]);
      }
      double* out = raw + PartialIndex(a, r - a) * work_;
      for (size_t x = 0; x < work_; ++x) out[x] = factor * differences[x];
    }
  }

  int degree_;
  int dimension_;
  size_t work_;  // values per homogeneous point
  int max_order_;
  int top_;  // highest order with nonzero partials
  bool rational_;
  ParameterMap map_;
  std::vector<double> control_;  // homogeneous when rational
};

// TriangularBernstein writes the degree-n basis at (u, v, w) into `values`
// by B(i,j,k) = u B(i-1,j,k) + v B(i,j-1,k) + w B(i,j,k-1)
// (docs/references.md, 'Triangular Bezier patches'); `scratch` holds
// 2 (n+1)(n+2)/2 doubles.
void TriangularBernstein(int n, double u, double v, double w, double* scratch,
                         double* values) {
  double* previous = scratch;
  double* current = scratch + TriangularPointCount(n);
  previous[0] = 1.0;
  for (int m = 1; m <= n; ++m) {
    for (int i = m; i >= 0; --i) {
      for (int j = m - i; j >= 0; --j) {
        double value = 0.0;
        if (i > 0) value += u * previous[TriangularIndex(m - 1, i - 1, j)];
        if (j > 0) value += v * previous[TriangularIndex(m - 1, i, j - 1)];
        if (m - i - j > 0) value += w * previous[TriangularIndex(m - 1, i, j)];
        current[TriangularIndex(m, i, j)] = value;
      }
    }
    std::swap(previous, current);
  }
  std::copy(previous, previous + TriangularPointCount(n), values);
}

}  // namespace

absl::Status ValidateTriangularPatch(const TriangularPatchView& patch) {
  if (patch.degree < 0) {
    return InvalidFieldError("degree",
                             absl::StrCat("must be >= 0, got ", patch.degree));
  }
  RETURN_IF_ERROR(ValidatePoints(patch.control_points, "control_points"));
  const size_t count = TriangularPointCount(patch.degree);
  if (patch.control_points.size() != count) {
    return InvalidFieldError(
        "control_points.coordinates",
        absl::StrCat("holds ", patch.control_points.size(),
                     " points, a triangular patch of degree ", patch.degree,
                     " needs (n+1)(n+2)/2 = ", count));
  }
  if (patch.rational()) {
    RETURN_IF_ERROR(ValidateWeights(patch.weights, patch.degree, count));
  }
  return ValidateDomainTriangle(patch.domain_triangle);
}

absl::Status EvaluateTriangularPatch(const TriangularPatchView& patch,
                                     absl::Span<const double> uv,
                                     SurfaceOutput output,
                                     const ExecutionContext& context) {
  RETURN_IF_ERROR(ValidateTriangularPatch(patch));
  return internal::EvaluateValidTriangularPatch(patch, uv, output, context);
}

namespace internal {

absl::Status ValidateTriangularPairs(const TriangularPatchView& patch,
                                     absl::Span<const double> uv) {
  return ValidatePairs(uv, ParameterMap(patch.domain_triangle));
}

absl::Status EvaluateValidTriangularPatch(const TriangularPatchView& patch,
                                          absl::Span<const double> uv,
                                          SurfaceOutput output,
                                          const ExecutionContext& context) {
  const ParameterMap map(patch.domain_triangle);
  RETURN_IF_ERROR(ValidatePairs(uv, map));
  const size_t count = uv.size() / 2;
  const int dimension = patch.control_points.dimension;
  RETURN_IF_ERROR(ValidateSurfaceOutput(output, count, dimension));
  const PatchEvaluator evaluator(patch, MaxOrderOf(output), map);
  const size_t dim = static_cast<size_t>(dimension);
  return ParallelFor(count, context, [&](size_t begin, size_t end) {
    std::vector<double> scratch(evaluator.scratch_size() +
                                evaluator.partials_size());
    double* partials = scratch.data() + evaluator.scratch_size();
    for (size_t r = begin; r < end; ++r) {
      double u, v, w;
      map.Clamped(uv[2 * r], uv[2 * r + 1], &u, &v, &w);
      evaluator.Evaluate(u, v, w, scratch.data(), partials);
      for (size_t p = 0; p < output.size(); ++p) {
        std::copy(partials + p * dim, partials + (p + 1) * dim,
                  output[p].data() + r * dim);
      }
    }
  });
}

}  // namespace internal

absl::Status EvaluateTriangularBasis(int n, absl::Span<const double> uv,
                                     absl::Span<double> values,
                                     const ExecutionContext& context) {
  if (n < 0) {
    return InvalidFieldError("degree", absl::StrCat("must be >= 0, got ", n));
  }
  const ParameterMap map({});
  RETURN_IF_ERROR(ValidatePairs(uv, map));
  const size_t points = uv.size() / 2;
  const size_t functions = TriangularPointCount(n);
  if (values.size() / functions != points || values.size() % functions != 0) {
    return InvalidFieldError(
        "values", absl::StrCat("holds ", values.size(), " values, expected ",
                               points, " points x ", functions, " functions"));
  }
  return ParallelFor(points, context, [&](size_t begin, size_t end) {
    std::vector<double> scratch(2 * functions);
    for (size_t r = begin; r < end; ++r) {
      double u, v, w;
      map.Clamped(uv[2 * r], uv[2 * r + 1], &u, &v, &w);
      TriangularBernstein(n, u, v, w, scratch.data(),
                          values.data() + r * functions);
    }
  });
}

}  // namespace freeform
