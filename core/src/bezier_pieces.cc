#include "freeform/core/bezier_pieces.h"

#include <algorithm>
#include <type_traits>
#include <utility>
#include <variant>

#include "freeform/core/elevation.h"
#include "freeform/core/lagrange.h"

namespace freeform {
namespace {

BezierDecomposition SinglePiece(int dimension, std::vector<double> coordinates,
                                std::vector<double> weights, double start,
                                double end) {
  BezierDecomposition pieces;
  pieces.segments.push_back({.dimension = dimension,
                             .coordinates = std::move(coordinates),
                             .weights = std::move(weights)});
  pieces.breakpoints = {start, end};
  return pieces;
}

// MissingMultiplicity returns the knot values to insert so that every
// distinct value of `knots` inside [lo, hi] appears at least p times.
std::vector<double> MissingMultiplicity(absl::Span<const double> knots, int p,
                                        double lo, double hi) {
  std::vector<double> insert;
  size_t run_start = 0;
  for (size_t i = 1; i <= knots.size(); ++i) {
    if (i < knots.size() && knots[i] == knots[run_start]) continue;
    const double value = knots[run_start];
    const int have = static_cast<int>(i - run_start);
    if (value >= lo && value <= hi)
      insert.insert(insert.end(), std::max(0, p - have), value);
    run_start = i;
  }
  return insert;
}

// SpanStarts returns the indices s in [p, count - 1] of the non-empty spans
// [knots[s], knots[s + 1]] of a spline with `count` control points.
std::vector<int> SpanStarts(const std::vector<double>& knots, int p,
                            int count) {
  std::vector<int> starts;
  for (int s = p; s < count; ++s) {
    if (knots[static_cast<size_t>(s)] < knots[static_cast<size_t>(s) + 1]) {
      starts.push_back(s);
    }
  }
  return starts;
}

// SubNet copies the (p + 1) x (q + 1) block of `refined` starting at
// (row, col) as a Bezier net.
SurfaceData SubNet(const SurfaceData& refined, int row, int col) {
  const int p = refined.degree_u;
  const int q = refined.degree_v;
  const int dim = refined.dimension;
  SurfaceData patch{.degree_u = p,
                    .degree_v = q,
                    .dimension = dim,
                    .count_u = p + 1,
                    .count_v = q + 1};
  for (int i = row; i <= row + p; ++i) {
    for (int j = col; j <= col + q; ++j) {
      const size_t k = static_cast<size_t>(i) * refined.count_v + j;
      const auto first =
          refined.coordinates.begin() + static_cast<std::ptrdiff_t>(k * dim);
      patch.coordinates.insert(patch.coordinates.end(), first, first + dim);
      if (!refined.weights.empty()) patch.weights.push_back(refined.weights[k]);
    }
  }
  return patch;
}

absl::StatusOr<SurfacePieces> BSplinePieces(const BSplineSurfaceView& view,
                                            const CancellationToken* cancel) {
  const SurfaceDomain domain = BSplineSurfaceDomain(view);
  absl::StatusOr<SurfaceData> refined =
      InsertSurfaceKnots(view, /*in_u=*/true,
                         MissingMultiplicity(view.knots_u, view.degree_u,
                                             domain.u_start, domain.u_end),
                         cancel);
  if (!refined.ok()) return refined.status();
  refined =
      InsertSurfaceKnots(refined->bspline_view(), /*in_u=*/false,
                         MissingMultiplicity(view.knots_v, view.degree_v,
                                             domain.v_start, domain.v_end),
                         cancel);
  if (!refined.ok()) return refined.status();
  const std::vector<int> rows =
      SpanStarts(refined->knots_u, view.degree_u, refined->count_u);
  const std::vector<int> cols =
      SpanStarts(refined->knots_v, view.degree_v, refined->count_v);
  SurfacePieces pieces;
  for (int s : rows) pieces.breakpoints_u.push_back(refined->knots_u[s]);
  pieces.breakpoints_u.push_back(refined->knots_u[rows.back() + 1]);
  for (int s : cols) pieces.breakpoints_v.push_back(refined->knots_v[s]);
  pieces.breakpoints_v.push_back(refined->knots_v[cols.back() + 1]);
  for (int s : rows) {
    if (absl::Status status = CheckCancelled(cancel); !status.ok()) {
      return status;
    }
    for (int c : cols) {
      pieces.patches.push_back(
          SubNet(*refined, s - view.degree_u, c - view.degree_v));
    }
  }
  return pieces;
}

SurfacePieces BezierPieces(const BezierSurfaceView& view) {
  const ControlNetView& net = view.control_net;
  SurfacePieces pieces;
  pieces.patches.push_back(
      {.degree_u = net.count_u - 1,
       .degree_v = net.count_v - 1,
       .dimension = net.dimension,
       .count_u = net.count_u,
       .count_v = net.count_v,
       .coordinates = {net.coordinates.begin(), net.coordinates.end()},
       .weights = {view.weights.begin(), view.weights.end()}});
  pieces.breakpoints_u = {0.0, 1.0};
  pieces.breakpoints_v = {0.0, 1.0};
  return pieces;
}

// TrianglePieces returns the degenerate tensor form of a triangular patch
// (see the header comment).
absl::StatusOr<SurfacePieces> TrianglePieces(const TriangularPatchView& view) {
  const int n = view.degree;
  const int dim = view.control_points.dimension;
  SurfaceData net{.degree_u = n,
                  .degree_v = n,
                  .dimension = dim,
                  .count_u = n + 1,
                  .count_v = n + 1};
  for (int i = 0; i <= n; ++i) {
    BezierCurveData row{.dimension = dim};
    for (int j = 0; j <= n - i; ++j) {
      const size_t k = TriangularIndex(n, i, j);
      const double* point = view.control_points.point(k);
      row.coordinates.insert(row.coordinates.end(), point, point + dim);
      if (view.rational()) row.weights.push_back(view.weights[k]);
    }
    if (i > 0) {
      absl::StatusOr<BezierCurveData> raised =
          ElevateBezierCurve(row.view(), i);
      if (!raised.ok()) return raised.status();
      row = *std::move(raised);
    }
    net.coordinates.insert(net.coordinates.end(), row.coordinates.begin(),
                           row.coordinates.end());
    net.weights.insert(net.weights.end(), row.weights.begin(),
                       row.weights.end());
  }
  SurfacePieces pieces;
  pieces.patches.push_back(std::move(net));
  pieces.breakpoints_u = {0.0, 1.0};
  pieces.breakpoints_v = {0.0, 1.0};
  pieces.triangular = true;
  pieces.domain_triangle.assign(view.domain_triangle.begin(),
                                view.domain_triangle.end());
  return pieces;
}

}  // namespace

absl::StatusOr<BezierDecomposition> CurveBezierPieces(
    const Curve& curve, const CancellationToken* cancel) {
  return std::visit(
      [&](const auto& kind) -> absl::StatusOr<BezierDecomposition> {
        using Kind = std::decay_t<decltype(kind)>;
        const auto& view = kind.view();
        if constexpr (std::is_same_v<Kind, BezierCurve>) {
          return SinglePiece(view.control_points.dimension,
                             {view.control_points.coordinates.begin(),
                              view.control_points.coordinates.end()},
                             {view.weights.begin(), view.weights.end()}, 0.0,
                             1.0);
        } else if constexpr (std::is_same_v<Kind, BSplineCurve>) {
          return DecomposeBSplineCurve(view, cancel);
        } else if constexpr (std::is_same_v<Kind, LagrangeCurve>) {
          const ParameterDomain domain = kind.domain();
          return SinglePiece(view.points.dimension, LagrangeToBezier(view), {},
                             domain.start, domain.end);
        } else {
          static_assert(std::is_same_v<Kind, HermiteCurve>);
          return DecomposeHermiteCurve(view);
        }
      },
      curve);
}

absl::StatusOr<SurfacePieces> SurfaceBezierPieces(
    const Surface& surface, const CancellationToken* cancel) {
  return std::visit(
      [&](const auto& kind) -> absl::StatusOr<SurfacePieces> {
        using Kind = std::decay_t<decltype(kind)>;
        if constexpr (std::is_same_v<Kind, BezierSurface>) {
          return BezierPieces(kind.view());
        } else if constexpr (std::is_same_v<Kind, BSplineSurface>) {
          return BSplinePieces(kind.view(), cancel);
        } else {
          static_assert(std::is_same_v<Kind, TriangularPatch>);
          return TrianglePieces(kind.view());
        }
      },
      surface);
}

std::array<double, 2> SurfacePieceParameters(const SurfacePieces& pieces,
                                             size_t index, double s, double t) {
  if (pieces.triangular) {
    const double u = s;
    const double v = (1.0 - s) * t;
    if (pieces.domain_triangle.empty()) return {u, v};
    const double w = 1.0 - u - v;
    const std::vector<double>& d = pieces.domain_triangle;
    return {u * d[0] + v * d[2] + w * d[4], u * d[1] + v * d[3] + w * d[5]};
  }
  const size_t columns = pieces.breakpoints_v.size() - 1;
  const size_t i = index / columns;
  const size_t j = index % columns;
  const double u0 = pieces.breakpoints_u[i];
  const double u1 = pieces.breakpoints_u[i + 1];
  const double v0 = pieces.breakpoints_v[j];
  const double v1 = pieces.breakpoints_v[j + 1];
  // Exact at the ends, so a piece's corner is its breakpoint.
  const double u = s >= 1.0 ? u1 : u0 + s * (u1 - u0);
  const double v = t >= 1.0 ? v1 : v0 + t * (v1 - v0);
  return {u, v};
}

}  // namespace freeform
