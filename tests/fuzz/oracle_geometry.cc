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

// Conditioning returns max(1, max(|a|, |b|) / (b - a)) over the
// non-empty spans between consecutive `breakpoints`.
double Conditioning(absl::Span<const double> breakpoints) {
  double worst = 1.0;
  for (size_t k = 1; k < breakpoints.size(); ++k) {
    const double a = breakpoints[k - 1], b = breakpoints[k];
    if (!(b > a)) continue;
    worst = std::max(worst, std::max(std::abs(a), std::abs(b)) / (b - a));
  }
  return worst;
}

// The measures of a set of Bezier pieces (coordinates, weights).
struct PieceMeasures {
  double scale = 0.0;
  bool positive_weights = true;
  bool polynomial = true;
  std::vector<double> lower, upper;

  PieceMeasures(int dimension)
      : lower(static_cast<size_t>(dimension), kInf),
        upper(static_cast<size_t>(dimension), -kInf) {}

  void Add(int dimension, absl::Span<const double> coordinates,
           absl::Span<const double> weights) {
    const size_t dim = static_cast<size_t>(dimension);
    for (size_t k = 0; k < coordinates.size(); ++k) {
      const double x = coordinates[k];
      if (!std::isfinite(x)) continue;
      scale = std::max(scale, std::abs(x));
      lower[k % dim] = std::min(lower[k % dim], x);
      upper[k % dim] = std::max(upper[k % dim], x);
    }
    for (double w : weights) {
      if (!(w > 0.0)) positive_weights = false;
      if (w != weights.front()) polynomial = false;
    }
  }
};

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

double LargestMagnitude(absl::Span<const double> values) {
  double largest = 0.0;
  for (double v : values) {
    if (std::isfinite(v)) largest = std::max(largest, std::abs(v));
  }
  return largest;
}

// ---------------------------------------------------------------- curves --

absl::StatusOr<OracleCurve> OracleCurve::Create(
    const v1::Curve& message, const server::ServiceLimits& limits,
    absl::string_view field) {
  absl::StatusOr<Curve> curve = server::PrepareCurve(message, limits, field);
  if (!curve.ok()) return curve.status();
  OracleCurve oracle(*std::move(curve));
  absl::StatusOr<BezierDecomposition> pieces = DecomposeCurve(oracle.curve_);
  if (!pieces.ok()) return pieces.status();
  oracle.pieces_ = *std::move(pieces);
  PieceMeasures measures(oracle.dimension());
  for (const BezierCurveData& piece : oracle.pieces_.segments) {
    measures.Add(piece.dimension, piece.coordinates, piece.weights);
  }
  oracle.scale_ = measures.scale;
  oracle.positive_weights_ = measures.positive_weights;
  oracle.polynomial_ = measures.polynomial;
  oracle.hull_lower_ = std::move(measures.lower);
  oracle.hull_upper_ = std::move(measures.upper);
  oracle.conditioning_ = Conditioning(oracle.pieces_.breakpoints);
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
  oracle.positive_weights_ = measures.positive_weights;
  oracle.hull_lower_ = std::move(measures.lower);
  oracle.hull_upper_ = std::move(measures.upper);
  if (pieces->triangular) {
    // Barycentric coordinates of a point of the domain triangle are ratios
    // of areas: their rounding is that of the corners' coordinates over
    // the triangle's size.
    const std::vector<double>& t = pieces->domain_triangle;
    if (t.size() == 6) {
      const double area = std::abs((t[2] - t[0]) * (t[5] - t[1]) -
                                   (t[4] - t[0]) * (t[3] - t[1]));
      const double edge =
          std::max({Distance(&t[0], &t[2], 2), Distance(&t[2], &t[4], 2),
                    Distance(&t[4], &t[0], 2)});
      oracle.conditioning_ =
          area > 0.0 ? std::max(1.0, LargestMagnitude(t) * edge / area) : kInf;
    }
  } else {
    oracle.conditioning_ = std::max(Conditioning(pieces->pieces.breakpoints_u),
                                    Conditioning(pieces->pieces.breakpoints_v));
  }
  return oracle;
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
