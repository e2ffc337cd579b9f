#include "queries/bezier_net.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "base/homogeneous.h"
#include "base/scaled.h"
#include "base/tessellation_checks.h"
#include "freeform/core/bezier.h"
#include "freeform/core/points.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "freeform/core/surface_output.h"
#include "freeform/core/tensor_surface.h"
#include "refine/bezier_halving.h"

namespace freeform::internal {
namespace {

// LocalOf returns where x lies in [a, b] as a fraction in [0, 1] (0 for an
// empty interval).
double LocalOf(double x, double a, double b) {
  if (!(b > a)) return 0.0;
  return std::clamp((x - a) / (b - a), 0.0, 1.0);
}

// SurfaceLocals inverts SurfacePieceParameters: the (s, t) of piece k at
// the surface parameters uv, clamped to [0, 1]^2. For a triangular patch,
// the barycentric (u, v) of uv in its domain triangle (Cramer's rule), then
// s = u, t = v / (1 - s).
void SurfaceLocals(const SurfaceDecomposition& decomposition, size_t k,
                   const double* uv, double* st) {
  if (!decomposition.triangular) {
    const std::array<double, 2> low =
        SurfacePieceParameters(decomposition, k, 0.0, 0.0);
    const std::array<double, 2> high =
        SurfacePieceParameters(decomposition, k, 1.0, 1.0);
    st[0] = LocalOf(uv[0], low[0], high[0]);
    st[1] = LocalOf(uv[1], low[1], high[1]);
    return;
  }
  double u = uv[0];
  double v = uv[1];
  const std::vector<double>& d = decomposition.domain_triangle;
  if (!d.empty()) {
    // uv - C = u (A - C) + v (B - C).
    const double a0 = d[0] - d[4], a1 = d[1] - d[5];
    const double b0 = d[2] - d[4], b1 = d[3] - d[5];
    const double r0 = uv[0] - d[4], r1 = uv[1] - d[5];
    const double det = a0 * b1 - a1 * b0;
    u = det != 0.0 ? (r0 * b1 - r1 * b0) / det : 0.0;
    v = det != 0.0 ? (a0 * r1 - a1 * r0) / det : 0.0;
  }
  st[0] = std::clamp(u, 0.0, 1.0);
  st[1] = st[0] < 1.0 ? std::clamp(v / (1.0 - st[0]), 0.0, 1.0) : 0.0;
}

Net Lifted(int dimension, int count_u, int count_v,
           const std::vector<double>& coordinates,
           const std::vector<double>& weights) {
  Net net{.dimension = dimension,
          .rational = !weights.empty(),
          .count_u = count_u,
          .count_v = count_v};
  net.values = LiftedValues({dimension, coordinates}, weights);
  return net;
}

// RaiseBasis turns the Bernstein basis of degree j - 1 at t in values[0..j-1]
// into that of degree j.
void RaiseBasis(int j, double t, double* values) {
  const double s = 1.0 - t;
  double carry = 0.0;  // t * B(j-1, i-1)
  for (int i = 0; i < j; ++i) {
    const double previous = values[i];
    values[i] = s * previous + carry;
    carry = t * previous;
  }
  values[j] = carry;
}

// BernsteinUpToSecond writes B(n,i,t) and its first and second derivatives
// into out[k * (n + 1) + i], k = 0, 1, 2 (docs/references.md, 'Bernstein
// polynomials': B'(n,i) = n (B(n-1,i-1) - B(n-1,i))), from the basis of
// degree n - 2 raised to n - 1 and n.
void BernsteinUpToSecond(int n, double t, double* out) {
  const size_t count = static_cast<size_t>(n) + 1;
  std::fill(out, out + 3 * count, 0.0);
  double* values = out;
  values[0] = 1.0;
  for (int j = 1; j <= n - 2; ++j) RaiseBasis(j, t, values);
  if (n >= 2) {
    const double scale = static_cast<double>(n) * (n - 1);
    double* second = out + 2 * count;
    for (int i = 0; i <= n - 2; ++i) {
      const double b = scale * values[i];
      second[i] += b;
      second[i + 1] -= 2.0 * b;
      second[i + 2] += b;
    }
    RaiseBasis(n - 1, t, values);
  }
  if (n >= 1) {
    double* first = out + count;
    for (int i = 0; i <= n - 1; ++i) {
      const double b = n * values[i];
      first[i] -= b;
      first[i + 1] += b;
    }
    RaiseBasis(n, t, values);
  }
}

// Cholesky solves the count x count system h d = -g in place when h is
// positive definite; returns false otherwise.
bool Cholesky(int count, double* h, const double* g, double* d) {
  double l[9] = {0};
  for (int i = 0; i < count; ++i) {
    for (int j = 0; j <= i; ++j) {
      double sum = h[i * count + j];
      for (int k = 0; k < j; ++k) sum -= l[i * 3 + k] * l[j * 3 + k];
      if (i == j) {
        if (!(sum > 0.0)) return false;
        l[i * 3 + i] = std::sqrt(sum);
      } else {
        l[i * 3 + j] = sum / l[j * 3 + j];
      }
    }
  }
  double y[3];
  for (int i = 0; i < count; ++i) {
    double sum = -g[i];
    for (int k = 0; k < i; ++k) sum -= l[i * 3 + k] * y[k];
    y[i] = sum / l[i * 3 + i];
  }
  for (int i = count - 1; i >= 0; --i) {
    double sum = y[i];
    for (int k = i + 1; k < count; ++k) sum -= l[k * 3 + i] * d[k];
    d[i] = sum / l[i * 3 + i];
  }
  return true;
}

// NewtonStep writes the step for the free variables (free[i]), the
// Hessian shifted by multiples of its largest diagonal until positive
// definite.
void NewtonStep(int count, const LocalModel& model, const bool* free,
                double* step) {
  int index[3];
  int m = 0;
  for (int i = 0; i < count; ++i) {
    step[i] = 0.0;
    if (free[i]) index[m++] = i;
  }
  if (m == 0) return;
  double scale = 0.0;
  for (int a = 0; a < m; ++a) {
    scale = std::max(scale, std::abs(model.hessian[index[a] * 3 + index[a]]));
  }
  if (scale == 0.0) scale = 1.0;
  double g[3];
  for (int a = 0; a < m; ++a) g[a] = model.gradient[index[a]];
  if (m == 1) {  // the same shifts without the square root
    const double h = model.hessian[index[0] * 4];
    for (double shift = 0.0;; shift = shift == 0.0 ? 1e-12 : shift * 100.0) {
      const double shifted = h + shift * scale;
      if (shifted > 0.0 || shift > 1e12) {
        const double d = -g[0] / shifted;
        step[index[0]] = std::isfinite(d) ? d : 0.0;
        return;
      }
    }
  }
  for (double shift = 0.0;; shift = shift == 0.0 ? 1e-12 : shift * 100.0) {
    double h[9];
    for (int a = 0; a < m; ++a) {
      for (int b = 0; b < m; ++b) {
        h[a * m + b] = model.hessian[index[a] * 3 + index[b]] +
                       (a == b ? shift * scale : 0.0);
      }
    }
    double d[3];
    if (Cholesky(m, h, g, d) || shift > 1e12) {
      for (int a = 0; a < m; ++a) {
        step[index[a]] = std::isfinite(d[a]) ? d[a] : 0.0;
      }
      return;
    }
  }
}

// Range returns the smallest and largest coordinate x of `points`.
std::pair<double, double> Range(absl::Span<const double> points, int dimension,
                                int x) {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (size_t k = static_cast<size_t>(x); k < points.size();
       k += static_cast<size_t>(dimension)) {
    lo = std::min(lo, points[k]);
    hi = std::max(hi, points[k]);
  }
  return {lo, hi};
}

// GradientNorm returns the norm of the projected gradient at x (parts
// pointing out of the box at a bound left out).
double GradientNorm(int count, const LocalModel& model, const double* x,
                    const double* lower, const double* upper) {
  double sum = 0.0;
  for (int i = 0; i < count; ++i) {
    const double g = model.gradient[i];
    if ((x[i] <= lower[i] && g > 0.0) || (x[i] >= upper[i] && g < 0.0)) {
      continue;
    }
    sum += g * g;
  }
  return std::sqrt(sum);
}

// LargestWeight returns the largest weight of a rational net.
double LargestWeight(const Net& net) {
  double largest = 0.0;
  const size_t stride = static_cast<size_t>(net.stride());
  for (size_t k = static_cast<size_t>(net.dimension); k < net.values.size();
       k += stride) {
    largest = std::max(largest, net.values[k]);
  }
  return largest;
}

}  // namespace

Net LiftCurve(const BezierCurveData& curve) {
  return Lifted(curve.dimension,
                static_cast<int>(curve.coordinates.size()) / curve.dimension, 1,
                curve.coordinates, curve.weights);
}

Net LiftSurface(const SurfaceData& surface) {
  return Lifted(surface.dimension, surface.count_u, surface.count_v,
                surface.coordinates, surface.weights);
}

absl::StatusOr<Pieces> LiftPieces(const Curve& curve,
                                  const CancellationToken* cancel) {
  absl::StatusOr<BezierDecomposition> pieces = DecomposeCurve(curve, cancel);
  if (!pieces.ok()) return pieces.status();
  Pieces result{.dimension = DimensionOf(curve), .parameter_count = 1};
  // Each piece is freed once lifted, so the pieces exist once at a time.
  result.nets.reserve(pieces->segments.size());
  for (BezierCurveData& segment : pieces->segments) {
    result.nets.push_back(LiftCurve(segment));
    segment = {};
  }
  auto breaks = std::make_shared<const std::vector<double>>(
      std::move(pieces->breakpoints));
  result.parameters = [breaks](size_t k, double s, double, double* out) {
    const std::vector<double>& b = *breaks;
    out[0] = s >= 1.0 ? b[k + 1] : b[k] + s * (b[k + 1] - b[k]);
  };
  result.locals = [breaks](size_t k, const double* global, double* st) {
    st[0] = LocalOf(global[0], (*breaks)[k], (*breaks)[k + 1]);
    st[1] = 0.0;
  };
  return result;
}

absl::StatusOr<Pieces> LiftPieces(const Surface& surface,
                                  const CancellationToken* cancel) {
  absl::StatusOr<SurfaceDecomposition> pieces =
      DecomposeSurface(surface, cancel);
  if (!pieces.ok()) return pieces.status();
  Pieces result{.dimension = DimensionOf(surface), .parameter_count = 2};
  // Each piece is freed once lifted, so the pieces exist once at a time;
  // the parameters need the breakpoints only.
  result.nets.reserve(pieces->pieces.patches.size());
  for (SurfaceData& patch : pieces->pieces.patches) {
    result.nets.push_back(LiftSurface(patch));
    patch = {};
  }
  std::vector<SurfaceData>().swap(pieces->pieces.patches);
  auto shared =
      std::make_shared<const SurfaceDecomposition>(*std::move(pieces));
  result.parameters = [shared](size_t k, double s, double t, double* out) {
    const std::array<double, 2> uv = SurfacePieceParameters(*shared, k, s, t);
    out[0] = uv[0];
    out[1] = uv[1];
  };
  result.locals = [shared](size_t k, const double* uv, double* st) {
    SurfaceLocals(*shared, k, uv, st);
  };
  return result;
}

absl::Status UnresolvedError(absl::string_view field,
                             absl::Span<const double> near, double apart) {
  return InvalidFieldError(
      field,
      absl::StrCat("an answer lies at parameters near (",
                   absl::StrJoin(near, ", "),
                   ") that double precision cannot resolve: at the nearest "
                   "doubles the inputs are ",
                   apart,
                   " apart, beyond the tolerance (knot spans too short for "
                   "their position, or weights too far apart)"));
}

void Halve(const Net& net, bool in_u, Net& low, Net& high) {
  for (Net* half : {&low, &high}) {
    half->dimension = net.dimension;
    half->rational = net.rational;
    half->count_u = net.count_u;
    half->count_v = net.count_v;
    half->values.resize(net.values.size());
  }
  HalveNet(net.values.data(), net.count_u, net.count_v, net.stride(), in_u,
           low.values.data(), high.values.data());
}

bool Point(const Net& net, int i, int j, double* point) {
  const double* p = net.at(i, j);
  if (!net.rational) {
    std::copy_n(p, net.dimension, point);
    return true;
  }
  return ProjectPositive(p, net.dimension, point);
}

bool Project(const Net& net, std::vector<double>& points) {
  points.resize(static_cast<size_t>(net.count_u) * net.count_v * net.dimension);
  bool positive = true;
  for (int i = 0; i < net.count_u; ++i) {
    for (int j = 0; j < net.count_v; ++j) {
      positive &=
          Point(net, i, j,
                points.data() +
                    (static_cast<size_t>(i) * net.count_v + j) * net.dimension);
    }
  }
  return positive;
}

absl::Status CheckTolerances(double tolerance, double separation) {
  if (!std::isfinite(tolerance) || tolerance <= 0.0) {
    return InvalidFieldError("tolerance", "must be positive and finite");
  }
  if (!std::isfinite(separation) || separation < 0.0) {
    return InvalidFieldError("separation", "must be finite and >= 0");
  }
  return absl::OkStatus();
}

double LargestNetCoordinate(const Net& net) {
  double largest = 0.0;
  std::vector<double> point(static_cast<size_t>(net.dimension));
  for (int i = 0; i < net.count_u; ++i) {
    for (int j = 0; j < net.count_v; ++j) {
      if (!Point(net, i, j, point.data())) continue;
      for (const double x : point) largest = std::max(largest, std::abs(x));
    }
  }
  return largest;
}

double LargestCoordinate(absl::Span<const Pieces* const> pieces) {
  double largest = 0.0;
  for (const Pieces* each : pieces) {
    for (const Net& net : each->nets) {
      largest = std::max(largest, LargestNetCoordinate(net));
    }
  }
  return largest;
}

absl::StatusOr<QueryScale> ScaleForQuery(double tolerance,
                                         absl::Span<Pieces* const> pieces) {
  const std::vector<const Pieces*> all(pieces.begin(), pieces.end());
  const double largest = LargestCoordinate(all);
  RETURN_IF_ERROR(CheckResolvableAt(tolerance, largest));
  if (!(largest > 0.0) || !std::isfinite(largest)) return QueryScale{};
  const int exponent = std::ilogb(largest);
  for (Pieces* each : pieces) {
    for (Net& net : each->nets) {
      const size_t stride = static_cast<size_t>(net.stride());
      for (size_t k = 0; k < net.values.size(); ++k) {
        if (k % stride < static_cast<size_t>(net.dimension)) {
          net.values[k] = std::ldexp(net.values[k], -exponent);
        }
      }
    }
  }
  return QueryScale{.exponent = exponent,
                    .largest = std::ldexp(largest, -exponent)};
}

absl::Status WorkBudget::Check() {
  if (spent_ > limit_) {
    return ExhaustedFieldError(
        field_, absl::StrCat(what_, " needs more than ", limit_,
                             " units of work (about one multiply-add each)"));
  }
  const uint64_t pending = pending_;
  pending_ = 0;
  return poll_.Done(static_cast<size_t>(pending));
}

double BoxDistance(absl::Span<const double> points, int dimension,
                   const double* query) {
  double sum = 0.0;
  for (int x = 0; x < dimension; ++x) {
    const auto [lo, hi] = Range(points, dimension, x);
    const double gap = std::max({lo - query[x], query[x] - hi, 0.0});
    sum += gap * gap;
  }
  return std::sqrt(sum);
}

double BoxDiameter(absl::Span<const double> points, int dimension) {
  double sum = 0.0;
  for (int x = 0; x < dimension; ++x) {
    const auto [lo, hi] = Range(points, dimension, x);
    sum += (hi - lo) * (hi - lo);
  }
  return std::sqrt(sum);
}

double DirectionalBound(absl::Span<const double> points, int dimension,
                        const double* query, const double* toward) {
  const double length = PointDistance(query, toward, dimension);
  if (!(length > 0.0)) return 0.0;
  double bound = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < points.size(); k += static_cast<size_t>(dimension)) {
    double along = 0.0;
    for (int x = 0; x < dimension; ++x) {
      along += (query[x] - toward[x]) * (query[x] - points[k + x]);
    }
    bound = std::min(bound, along / length);
  }
  return std::max(bound, 0.0);
}

void PolygonLengths(absl::Span<const double> points, int dimension, int count_u,
                    int count_v, double& along_u, double& along_v) {
  auto distance = [&](int i0, int j0, int i1, int j1) {
    const double* a =
        points.data() + (static_cast<size_t>(i0) * count_v + j0) * dimension;
    const double* b =
        points.data() + (static_cast<size_t>(i1) * count_v + j1) * dimension;
    double sum = 0.0;
    for (int x = 0; x < dimension; ++x) sum += (a[x] - b[x]) * (a[x] - b[x]);
    return std::sqrt(sum);
  };
  along_u = 0.0;
  along_v = 0.0;
  for (int j = 0; j < count_v; ++j) {
    double length = 0.0;
    for (int i = 0; i + 1 < count_u; ++i) length += distance(i, j, i + 1, j);
    along_u = std::max(along_u, length);
  }
  for (int i = 0; i < count_u; ++i) {
    double length = 0.0;
    for (int j = 0; j + 1 < count_v; ++j) length += distance(i, j, i, j + 1);
    along_v = std::max(along_v, length);
  }
}

void NetEvaluator::EvaluateCurve(const Net& net, double s, double* partials) {
  const int nu = net.count_u;
  const int stride = net.stride();
  basis_u_.resize(3 * static_cast<size_t>(nu));
  BernsteinUpToSecond(nu - 1, s, basis_u_.data());
  homogeneous_.resize(PartialCount(2) * static_cast<size_t>(stride));
  double* out = net.rational ? homogeneous_.data() : partials;
  std::fill(out, out + PartialCount(2) * stride, 0.0);
  double* rows[3] = {out + PartialIndex(0, 0) * stride,
                     out + PartialIndex(1, 0) * stride,
                     out + PartialIndex(2, 0) * stride};
  for (int i = 0; i < nu; ++i) {
    const double* p = net.at(i, 0);
    for (int k = 0; k < 3; ++k) {
      const double b = basis_u_[static_cast<size_t>(k) * nu + i];
      for (int x = 0; x < stride; ++x) rows[k][x] += b * p[x];
    }
  }
  if (net.rational) {
    ProjectHomogeneousSurfaceDerivatives(out, net.dimension, 2, partials);
  }
}

void NetEvaluator::Evaluate(const Net& net, double s, double t,
                            double* partials) {
  if (net.count_v == 1) {
    EvaluateCurve(net, s, partials);
    return;
  }
  const int nu = net.count_u;
  const int nv = net.count_v;
  const int stride = net.stride();
  basis_u_.resize(3 * static_cast<size_t>(nu));
  basis_v_.resize(3 * static_cast<size_t>(nv));
  BernsteinUpToSecond(nu - 1, s, basis_u_.data());
  BernsteinUpToSecond(nv - 1, t, basis_v_.data());
  homogeneous_.resize(PartialCount(2) * static_cast<size_t>(stride));
  double* out = net.rational ? homogeneous_.data() : partials;
  std::fill(out, out + PartialCount(2) * stride, 0.0);
  for (int k = 0; k <= 2; ++k) {
    for (int l = 0; k + l <= 2; ++l) {
      double* target = out + PartialIndex(k, l) * stride;
      for (int i = 0; i < nu; ++i) {
        const double bu = basis_u_[static_cast<size_t>(k) * nu + i];
        if (bu == 0.0) continue;
        for (int j = 0; j < nv; ++j) {
          const double b = bu * basis_v_[static_cast<size_t>(l) * nv + j];
          const double* p = net.at(i, j);
          for (int x = 0; x < stride; ++x) target[x] += b * p[x];
        }
      }
    }
  }
  if (net.rational) {
    ProjectHomogeneousSurfaceDerivatives(out, net.dimension, 2, partials);
  }
}

double NetEvaluator::Value(const Net& scalar, double s, double t,
                           double& magnitude) {
  const int nu = scalar.count_u;
  const int nv = scalar.count_v;
  basis_u_.assign(static_cast<size_t>(nu), 0.0);
  basis_v_.assign(static_cast<size_t>(nv), 0.0);
  basis_u_[0] = 1.0;
  basis_v_[0] = 1.0;
  for (int j = 1; j < nu; ++j) RaiseBasis(j, s, basis_u_.data());
  for (int j = 1; j < nv; ++j) RaiseBasis(j, t, basis_v_.data());
  double value = 0.0;
  magnitude = 0.0;
  for (int i = 0; i < nu; ++i) {
    double row = 0.0;
    double row_magnitude = 0.0;
    for (int j = 0; j < nv; ++j) {
      const double term = basis_v_[j] * scalar.at(i, j)[0];
      row += term;
      row_magnitude += std::abs(term);
    }
    value += basis_u_[i] * row;
    magnitude += basis_u_[i] * row_magnitude;
  }
  return value;
}

void DistanceModel(NetEvaluator& evaluator, const Net& net, int parameter_count,
                   const double* query, const double* x, double* partials,
                   LocalModel& model) {
  const int dim = net.dimension;
  evaluator.Evaluate(net, x[0], parameter_count == 2 ? x[1] : 0.0, partials);
  const double* s = partials;
  const double* su = s + dim;
  const double* sv = s + 2 * dim;
  double value = 0, g0 = 0, g1 = 0, h00 = 0, h01 = 0, h11 = 0;
  for (int k = 0; k < dim; ++k) {
    const double r = s[k] - query[k];
    value += r * r;
    g0 += r * su[k];
    g1 += r * sv[k];
    h00 += su[k] * su[k] + r * s[3 * dim + k];
    h01 += su[k] * sv[k] + r * s[4 * dim + k];
    h11 += sv[k] * sv[k] + r * s[5 * dim + k];
  }
  model = LocalModel{};
  model.value = 0.5 * value;
  model.gradient[0] = g0;
  model.gradient[1] = g1;
  model.hessian[0] = h00;
  model.hessian[1] = model.hessian[3] = h01;
  model.hessian[4] = h11;
}

double MinimizeInBox(int count, const double* lower, const double* upper,
                     double* x,
                     absl::FunctionRef<void(const double*, LocalModel&)> model,
                     int max_iterations) {
  LocalModel current;
  model(x, current);
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    bool free[3];
    for (int i = 0; i < count; ++i) {
      const double g = current.gradient[i];
      free[i] =
          !((x[i] <= lower[i] && g > 0.0) || (x[i] >= upper[i] && g < 0.0));
    }
    double step[3];
    NewtonStep(count, current, free, step);
    // Converged: the step is within a few rounding errors of x.
    bool negligible = true;
    for (int i = 0; i < count; ++i) {
      negligible &= std::abs(step[i]) <=
                    4.0 * std::numeric_limits<double>::epsilon() *
                        std::max(std::abs(x[i]), upper[i] - lower[i]);
    }
    if (negligible) break;
    bool moved = false;
    for (double fraction = 1.0; fraction > 1e-12; fraction *= 0.5) {
      double trial[3];
      bool changed = false;
      for (int i = 0; i < count; ++i) {
        trial[i] = std::clamp(x[i] + fraction * step[i], lower[i], upper[i]);
        changed |= trial[i] != x[i];
      }
      if (!changed) break;
      LocalModel next;
      model(trial, next);
      // Near the minimum the value stops resolving the step (it changes
      // by rounding only) while the gradient still does: a step that halves
      // the projected gradient and keeps the value within rounding counts.
      const bool better =
          next.value < current.value ||
          (next.value <= current.value * (1.0 + 1e-10) &&
           GradientNorm(count, next, trial, lower, upper) <
               0.5 * GradientNorm(count, current, x, lower, upper));
      if (better) {
        std::copy_n(trial, count, x);
        current = next;
        moved = true;
        break;
      }
    }
    if (!moved) break;
  }
  return current.value;
}

void NormalizeWeights(Net& net) {
  if (!net.rational) return;
  const int e = ExponentAbove(LargestWeight(net));
  if (e == 0) return;
  for (double& value : net.values) value = std::ldexp(value, -e);
}

}  // namespace freeform::internal
