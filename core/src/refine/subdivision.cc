#include "freeform/core/subdivision.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/types/span.h"
#include "base/homogeneous.h"
#include "base/point_array.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "refine/knot_insertion.h"
#include "refine/knots.h"

namespace freeform {
namespace {

using internal::Lift;
using internal::PointArray;
using internal::ProjectAllowingDirections;
using internal::RefineKnots;
using internal::Spline;
using internal::TransposeBlocks;

BezierCurveData ToBezierCurve(const PointArray& points, bool rational) {
  BezierCurveData curve;
  curve.dimension = rational ? points.dim - 1 : points.dim;
  ProjectAllowingDirections(points, rational, curve.coordinates, curve.weights,
                            internal::ZeroWeights::kExact);
  return curve;
}

// ---------------------------------------------------------------------------
// de Casteljau subdivision (docs/references.md,
// 'de Casteljau evaluation and subdivision').

// SplitAt writes the left ([0, t]) and right ([t, 1]) halves of the Bezier
// polygon `points`; either output may be null.
void SplitAt(const PointArray& points, double t, PointArray* left,
             PointArray* right) {
  const int n = static_cast<int>(points.count()) - 1;
  const int dim = points.dim;
  PointArray work = points;
  if (left != nullptr) *left = PointArray{dim, points.values};
  if (right != nullptr) *right = PointArray{dim, points.values};
  for (int r = 1; r <= n; ++r) {
    for (int i = 0; i <= n - r; ++i) {
      double* a = work.at(i);
      const double* b = work.at(i + 1);
      for (int x = 0; x < dim; ++x) a[x] = (1.0 - t) * a[x] + t * b[x];
    }
    if (left != nullptr) std::copy_n(work.at(0), dim, left->at(r));
    if (right != nullptr) std::copy_n(work.at(n - r), dim, right->at(n - r));
  }
}

// Piece returns the Bezier polygon of the curve on [a, b] within [0, 1].
PointArray Piece(const PointArray& points, double a, double b) {
  PointArray left = points;
  if (b < 1.0) SplitAt(points, b, &left, nullptr);
  if (a <= 0.0) return left;
  PointArray right;
  SplitAt(left, a / b, nullptr, &right);
  return right;
}

absl::Status CheckSplitParameters(absl::Span<const double> parameters) {
  for (size_t i = 0; i < parameters.size(); ++i) {
    const double t = parameters[i];
    const std::string field = IndexedField("parameters", i);
    if (!std::isfinite(t) || t <= 0.0 || t >= 1.0) {
      return InvalidFieldError(field, "must lie strictly between 0 and 1");
    }
    if (i > 0 && t <= parameters[i - 1]) {
      return InvalidFieldError(field, "parameters must be strictly increasing");
    }
  }
  return absl::OkStatus();
}

// ---------------------------------------------------------------------------
// Knot refinement.

// CheckKnotsToInsert checks the rules of InsertKnots for `x` against a
// spline of degree p with `knots` and domain [lo, hi].
absl::Status CheckKnotsToInsert(int p, absl::Span<const double> knots,
                                absl::Span<const double> x) {
  const size_t n = knots.size() - static_cast<size_t>(p) - 2;
  const double lo = knots[static_cast<size_t>(p)];
  const double hi = knots[n + 1];
  int run = 0;  // copies of x[i] among x[0..i]
  for (size_t i = 0; i < x.size(); ++i) {
    const std::string field = IndexedField("knots", i);
    const double u = x[i];
    if (!std::isfinite(u)) return InvalidFieldError(field, "must be finite");
    if (u < lo || u > hi) {
      return InvalidFieldError(
          field, absl::StrCat("must lie in the domain [", lo, ", ", hi, "]"));
    }
    if (i > 0 && u < x[i - 1]) {
      return InvalidFieldError(field, "knots must be non-decreasing");
    }
    run = (i > 0 && u == x[i - 1]) ? run + 1 : 1;
    const int existing = internal::Multiplicity(knots, u);
    const int limit = (u > lo && u < hi) ? p : p + 1;
    if (existing + run > limit) {
      return InvalidFieldError(
          field, absl::StrCat("raises the multiplicity of ", u, " to ",
                              existing + run, ", above the allowed ", limit,
                              (limit == p ? " (the degree) inside the domain"
                                          : " (degree + 1) at a domain end")));
    }
  }
  return absl::OkStatus();
}

Spline LiftCurve(const BSplineCurveView& curve) {
  return {curve.degree,
          std::vector<double>(curve.knots.begin(), curve.knots.end()),
          Lift(curve.control_points, curve.weights)};
}

// ---------------------------------------------------------------------------
// Polygon subdivision (Lane-Riesenfeld 1980; docs/references.md,
// 'Uniform B-spline subdivision (Chaikin, Lane-Riesenfeld)').

// Mask returns s_k = binom(d + 1, k) / 2^d for k = 0..d+1.
std::vector<double> Mask(int d) {
  std::vector<double> mask(static_cast<size_t>(d) + 2);
  long double binomial = 1.0L;
  const long double scale = std::ldexp(1.0L, -d);
  for (int k = 0; k <= d + 1; ++k) {
    mask[static_cast<size_t>(k)] = static_cast<double>(binomial * scale);
    binomial = binomial * (d + 1 - k) / (k + 1);
  }
  return mask;
}

// FloorDiv2 returns floor(a / 2) for any sign of a.
int FloorDiv2(int a) { return a >= 0 ? a / 2 : -((1 - a) / 2); }

// RefinePolygon applies one subdivision step: point r of the result is
// Q_{r+d} = sum_i s_{r+d-2i} P_i, the indices i taken modulo m when closed;
// open polygons keep r in [0, 2m - d), where every P_i lies in the polygon.
absl::StatusOr<PointArray> RefinePolygon(const PointArray& points, bool closed,
                                         const std::vector<double>& mask,
                                         const CancellationToken* cancel) {
  CancellationPoll poll(cancel);
  const int d = static_cast<int>(mask.size()) - 2;
  const int m = static_cast<int>(points.count());
  const int dim = points.dim;
  const int count = closed ? 2 * m : 2 * m - d;
  PointArray out{dim,
                 std::vector<double>(static_cast<size_t>(count) * dim, 0.0)};
  for (int r = 0; r < count; ++r) {
    RETURN_IF_ERROR(poll.Done(static_cast<size_t>(d + 2) * dim));
    const int j = r + d;
    double* q = out.at(r);
    for (int i = FloorDiv2(j - d); i <= FloorDiv2(j); ++i) {
      if (j - 2 * i > d + 1) continue;
      const int index = closed ? ((i % m) + m) % m : i;  // m >= 3 if closed
      const double s = mask[static_cast<size_t>(j - 2 * i)];
      const double* point = points.at(index);
      for (int x = 0; x < dim; ++x) q[x] += s * point[x];
    }
  }
  return out;
}

absl::Status CheckSubdivision(size_t points, bool closed, int degree,
                              int levels) {
  if (levels < 1) return InvalidFieldError("levels", "must be at least 1");
  if (degree < 1 || degree > kMaxSubdivisionDegree) {
    return InvalidFieldError(
        "degree", absl::StrCat("must lie in [1, ", kMaxSubdivisionDegree, "]"));
  }
  const size_t needed = closed ? 3 : static_cast<size_t>(degree) + 1;
  if (points < needed) {
    return InvalidFieldError(
        "polygon.coordinates",
        absl::StrCat(closed ? "a closed" : "an open", " polygon of degree ",
                     degree, " needs at least ", needed, " points, got ",
                     points));
  }
  return absl::OkStatus();
}

// ---------------------------------------------------------------------------
// Surfaces.

// RowsOf returns the net as a polygon of count_u "points", each a whole
// (homogeneous) row of count_v points, or of count_v columns when !in_u.
PointArray RowsOf(const ControlNetView& net, absl::Span<const double> weights,
                  bool in_u) {
  const PointArray lifted =
      Lift(PointsView{net.dimension, net.coordinates}, weights);
  if (in_u) return {lifted.dim * net.count_v, lifted.values};
  return {lifted.dim * net.count_u,
          TransposeBlocks(lifted.values, net.count_u, net.count_v, lifted.dim)};
}

// FillNet writes `rows` (from RowsOf with the same in_u) into `surface`,
// whose degrees, dimension and knots are already set.
void FillNet(const PointArray& rows, bool in_u, bool rational,
             SurfaceData& surface) {
  const int point_dim = surface.dimension + (rational ? 1 : 0);
  const int lines = static_cast<int>(rows.count());
  const int per_line = rows.dim / point_dim;
  surface.count_u = in_u ? lines : per_line;
  surface.count_v = in_u ? per_line : lines;
  PointArray net{point_dim, in_u ? rows.values
                                 : TransposeBlocks(rows.values, lines, per_line,
                                                   point_dim)};
  ProjectAllowingDirections(net, rational, surface.coordinates, surface.weights,
                            internal::ZeroWeights::kExact);
}

// ---------------------------------------------------------------------------
// Triangular patches.

absl::Status CheckTrianglePoint(double u, double v) {
  if (!std::isfinite(u) || u <= 0.0) {
    return InvalidFieldError("u", "must be finite and positive (inside)");
  }
  if (!std::isfinite(v) || v <= 0.0 || u + v >= 1.0) {
    return InvalidFieldError(
        "v", "must be finite and positive with u + v < 1 (inside)");
  }
  return absl::OkStatus();
}

// Pyramid returns the triangular de Casteljau levels R^0..R^n at (u, v, w):
// level l holds the degree n - l net in storage order (triangular.h).
std::vector<PointArray> Pyramid(const PointArray& points, int n, double u,
                                double v) {
  const double w = 1.0 - u - v;
  const int dim = points.dim;
  std::vector<PointArray> levels{points};
  for (int l = 1; l <= n; ++l) {
    const PointArray& prev = levels.back();
    const int deg = n - l;
    PointArray next{dim, std::vector<double>(TriangularPointCount(deg) * dim)};
    for (int i = 0; i <= deg; ++i) {
      for (int j = 0; i + j <= deg; ++j) {
        const double* a =
            prev.at(static_cast<int>(TriangularIndex(deg + 1, i + 1, j)));
        const double* b =
            prev.at(static_cast<int>(TriangularIndex(deg + 1, i, j + 1)));
        const double* c =
            prev.at(static_cast<int>(TriangularIndex(deg + 1, i, j)));
        double* q = next.at(static_cast<int>(TriangularIndex(deg, i, j)));
        for (int x = 0; x < dim; ++x) q[x] = u * a[x] + v * b[x] + w * c[x];
      }
    }
    levels.push_back(std::move(next));
  }
  return levels;
}

// SubPatch returns the control points of the piece that replaces vertex
// `vertex` (0, 1, 2) by the pyramid's point: P(a,b,c) = R^a(0,b,c),
// R^b(a,0,c) or R^c(a,b,0).
PointArray SubPatch(const std::vector<PointArray>& levels, int n, int vertex) {
  const int dim = levels[0].dim;
  PointArray out{dim, std::vector<double>(TriangularPointCount(n) * dim)};
  for (int a = 0; a <= n; ++a) {
    for (int b = 0; a + b <= n; ++b) {
      const int c = n - a - b;
      const int level = vertex == 0 ? a : (vertex == 1 ? b : c);
      const int i = vertex == 0 ? 0 : a;
      const int j = vertex == 1 ? 0 : b;
      const PointArray& source = levels[static_cast<size_t>(level)];
      std::copy_n(source.at(static_cast<int>(TriangularIndex(n - level, i, j))),
                  dim, out.at(static_cast<int>(TriangularIndex(n, a, b))));
    }
  }
  return out;
}

// SplitPieces returns the pieces of SplitTriangularPatch at the point
// (u, v, 1 - u - v) of the closed triangle for the given vertices, in their
// order: piece `vertex` has the point in place of that vertex.
std::vector<TriangularPatchData> SplitPieces(
    const TriangularPatchView& patch, double u, double v,
    std::initializer_list<int> vertices) {
  const int n = patch.degree;
  const std::vector<PointArray> levels =
      Pyramid(Lift(patch.control_points, patch.weights), n, u, v);
  const double barycentric[3] = {u, v, 1.0 - u - v};
  std::vector<TriangularPatchData> result;
  for (const int vertex : vertices) {
    TriangularPatchData& piece = result.emplace_back();
    piece.degree = n;
    piece.dimension = patch.control_points.dimension;
    ProjectAllowingDirections(SubPatch(levels, n, vertex), patch.rational(),
                              piece.coordinates, piece.weights,
                              internal::ZeroWeights::kExact);
    if (patch.domain_triangle.empty()) continue;
    piece.domain_triangle.assign(patch.domain_triangle.begin(),
                                 patch.domain_triangle.end());
    for (int x = 0; x < 2; ++x) {
      double point = 0.0;
      for (int c = 0; c < 3; ++c) {
        point += barycentric[c] * patch.domain_triangle[2 * c + x];
      }
      piece.domain_triangle[static_cast<size_t>(2 * vertex + x)] = point;
    }
  }
  return result;
}

// KnotsToDecompose returns the knots that raise every distinct value of
// the sorted `knots` inside the domain [u_p, u_{n+1}] to multiplicity p (at
// least), after which the p + 1 control points of each non-empty span are
// its Bezier points (The NURBS Book A5.6). Each value's multiplicity is its
// run.
std::vector<double> KnotsToDecompose(absl::Span<const double> knots, int p) {
  const double lo = knots[static_cast<size_t>(p)];
  const double hi = knots[knots.size() - static_cast<size_t>(p) - 1];
  std::vector<double> insert;
  for (size_t i = 0; i < knots.size();) {
    const double u = knots[i];
    size_t run = i + 1;
    while (run < knots.size() && knots[run] == u) ++run;
    const int have = static_cast<int>(run - i);
    i = run;
    if (u < lo || u > hi) continue;
    for (int c = have; c < p; ++c) insert.push_back(u);
  }
  return insert;
}

// NonEmptySpans returns the spans s in [p, count - 1] with u_s < u_{s+1}.
std::vector<int> NonEmptySpans(absl::Span<const double> knots, int p,
                               int count) {
  std::vector<int> spans;
  for (int s = p; s < count; ++s) {
    if (knots[static_cast<size_t>(s)] < knots[static_cast<size_t>(s) + 1]) {
      spans.push_back(s);
    }
  }
  return spans;
}

// SpanBreakpoints returns the start of the first span and the end of every
// span.
std::vector<double> SpanBreakpoints(absl::Span<const double> knots,
                                    const std::vector<int>& spans) {
  std::vector<double> breakpoints = {knots[static_cast<size_t>(spans[0])]};
  for (const int s : spans)
    breakpoints.push_back(knots[static_cast<size_t>(s) + 1]);
  return breakpoints;
}

// PatchOfSpans returns the Bezier patch of the span rectangle (s, t) of a
// surface refined by KnotsToDecompose in both directions: its
// (p + 1) x (q + 1) active control points and weights.
SurfaceData PatchOfSpans(const SurfaceData& refined, int s, int t) {
  const int p = refined.degree_u;
  const int q = refined.degree_v;
  const size_t dim = static_cast<size_t>(refined.dimension);
  SurfaceData patch{.degree_u = p,
                    .degree_v = q,
                    .dimension = refined.dimension,
                    .count_u = p + 1,
                    .count_v = q + 1};
  for (int i = s - p; i <= s; ++i) {
    for (int j = t - q; j <= t; ++j) {
      const size_t k =
          static_cast<size_t>(i) * static_cast<size_t>(refined.count_v) +
          static_cast<size_t>(j);
      patch.coordinates.insert(patch.coordinates.end(),
                               refined.coordinates.begin() + k * dim,
                               refined.coordinates.begin() + (k + 1) * dim);
      if (!refined.weights.empty()) patch.weights.push_back(refined.weights[k]);
    }
  }
  return patch;
}

}  // namespace

absl::StatusOr<std::vector<BezierCurveData>> SplitBezierCurve(
    const BezierCurveView& curve, absl::Span<const double> parameters,
    const CancellationToken* cancel) {
  RETURN_IF_ERROR(CheckSplitParameters(parameters));
  const PointArray points = Lift(curve.control_points, curve.weights);
  std::vector<BezierCurveData> pieces;
  pieces.reserve(parameters.size() + 1);
  const size_t piece_work = points.values.size() * points.values.size();
  CancellationPoll poll(cancel);
  for (size_t k = 0; k <= parameters.size(); ++k) {
    RETURN_IF_ERROR(poll.Done(piece_work));
    const double a = k == 0 ? 0.0 : parameters[k - 1];
    const double b = k == parameters.size() ? 1.0 : parameters[k];
    pieces.push_back(ToBezierCurve(Piece(points, a, b), curve.rational()));
  }
  return pieces;
}

absl::StatusOr<BSplineCurveData> InsertKnots(const BSplineCurveView& curve,
                                             absl::Span<const double> knots,
                                             const CancellationToken* cancel) {
  RETURN_IF_ERROR(CheckKnotsToInsert(curve.degree, curve.knots, knots));
  absl::StatusOr<Spline> refined = RefineKnots(LiftCurve(curve), knots, cancel);
  if (!refined.ok()) return refined.status();
  BSplineCurveData result;
  result.degree = curve.degree;
  result.dimension = curve.control_points.dimension;
  result.knots = refined->knots;
  ProjectAllowingDirections(refined->points, curve.rational(),
                            result.coordinates, result.weights,
                            internal::ZeroWeights::kExact);
  return result;
}

absl::StatusOr<BezierPatchDecomposition> DecomposeBSplineSurface(
    const BSplineSurfaceView& surface, const CancellationToken* cancel) {
  absl::StatusOr<SurfaceData> in_u = InsertSurfaceKnots(
      surface, true, KnotsToDecompose(surface.knots_u, surface.degree_u),
      cancel);
  if (!in_u.ok()) return in_u.status();
  absl::StatusOr<SurfaceData> refined = InsertSurfaceKnots(
      in_u->bspline_view(), false,
      KnotsToDecompose(surface.knots_v, surface.degree_v), cancel);
  if (!refined.ok()) return refined.status();
  const std::vector<int> spans_u =
      NonEmptySpans(refined->knots_u, refined->degree_u, refined->count_u);
  const std::vector<int> spans_v =
      NonEmptySpans(refined->knots_v, refined->degree_v, refined->count_v);
  BezierPatchDecomposition result;
  result.breakpoints_u = SpanBreakpoints(refined->knots_u, spans_u);
  result.breakpoints_v = SpanBreakpoints(refined->knots_v, spans_v);
  result.patches.reserve(spans_u.size() * spans_v.size());
  for (const int s : spans_u) {
    for (const int t : spans_v) {
      result.patches.push_back(PatchOfSpans(*refined, s, t));
    }
  }
  return result;
}

absl::StatusOr<BezierDecomposition> DecomposeBSplineCurve(
    const BSplineCurveView& curve, const CancellationToken* cancel) {
  const int p = curve.degree;
  absl::StatusOr<Spline> refined =
      RefineKnots(LiftCurve(curve), KnotsToDecompose(curve.knots, p), cancel);
  if (!refined.ok()) return refined.status();
  const std::vector<int> spans = NonEmptySpans(
      refined->knots, p, static_cast<int>(refined->points.count()));
  const int dim = refined->points.dim;
  BezierDecomposition result;
  result.breakpoints = SpanBreakpoints(refined->knots, spans);
  result.segments.reserve(spans.size());
  for (const int s : spans) {
    const auto first = refined->points.values.begin() +
                       static_cast<std::ptrdiff_t>(s - p) * dim;
    PointArray segment{
        dim, std::vector<double>(
                 first, first + static_cast<std::ptrdiff_t>(p + 1) * dim)};
    result.segments.push_back(ToBezierCurve(segment, curve.rational()));
  }
  return result;
}

absl::StatusOr<std::vector<std::vector<double>>> SubdividePolygon(
    const PointsView& polygon, bool closed, SubdivisionScheme scheme,
    int degree, int levels, const CancellationToken* cancel) {
  const int d = scheme == SubdivisionScheme::kChaikin ? 2 : degree;
  RETURN_IF_ERROR(CheckSubdivision(polygon.size(), closed, d, levels));
  const std::vector<double> mask = Mask(d);
  PointArray current{polygon.dimension,
                     std::vector<double>(polygon.coordinates.begin(),
                                         polygon.coordinates.end())};
  std::vector<std::vector<double>> result;
  result.reserve(static_cast<size_t>(levels));
  for (int level = 0; level < levels; ++level) {
    absl::StatusOr<PointArray> refined =
        RefinePolygon(current, closed, mask, cancel);
    if (!refined.ok()) return refined.status();
    current = *std::move(refined);
    result.push_back(current.values);
  }
  return result;
}

absl::StatusOr<SurfaceData> InsertSurfaceKnots(
    const BSplineSurfaceView& surface, bool in_u,
    absl::Span<const double> knots, const CancellationToken* cancel) {
  const int degree = in_u ? surface.degree_u : surface.degree_v;
  const absl::Span<const double> old_knots =
      in_u ? surface.knots_u : surface.knots_v;
  RETURN_IF_ERROR(CheckKnotsToInsert(degree, old_knots, knots));
  const Spline lines{degree,
                     std::vector<double>(old_knots.begin(), old_knots.end()),
                     RowsOf(surface.control_net, surface.weights, in_u)};
  absl::StatusOr<Spline> refined = RefineKnots(lines, knots, cancel);
  if (!refined.ok()) return refined.status();
  SurfaceData result;
  result.degree_u = surface.degree_u;
  result.degree_v = surface.degree_v;
  result.dimension = surface.control_net.dimension;
  result.knots_u.assign(surface.knots_u.begin(), surface.knots_u.end());
  result.knots_v.assign(surface.knots_v.begin(), surface.knots_v.end());
  (in_u ? result.knots_u : result.knots_v) = refined->knots;
  FillNet(refined->points, in_u, surface.rational(), result);
  return result;
}

absl::StatusOr<std::vector<SurfaceData>> SplitBezierSurface(
    const BezierSurfaceView& surface, bool in_u, double t) {
  if (!std::isfinite(t) || t <= 0.0 || t >= 1.0) {
    return InvalidFieldError("parameter", "must lie strictly between 0 and 1");
  }
  const PointArray lines = RowsOf(surface.control_net, surface.weights, in_u);
  PointArray halves[2];
  SplitAt(lines, t, &halves[0], &halves[1]);
  std::vector<SurfaceData> result(2);
  for (int h = 0; h < 2; ++h) {
    SurfaceData& piece = result[static_cast<size_t>(h)];
    piece.dimension = surface.control_net.dimension;
    FillNet(halves[h], in_u, surface.rational(), piece);
    piece.degree_u = piece.count_u - 1;
    piece.degree_v = piece.count_v - 1;
  }
  return result;
}

absl::StatusOr<std::vector<TriangularPatchData>> SplitTriangularPatch(
    const TriangularPatchView& patch, double u, double v) {
  RETURN_IF_ERROR(CheckTrianglePoint(u, v));
  return SplitPieces(patch, u, v, {0, 1, 2});
}

absl::StatusOr<std::vector<TriangularPatchData>> BisectTriangularPatch(
    const TriangularPatchView& patch, int edge) {
  if (edge < 0 || edge > 2) {
    return InvalidFieldError("edge", "must be 0, 1 or 2");
  }
  constexpr double kMidpoints[3][2] = {{0.0, 0.5}, {0.5, 0.0}, {0.5, 0.5}};
  const double u = kMidpoints[edge][0];
  const double v = kMidpoints[edge][1];
  if (edge == 0) return SplitPieces(patch, u, v, {1, 2});
  if (edge == 1) return SplitPieces(patch, u, v, {0, 2});
  return SplitPieces(patch, u, v, {0, 1});
}

BezierDecomposition DecomposeHermiteCurve(const HermiteCurveView& curve) {
  BezierDecomposition decomposition;
  decomposition.breakpoints = HermiteNodes(curve);
  const size_t pieces = decomposition.breakpoints.size() - 1;
  decomposition.segments.reserve(pieces);
  for (size_t k = 0; k < pieces; ++k) {
    decomposition.segments.push_back({.dimension = curve.points.dimension,
                                      .coordinates = HermiteSegmentBezier(
                                          curve, decomposition.breakpoints, k),
                                      .weights = {}});
  }
  return decomposition;
}

}  // namespace freeform
