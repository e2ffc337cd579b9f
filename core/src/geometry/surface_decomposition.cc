// DecomposeSurface and SurfacePieceParameters of surface.h: the Bezier
// pieces of every surface kind, which the bounding boxes and the geometric
// queries (closest points, intersections, sections) cut surfaces into.
#include <array>
#include <cstddef>
#include <utility>
#include <vector>

#include "freeform/core/elevation.h"
#include "freeform/core/surface.h"
#include "geometry/variant_dispatch.h"

namespace freeform {
namespace {

SurfaceDecomposition SinglePiece(SurfaceData net) {
  SurfaceDecomposition decomposition;
  decomposition.pieces.patches.push_back(std::move(net));
  decomposition.pieces.breakpoints_u = {0.0, 1.0};
  decomposition.pieces.breakpoints_v = {0.0, 1.0};
  return decomposition;
}

// A Bezier surface's own net.
SurfaceData NetOf(const BezierSurfaceView& view) {
  const ControlNetView& net = view.control_net;
  return {.degree_u = net.count_u - 1,
          .degree_v = net.count_v - 1,
          .dimension = net.dimension,
          .count_u = net.count_u,
          .count_v = net.count_v,
          .coordinates = {net.coordinates.begin(), net.coordinates.end()},
          .knots_u = {},
          .knots_v = {},
          .weights = {view.weights.begin(), view.weights.end()}};
}

// DegenerateTensorNet returns the tensor net of degrees (n, n) of a
// triangular patch (see DecomposeSurface).
absl::StatusOr<SurfaceData> DegenerateTensorNet(
    const TriangularPatchView& view) {
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
  return net;
}

}  // namespace

absl::StatusOr<SurfaceDecomposition> DecomposeSurface(
    const Surface& surface, const CancellationToken* cancel) {
  return std::visit(
      internal::Overloaded{
          [](const BezierSurface& bezier)
              -> absl::StatusOr<SurfaceDecomposition> {
            return SinglePiece(NetOf(bezier.view()));
          },
          [cancel](const BSplineSurface& bspline)
              -> absl::StatusOr<SurfaceDecomposition> {
            absl::StatusOr<BezierPatchDecomposition> pieces =
                DecomposeBSplineSurface(bspline.view(), cancel);
            if (!pieces.ok()) return pieces.status();
            return SurfaceDecomposition{.pieces = *std::move(pieces)};
          },
          [](const TriangularPatch& patch)
              -> absl::StatusOr<SurfaceDecomposition> {
            absl::StatusOr<SurfaceData> net = DegenerateTensorNet(patch.view());
            if (!net.ok()) return net.status();
            SurfaceDecomposition decomposition = SinglePiece(*std::move(net));
            decomposition.triangular = true;
            decomposition.domain_triangle.assign(
                patch.view().domain_triangle.begin(),
                patch.view().domain_triangle.end());
            return decomposition;
          }},
      surface);
}

std::array<double, 2> SurfacePieceParameters(
    const SurfaceDecomposition& decomposition, size_t index, double s,
    double t) {
  if (decomposition.triangular) {
    const double u = s;
    const double v = (1.0 - s) * t;
    const std::vector<double>& d = decomposition.domain_triangle;
    if (d.empty()) return {u, v};
    const double w = 1.0 - u - v;
    return {u * d[0] + v * d[2] + w * d[4], u * d[1] + v * d[3] + w * d[5]};
  }
  const BezierPatchDecomposition& pieces = decomposition.pieces;
  const size_t columns = pieces.breakpoints_v.size() - 1;
  const size_t i = index / columns;
  const size_t j = index % columns;
  const double u0 = pieces.breakpoints_u[i];
  const double u1 = pieces.breakpoints_u[i + 1];
  const double v0 = pieces.breakpoints_v[j];
  const double v1 = pieces.breakpoints_v[j + 1];
  const double u = s >= 1.0 ? u1 : u0 + s * (u1 - u0);
  const double v = t >= 1.0 ? v1 : v0 + t * (v1 - v0);
  return {u, v};
}

}  // namespace freeform
