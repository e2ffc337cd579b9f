// Bounds on the partials of span rectangles (piece_bounds.h).
#include "meshing/piece_bounds.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <utility>
#include <variant>
#include <vector>

#include "geometry/variant_dispatch.h"

namespace freeform::internal {
namespace {

// A homogeneous net of the active control points of a span rectangle,
// (w (P - c), w) per point, and the derivative nets made from it.
class ActiveNet {
 public:
  ActiveNet(int count_u, int count_v)
      : count_u_(count_u),
        count_v_(count_v),
        values_(4 * static_cast<size_t>(count_u) * count_v, 0.0) {}
  int count_u() const { return count_u_; }
  int count_v() const { return count_v_; }
  double* at(int a, int b) {
    return &values_[4 * (static_cast<size_t>(a) * count_v_ + b)];
  }
  const double* at(int a, int b) const {
    return &values_[4 * (static_cast<size_t>(a) * count_v_ + b)];
  }
  // The largest spatial norm and weight magnitude over the net.
  std::pair<double, double> Largest() const {
    double spatial = 0.0, weight = 0.0;
    for (size_t k = 0; k < values_.size(); k += 4) {
      spatial = std::max(
          spatial, std::hypot(values_[k], values_[k + 1], values_[k + 2]));
      weight = std::max(weight, std::abs(values_[k + 3]));
    }
    return {spatial, weight};
  }

 private:
  int count_u_, count_v_;
  std::vector<double> values_;
};

// Derivative returns the control points of the derivative in u (in_u) or v
// of the B-spline part whose control points are `net`, the first of them
// being control point `first` of a knot vector `knots` of degree `degree`
// in that direction: degree (G_{i+1} - G_i) / (t_{i+degree+1} - t_{i+1})
// (The NURBS Book, eq. 3.8). The denominators of points active on a
// non-empty span are at least its width.
ActiveNet Derivative(const ActiveNet& net, bool in_u, int degree, int first,
                     absl::Span<const double> knots) {
  ActiveNet result(net.count_u() - (in_u ? 1 : 0),
                   net.count_v() - (in_u ? 0 : 1));
  for (int a = 0; a < result.count_u(); ++a) {
    for (int b = 0; b < result.count_v(); ++b) {
      const int i = first + (in_u ? a : b);
      const double scale =
          degree / (knots[static_cast<size_t>(i + degree + 1)] -
                    knots[static_cast<size_t>(i + 1)]);
      const double* lo = net.at(a, b);
      const double* hi = in_u ? net.at(a + 1, b) : net.at(a, b + 1);
      for (int x = 0; x < 4; ++x) result.at(a, b)[x] = scale * (hi[x] - lo[x]);
    }
  }
  return result;
}

double PointWeight(const BSplineSurfaceView& surface, int i, int j) {
  return surface.rational()
             ? surface.weights[WeightIndex(surface.control_net, i, j)]
             : 1.0;
}

double Distance(const double* point, const PieceFrame& frame) {
  return std::hypot(point[0] - frame.centre[0], point[1] - frame.centre[1],
                    point[2] - frame.centre[2]);
}

std::vector<double> ClampedUnitKnots(int degree) {
  std::vector<double> knots(static_cast<size_t>(degree + 1), 0.0);
  knots.resize(2 * static_cast<size_t>(degree + 1), 1.0);
  return knots;
}

}  // namespace

// WeightIndex returns the position of the weight of P[i][j].
size_t WeightIndex(const ControlNetView& net, int i, int j) {
  return static_cast<size_t>(i) * static_cast<size_t>(net.count_v) +
         static_cast<size_t>(j);
}

absl::StatusOr<TensorForm> TensorFormOf(const Surface& surface) {
  return std::visit(
      internal::Overloaded{
          [](const BezierSurface& bezier) -> absl::StatusOr<TensorForm> {
            const BezierSurfaceView& view = bezier.view();
            const ControlNetView& net = view.control_net;
            TensorForm form{.kind = "bezier"};
            form.owned = {
                .degree_u = net.count_u - 1,
                .degree_v = net.count_v - 1,
                .dimension = net.dimension,
                .count_u = net.count_u,
                .count_v = net.count_v,
                .coordinates = {net.coordinates.begin(), net.coordinates.end()},
                .knots_u = ClampedUnitKnots(net.count_u - 1),
                .knots_v = ClampedUnitKnots(net.count_v - 1),
                .weights = {view.weights.begin(), view.weights.end()}};
            return form;
          },
          [](const BSplineSurface& bspline) -> absl::StatusOr<TensorForm> {
            return TensorForm{.external = bspline.view(), .kind = "bspline"};
          },
          [&](const TriangularPatch&) -> absl::StatusOr<TensorForm> {
            absl::StatusOr<SurfaceDecomposition> decomposition =
                DecomposeSurface(surface);
            if (!decomposition.ok()) return decomposition.status();
            TensorForm form{.kind = "triangular_bezier"};
            form.owned = std::move(decomposition->pieces.patches.front());
            form.owned.knots_u = ClampedUnitKnots(form.owned.degree_u);
            form.owned.knots_v = ClampedUnitKnots(form.owned.degree_v);
            return form;
          }},
      surface);
}

namespace {

// FrameOfPoints returns the frame of control points [i0, i1] x [j0, j1].
PieceFrame FrameOfPoints(const BSplineSurfaceView& surface, int i0, int i1,
                         int j0, int j1) {
  const ControlNetView& net = surface.control_net;
  std::array<double, 3> lo = {INFINITY, INFINITY, INFINITY};
  std::array<double, 3> hi = {-INFINITY, -INFINITY, -INFINITY};
  PieceFrame frame{.min_weight = INFINITY};
  for (int i = i0; i <= i1; ++i) {
    for (int j = j0; j <= j1; ++j) {
      const double* point = net.point(i, j);
      for (int x = 0; x < 3; ++x) {
        lo[x] = std::min(lo[x], point[x]);
        hi[x] = std::max(hi[x], point[x]);
      }
      frame.min_weight = std::min(frame.min_weight, PointWeight(surface, i, j));
    }
  }
  for (int x = 0; x < 3; ++x) frame.centre[x] = lo[x] + (hi[x] - lo[x]) / 2;
  for (int i = i0; i <= i1; ++i) {
    for (int j = j0; j <= j1; ++j) {
      frame.radius = std::max(frame.radius, Distance(net.point(i, j), frame));
    }
  }
  return frame;
}

}  // namespace

PieceFrame NetFrame(const BSplineSurfaceView& surface) {
  return FrameOfPoints(surface, 0, surface.control_net.count_u - 1, 0,
                       surface.control_net.count_v - 1);
}

PieceBounds BoundPiece(const BSplineSurfaceView& surface, int su, int sv) {
  return BoundPieceIn(surface, su, sv,
                      FrameOfPoints(surface, su - surface.degree_u, su,
                                    sv - surface.degree_v, sv));
}

PieceBounds BoundPieceIn(const BSplineSurfaceView& surface, int su, int sv,
                         const PieceFrame& frame) {
  const int p = surface.degree_u, q = surface.degree_v;
  const ControlNetView& net = surface.control_net;
  const std::array<double, 3>& centre = frame.centre;
  const double radius = frame.radius, w_min = frame.min_weight;
  ActiveNet active(p + 1, q + 1);
  for (int a = 0; a <= p; ++a) {
    for (int b = 0; b <= q; ++b) {
      const int i = su - p + a, j = sv - q + b;
      const double* point = net.point(i, j);
      const double w = PointWeight(surface, i, j);
      double* g = active.at(a, b);
      for (int x = 0; x < 3; ++x) g[x] = w * (point[x] - centre[x]);
      g[3] = w;
    }
  }
  const double du = surface.knots_u[static_cast<size_t>(su + 1)] -
                    surface.knots_u[static_cast<size_t>(su)];
  const double dv = surface.knots_v[static_cast<size_t>(sv + 1)] -
                    surface.knots_v[static_cast<size_t>(sv)];
  auto bound = [&](const ActiveNet& derivative, double scale) {
    const auto [spatial, weight] = derivative.Largest();
    return scale * (spatial + radius * weight) / w_min;
  };
  PieceBounds bounds;
  if (p >= 1) {
    const ActiveNet d_u = Derivative(active, true, p, su - p, surface.knots_u);
    bounds.u = bound(d_u, du);
    if (p >= 2) {
      bounds.uu = bound(
          Derivative(d_u, true, p - 1, su - p + 1, surface.knots_u), du * du);
    }
    if (q >= 1) {
      bounds.uv =
          bound(Derivative(d_u, false, q, sv - q, surface.knots_v), du * dv);
    }
  }
  if (q >= 1) {
    const ActiveNet d_v = Derivative(active, false, q, sv - q, surface.knots_v);
    bounds.v = bound(d_v, dv);
    if (q >= 2) {
      bounds.vv = bound(
          Derivative(d_v, false, q - 1, sv - q + 1, surface.knots_v), dv * dv);
    }
  }
  return bounds;
}

// NeededCells returns ceil(sqrt(m / (4 tolerance))), at least 1, as a
// double (it may be huge): with h = 1 / cells, h^2 m / 8 <= tolerance / 2.
double NeededCells(double m, double tolerance) {
  return std::max(1.0, std::ceil(std::sqrt(m / (4.0 * tolerance))));
}

// The non-empty spans s (knots[s] < knots[s + 1]) of a domain [t_p,
// t_{count}].
std::vector<int> NonEmptySpans(absl::Span<const double> knots, int degree,
                               int count) {
  std::vector<int> spans;
  for (int s = degree; s < count; ++s) {
    if (knots[static_cast<size_t>(s)] < knots[static_cast<size_t>(s + 1)]) {
      spans.push_back(s);
    }
  }
  return spans;
}
}  // namespace freeform::internal
