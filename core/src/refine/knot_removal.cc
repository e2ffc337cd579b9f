#include "freeform/core/knot_removal.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "absl/functional/function_ref.h"
#include "absl/strings/str_cat.h"
#include "base/homogeneous.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "refine/certified_knot_removal.h"

namespace freeform {
namespace {

using internal::BlockSpline;
using internal::KnotRemover;
using internal::LineReference;

// The work a pass does on its remover: Remove or Simplify.
using Work = absl::FunctionRef<absl::Status(KnotRemover&, CancellationPoll&)>;

absl::Status CheckTimes(int times) {
  if (times < 1) return InvalidFieldError("times", "must be at least 1");
  return absl::OkStatus();
}

absl::Status CheckPositiveWeights(absl::Span<const double> weights) {
  for (size_t i = 0; i < weights.size(); ++i) {
    if (!(weights[i] > 0.0)) {
      return InvalidFieldError(
          IndexedField("weights", i),
          "must be positive for knot removal (its error bound divides by "
          "the weights)");
    }
  }
  return absl::OkStatus();
}

// CheckInput checks the tolerance, then the geometry (`validation`, the
// status of its Validate* function), then its weights.
absl::Status CheckInput(double tolerance, const absl::Status& validation,
                        absl::Span<const double> weights) {
  RETURN_IF_ERROR(ValidatePositive(tolerance, "tolerance"));
  if (!validation.ok()) return validation;
  return CheckPositiveWeights(weights);
}

// CheckInteriorKnot checks that `knot` is one of the valid `knots` of
// degree p strictly inside the domain (u_p, u_{n+1}).
absl::Status CheckInteriorKnot(absl::Span<const double> knots, int p,
                               double knot) {
  const double lo = knots[static_cast<size_t>(p)];
  const double hi = knots[knots.size() - static_cast<size_t>(p) - 1];
  if (std::isfinite(knot) && knot > lo && knot < hi &&
      std::binary_search(knots.begin(), knots.end(), knot)) {
    return absl::OkStatus();
  }
  return InvalidFieldError(
      "knot", absl::StrCat(knot,
                           " is not there: not a knot strictly inside "
                           "the domain (",
                           lo, ", ", hi, ")"));
}

// ProjectRemoved writes the remover's points (homogeneous when rational)
// back as coordinates and weights. The remover refuses a removal that would
// make a weight zero or negative, so every weight is positive and each point
// is its homogeneous point divided by its weight (ProjectPositive; the
// algorithms that take zero weights snap tiny ones to 0 instead, see
// homogeneous.h).
void ProjectRemoved(const std::vector<double>& points, int dimension,
                    bool rational, std::vector<double>& coordinates,
                    std::vector<double>& weights) {
  if (!rational) {
    coordinates = points;
    weights.clear();
    return;
  }
  const size_t dim = static_cast<size_t>(dimension);
  const size_t count = points.size() / (dim + 1);
  coordinates.resize(count * dim);
  weights.resize(count);
  for (size_t i = 0; i < count; ++i) {
    const double* h = &points[i * (dim + 1)];
    weights[i] = h[dim];
    internal::ProjectPositive(h, dimension, &coordinates[i * dim]);
  }
}

// RunOnCurve runs `work` on a remover of the (homogeneous) points of a
// checked curve.
absl::StatusOr<CurveKnotRemoval> RunOnCurve(const BSplineCurveView& curve,
                                            const CancellationToken* cancel,
                                            Work work) {
  const int dim = curve.control_points.dimension;
  const int width = curve.rational() ? dim + 1 : dim;
  std::vector<double> points =
      internal::LiftedValues(curve.control_points, curve.weights);
  const LineReference reference(points, 1, width, curve.rational(), {1},
                                std::nullopt);
  CancellationPoll poll(cancel);
  absl::StatusOr<KnotRemover> remover = KnotRemover::Create(
      BlockSpline{.degree = curve.degree,
                  .block = width,
                  .knots = {curve.knots.begin(), curve.knots.end()},
                  .points = std::move(points)},
      &reference, poll);
  if (!remover.ok()) return remover.status();
  RETURN_IF_ERROR(work(*remover, poll));
  CurveKnotRemoval result{.curve = {.degree = curve.degree, .dimension = dim},
                          .removals = remover->removals(),
                          .error_bound = remover->bound()};
  if (result.removals == 0) {
    result.curve.coordinates.assign(curve.control_points.coordinates.begin(),
                                    curve.control_points.coordinates.end());
    result.curve.knots.assign(curve.knots.begin(), curve.knots.end());
    result.curve.weights.assign(curve.weights.begin(), curve.weights.end());
    return result;
  }
  result.curve.knots = remover->spline().knots;
  ProjectRemoved(remover->spline().points, dim, curve.rational(),
                 result.curve.coordinates, result.curve.weights);
  return result;
}

// ---------------------------------------------------------------------------
// Surfaces.

// A surface's net in homogeneous form (weight last when rational) with its
// knots: the state between the passes of SimplifySurfaceKnots.
struct HomogeneousSurface {
  int degree_u = 0;
  int degree_v = 0;
  int width = 0;
  bool rational = false;
  int count_u = 0;
  int count_v = 0;
  std::vector<double> knots_u;
  std::vector<double> knots_v;
  std::vector<double> net;  // P[i][j] at (i * count_v + j) * width

  int degree(bool in_u) const { return in_u ? degree_u : degree_v; }
  const std::vector<double>& knots(bool in_u) const {
    return in_u ? knots_u : knots_v;
  }
  int count(bool in_u) const { return in_u ? count_u : count_v; }
};

HomogeneousSurface LiftSurface(const BSplineSurfaceView& surface) {
  const ControlNetView& net = surface.control_net;
  return {.degree_u = surface.degree_u,
          .degree_v = surface.degree_v,
          .width = net.dimension + (surface.rational() ? 1 : 0),
          .rational = surface.rational(),
          .count_u = net.count_u,
          .count_v = net.count_v,
          .knots_u = {surface.knots_u.begin(), surface.knots_u.end()},
          .knots_v = {surface.knots_v.begin(), surface.knots_v.end()},
          .net = internal::LiftedValues({net.dimension, net.coordinates},
                                        surface.weights)};
}

// Reorder copies a count_u x count_v net of `width`-value points between
// net order and line order, where line k holds the points of row k (in_u:
// P[k][0..count_v-1], a control point of the curves in u) or of column k
// (P[0..count_u-1][k]). to_lines: net -> lines, else lines -> net.
std::vector<double> Reorder(const std::vector<double>& values, int width,
                            int count_u, int count_v, bool in_u,
                            bool to_lines) {
  std::vector<double> result(values.size());
  const size_t w = static_cast<size_t>(width);
  for (size_t i = 0; i < static_cast<size_t>(count_u); ++i) {
    for (size_t j = 0; j < static_cast<size_t>(count_v); ++j) {
      const size_t net = i * count_v + j;
      const size_t line = in_u ? net : j * count_u + i;
      const size_t from = to_lines ? net : line;
      const size_t to = to_lines ? line : net;
      std::copy_n(values.begin() + from * w, w, result.begin() + to * w);
    }
  }
  return result;
}

// What a pass of SurfacePass did.
struct PassResult {
  int removals = 0;
  double error_bound = 0.0;
};

// SurfacePass runs `work` on the knots of `current` in u (in_u) or v,
// certified against `original`, and writes the result into `current`.
// `current` has the original knots in that direction; in the other it may
// have fewer, and candidates are then refined onto the original's there.
absl::StatusOr<PassResult> SurfacePass(HomogeneousSurface& current,
                                       const HomogeneousSurface& original,
                                       bool in_u, CancellationPoll& poll,
                                       Work work) {
  const bool other = !in_u;
  std::optional<LineReference::Refinement> refinement;
  if (current.knots(other) != original.knots(other)) {
    refinement = LineReference::Refinement{.degree = original.degree(other),
                                           .coarse = current.knots(other),
                                           .fine = original.knots(other)};
  }
  const LineReference reference(
      Reorder(original.net, original.width, original.count_u, original.count_v,
              in_u, true),
      original.count(other), original.width, original.rational,
      internal::RelevantFunctions(original.knots(other),
                                  original.degree(other)),
      std::move(refinement));
  const int sub_count = current.count(other);
  if (sub_count > std::numeric_limits<int>::max() / current.width) {
    return ExhaustedFieldError("control_net",
                               "a line of the net has too many values");
  }
  absl::StatusOr<KnotRemover> remover = KnotRemover::Create(
      BlockSpline{.degree = current.degree(in_u),
                  .block = sub_count * current.width,
                  .knots = current.knots(in_u),
                  .points = Reorder(current.net, current.width, current.count_u,
                                    current.count_v, in_u, true)},
      &reference, poll);
  if (!remover.ok()) return remover.status();
  RETURN_IF_ERROR(work(*remover, poll));
  const BlockSpline& result = remover->spline();
  (in_u ? current.knots_u : current.knots_v) = result.knots;
  (in_u ? current.count_u : current.count_v) = result.count();
  current.net = Reorder(result.points, current.width, current.count_u,
                        current.count_v, in_u, false);
  return PassResult{remover->removals(), remover->bound()};
}

// RunOnSurface runs `work` on a checked surface in u, then in v, as
// `directions` say.
absl::StatusOr<SurfaceKnotRemoval> RunOnSurface(
    const BSplineSurfaceView& surface, KnotDirections directions,
    const CancellationToken* cancel, Work work) {
  const HomogeneousSurface original = LiftSurface(surface);
  HomogeneousSurface current = original;
  CancellationPoll poll(cancel);
  SurfaceKnotRemoval result;
  for (const bool in_u : {true, false}) {
    if (directions == (in_u ? KnotDirections::kV : KnotDirections::kU)) {
      continue;
    }
    absl::StatusOr<PassResult> pass =
        SurfacePass(current, original, in_u, poll, work);
    if (!pass.ok()) return pass.status();
    (in_u ? result.removals_u : result.removals_v) = pass->removals;
    result.error_bound = pass->error_bound;
  }
  const int dim = surface.control_net.dimension;
  SurfaceData& data = result.surface;
  data = {.degree_u = surface.degree_u,
          .degree_v = surface.degree_v,
          .dimension = dim,
          .count_u = current.count_u,
          .count_v = current.count_v,
          .knots_u = std::move(current.knots_u),
          .knots_v = std::move(current.knots_v)};
  if (result.removals_u + result.removals_v == 0) {
    data.coordinates.assign(surface.control_net.coordinates.begin(),
                            surface.control_net.coordinates.end());
    data.weights.assign(surface.weights.begin(), surface.weights.end());
    return result;
  }
  ProjectRemoved(current.net, dim, surface.rational(), data.coordinates,
                 data.weights);
  return result;
}

}  // namespace

absl::StatusOr<CurveKnotRemoval> RemoveCurveKnot(
    const BSplineCurveView& curve, double knot, int times, double tolerance,
    const CancellationToken* cancel) {
  RETURN_IF_ERROR(
      CheckInput(tolerance, ValidateBSplineCurve(curve), curve.weights));
  RETURN_IF_ERROR(CheckTimes(times));
  RETURN_IF_ERROR(CheckInteriorKnot(curve.knots, curve.degree, knot));
  return RunOnCurve(curve, cancel,
                    [&](KnotRemover& remover, CancellationPoll& poll) {
                      return remover.Remove(knot, times, tolerance, poll);
                    });
}

absl::StatusOr<CurveKnotRemoval> SimplifyCurveKnots(
    const BSplineCurveView& curve, double tolerance,
    const CancellationToken* cancel) {
  RETURN_IF_ERROR(
      CheckInput(tolerance, ValidateBSplineCurve(curve), curve.weights));
  return RunOnCurve(curve, cancel,
                    [&](KnotRemover& remover, CancellationPoll& poll) {
                      return remover.Simplify(tolerance, poll);
                    });
}

absl::StatusOr<SurfaceKnotRemoval> RemoveSurfaceKnot(
    const BSplineSurfaceView& surface, bool in_u, double knot, int times,
    double tolerance, const CancellationToken* cancel) {
  RETURN_IF_ERROR(
      CheckInput(tolerance, ValidateBSplineSurface(surface), surface.weights));
  RETURN_IF_ERROR(CheckTimes(times));
  RETURN_IF_ERROR(CheckInteriorKnot(in_u ? surface.knots_u : surface.knots_v,
                                    in_u ? surface.degree_u : surface.degree_v,
                                    knot));
  return RunOnSurface(surface, in_u ? KnotDirections::kU : KnotDirections::kV,
                      cancel,
                      [&](KnotRemover& remover, CancellationPoll& poll) {
                        return remover.Remove(knot, times, tolerance, poll);
                      });
}

absl::StatusOr<SurfaceKnotRemoval> SimplifySurfaceKnots(
    const BSplineSurfaceView& surface, KnotDirections directions,
    double tolerance, const CancellationToken* cancel) {
  RETURN_IF_ERROR(
      CheckInput(tolerance, ValidateBSplineSurface(surface), surface.weights));
  return RunOnSurface(surface, directions, cancel,
                      [&](KnotRemover& remover, CancellationPoll& poll) {
                        return remover.Simplify(tolerance, poll);
                      });
}

}  // namespace freeform
