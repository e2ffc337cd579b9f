// Tensor-product Bezier and B-spline (NURBS) surfaces: validation and batch
// evaluation of positions and partial derivatives.
//
// A tensor-product surface is S(u, v) = sum_i sum_j f_i(u) g_j(v) P[i][j]
// over a rectangular control net (docs/references.md, 'Tensor-product
// surfaces'): the Bernstein polynomials of degrees count_u - 1 and
// count_v - 1 on [0, 1]^2 for a Bezier surface, the B-spline bases
// N_{i,p}(u) and N_{j,q}(v) on [u_p, u_{n+1}] x [v_q, v_{m+1}] for a
// B-spline surface. With weights w[i][j] it is rational,
// S = sum w_ij f_i g_j P_ij / sum w_ij f_i g_j, evaluated in homogeneous form
// (w_ij P_ij, w_ij) and projected by the surface quotient rule (The NURBS
// Book, eq. 4.20, A4.4). As for curves (rational.h), a point with weight 0
// is a point at infinity whose coordinates are its direction.
//
// The net is count_u rows of count_v points, P[i][j] at (i * count_v + j);
// u goes with i, v with j. Evaluation at (u, v) pairs costs one u basis and
// one v basis per point (A3.6); a grid uses the separable structure: each u
// row forms the v-direction "curve" Q_k[j] = sum_i N^(k)_i(u) P[i][j] once,
// the v bases are computed once per v, and each grid point is then a short
// dot product. Outputs follow surface_output.h.
//
// Example, a bicubic B-spline surface with 4 x 5 points in 3D on a grid:
//   BSplineSurfaceView surface{
//       .degree_u = 3, .degree_v = 3,
//       .control_net = {.dimension = 3, .count_u = 4, .count_v = 5,
//                       .coordinates = net},
//       .knots_u = knots_u, .knots_v = knots_v};
//   SurfaceSamples samples{.grid = true, .u = us, .v = vs};
//   std::vector<double> xyz(3 * samples.size());
//   std::vector<absl::Span<double>> output = {absl::MakeSpan(xyz)};
//   absl::Status status = EvaluateBSplineSurface(surface, samples, output);
//
// All functions are thread-safe; evaluation allocates per call or per chunk,
// never per point.
#ifndef FREEFORM_CORE_TENSOR_SURFACE_H_
#define FREEFORM_CORE_TENSOR_SURFACE_H_

#include <cstddef>

#include "absl/status/status.h"
#include "absl/strings/string_view.h"
#include "absl/types/span.h"
#include "freeform/core/surface_output.h"
#include "freeform/core/thread_pool.h"

namespace freeform {

// A rectangular net in caller memory: count_u rows of count_v points of
// `dimension` coordinates, P[i][j] at coordinates[(i * count_v + j) *
// dimension].
struct ControlNetView {
  int dimension = 0;
  int count_u = 0;
  int count_v = 0;
  absl::Span<const double> coordinates;

  // point returns the first coordinate of P[i][j].
  const double* point(int i, int j) const {
    return coordinates.data() +
           (static_cast<size_t>(i) * static_cast<size_t>(count_v) +
            static_cast<size_t>(j)) *
               static_cast<size_t>(dimension);
  }
};

// ValidateControlNet checks a dimension in [1, kMaxDimension]
// ("<field>.dimension"), count_u >= min_u and count_v >= min_v
// ("<field>.count_u", "<field>.count_v"), count_u * count_v * dimension
// coordinates ("<field>.coordinates") and only finite ones
// ("<field>.coordinates[k]").
absl::Status ValidateControlNet(const ControlNetView& net,
                                absl::string_view field, int min_u = 1,
                                int min_v = 1);

// A Bezier surface of degrees (count_u - 1, count_v - 1) on [0, 1]^2.
struct BezierSurfaceView {
  ControlNetView control_net;
  // Empty: polynomial. Otherwise one weight per net point, in net order.
  absl::Span<const double> weights;

  bool rational() const { return !weights.empty(); }
};

// A B-spline (NURBS with weights) surface of degrees (degree_u, degree_v)
// with count_u + degree_u + 1 knots in u and count_v + degree_v + 1 in v.
// Knot vectors follow the curve rules of bspline.h (clamped or not).
struct BSplineSurfaceView {
  int degree_u = 0;
  int degree_v = 0;
  ControlNetView control_net;
  absl::Span<const double> knots_u;
  absl::Span<const double> knots_v;
  // Empty: non-rational. Otherwise one weight per net point, in net order.
  absl::Span<const double> weights;

  bool rational() const { return !weights.empty(); }
};

// A closed parameter rectangle [u_start, u_end] x [v_start, v_end].
struct SurfaceDomain {
  double u_start = 0.0;
  double u_end = 0.0;
  double v_start = 0.0;
  double v_end = 0.0;
};

// ValidateBezierSurface checks the net ("control_net...") and the weights:
// one per net point ("weights"), finite and >= 0 ("weights[k]"), and the
// four corner weights positive ("weights[k]" of the first zero corner). With
// nonnegative weights the denominator is positive on the open square as soon
// as one weight is, on an open edge as soon as one weight of that boundary
// row or column is, and at a corner exactly when the corner weight is; so it
// is positive on all of [0, 1]^2 iff the four corner weights are.
absl::Status ValidateBezierSurface(const BezierSurfaceView& surface);

// ValidateBSplineSurface checks "degree_u" / "degree_v" (>= 0), the net
// ("control_net...", with at least degree + 1 points each way), the knot
// vectors by the rules of ValidateBSplineCurve ("knots_u" for the count or
// an empty domain, "knots_u[i]" for order, finiteness and multiplicity; the
// same for v) and the weights: one per net point ("weights"), finite and
// >= 0 ("weights[k]"), and a denominator positive on every non-empty span
// rectangle, checked at its corners, edge midpoints and centre with the
// basis code that evaluates (one-sided limits at knots); the error names the
// weight with the largest basis product where the surface is infinite.
absl::Status ValidateBSplineSurface(const BSplineSurfaceView& surface);

// BezierSurfaceDomain returns [0, 1] x [0, 1].
SurfaceDomain BezierSurfaceDomain();

// BSplineSurfaceDomain returns [u_p, u_{n+1}] x [v_q, v_{m+1}] of a valid
// surface.
SurfaceDomain BSplineSurfaceDomain(const BSplineSurfaceView& surface);

// EvaluateBezierSurface writes every partial d^(k+l) S / du^k dv^l with
// k + l <= MaxOrderOf(output) at every sample into `output`. Fails with
// INVALID_ARGUMENT for an invalid surface (see ValidateBezierSurface), samples
// outside [0, 1]^2 or not finite ("uv", "uv[i]", "u[i]", "v[i]") or wrongly
// sized output, and with CANCELLED / DEADLINE_EXCEEDED when the context's
// token stops the batch (the output is then partly written). Partials of
// order above the degree of a polynomial surface are zero.
absl::Status EvaluateBezierSurface(const BezierSurfaceView& surface,
                                   const SurfaceSamples& samples,
                                   SurfaceOutput output,
                                   const ExecutionContext& context = {});

// EvaluateBSplineSurface is EvaluateBezierSurface for a B-spline surface on
// its domain (BSplineSurfaceDomain). At an interior knot values are
// right-hand limits, at the end of the domain left-hand limits.
absl::Status EvaluateBSplineSurface(const BSplineSurfaceView& surface,
                                    const SurfaceSamples& samples,
                                    SurfaceOutput output,
                                    const ExecutionContext& context = {});

// ProjectHomogeneousSurfaceDerivatives turns the partials A_{k,l} of a
// homogeneous surface (dimension + 1 values each, weight w last) into those
// of its projection (The NURBS Book, eq. 4.20 and A4.4):
//   S_{k,l} = (A_{k,l} - sum_{j=1..l} C(l,j) w_{0,j} S_{k,l-j}
//              - sum_{i=1..k} C(k,i) sum_{j=0..l} C(l,j) w_{i,j}
//                S_{k-i,l-j}) / w_{0,0}.
// Reads homogeneous[PartialIndex(k, l) * (dimension + 1) + x] and writes
// partials[PartialIndex(k, l) * dimension + x] for k + l <= max_order.
void ProjectHomogeneousSurfaceDerivatives(const double* homogeneous,
                                          int dimension, int max_order,
                                          double* partials);

}  // namespace freeform

#endif  // FREEFORM_CORE_TENSOR_SURFACE_H_
