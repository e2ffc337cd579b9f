// The area of a trimmed face (trimmed_surface.h, FaceArea): Green's theorem
// turns the surface integral over the trimmed domain into integrals of
// F(u, v) v' along the trims, F the integral of the area density along u
// from the domain's start.
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "faces/face_boundary.h"
#include "faces/quadrature.h"
#include "freeform/core/bezier.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "freeform/core/surface.h"
#include "freeform/core/trimmed_surface.h"

namespace freeform {
namespace {

using internal::Estimate;
using internal::FaceBoundary;
using internal::kKronrodPoints;
using internal::KronrodNode;
using internal::TrimPiece;

// The most intervals of one inner integral over a knot span.
constexpr size_t kMaxInnerIntervals = 4096;

// The distinct knot values strictly inside [start, end], with both ends.
std::vector<double> Breaks(absl::Span<const double> knots, double start,
                           double end) {
  std::vector<double> breaks = {start};
  for (const double k : knots) {
    if (k > breaks.back() && k < end) breaks.push_back(k);
  }
  breaks.push_back(end);
  return breaks;
}

// The area density |S_u x S_v| (the root of the Gram determinant outside
// 3D) at (u, v) pairs, and F, its integral along u.
class AreaDensity {
 public:
  // `cancel` is polled within the inner integrals too: one outer interval
  // may refine its 15 inner integrals for long.
  // At most `max_points` surface points are evaluated in all
  // (RESOURCE_EXHAUSTED naming "max_work" beyond).
  AreaDensity(const Surface& surface, const SurfaceDomain& domain,
              std::vector<double> u_breaks, double tolerance_per_unit_u,
              const CancellationToken* cancel, uint64_t max_points)
      : surface_(surface),
        domain_(domain),
        u_breaks_(std::move(u_breaks)),
        tolerance_per_unit_u_(tolerance_per_unit_u),
        dimension_(DimensionOf(surface)),
        cancel_(cancel),
        max_points_(max_points) {}

  // Integrals writes F(u[i], v[i]) for i < kKronrodPoints, u and v clamped
  // into the domain, F integrated from the knot u_breaks[base]: one Kronrod
  // rule per knot span for all of them in one evaluation, then adaptive
  // halving of the spans that need it.
  absl::Status Integrals(size_t base, const double* u, const double* v,
                         Estimate* out) {
    spans_.clear();
    for (int i = 0; i < kKronrodPoints; ++i) {
      out[i] = {};
      const double ui = std::clamp(u[i], domain_.u_start, domain_.u_end);
      for (size_t k = base; k + 1 < u_breaks_.size() && u_breaks_[k] < ui;
           ++k) {
        spans_.push_back(
            {.node = i,
             .a = u_breaks_[k],
             .b = std::min(u_breaks_[k + 1], ui),
             .v = std::clamp(v[i], domain_.v_start, domain_.v_end)});
      }
    }
    uv_.clear();
    for (const Span& span : spans_) AppendNodes(span.a, span.b, span.v);
    RETURN_IF_ERROR(EvaluateDensities());
    for (size_t k = 0; k < spans_.size(); ++k) {
      const Span& span = spans_[k];
      for (int j = 0; j < kKronrodPoints; ++j) {
        values_[j] = {.value = density_[k * kKronrodPoints + j], .error = 0.0};
      }
      Estimate estimate =
          internal::KronrodInterval(span.a, span.b, values_.data());
      const double target = tolerance_per_unit_u_ * (span.b - span.a);
      if (estimate.error > target) {
        ASSIGN_OR_RETURN(estimate, Refined(span, target));
      }
      out[span.node].value += estimate.value;
      out[span.node].error += estimate.error;
    }
    return absl::OkStatus();
  }

 private:
  // One knot span [a, b] of the integral of node `node`, at v.
  struct Span {
    int node;
    double a;
    double b;
    double v;
  };

  absl::StatusOr<Estimate> Refined(const Span& span, double target) {
    const auto along_u = [&](size_t, double x, double y, Estimate* values) {
      uv_.clear();
      AppendNodes(x, y, span.v);
      RETURN_IF_ERROR(EvaluateDensities());
      for (int j = 0; j < kKronrodPoints; ++j) {
        values[j] = {.value = density_[j], .error = 0.0};
      }
      return absl::OkStatus();
    };
    return internal::IntegrateAdaptive(along_u, span.a, span.b, target,
                                       kMaxInnerIntervals, cancel_);
  }

  void AppendNodes(double a, double b, double v) {
    for (int j = 0; j < kKronrodPoints; ++j) {
      uv_.push_back(
          std::clamp(KronrodNode(a, b, j), domain_.u_start, domain_.u_end));
      uv_.push_back(v);
    }
  }

  // EvaluateDensities fills density_ at the pairs of uv_.
  absl::Status EvaluateDensities() {
    const size_t count = uv_.size() / 2;
    evaluated_points_ += count;
    if (evaluated_points_ > max_points_) {
      return ExhaustedFieldError(
          "max_work",
          absl::StrCat("the area needs more than ", max_points_,
                       " surface evaluations to reach the tolerance"));
    }
    for (std::vector<double>& buffer : partials_) {
      buffer.resize(count * dimension_);
    }
    const absl::Span<double> output[3] = {absl::MakeSpan(partials_[0]),
                                          absl::MakeSpan(partials_[1]),
                                          absl::MakeSpan(partials_[2])};
    RETURN_IF_ERROR(
        EvaluateSurface(surface_, SurfaceSamples::Pairs(uv_), output, {}));
    density_.resize(count);
    for (size_t k = 0; k < count; ++k) {
      density_[k] =
          Density(&partials_[1][k * dimension_], &partials_[2][k * dimension_]);
    }
    return absl::OkStatus();
  }

  double Density(const double* su, const double* sv) const {
    if (dimension_ == 3) {
      return std::hypot(su[1] * sv[2] - su[2] * sv[1],
                        su[2] * sv[0] - su[0] * sv[2],
                        su[0] * sv[1] - su[1] * sv[0]);
    }
    if (dimension_ == 2) return std::abs(su[0] * sv[1] - su[1] * sv[0]);
    double uu = 0.0, vv = 0.0, uv = 0.0;
    for (int j = 0; j < dimension_; ++j) {
      uu += su[j] * su[j];
      vv += sv[j] * sv[j];
      uv += su[j] * sv[j];
    }
    return std::sqrt(std::max(0.0, uu * vv - uv * uv));
  }

  const Surface& surface_;
  const SurfaceDomain domain_;
  const std::vector<double> u_breaks_;
  const double tolerance_per_unit_u_;
  const int dimension_;
  const CancellationToken* const cancel_;
  const uint64_t max_points_;
  uint64_t evaluated_points_ = 0;
  std::vector<Span> spans_;
  std::vector<double> uv_;
  std::array<std::vector<double>, 3> partials_;
  std::vector<double> density_;
  std::array<Estimate, kKronrodPoints> values_;
};

// VVariation returns the v-variation of a piece's control polygon (at
// least the piece's own for a polynomial piece).
double VVariation(const TrimPiece& piece) {
  const std::vector<double>& c = piece.bezier.coordinates;
  double variation = 0.0;
  for (size_t i = 3; i < c.size(); i += 2)
    variation += std::abs(c[i] - c[i - 2]);
  return variation;
}

// PieceBreaks returns the parameters of a piece to integrate between: 0,
// 1, and for a segment where it crosses an interior knot line (the density
// may have a kink there).
std::vector<double> PieceBreaks(const TrimPiece& piece,
                                const std::vector<double>& u_breaks,
                                const std::vector<double>& v_breaks) {
  std::vector<double> t = {0.0, 1.0};
  if (piece.bezier.coordinates.size() == 4) {
    for (int j = 0; j < 2; ++j) {
      const double from = piece.first[j], to = piece.last[j];
      const std::vector<double>& knots = j == 0 ? u_breaks : v_breaks;
      for (size_t k = 1; k + 1 < knots.size(); ++k) {
        const double s = (knots[k] - from) / (to - from);
        if (s > 0.0 && s < 1.0) t.push_back(s);
      }
    }
  }
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end()), t.end());
  return t;
}

std::vector<double> KnotsOf(const Surface& surface, bool in_u) {
  if (const auto* bspline = std::get_if<BSplineSurface>(&surface)) {
    return in_u ? std::vector<double>(bspline->view().knots_u.begin(),
                                      bspline->view().knots_u.end())
                : std::vector<double>(bspline->view().knots_v.begin(),
                                      bspline->view().knots_v.end());
  }
  return {};
}

// BoundaryIntegrand writes F(c(t)) v'(t) at the Kronrod nodes of [a, b]
// of one piece, F from the knot u_breaks[base].
absl::Status BoundaryIntegrand(const TrimPiece& piece, size_t base, double a,
                               double b, AreaDensity& density,
                               Estimate* values) {
  const BezierPointEvaluator evaluator(piece.bezier.view(), 1);
  std::vector<double> scratch(evaluator.scratch_size());
  double u[kKronrodPoints], v[kKronrodPoints], dv[kKronrodPoints];
  for (int k = 0; k < kKronrodPoints; ++k) {
    double c[4];
    evaluator.Evaluate(KronrodNode(a, b, k), scratch.data(), c);
    u[k] = c[0];
    v[k] = c[1];
    dv[k] = c[3];
  }
  Estimate f[kKronrodPoints];
  RETURN_IF_ERROR(density.Integrals(base, u, v, f));
  for (int k = 0; k < kKronrodPoints; ++k) {
    values[k] = {.value = f[k].value * dv[k],
                 .error = f[k].error * std::abs(dv[k])};
  }
  return absl::OkStatus();
}

}  // namespace

uint64_t FaceAreaWorkBytes(const Surface& surface, uint64_t pieces) {
  const SurfaceDomain d = DomainOf(surface);
  const uint64_t u_breaks =
      Breaks(KnotsOf(surface, true), d.u_start, d.u_end).size();
  const uint64_t v_breaks =
      Breaks(KnotsOf(surface, false), d.v_start, d.v_end).size();
  // A piece is cut where it crosses a knot line: at most once per line in
  // each direction per monotone stretch, bounded here by every line.
  const uint64_t parts = pieces * (u_breaks + v_breaks + 1);
  const uint64_t dimension = static_cast<uint64_t>(DimensionOf(surface));
  // The inner integrals: one heap of kMaxInnerIntervals at a time, and the
  // nodes of every u span of an outer interval's 15 nodes with their
  // partials (value, S_u, S_v) and densities.
  const uint64_t nodes = (u_breaks + 1) * kKronrodPoints * kKronrodPoints;
  return 2 * parts * sizeof(internal::PartInterval) +
         internal::IntegrateAdaptiveBytes(parts + kMaxFaceAreaIntervals) +
         internal::IntegrateAdaptiveBytes(kMaxInnerIntervals) +
         2 * nodes * (2 + 3 * dimension + 1) * sizeof(double) +
         2 * (u_breaks + v_breaks) * sizeof(double);
}

absl::StatusOr<FaceAreaResult> FaceArea(const TrimmedSurface& face,
                                        double tolerance,
                                        const CancellationToken* cancel,
                                        uint64_t max_points) {
  RETURN_IF_ERROR(ValidatePositive(tolerance, "tolerance"));
  const FaceBoundary& boundary = face.boundary();
  const SurfaceDomain& d = boundary.domain;
  const std::vector<double> u_breaks =
      Breaks(KnotsOf(face.surface(), true), d.u_start, d.u_end);
  const std::vector<double> v_breaks =
      Breaks(KnotsOf(face.surface(), false), d.v_start, d.v_end);
  // Each loop integrates F from the last knot at or below its box: a
  // function G(v) alone integrates to 0 around a closed loop, so moving
  // F's base changes nothing but the work.
  std::vector<size_t> bases(boundary.loops.size(), 0);
  for (size_t l = 0; l < bases.size(); ++l) {
    while (bases[l] + 2 < u_breaks.size() &&
           u_breaks[bases[l] + 1] <= boundary.loops[l].box.lo[0]) {
      ++bases[l];
    }
  }
  double variation = 0.0;
  std::vector<internal::PartInterval> parts;
  for (size_t i = 0; i < boundary.pieces.size(); ++i) {
    const TrimPiece& piece = boundary.pieces[i];
    const double piece_variation = VVariation(piece);
    if (piece_variation == 0.0) continue;
    variation += piece_variation;
    const std::vector<double> breaks = PieceBreaks(piece, u_breaks, v_breaks);
    for (size_t k = 0; k + 1 < breaks.size(); ++k) {
      parts.push_back({.part = i, .a = breaks[k], .b = breaks[k + 1]});
    }
  }
  if (parts.empty()) return FaceAreaResult{};
  // A quarter of the tolerance for the inner integrals (weighted by |v'|,
  // whose integral the control polygons' variation bounds for polynomial
  // pieces), the rest for the outer ones, all pieces' intervals refined
  // together.
  AreaDensity density(face.surface(), d, u_breaks,
                      0.25 * tolerance / (variation * (d.u_end - d.u_start)),
                      cancel, max_points);
  const auto integrand = [&](size_t part, double a, double b,
                             Estimate* values) {
    const TrimPiece& piece = boundary.pieces[part];
    return BoundaryIntegrand(piece, bases[piece.loop], a, b, density, values);
  };
  ASSIGN_OR_RETURN(Estimate total,
                   internal::IntegrateAdaptive(
                       integrand, parts, 0.75 * tolerance,
                       parts.size() + kMaxFaceAreaIntervals, cancel));
  const FaceAreaResult result{.area = total.value, .error_bound = total.error};
  if (!std::isfinite(result.area) || !std::isfinite(result.error_bound)) {
    return InvalidFieldError("surface",
                             "the area density is not finite on the face");
  }
  return result;
}

}  // namespace freeform
