#include "oracle_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <variant>
#include <vector>

#include "prepare.h"

namespace freeform::fuzz {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// PieceStart returns the largest breakpoint <= x (the first one when x is
// below them all): where the piece holding x starts.
double PieceStart(absl::Span<const double> breakpoints, double x) {
  if (breakpoints.empty()) return 0.0;
  const auto after =
      std::upper_bound(breakpoints.begin(), breakpoints.end(), x);
  return after == breakpoints.begin() ? breakpoints.front() : *(after - 1);
}

// Below this a homogeneous coordinate w x, and the products of the
// evaluator's basis with it, lose their last bits to gradual underflow
// (2^52 times the smallest normal double).
constexpr double kUnderflow = 0x1p-970;

// UnderflowOf returns the largest |x| of the control points' coordinates
// (`dim` per point, with their weights, or none) whose homogeneous value
// w x lies below kUnderflow; 0 when none does.
double UnderflowOf(size_t dim, absl::Span<const double> coordinates,
                   absl::Span<const double> weights) {
  double underflow = 0.0;
  for (size_t k = 0; k < coordinates.size(); ++k) {
    const double w = weights.empty() ? 1.0 : weights[k / dim];
    const double x = coordinates[k];
    if (x != 0.0 && std::isfinite(x) && std::abs(w * x) < kUnderflow) {
      underflow = std::max(underflow, std::abs(x));
    }
  }
  return underflow;
}

// GeometryUnderflow is UnderflowOf the geometry's own control points (its
// Bezier pieces are projected from homogeneous values that may have
// underflowed already).
double GeometryUnderflow(const Curve& curve) {
  const size_t dim = static_cast<size_t>(DimensionOf(curve));
  if (const auto* c = std::get_if<BezierCurve>(&curve)) {
    return UnderflowOf(dim, c->view().control_points.coordinates,
                       c->view().weights);
  }
  if (const auto* c = std::get_if<BSplineCurve>(&curve)) {
    return UnderflowOf(dim, c->view().control_points.coordinates,
                       c->view().weights);
  }
  if (const auto* c = std::get_if<LagrangeCurve>(&curve)) {
    return UnderflowOf(dim, c->view().points.coordinates, {});
  }
  const auto& hermite = std::get<HermiteCurve>(curve);
  return UnderflowOf(dim, hermite.view().points.coordinates, {});
}

double GeometryUnderflow(const Surface& surface) {
  const size_t dim = static_cast<size_t>(DimensionOf(surface));
  if (const auto* s = std::get_if<BezierSurface>(&surface)) {
    return UnderflowOf(dim, s->view().control_net.coordinates,
                       s->view().weights);
  }
  if (const auto* s = std::get_if<BSplineSurface>(&surface)) {
    return UnderflowOf(dim, s->view().control_net.coordinates,
                       s->view().weights);
  }
  const auto& patch = std::get<TriangularPatch>(surface);
  return UnderflowOf(dim, patch.view().control_points.coordinates,
                     patch.view().weights);
}

// The measures of a set of Bezier pieces (coordinates, weights).
struct PieceMeasures {
  double scale = 0.0;
  double underflow = 0.0;
  bool positive_weights = true;
  bool polynomial = true;
  std::vector<double> lower, upper;
  std::vector<double> axis_scale;  // largest |coordinate| per axis

  explicit PieceMeasures(int dimension)
      : lower(static_cast<size_t>(dimension), kInf),
        upper(static_cast<size_t>(dimension), -kInf),
        axis_scale(static_cast<size_t>(dimension), 0.0) {}

  void Add(int dimension, absl::Span<const double> coordinates,
           absl::Span<const double> weights) {
    const size_t dim = static_cast<size_t>(dimension);
    for (size_t k = 0; k < coordinates.size(); ++k) {
      const double x = coordinates[k];
      if (!std::isfinite(x)) {
        // The Bezier form overflows in the geometry's own units (w x past
        // 1e308; the queries work on a rescaled copy): this axis has no
        // known hull.
        lower[k % dim] = -kInf;
        upper[k % dim] = kInf;
        continue;
      }
      scale = std::max(scale, std::abs(x));
      axis_scale[k % dim] = std::max(axis_scale[k % dim], std::abs(x));
      lower[k % dim] = std::min(lower[k % dim], x);
      upper[k % dim] = std::max(upper[k % dim], x);
    }
    underflow = std::max(underflow, UnderflowOf(dim, coordinates, weights));
    for (double w : weights) {
      if (!(w > 0.0)) positive_weights = false;
      if (w != weights.front()) polynomial = false;
    }
  }
};

// MovedBack returns `values` with every value of the axes in `axes` (bit
// k for values k, k + stride, ...) one ulp lower, but not below `start`.
std::vector<double> MovedBack(absl::Span<const double> values, size_t stride,
                              unsigned axes, const double* start) {
  std::vector<double> moved(values.begin(), values.end());
  for (size_t k = 0; k < moved.size(); ++k) {
    const size_t axis = k % stride;
    if ((axes >> axis) & 1u) {
      moved[k] = std::max(start[axis], std::nextafter(moved[k], -kInf));
    }
  }
  return moved;
}

}  // namespace

double Distance(const double* a, const double* b, int dimension) {
  double largest = 0.0;
  for (int j = 0; j < dimension; ++j) {
    largest = std::max(largest, std::abs(0.5 * a[j] - 0.5 * b[j]));
  }
  if (largest == 0.0 || !std::isfinite(largest)) return 2.0 * largest;
  double sum = 0.0;
  for (int j = 0; j < dimension; ++j) {
    const double d = (0.5 * a[j] - 0.5 * b[j]) / largest;
    sum += d * d;
  }
  return 2.0 * largest * std::sqrt(sum);
}

double Norm(const double* a, int dimension) {
  const std::vector<double> zero(static_cast<size_t>(dimension), 0.0);
  return Distance(a, zero.data(), dimension);
}

bool AllFinite(absl::Span<const double> values) {
  return std::all_of(values.begin(), values.end(),
                     [](double v) { return std::isfinite(v); });
}

double LargestMagnitude(absl::Span<const double> values) {
  double largest = 0.0;
  for (double v : values) {
    if (std::isfinite(v)) largest = std::max(largest, std::abs(v));
  }
  return largest;
}

double Evaluation::DistanceTo(size_t k, absl::Span<const double> x) const {
  double best = std::numeric_limits<double>::quiet_NaN();
  if (!AllFinite(x)) return best;
  for (size_t side = 0; side < sides_.size(); ++side) {
    const absl::Span<const double> p = Side(side, k);
    if (!AllFinite(p)) continue;
    const double d = Distance(p.data(), x.data(), dimension_);
    if (!(d >= best)) best = d;
  }
  return best;
}

double Evaluation::Gap(size_t k, const Evaluation& other,
                       size_t other_k) const {
  double best = std::numeric_limits<double>::quiet_NaN();
  for (size_t side = 0; side < other.sides_.size(); ++side) {
    const double d = DistanceTo(k, other.Side(side, other_k));
    if (!(d >= best)) best = d;
  }
  return best;
}

// ---------------------------------------------------------------- curves --

absl::StatusOr<OracleCurve> OracleCurve::Create(
    const v1::Curve& message, const server::ServiceLimits& limits,
    absl::string_view field) {
  absl::StatusOr<Curve> curve = server::PrepareCurve(message, limits, field);
  if (!curve.ok()) return curve.status();
  OracleCurve oracle(*std::move(curve));
  if (const auto* bspline = std::get_if<BSplineCurve>(&oracle.curve_)) {
    oracle.continuous_ = bspline->degree() > 0;
  }
  absl::StatusOr<BezierDecomposition> pieces = DecomposeCurve(oracle.curve_);
  if (!pieces.ok()) return pieces.status();
  oracle.pieces_ = *std::move(pieces);
  PieceMeasures measures(oracle.dimension());
  for (const BezierCurveData& piece : oracle.pieces_.segments) {
    measures.Add(piece.dimension, piece.coordinates, piece.weights);
  }
  oracle.scale_ = measures.scale;
  oracle.underflow_ =
      std::max(measures.underflow, GeometryUnderflow(oracle.curve_));
  oracle.positive_weights_ = measures.positive_weights;
  oracle.polynomial_ = measures.polynomial;
  oracle.hull_lower_ = std::move(measures.lower);
  oracle.hull_upper_ = std::move(measures.upper);
  oracle.axis_scale_ = std::move(measures.axis_scale);
  return oracle;
}

absl::StatusOr<std::vector<double>> OracleCurve::Evaluate(
    absl::Span<const double> parameters) const {
  std::vector<double> points(parameters.size() *
                             static_cast<size_t>(dimension()));
  const absl::Span<double> output[] = {absl::MakeSpan(points)};
  if (absl::Status status = EvaluateCurve(curve_, parameters, output);
      !status.ok()) {
    return status;
  }
  return points;
}

absl::StatusOr<Evaluation> OracleCurve::EvaluateSides(
    absl::Span<const double> parameters) const {
  const size_t dim = static_cast<size_t>(dimension());
  std::vector<double> points(parameters.size() * dim);
  std::vector<double> derivatives(points.size());
  const absl::Span<double> output[] = {absl::MakeSpan(points),
                                       absl::MakeSpan(derivatives)};
  if (absl::Status status = EvaluateCurve(curve_, parameters, output);
      !status.ok()) {
    return status;
  }
  std::vector<double> slack(parameters.size());
  for (size_t k = 0; k < parameters.size(); ++k) {
    const double t = parameters[k];
    const double magnitude =
        std::abs(t) + 2.0 * std::abs(PieceStart(pieces_.breakpoints, t));
    slack[k] = kParameterRounding * Norm(&derivatives[k * dim], dimension()) *
               magnitude;
    if (std::isnan(slack[k])) slack[k] = kInf;
  }
  std::vector<std::vector<double>> sides;
  sides.push_back(std::move(points));
  if (!continuous_) {
    const double start = domain().start;
    absl::StatusOr<std::vector<double>> left =
        Evaluate(MovedBack(parameters, 1, 1u, &start));
    if (!left.ok()) return left.status();
    sides.push_back(*std::move(left));
  }
  return Evaluation(dimension(), std::move(sides), std::move(slack));
}

std::vector<double> OracleCurve::Samples(double a, double b, size_t count,
                                         bool breakpoints) const {
  std::vector<double> samples;
  for (size_t k = 0; k < count; ++k) {
    const double f = static_cast<double>(k) / static_cast<double>(count - 1);
    samples.push_back(k + 1 == count ? b : a + f * (b - a));
  }
  for (double breakpoint : pieces_.breakpoints) {
    if (breakpoints && breakpoint > a && breakpoint < b) {
      samples.push_back(breakpoint);
    }
  }
  std::sort(samples.begin(), samples.end());
  return samples;
}

double OracleCurve::PolygonLength(double a, double b) const {
  double length = 0.0;
  const std::vector<double>& breaks = pieces_.breakpoints;
  for (size_t k = 0; k < pieces_.segments.size() && k + 1 < breaks.size();
       ++k) {
    const bool meets = breaks[k] <= b && breaks[k + 1] >= a;
    if (!meets) continue;
    const BezierCurveData& piece = pieces_.segments[k];
    const size_t dim = static_cast<size_t>(piece.dimension);
    for (size_t i = dim; i < piece.coordinates.size(); i += dim) {
      length += Distance(&piece.coordinates[i - dim], &piece.coordinates[i],
                         piece.dimension);
    }
  }
  return length;
}

// -------------------------------------------------------------- surfaces --

absl::StatusOr<OracleSurface> OracleSurface::Create(
    const v1::Surface& message, const server::ServiceLimits& limits,
    absl::string_view field) {
  absl::StatusOr<Surface> surface =
      server::PrepareSurface(message, limits, field);
  if (!surface.ok()) return surface.status();
  OracleSurface oracle(*std::move(surface));
  absl::StatusOr<SurfaceDecomposition> pieces =
      DecomposeSurface(oracle.surface_);
  if (!pieces.ok()) return pieces.status();
  PieceMeasures measures(oracle.dimension());
  for (const SurfaceData& patch : pieces->pieces.patches) {
    measures.Add(patch.dimension, patch.coordinates, patch.weights);
  }
  oracle.scale_ = measures.scale;
  oracle.underflow_ =
      std::max(measures.underflow, GeometryUnderflow(oracle.surface_));
  oracle.positive_weights_ = measures.positive_weights;
  oracle.hull_lower_ = std::move(measures.lower);
  oracle.hull_upper_ = std::move(measures.upper);
  oracle.axis_scale_ = std::move(measures.axis_scale);
  if (const auto* triangle = std::get_if<TriangularPatch>(&oracle.surface_)) {
    // The core boxes a triangle as itself, not as its degenerate tensor
    // form (whose rational hull is tighter): its own points set the scale.
    PieceMeasures own(oracle.dimension());
    own.Add(oracle.dimension(), triangle->view().control_points.coordinates,
            triangle->view().weights);
    oracle.axis_scale_ = std::move(own.axis_scale);
  }
  oracle.breakpoints_[0] = pieces->pieces.breakpoints_u;
  oracle.breakpoints_[1] = pieces->pieces.breakpoints_v;
  oracle.triangle_magnitude_ = LargestMagnitude(pieces->domain_triangle);
  return oracle;
}

double OracleSurface::ParameterMagnitude(int axis, double x) const {
  // On a domain triangle the parameters are its points, rounded against
  // its corners; barycentric and tensor parameters against their piece.
  if (triangle_magnitude_ > 0.0) {
    return std::abs(x) + 2.0 * triangle_magnitude_;
  }
  return std::abs(x) +
         2.0 * std::abs(PieceStart(breakpoints_[static_cast<size_t>(axis)], x));
}

absl::StatusOr<std::vector<double>> OracleSurface::Evaluate(
    absl::Span<const double> uv) const {
  std::vector<double> points(uv.size() / 2 * static_cast<size_t>(dimension()));
  const absl::Span<double> output[] = {absl::MakeSpan(points)};
  if (absl::Status status =
          EvaluateSurface(surface_, SurfaceSamples::Pairs(uv), output, {});
      !status.ok()) {
    return status;
  }
  return points;
}

absl::StatusOr<Evaluation> OracleSurface::EvaluateSides(
    absl::Span<const double> uv) const {
  const size_t dim = static_cast<size_t>(dimension());
  const size_t count = uv.size() / 2;
  // The points and their partials S_u and S_v.
  std::vector<double> partials[3];
  for (std::vector<double>& p : partials) p.resize(count * dim);
  const absl::Span<double> output[] = {absl::MakeSpan(partials[0]),
                                       absl::MakeSpan(partials[1]),
                                       absl::MakeSpan(partials[2])};
  if (absl::Status status =
          EvaluateSurface(surface_, SurfaceSamples::Pairs(uv), output, {});
      !status.ok()) {
    return status;
  }
  std::vector<double> slack(count);
  for (size_t k = 0; k < count; ++k) {
    slack[k] = kParameterRounding * (Norm(&partials[1][k * dim], dimension()) *
                                         ParameterMagnitude(0, uv[2 * k]) +
                                     Norm(&partials[2][k * dim], dimension()) *
                                         ParameterMagnitude(1, uv[2 * k + 1]));
    if (std::isnan(slack[k])) slack[k] = kInf;
  }
  // The directions that jump at their knots: the degree-0 ones of a
  // B-spline surface. Side s moves u back when bit 0 of s is set, v when
  // bit 1 is.
  unsigned jumps = 0;
  double start[2] = {0.0, 0.0};
  if (const auto* bspline = std::get_if<BSplineSurface>(&surface_)) {
    jumps = (bspline->view().degree_u == 0 ? 1u : 0u) |
            (bspline->view().degree_v == 0 ? 2u : 0u);
    start[0] = bspline->domain().u_start;
    start[1] = bspline->domain().v_start;
  }
  std::vector<std::vector<double>> sides;
  sides.push_back(std::move(partials[0]));
  for (unsigned side = 1; side < 4; ++side) {
    if ((side & ~jumps) != 0) continue;
    absl::StatusOr<std::vector<double>> points =
        Evaluate(MovedBack(uv, 2, side, start));
    if (!points.ok()) return points.status();
    sides.push_back(*std::move(points));
  }
  return Evaluation(dimension(), std::move(sides), std::move(slack));
}

std::vector<double> OracleSurface::Samples() const {
  constexpr int kSteps = 16;
  std::vector<double> uv;
  if (!IsTriangular(surface_)) {
    const SurfaceDomain d = DomainOf(surface_);
    for (int i = 0; i <= kSteps; ++i) {
      for (int j = 0; j <= kSteps; ++j) {
        const double fu = static_cast<double>(i) / kSteps;
        const double fv = static_cast<double>(j) / kSteps;
        uv.push_back(i == kSteps ? d.u_end
                                 : d.u_start + fu * (d.u_end - d.u_start));
        uv.push_back(j == kSteps ? d.v_end
                                 : d.v_start + fv * (d.v_end - d.v_start));
      }
    }
    return uv;
  }
  const absl::Span<const double> t =
      std::get<TriangularPatch>(surface_).view().domain_triangle;
  for (int i = 0; i <= kSteps; ++i) {
    for (int j = 0; i + j <= kSteps; ++j) {
      const double u = static_cast<double>(i) / kSteps;
      const double v = static_cast<double>(j) / kSteps;
      if (t.size() != 6) {
        uv.push_back(u);
        uv.push_back(v);
        continue;
      }
      // The point u A + v B + w C of the domain triangle; only interior
      // points, so that rounding does not put one outside it.
      if (i == 0 || j == 0 || i + j == kSteps) continue;
      const double w = 1.0 - u - v;
      uv.push_back(u * t[0] + v * t[2] + w * t[4]);
      uv.push_back(u * t[1] + v * t[3] + w * t[5]);
    }
  }
  return uv;
}

}  // namespace freeform::fuzz
