// Trim curves sampled under a 3D chord bound (trimmed_surface.h,
// SampleTrimCurve).
//
// The composed curve g(s) = S(c(s)) of a trim part c on s in [0, 1] departs
// from the chord between its ends by at most max |g''| / 8 (the error of
// linear interpolation). |g''| is bounded from the control points alone:
//   - the part c = n / w (w = 1 when polynomial), about the centre m of its
//     control box: |c - m| <= C0 (hull), and per coordinate the hodograph
//     bounds of the homogeneous n and w give, from c w = n,
//     |c'| <= (|n'| + C0 |w'|) / w_min and
//     |c''| <= (|n''| + 2 |c'| |w'| + C0 |w''|) / w_min;
//   - the surface S = H / W on the Bezier pieces that the part's control
//     box meets, about the centre M of their control points: |S - M| <= G0
//     (hull), and the first and second differences of the homogeneous nets
//     W (P - M) and W, scaled by the degrees and span widths, bound H_u,
//     H_v, H_uu, H_uv, H_vv and those of W;
//   - along c, a field F has |F'| <= F_u |u'| + F_v |v'| and
//     |F''| <= F_uu u'^2 + 2 F_uv |u' v'| + F_vv v'^2 + F_u |u''| + F_v |v''|,
//     and g W = H gives |g'| <= (|H'| + G0 |W'|) / W_min and
//     |g''| <= (|H''| + 2 |g'| |W'| + G0 |W''|) / W_min.
// A part whose bound exceeds 8 tolerances is halved (de Casteljau) and
// both halves bounded again; every weight must be positive for the hulls
// (a part with a weight of 0 is halved first).
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "faces/face_boundary.h"
#include "faces/surface_pieces.h"
#include "freeform/core/bezier.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "freeform/core/subdivision.h"
#include "freeform/core/surface.h"
#include "freeform/core/trimmed_surface.h"

namespace freeform {
namespace {

using internal::FaceBoundary;
using internal::SurfacePieces;
using internal::TrimPiece;

// A part is halved at most this often.
constexpr int kMaxSamplingDepth = 40;

// Bounds of a field and its first and second partials over a region.
struct FieldBounds {
  double u = 0.0, v = 0.0, uu = 0.0, uv = 0.0, vv = 0.0;
};

// Bounds of a trim part's derivatives, per coordinate.
struct TrimBounds {
  double first[2] = {0.0, 0.0};
  double second[2] = {0.0, 0.0};
  bool finite = true;
};

// Bounds of the surface over a region about a centre.
struct SurfaceBounds {
  double radius = 0.0;  // G0
  double min_weight = 1.0;
  FieldBounds numerator;
  FieldBounds weight;
  bool finite = true;
};

double Weight(const std::vector<double>& weights, size_t i) {
  return weights.empty() ? 1.0 : weights[i];
}

// TrimPartBounds bounds c' and c'' of a 2D (rational) Bezier part on
// [0, 1] (see the file comment).
TrimBounds TrimPartBounds(const BezierCurveData& part) {
  TrimBounds bounds;
  const std::vector<double>& c = part.coordinates;
  const size_t count = c.size() / 2;
  const double n = static_cast<double>(count) - 1.0;
  double min_weight = INFINITY, weight1 = 0.0, weight2 = 0.0;
  for (size_t i = 0; i < count; ++i) {
    min_weight = std::min(min_weight, Weight(part.weights, i));
    if (i + 1 < count) {
      weight1 = std::max(weight1, n * std::abs(Weight(part.weights, i + 1) -
                                               Weight(part.weights, i)));
    }
    if (i + 2 < count) {
      weight2 = std::max(weight2, n * (n - 1) *
                                      std::abs(Weight(part.weights, i + 2) -
                                               2 * Weight(part.weights, i + 1) +
                                               Weight(part.weights, i)));
    }
  }
  if (!(min_weight > 0.0)) {
    bounds.finite = false;
    return bounds;
  }
  for (int j = 0; j < 2; ++j) {
    double lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < count; ++i) {
      lo = std::min(lo, c[2 * i + j]);
      hi = std::max(hi, c[2 * i + j]);
    }
    const double centre = 0.5 * (lo + hi), radius = 0.5 * (hi - lo);
    const auto h = [&](size_t i) {
      return Weight(part.weights, i) * (c[2 * i + j] - centre);
    };
    double first = 0.0, second = 0.0;
    for (size_t i = 0; i + 1 < count; ++i) {
      first = std::max(first, n * std::abs(h(i + 1) - h(i)));
      if (i + 2 < count) {
        second = std::max(
            second, n * (n - 1) * std::abs(h(i + 2) - 2 * h(i + 1) + h(i)));
      }
    }
    bounds.first[j] = (first + radius * weight1) / min_weight;
    bounds.second[j] =
        (second + 2 * bounds.first[j] * weight1 + radius * weight2) /
        min_weight;
  }
  return bounds;
}

// AddNetBounds raises `field` by the difference bounds of the scalar net
// value(k, l) of a piece of degrees (p, q) over a du x dv rectangle.
template <typename Value>
void AddNetBounds(const SurfaceData& net, double du, double dv,
                  const Value& value, FieldBounds& field) {
  const int p = net.count_u - 1, q = net.count_v - 1;
  for (int k = 0; k <= p; ++k) {
    for (int l = 0; l <= q; ++l) {
      if (k < p) {
        field.u =
            std::max(field.u, p / du * std::abs(value(k + 1, l) - value(k, l)));
      }
      if (l < q) {
        field.v =
            std::max(field.v, q / dv * std::abs(value(k, l + 1) - value(k, l)));
      }
      if (k + 1 < p) {
        field.uu = std::max(
            field.uu,
            p * (p - 1) / (du * du) *
                std::abs(value(k + 2, l) - 2 * value(k + 1, l) + value(k, l)));
      }
      if (l + 1 < q) {
        field.vv = std::max(
            field.vv,
            q * (q - 1) / (dv * dv) *
                std::abs(value(k, l + 2) - 2 * value(k, l + 1) + value(k, l)));
      }
      if (k < p && l < q) {
        field.uv = std::max(field.uv,
                            p * q / (du * dv) *
                                std::abs(value(k + 1, l + 1) - value(k + 1, l) -
                                         value(k, l + 1) + value(k, l)));
      }
    }
  }
}

// RegionBounds bounds the surface on the pieces meeting `box` (see the
// file comment).
SurfaceBounds RegionBounds(const SurfacePieces& pieces,
                           const internal::Box2& box) {
  const internal::Point2& lo = box.lo;
  const internal::Point2& hi = box.hi;
  std::vector<size_t> meeting;
  const size_t count = pieces.decomposition.pieces.patches.size();
  for (size_t index = 0; index < count; ++index) {
    const std::array<double, 4> r = pieces.Rectangle(index);
    if (r[0] <= hi[0] && lo[0] <= r[1] && r[2] <= hi[1] && lo[1] <= r[3]) {
      meeting.push_back(index);
    }
  }
  SurfaceBounds bounds;
  const int dimension = pieces.decomposition.pieces.patches[0].dimension;
  std::vector<double> low(dimension, INFINITY), high(dimension, -INFINITY);
  for (const size_t index : meeting) {
    const SurfaceData& net = pieces.decomposition.pieces.patches[index];
    for (size_t i = 0; i < net.coordinates.size(); ++i) {
      low[i % dimension] = std::min(low[i % dimension], net.coordinates[i]);
      high[i % dimension] = std::max(high[i % dimension], net.coordinates[i]);
    }
  }
  bounds.min_weight = INFINITY;
  for (const size_t index : meeting) {
    const SurfaceData& net = pieces.decomposition.pieces.patches[index];
    const std::array<double, 4> r = pieces.Rectangle(index);
    const double du = r[1] - r[0], dv = r[3] - r[2];
    const auto weight = [&net](int k, int l) {
      return Weight(net.weights, static_cast<size_t>(k) * net.count_v + l);
    };
    for (int k = 0; k < net.count_u; ++k) {
      for (int l = 0; l < net.count_v; ++l) {
        bounds.min_weight = std::min(bounds.min_weight, weight(k, l));
        double squared = 0.0;
        for (int x = 0; x < dimension; ++x) {
          const double centre = 0.5 * (low[x] + high[x]);
          const double d =
              net.coordinates[(static_cast<size_t>(k) * net.count_v + l) *
                                  dimension +
                              x] -
              centre;
          squared += d * d;
        }
        bounds.radius = std::max(bounds.radius, std::sqrt(squared));
      }
    }
    AddNetBounds(net, du, dv, weight, bounds.weight);
    // The numerator's partials bounded coordinate by coordinate, summed
    // in quadrature (|F| <= the norm of the per-coordinate bounds).
    FieldBounds numerator;
    for (int x = 0; x < dimension; ++x) {
      const double centre = 0.5 * (low[x] + high[x]);
      FieldBounds coordinate;
      AddNetBounds(
          net, du, dv,
          [&](int k, int l) {
            return weight(k, l) *
                   (net.coordinates[(static_cast<size_t>(k) * net.count_v + l) *
                                        dimension +
                                    x] -
                    centre);
          },
          coordinate);
      numerator.u = std::hypot(numerator.u, coordinate.u);
      numerator.v = std::hypot(numerator.v, coordinate.v);
      numerator.uu = std::hypot(numerator.uu, coordinate.uu);
      numerator.uv = std::hypot(numerator.uv, coordinate.uv);
      numerator.vv = std::hypot(numerator.vv, coordinate.vv);
    }
    bounds.numerator.u = std::max(bounds.numerator.u, numerator.u);
    bounds.numerator.v = std::max(bounds.numerator.v, numerator.v);
    bounds.numerator.uu = std::max(bounds.numerator.uu, numerator.uu);
    bounds.numerator.uv = std::max(bounds.numerator.uv, numerator.uv);
    bounds.numerator.vv = std::max(bounds.numerator.vv, numerator.vv);
  }
  bounds.finite = !meeting.empty() && bounds.min_weight > 0.0;
  return bounds;
}

// Along returns the bounds of F' and F'' of a field along a trim part.
std::array<double, 2> Along(const FieldBounds& f, const TrimBounds& c) {
  const double u1 = c.first[0], v1 = c.first[1];
  return {f.u * u1 + f.v * v1, f.uu * u1 * u1 + 2 * f.uv * u1 * v1 +
                                   f.vv * v1 * v1 + f.u * c.second[0] +
                                   f.v * c.second[1]};
}

// ChordDeviationBound returns the bound of max |g''| / 8 of a trim part,
// or infinity when a weight is not positive.
double ChordDeviationBound(const BezierCurveData& part,
                           const SurfacePieces& pieces) {
  const TrimBounds trim = TrimPartBounds(part);
  if (!trim.finite) return INFINITY;
  const SurfaceBounds s =
      RegionBounds(pieces, internal::ControlBox(part.coordinates));
  if (!s.finite) return INFINITY;
  const std::array<double, 2> h = Along(s.numerator, trim);
  const std::array<double, 2> w = Along(s.weight, trim);
  const double g1 = (h[0] + s.radius * w[0]) / s.min_weight;
  const double g2 = (h[1] + 2 * g1 * w[0] + s.radius * w[1]) / s.min_weight;
  return g2 / 8.0;
}

// The sampling of one piece: parameters s in [0, 1] of the piece.
class PieceSampler {
 public:
  PieceSampler(const SurfacePieces& pieces, double tolerance,
               size_t max_samples)
      : pieces_(pieces), tolerance_(tolerance), max_samples_(max_samples) {}

  // Sample appends the parameters after s0 = 0 of every accepted part.
  absl::Status Sample(const BezierCurveData& part, double s0, double s1,
                      int depth, std::vector<double>& parameters) {
    if (ChordDeviationBound(part, pieces_) <= tolerance_) {
      if (++accepted_ >= max_samples_) {
        return ExhaustedFieldError(
            "max_samples",
            absl::StrCat("the trim curve needs more than ", max_samples_,
                         " samples at a tolerance of ", tolerance_));
      }
      parameters.push_back(s1);
      return absl::OkStatus();
    }
    if (depth >= kMaxSamplingDepth) {
      return InvalidFieldError(
          "tolerance",
          absl::StrCat(tolerance_,
                       " is not met by halving the trim near "
                       "piece parameter ",
                       s0, " (the surface or the trim degenerates there)"));
    }
    const double half[] = {0.5};
    ASSIGN_OR_RETURN(std::vector<BezierCurveData> halves,
                     SplitBezierCurve(part.view(), half));
    const double middle = 0.5 * (s0 + s1);
    RETURN_IF_ERROR(Sample(halves[0], s0, middle, depth + 1, parameters));
    return Sample(halves[1], middle, s1, depth + 1, parameters);
  }

 private:
  const SurfacePieces& pieces_;
  const double tolerance_;
  const size_t max_samples_;
  size_t accepted_ = 0;  // over every piece sampled, with the first point
};

absl::StatusOr<int> LoopIndex(const TrimmedSurface& face, int hole) {
  if (hole < 0) {
    if (!face.outer().has_value()) {
      return InvalidFieldError("hole", "the face has no outer loop");
    }
    return 0;
  }
  if (static_cast<size_t>(hole) >= face.holes().size()) {
    return InvalidFieldError(
        "hole", absl::StrCat(hole, " is not below the number of holes ",
                             face.holes().size()));
  }
  return hole + 1;
}

}  // namespace

absl::StatusOr<TrimSamples> SampleTrimCurve(const TrimmedSurface& face,
                                            int hole, int curve,
                                            double tolerance,
                                            size_t max_samples,
                                            const CancellationToken* cancel) {
  RETURN_IF_ERROR(ValidatePositive(tolerance, "tolerance"));
  ASSIGN_OR_RETURN(const int loop, LoopIndex(face, hole));
  const FaceBoundary& boundary = face.boundary();
  const internal::BoundaryLoop& l = boundary.loops[loop];
  const int curves = hole < 0
                         ? static_cast<int>(face.outer()->curves.size())
                         : static_cast<int>(face.holes()[hole].curves.size());
  if (curve < 0 || curve >= curves) {
    return InvalidFieldError(
        "curve", absl::StrCat(curve, " is not a curve of the loop (it has ",
                              curves, ")"));
  }
  ASSIGN_OR_RETURN(SurfacePieces pieces,
                   [&]() -> absl::StatusOr<SurfacePieces> {
                     ASSIGN_OR_RETURN(SurfaceDecomposition d,
                                      DecomposeSurface(face.surface(), cancel));
                     return SurfacePieces{std::move(d)};
                   }());
  PieceSampler sampler(pieces, tolerance, max_samples);
  TrimSamples samples;
  for (int k = 0; k < l.piece_count; ++k) {
    const TrimPiece& piece = boundary.pieces[l.first_piece + k];
    if (piece.curve != curve) continue;
    // A zero-length piece adds nothing (unless the curve starts with it).
    if (piece.degenerate && !samples.parameters.empty()) continue;
    std::vector<double> s = {0.0};
    RETURN_IF_ERROR(sampler.Sample(piece.bezier, 0.0, 1.0, 0, s));
    const BezierPointEvaluator evaluator(piece.bezier.view(), 0);
    std::vector<double> scratch(evaluator.scratch_size());
    // A piece after the first starts where the one before ended.
    for (size_t r = samples.parameters.empty() ? 0 : 1; r < s.size(); ++r) {
      double point[2];
      evaluator.Evaluate(s[r], scratch.data(), point);
      samples.uv.insert(samples.uv.end(), {point[0], point[1]});
      samples.parameters.push_back(piece.start +
                                   (piece.end - piece.start) * s[r]);
    }
    RETURN_IF_ERROR(CheckCancelled(cancel));
  }
  return samples;
}

}  // namespace freeform
