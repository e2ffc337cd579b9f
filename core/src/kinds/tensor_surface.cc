#include "freeform/core/tensor_surface.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "base/binomial.h"
#include "freeform/core/bspline.h"
#include "freeform/core/points.h"
#include "freeform/core/rational.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "kinds/scalar_reference.h"
#include "kinds/simd/surface_simd.h"
#include "kinds/validated_tensor_surface.h"

namespace freeform {
namespace {

// One parameter direction of a tensor-product surface: a basis of degree p
// with n + 1 functions on `knots` (Bezier: p = n on [0..0, 1..1]).
struct Direction {
  int degree = 0;
  int n = 0;
  absl::Span<const double> knots;
};

// The knot vector whose B-spline basis is the Bernstein basis of `degree`.
std::vector<double> BezierKnots(int degree) {
  std::vector<double> knots(2 * (static_cast<size_t>(degree) + 1), 0.0);
  std::fill(knots.begin() + degree + 1, knots.end(), 1.0);
  return knots;
}

// Per-chunk workspace for the local basis derivatives of one direction
// (The NURBS Book A2.1 and A2.3).
class LocalBasis {
 public:
  LocalBasis(const Direction& direction, int max_order)
      : direction_(direction),
        max_order_(max_order),
        ders_((static_cast<size_t>(max_order) + 1) *
              (static_cast<size_t>(direction.degree) + 1)),
        scratch_(BasisDerivativesScratchSize(direction.degree)) {}

  // Evaluate finds the span of t (searching from the previous one) and
  // fills ders(): N^(k)_{span-p+a}(t) at [k * (p + 1) + a].
  int Evaluate(double t) {
    span_ = FindSpanFrom(span_, direction_.n, direction_.degree, t,
                         direction_.knots);
    BasisFunctionDerivatives(span_, t, direction_.degree, max_order_,
                             direction_.knots, absl::MakeSpan(ders_),
                             absl::MakeSpan(scratch_));
    return span_;
  }
  const double* ders() const { return ders_.data(); }

 private:
  Direction direction_;
  int max_order_;
  int span_ = 0;
  std::vector<double> ders_;
  std::vector<double> scratch_;
};

// What every chunk of one surface evaluation reads.
struct TensorBatch {
  Direction u;
  Direction v;
  int count_v = 0;
  int dimension = 0;
  // dimension + 1 for a rational surface (homogeneous points).
  int work = 0;
  int max_order = 0;
  const double* control = nullptr;  // the net, `work` values per point
  std::vector<double*> output;      // one buffer per partial

  bool rational() const { return work != dimension; }
  size_t partials() const { return PartialCount(max_order); }
};

// out = sum_b basis[b] * points[b * stride .. + work).
inline void Combine(const double* basis, int count, const double* points,
                    size_t stride, int work, double* out) {
  for (int x = 0; x < work; ++x) {
    double sum = 0.0;  // in a register: `out` may be the caller's buffer
    for (int b = 0; b < count; ++b) {
      sum += basis[b] * points[static_cast<size_t>(b) * stride + x];
    }
    out[x] = sum;
  }
}

// Scratch for the partials of one point; positions of a polynomial surface
// go straight to the output.
class PointPartials {
 public:
  explicit PointPartials(const TensorBatch& batch)
      : batch_(batch),
        homogeneous_(batch.rational()
                         ? batch.partials() * static_cast<size_t>(batch.work)
                         : 0),
        projected_(batch.rational()
                       ? batch.partials() * static_cast<size_t>(batch.dimension)
                       : 0) {}

  // Where partial m (PartialIndex order) of point r is accumulated.
  double* Target(size_t m, size_t r) {
    if (batch_.rational()) {
      return homogeneous_.data() + m * static_cast<size_t>(batch_.work);
    }
    return batch_.output[m] + r * static_cast<size_t>(batch_.dimension);
  }

  // Finish projects the homogeneous partials of point r into the output.
  void Finish(size_t r) {
    if (!batch_.rational()) return;
    const size_t dim = static_cast<size_t>(batch_.dimension);
    ProjectHomogeneousSurfaceDerivatives(homogeneous_.data(), batch_.dimension,
                                         batch_.max_order, projected_.data());
    for (size_t m = 0; m < batch_.partials(); ++m) {
      std::copy_n(projected_.data() + m * dim, dim, batch_.output[m] + r * dim);
    }
  }

 private:
  const TensorBatch& batch_;
  std::vector<double> homogeneous_;
  std::vector<double> projected_;
};

// Evaluates (u, v) pairs [begin, end): per point the u and v bases, the
// v-direction points Q_k[b] = sum_a N^(k)_a(u) P[su-p+a][sv-q+b] of each
// order k, then A_{k,l} = sum_b N^(l)_b(v) Q_k[b] (The NURBS Book A3.6).
void EvaluatePairsChunk(const TensorBatch& batch, absl::Span<const double> uv,
                        size_t begin, size_t end) {
  const int p = batch.u.degree;
  const int q = batch.v.degree;
  const int d = batch.max_order;
  const int w = batch.work;
  const size_t row_stride = static_cast<size_t>(batch.count_v) * w;
  LocalBasis basis_u(batch.u, d);
  LocalBasis basis_v(batch.v, d);
  std::vector<double> row(static_cast<size_t>(q + 1) * w);
  PointPartials partials(batch);
  for (size_t r = begin; r < end; ++r) {
    const int su = basis_u.Evaluate(uv[2 * r]);
    const int sv = basis_v.Evaluate(uv[2 * r + 1]);
    const double* corner =
        batch.control + (su - p) * row_stride + static_cast<size_t>(sv - q) * w;
    for (int k = 0; k <= d; ++k) {
      for (int b = 0; b <= q; ++b) {
        Combine(basis_u.ders() + k * (p + 1), p + 1,
                corner + static_cast<size_t>(b) * w, row_stride, w,
                row.data() + static_cast<size_t>(b) * w);
      }
      for (int l = 0; l <= d - k; ++l) {
        Combine(basis_v.ders() + l * (q + 1), q + 1, row.data(),
                static_cast<size_t>(w), w,
                partials.Target(PartialIndex(k, l), r));
      }
    }
    partials.Finish(r);
  }
}

// How a grid row combines its v-direction nets with the column bases.
enum class GridKernel {
  kLanes,   // simd/surface_simd.h for polynomial surfaces
  kScalar,  // point by point
};

// The v bases of a grid, computed once, in the planes of
// simd::GridRowLanesBatch: N^(l)_{spans[j]-q+b}(v_j) at
// planes[(l * (q + 1) + b) * stride + j].
struct GridColumns {
  std::vector<int> spans;
  std::vector<size_t> run_ends;  // where the run of equal spans from j ends
  size_t stride = 0;
  std::vector<double> planes;
};

GridColumns ColumnBases(const Direction& v_direction, int max_order,
                        absl::Span<const double> v) {
  const size_t block = (static_cast<size_t>(max_order) + 1) *
                       (static_cast<size_t>(v_direction.degree) + 1);
  const size_t stride = v.size() + simd::kPlanePadding;
  GridColumns columns{.spans = std::vector<int>(v.size()),
                      .run_ends = std::vector<size_t>(v.size()),
                      .stride = stride,
                      .planes = std::vector<double>(block * stride, 0.0)};
  LocalBasis basis(v_direction, max_order);
  for (size_t j = 0; j < v.size(); ++j) {
    columns.spans[j] = basis.Evaluate(v[j]);
    for (size_t x = 0; x < block; ++x) {
      columns.planes[x * stride + j] = basis.ders()[x];
    }
  }
  for (size_t j = v.size(); j-- > 0;) {
    const bool run_goes_on =
        j + 1 < v.size() && columns.spans[j + 1] == columns.spans[j];
    columns.run_ends[j] = run_goes_on ? columns.run_ends[j + 1] : j + 1;
  }
  return columns;
}

// The points of grid row i, columns j, partials m = PartialIndex(k, l),
// one at a time: out = sum_b N^(l)_b(v_j) Q_k[span_j - q + b].
void CombineRowScalar(const TensorBatch& batch, const GridColumns& columns,
                      const double* nets, size_t i, PointPartials& partials,
                      std::vector<double>& basis) {
  const int q = batch.v.degree;
  const int d = batch.max_order;
  const int w = batch.work;
  const size_t count_v = columns.spans.size();
  const size_t net_stride = static_cast<size_t>(batch.count_v) * w;
  for (size_t j = 0; j < count_v; ++j) {
    const size_t r = i * count_v + j;
    const size_t offset = static_cast<size_t>(columns.spans[j] - q) * w;
    for (int k = 0; k <= d; ++k) {
      for (int l = 0; l <= d - k; ++l) {
        for (int b = 0; b <= q; ++b) {
          basis[b] = columns.planes[(l * (q + 1) + b) * columns.stride + j];
        }
        Combine(basis.data(), q + 1, nets + k * net_stride + offset,
                static_cast<size_t>(w), w,
                partials.Target(PartialIndex(k, l), r));
      }
    }
    partials.Finish(r);
  }
}

// Evaluates grid rows [begin, end): per u_i the whole v-direction net
// Q_k[j] = sum_a N^(k)_a(u_i) P[su-p+a][j] of each order k, then per v_j
// the dot products with the precomputed v basis.
void EvaluateGridRows(const TensorBatch& batch, absl::Span<const double> u,
                      const GridColumns& columns, GridKernel kernel,
                      size_t begin, size_t end) {
  const int p = batch.u.degree;
  const int d = batch.max_order;
  const size_t count_v = columns.spans.size();
  const size_t net_stride = static_cast<size_t>(batch.count_v) * batch.work;
  LocalBasis basis_u(batch.u, d);
  std::vector<double> nets(static_cast<size_t>(d + 1) * net_stride);
  std::vector<double> basis_v(static_cast<size_t>(batch.v.degree) + 1);
  std::vector<double*> row_output(batch.partials());
  PointPartials partials(batch);
  const bool lanes = kernel == GridKernel::kLanes && !batch.rational();
  for (size_t i = begin; i < end; ++i) {
    const int su = basis_u.Evaluate(u[i]);
    const double* first_row = batch.control + (su - p) * net_stride;
    for (int k = 0; k <= d; ++k) {
      const double* basis = basis_u.ders() + k * (p + 1);
      double* net = nets.data() + k * net_stride;
      std::fill_n(net, net_stride, 0.0);
      for (int a = 0; a <= p; ++a) {
        const double* points = first_row + a * net_stride;
        for (size_t x = 0; x < net_stride; ++x) net[x] += basis[a] * points[x];
      }
    }
    if (!lanes) {
      CombineRowScalar(batch, columns, nets.data(), i, partials, basis_v);
      continue;
    }
    for (size_t m = 0; m < row_output.size(); ++m) {
      row_output[m] = batch.output[m] + i * count_v * batch.dimension;
    }
    simd::EvaluateGridRow({.q = batch.v.degree,
                           .dimension = batch.dimension,
                           .max_order = d,
                           .columns = count_v,
                           .spans = columns.spans.data(),
                           .run_ends = columns.run_ends.data(),
                           .planes = columns.planes.data(),
                           .plane_stride = columns.stride,
                           .nets = nets.data(),
                           .net_stride = net_stride,
                           .output = row_output.data()});
  }
}

// Validates the samples and output, then evaluates the surface over
// directions u and v with the net (and weights) of `net`.
absl::Status EvaluateTensorSurface(
    const Direction& u, const Direction& v, const ControlNetView& net,
    absl::Span<const double> weights, const SurfaceDomain& domain,
    const SurfaceSamples& samples, SurfaceOutput output,
    const ExecutionContext& context, GridKernel kernel = GridKernel::kLanes) {
  RETURN_IF_ERROR(ValidateSurfaceSamples(samples, domain.u_start, domain.u_end,
                                         domain.v_start, domain.v_end));
  RETURN_IF_ERROR(ValidateSurfaceOutput(output, samples.size(), net.dimension));
  const bool rational = !weights.empty();
  const std::vector<double> homogeneous =
      rational ? HomogeneousPoints({.dimension = net.dimension,
                                    .coordinates = net.coordinates},
                                   weights)
               : std::vector<double>();
  TensorBatch batch{
      .u = u,
      .v = v,
      .count_v = net.count_v,
      .dimension = net.dimension,
      .work = rational ? net.dimension + 1 : net.dimension,
      .max_order = MaxOrderOf(output),
      .control = rational ? homogeneous.data() : net.coordinates.data(),
      .output = {}};
  for (const absl::Span<double> buffer : output) {
    batch.output.push_back(buffer.data());
  }
  if (!samples.grid) {
    return ParallelFor(samples.size(), context, [&](size_t b, size_t e) {
      EvaluatePairsChunk(batch, samples.uv, b, e);
    });
  }
  const GridColumns columns = ColumnBases(v, batch.max_order, samples.v);
  ExecutionContext rows_context = context;
  rows_context.grain = std::max<size_t>(
      1, context.grain / std::max<size_t>(1, samples.v.size()));
  return ParallelFor(samples.u.size(), rows_context, [&](size_t b, size_t e) {
    EvaluateGridRows(batch, samples.u, columns, kernel, b, e);
  });
}

// Weights: one per net point, finite and >= 0.
absl::Status ValidateNetWeights(const ControlNetView& net,
                                absl::Span<const double> weights) {
  const size_t count = static_cast<size_t>(net.count_u) * net.count_v;
  if (weights.size() != count) {
    return InvalidFieldError(
        "weights",
        absl::StrCat("has ", weights.size(), " weights for ", count,
                     " net points (", net.count_u, " x ", net.count_v, ")"));
  }
  return ValidateWeightValues(weights);
}

// "degree_u" must be >= 0.
absl::Status ValidateDegree(int degree, absl::string_view field) {
  if (degree < 0) {
    return InvalidFieldError(field, absl::StrCat("must be >= 0, got ", degree));
  }
  return absl::OkStatus();
}

// The knot vector of one direction by the curve rules, with the curve's
// "knots..." paths renamed to `field` ("knots_u...").
absl::Status ValidateDirectionKnots(int degree, int count,
                                    absl::Span<const double> knots,
                                    absl::string_view field) {
  const size_t expected = static_cast<size_t>(count) + degree + 1;
  if (knots.size() != expected) {
    return InvalidFieldError(
        field, absl::StrCat("expected ", expected, " knots (", count,
                            " net points + degree ", degree, " + 1), got ",
                            knots.size()));
  }
  const absl::Status status = ValidateBSplineBasis(degree, knots, {});
  const std::optional<std::string> path = FieldPathOf(status);
  if (!path.has_value() || path->rfind("knots", 0) != 0) return status;
  return InvalidFieldError(absl::StrCat(field, path->substr(5)),
                           FieldRuleOf(status));
}

// The non-zero basis functions at the start, middle and end of every
// non-empty span of a direction, evaluated as EvaluateTensorSurface does
// (span fixed, so one-sided limits at the knots).
struct SpanSamples {
  std::vector<int> spans;
  std::vector<double> parameters;  // 3 per span
  std::vector<double> values;      // 3 * (p + 1) per span
};

SpanSamples SampleSpans(const Direction& direction) {
  const int p = direction.degree;
  SpanSamples samples;
  std::vector<double> values(static_cast<size_t>(p) + 1);
  std::vector<double> scratch(BasisScratchSize(p));
  for (int s = p; s <= direction.n; ++s) {
    const double start = direction.knots[s];
    const double end = direction.knots[s + 1];
    if (!(start < end)) continue;
    samples.spans.push_back(s);
    for (const double t : {start, 0.5 * (start + end), end}) {
      BasisFunctions(s, t, p, direction.knots, absl::MakeSpan(values),
                     absl::MakeSpan(scratch));
      samples.parameters.push_back(t);
      samples.values.insert(samples.values.end(), values.begin(), values.end());
    }
  }
  return samples;
}

// The weight of the largest basis product at a sample of span rectangle
// (su, sv), or -1 when the denominator there is positive.
int64_t ZeroDenominatorWeight(const double* nu, int p, int su, const double* nv,
                              int q, int sv, int count_v,
                              absl::Span<const double> weights) {
  double denominator = 0.0;
  double largest = -1.0;
  int64_t index = -1;
  for (int a = 0; a <= p; ++a) {
    for (int b = 0; b <= q; ++b) {
      const int64_t k =
          static_cast<int64_t>(su - p + a) * count_v + (sv - q + b);
      const double product = nu[a] * nv[b];
      denominator += product * weights[static_cast<size_t>(k)];
      if (product > largest) {
        largest = product;
        index = k;
      }
    }
  }
  return denominator > 0.0 ? -1 : index;
}

// With nonnegative weights and N_a, M_b >= 0, the denominator at a corner
// being positive means one positive weight whose product is positive there;
// the same product stays positive along the adjoining open edges and inside,
// so the corners decide, and the midpoints cost little to check as well.
absl::Status ValidateDenominator(const Direction& u, const Direction& v,
                                 int count_v,
                                 absl::Span<const double> weights) {
  if (std::all_of(weights.begin(), weights.end(),
                  [](double w) { return w > 0; })) {
    return absl::OkStatus();  // a convex combination of positive weights
  }
  const SpanSamples us = SampleSpans(u);
  const SpanSamples vs = SampleSpans(v);
  const size_t pu = static_cast<size_t>(u.degree) + 1;
  const size_t pv = static_cast<size_t>(v.degree) + 1;
  for (size_t a = 0; a < us.parameters.size(); ++a) {
    for (size_t b = 0; b < vs.parameters.size(); ++b) {
      const int64_t k =
          ZeroDenominatorWeight(us.values.data() + a * pu, u.degree,
                                us.spans[a / 3], vs.values.data() + b * pv,
                                v.degree, vs.spans[b / 3], count_v, weights);
      if (k < 0) continue;
      return InvalidFieldError(
          IndexedField("weights", static_cast<size_t>(k)),
          absl::StrCat("the surface is infinite at (u, v) = (",
                       us.parameters[a], ", ", vs.parameters[b],
                       "): the net points whose basis functions are nonzero "
                       "there all have weight 0"));
    }
  }
  return absl::OkStatus();
}

Direction BSplineDirection(int degree, int count,
                           absl::Span<const double> knots) {
  return {.degree = degree, .n = count - 1, .knots = knots};
}

// EvaluateValidBSplineSurface with the grid rows finished by `kernel`.
absl::Status EvaluateValidBSplineSurfaceWith(const BSplineSurfaceView& surface,
                                             const SurfaceSamples& samples,
                                             SurfaceOutput output,
                                             const ExecutionContext& context,
                                             GridKernel kernel) {
  const ControlNetView& net = surface.control_net;
  return EvaluateTensorSurface(
      BSplineDirection(surface.degree_u, net.count_u, surface.knots_u),
      BSplineDirection(surface.degree_v, net.count_v, surface.knots_v), net,
      surface.weights, BSplineSurfaceDomain(surface), samples, output, context,
      kernel);
}

}  // namespace

absl::Status ValidateControlNet(const ControlNetView& net,
                                absl::string_view field, int min_u, int min_v) {
  if (net.dimension < 1 || net.dimension > kMaxDimension) {
    return InvalidFieldError(
        absl::StrCat(field, ".dimension"),
        absl::StrCat("dimension must be between 1 and ", kMaxDimension,
                     ", got ", net.dimension));
  }
  if (net.count_u < min_u) {
    return InvalidFieldError(
        absl::StrCat(field, ".count_u"),
        absl::StrCat("needs at least ", min_u, " rows, got ", net.count_u));
  }
  if (net.count_v < min_v) {
    return InvalidFieldError(
        absl::StrCat(field, ".count_v"),
        absl::StrCat("needs at least ", min_v, " columns, got ", net.count_v));
  }
  // Compared by division so that huge counts cannot overflow.
  const size_t size = net.coordinates.size();
  const size_t row = static_cast<size_t>(net.count_v) * net.dimension;
  const size_t count_u = static_cast<size_t>(net.count_u);
  if (size % row != 0 || size / row != count_u) {
    return InvalidFieldError(
        absl::StrCat(field, ".coordinates"),
        absl::StrCat("has ", size,
                     " values, expected count_u * count_v * "
                     "dimension = ",
                     net.count_u, " * ", net.count_v, " * ", net.dimension));
  }
  // The field's name is made only for an error (evaluators validate every
  // Bezier piece of a mesh).
  if (std::all_of(net.coordinates.begin(), net.coordinates.end(),
                  [](double x) { return std::isfinite(x); })) {
    return absl::OkStatus();
  }
  return ValidateFinite(net.coordinates, absl::StrCat(field, ".coordinates"));
}

absl::Status ValidateBezierSurface(const BezierSurfaceView& surface) {
  const ControlNetView& net = surface.control_net;
  RETURN_IF_ERROR(ValidateControlNet(net, "control_net"));
  if (!surface.rational()) return absl::OkStatus();
  RETURN_IF_ERROR(ValidateNetWeights(net, surface.weights));
  for (const int i : {0, net.count_u - 1}) {
    for (const int j : {0, net.count_v - 1}) {
      const size_t k = static_cast<size_t>(i) * net.count_v + j;
      if (surface.weights[k] > 0) continue;
      return InvalidFieldError(
          IndexedField("weights", k),
          absl::StrCat("a corner weight must be positive: with weight 0 the "
                       "surface is infinite at (u, v) = (",
                       i == 0 ? 0 : 1, ", ", j == 0 ? 0 : 1, ")"));
    }
  }
  return absl::OkStatus();
}

absl::Status ValidateBSplineSurface(const BSplineSurfaceView& surface) {
  const int p = surface.degree_u;
  const int q = surface.degree_v;
  RETURN_IF_ERROR(ValidateDegree(p, "degree_u"));
  RETURN_IF_ERROR(ValidateDegree(q, "degree_v"));
  const ControlNetView& net = surface.control_net;
  RETURN_IF_ERROR(ValidateControlNet(net, "control_net", p + 1, q + 1));
  RETURN_IF_ERROR(
      ValidateDirectionKnots(p, net.count_u, surface.knots_u, "knots_u"));
  RETURN_IF_ERROR(
      ValidateDirectionKnots(q, net.count_v, surface.knots_v, "knots_v"));
  if (!surface.rational()) return absl::OkStatus();
  RETURN_IF_ERROR(ValidateNetWeights(net, surface.weights));
  return ValidateDenominator(BSplineDirection(p, net.count_u, surface.knots_u),
                             BSplineDirection(q, net.count_v, surface.knots_v),
                             net.count_v, surface.weights);
}

SurfaceDomain BezierSurfaceDomain() {
  return {.u_start = 0.0, .u_end = 1.0, .v_start = 0.0, .v_end = 1.0};
}

SurfaceDomain BSplineSurfaceDomain(const BSplineSurfaceView& surface) {
  const size_t p = static_cast<size_t>(surface.degree_u);
  const size_t q = static_cast<size_t>(surface.degree_v);
  const size_t nu = static_cast<size_t>(surface.control_net.count_u);
  const size_t nv = static_cast<size_t>(surface.control_net.count_v);
  return {.u_start = surface.knots_u[p],
          .u_end = surface.knots_u[nu],
          .v_start = surface.knots_v[q],
          .v_end = surface.knots_v[nv]};
}

absl::Status EvaluateBezierSurface(const BezierSurfaceView& surface,
                                   const SurfaceSamples& samples,
                                   SurfaceOutput output,
                                   const ExecutionContext& context) {
  RETURN_IF_ERROR(ValidateBezierSurface(surface));
  return internal::EvaluateValidBezierSurface(surface, samples, output,
                                              context);
}

namespace internal {

absl::Status EvaluateValidBezierSurface(const BezierSurfaceView& surface,
                                        const SurfaceSamples& samples,
                                        SurfaceOutput output,
                                        const ExecutionContext& context) {
  // The Bernstein basis is the B-spline basis on [0..0, 1..1], and A2.3
  // computes it with its derivatives by the triangular recurrence.
  const ControlNetView& net = surface.control_net;
  const std::vector<double> knots_u = BezierKnots(net.count_u - 1);
  const std::vector<double> knots_v = BezierKnots(net.count_v - 1);
  return EvaluateTensorSurface(
      BSplineDirection(net.count_u - 1, net.count_u, knots_u),
      BSplineDirection(net.count_v - 1, net.count_v, knots_v), net,
      surface.weights, BezierSurfaceDomain(), samples, output, context);
}

}  // namespace internal

absl::Status EvaluateBSplineSurface(const BSplineSurfaceView& surface,
                                    const SurfaceSamples& samples,
                                    SurfaceOutput output,
                                    const ExecutionContext& context) {
  RETURN_IF_ERROR(ValidateBSplineSurface(surface));
  return internal::EvaluateValidBSplineSurface(surface, samples, output,
                                               context);
}

namespace internal {

absl::Status EvaluateValidBSplineSurface(const BSplineSurfaceView& surface,
                                         const SurfaceSamples& samples,
                                         SurfaceOutput output,
                                         const ExecutionContext& context) {
  return EvaluateValidBSplineSurfaceWith(surface, samples, output, context,
                                         GridKernel::kLanes);
}

absl::Status EvaluateBSplineSurfaceScalar(const BSplineSurfaceView& surface,
                                          const SurfaceSamples& samples,
                                          SurfaceOutput output) {
  RETURN_IF_ERROR(ValidateBSplineSurface(surface));
  return EvaluateValidBSplineSurfaceWith(surface, samples, output, {},
                                         GridKernel::kScalar);
}

}  // namespace internal

void ProjectHomogeneousSurfaceDerivatives(const double* homogeneous,
                                          int dimension, int max_order,
                                          double* partials) {
  const size_t dim = static_cast<size_t>(dimension);
  const size_t stride = dim + 1;
  const auto weight = [&](int k, int l) {
    return homogeneous[PartialIndex(k, l) * stride + dim];
  };
  const auto projected = [&](int k, int l) {
    return partials + PartialIndex(k, l) * dim;
  };
  for (int k = 0; k <= max_order; ++k) {
    for (int l = 0; l <= max_order - k; ++l) {
      double* out = projected(k, l);
      std::copy_n(homogeneous + PartialIndex(k, l) * stride, dim, out);
      for (int i = 0; i <= k; ++i) {
        for (int j = i == 0 ? 1 : 0; j <= l; ++j) {
          const double factor = internal::Binomial(k, i) *
                                internal::Binomial(l, j) * weight(i, j);
          const double* lower = projected(k - i, l - j);
          for (size_t x = 0; x < dim; ++x) out[x] -= factor * lower[x];
        }
      }
      const double w = weight(0, 0);
      for (size_t x = 0; x < dim; ++x) out[x] /= w;
    }
  }
}

}  // namespace freeform
