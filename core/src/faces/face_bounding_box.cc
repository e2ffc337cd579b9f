// The tight bounding box of a trimmed face (trimmed_surface.h,
// FaceBoundingBox): branch and bound over the surface's Bezier pieces
// restricted to the trimmed domain.
//
// For one side (the largest value of coordinate j, or of -x_j), every part
// of the surface carries its (u, v) rectangle and an upper bound, its
// largest control coordinate (the hull; a rational part needs positive
// weights, and one without is halved first). A part whose rectangle lies
// outside the face (its centre outside, no trim within its half diagonal)
// is dropped; one inside keeps its children inside; one the trims cross
// is classified again when halved. Lower bounds are values at points of
// the closed face: the trims' polyline vertices (on the trim curves) and
// the corners of parts that are not outside. The part of largest upper
// bound is halved (the longer side of its rectangle) until that bound is
// within the tolerance of the best lower bound: the side is that upper
// bound, which no point of the face exceeds. After kMaxBoxHalvings
// halvings the side is the best upper bound so far, still a bound.
#include <algorithm>
#include <array>
#include <cmath>
#include <queue>
#include <vector>

#include "absl/status/status.h"
#include "faces/face_boundary.h"
#include "faces/surface_pieces.h"
#include "faces/winding.h"
#include "freeform/core/bounding_box.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "freeform/core/subdivision.h"
#include "freeform/core/trimmed_surface.h"

namespace freeform {
namespace {

using internal::FaceBoundary;
using internal::Point2;
using internal::SurfacePieces;

// The margin added to every side for the rounding of the hulls and
// evaluations, relative to the largest control coordinate.
constexpr double kBoxMargin = 0x1p-44;

enum class Where { kInside, kOutside, kCrossed };

// A part of the surface over the rectangle {u0, u1, v0, v1}.
struct BoxPart {
  SurfaceData net;
  std::array<double, 4> rectangle;
  Where where = Where::kCrossed;
  double upper = INFINITY;
  bool operator<(const BoxPart& other) const { return upper < other.upper; }
};

// Locate classifies a rectangle against the face: crossed when a trim may
// come within half its diagonal (times 1.02, above the classification's
// certainty of 1 - 1/256) of its centre. Far from every chord the ray
// alone decides; near one, the arcs are refined (FaceWinding).
Where Locate(const FaceBoundary& boundary, const std::array<double, 4>& r) {
  const Point2 centre{0.5 * (r[0] + r[1]), 0.5 * (r[2] + r[3])};
  const double reach = 0.51 * std::hypot(r[1] - r[0], r[3] - r[2]);
  const bool near = internal::TrimMayBeWithin(boundary, centre, reach);
  const internal::WindingAt at =
      internal::FaceWinding(boundary, centre, near ? reach : 0.0);
  if (at.on_boundary) return Where::kCrossed;
  return at.winding > 0 ? Where::kInside : Where::kOutside;
}

// UpperBound returns the largest control value of coordinate j (times
// `sign`), or infinity while a weight is not positive.
double UpperBound(const SurfaceData& net, int j, double sign) {
  if (!internal::HasHull(net.weights)) return INFINITY;
  double upper = -INFINITY;
  for (size_t i = j; i < net.coordinates.size();
       i += static_cast<size_t>(net.dimension)) {
    upper = std::max(upper, sign * net.coordinates[i]);
  }
  return upper;
}

// The search for one side of the box.
class SideSearch {
 public:
  SideSearch(const TrimmedSurface& face, int coordinate, double sign,
             double tolerance)
      : face_(face),
        boundary_(face.boundary()),
        j_(coordinate),
        sign_(sign),
        tolerance_(tolerance) {}

  absl::StatusOr<double> Run(const SurfacePieces& pieces,
                             double lower_from_trims,
                             const CancellationToken* cancel) {
    best_ = lower_from_trims;
    const auto& patches = pieces.decomposition.pieces.patches;
    for (size_t index = 0; index < patches.size(); ++index) {
      RETURN_IF_ERROR(
          Push({.net = patches[index], .rectangle = pieces.Rectangle(index)},
               Where::kCrossed));
    }
    for (int halvings = 0; !heap_.empty(); ++halvings) {
      const BoxPart& top = heap_.top();
      if (top.upper - best_ <= tolerance_ || halvings >= kMaxBoxHalvings) {
        return top.upper;
      }
      BoxPart part = top;
      heap_.pop();
      RETURN_IF_ERROR(Halve(part));
      RETURN_IF_ERROR(CheckCancelled(cancel));
    }
    return best_;  // Every part was outside: only the trims' points count.
  }

 private:
  // Push classifies a part (unless its parent was inside), raises the
  // lower bound by its corners on the face and keeps it unless outside.
  absl::Status Push(BoxPart part, Where parent) {
    part.where =
        parent == Where::kInside ? parent : Locate(boundary_, part.rectangle);
    if (part.where == Where::kOutside) return absl::OkStatus();
    RETURN_IF_ERROR(RaiseByCorners(part));
    part.upper = UpperBound(part.net, j_, sign_);
    if (part.upper > best_ - tolerance_ || !std::isfinite(part.upper)) {
      heap_.push(std::move(part));
    }
    return absl::OkStatus();
  }

  // RaiseByCorners evaluates the part's corners that lie on the face.
  absl::Status RaiseByCorners(const BoxPart& part) {
    const auto& r = part.rectangle;
    const double uv[] = {r[0], r[2], r[0], r[3], r[1], r[2], r[1], r[3]};
    absl::StatusOr<std::vector<PointLocation>> at =
        part.where == Where::kInside
            ? std::vector<PointLocation>(4, PointLocation::kInside)
            : ClassifyPoints(face_, uv, 0.0);
    if (!at.ok()) return at.status();
    const int dimension = part.net.dimension;
    std::vector<double> points(4 * static_cast<size_t>(dimension));
    const absl::Span<double> output[] = {absl::MakeSpan(points)};
    RETURN_IF_ERROR(EvaluateSurface(face_.surface(), SurfaceSamples::Pairs(uv),
                                    output, {}));
    for (int k = 0; k < 4; ++k) {
      if ((*at)[k] == PointLocation::kOutside) continue;
      best_ = std::max(best_, sign_ * points[k * dimension + j_]);
    }
    return absl::OkStatus();
  }

  // Halve splits a part across the longer side of its rectangle.
  absl::Status Halve(const BoxPart& part) {
    const auto& r = part.rectangle;
    const bool in_u = r[1] - r[0] >= r[3] - r[2];
    ASSIGN_OR_RETURN(std::vector<SurfaceData> halves,
                     SplitBezierSurface(part.net.bezier_view(), in_u, 0.5));
    const double middle = in_u ? 0.5 * (r[0] + r[1]) : 0.5 * (r[2] + r[3]);
    std::array<double, 4> first = r, second = r;
    (in_u ? first[1] : first[3]) = middle;
    (in_u ? second[0] : second[2]) = middle;
    RETURN_IF_ERROR(
        Push({.net = std::move(halves[0]), .rectangle = first}, part.where));
    return Push({.net = std::move(halves[1]), .rectangle = second}, part.where);
  }

  const TrimmedSurface& face_;
  const FaceBoundary& boundary_;
  const int j_;
  const double sign_;
  const double tolerance_;
  double best_ = -INFINITY;
  std::priority_queue<BoxPart> heap_;
};

// TrimPoints returns the surface's points at the polylines' vertices (on
// the trim curves, inside the domain up to the tolerance: clamped).
absl::StatusOr<std::vector<double>> TrimPoints(const TrimmedSurface& face) {
  const FaceBoundary& boundary = face.boundary();
  const SurfaceDomain& d = boundary.domain;
  std::vector<double> uv;
  uv.reserve(2 * boundary.segments.size());
  for (const internal::BoundarySegment& s : boundary.segments) {
    uv.push_back(std::clamp(s.a[0], d.u_start, d.u_end));
    uv.push_back(std::clamp(s.a[1], d.v_start, d.v_end));
  }
  std::vector<double> points(uv.size() / 2 * DimensionOf(face.surface()));
  const absl::Span<double> output[] = {absl::MakeSpan(points)};
  RETURN_IF_ERROR(
      EvaluateSurface(face.surface(), SurfaceSamples::Pairs(uv), output, {}));
  return points;
}

}  // namespace

absl::StatusOr<BoundingBox> FaceBoundingBox(const TrimmedSurface& face,
                                            double tolerance,
                                            const CancellationToken* cancel) {
  RETURN_IF_ERROR(ValidatePositive(tolerance, "tolerance"));
  ASSIGN_OR_RETURN(SurfaceDecomposition decomposition,
                   DecomposeSurface(face.surface(), cancel));
  const SurfacePieces pieces{std::move(decomposition)};
  ASSIGN_OR_RETURN(const std::vector<double> trim_points, TrimPoints(face));
  const int dimension = DimensionOf(face.surface());
  double scale = 0.0;
  for (const SurfaceData& net : pieces.decomposition.pieces.patches) {
    for (const double c : net.coordinates) scale = std::max(scale, std::abs(c));
  }
  BoundingBox box{.lower = std::vector<double>(dimension),
                  .upper = std::vector<double>(dimension)};
  for (int j = 0; j < dimension; ++j) {
    for (const double sign : {1.0, -1.0}) {
      double lower_from_trims = -INFINITY;
      for (size_t i = j; i < trim_points.size();
           i += static_cast<size_t>(dimension)) {
        lower_from_trims = std::max(lower_from_trims, sign * trim_points[i]);
      }
      SideSearch search(face, j, sign, tolerance);
      ASSIGN_OR_RETURN(const double side,
                       search.Run(pieces, lower_from_trims, cancel));
      const double widened = side + kBoxMargin * scale;
      (sign > 0 ? box.upper[j] : box.lower[j]) = sign * widened;
    }
  }
  return box;
}

}  // namespace freeform
