// Surface: a validated surface of any kind the core evaluates, ready to be
// evaluated again and again (the surface counterpart of curve.h).
//
// Tensor-product Bezier and B-spline/NURBS surfaces and triangular Bezier
// patches are made by Create functions that validate them once. Like the
// curves (curve.h), a surface made by Create holds a view of the caller's
// arrays (the request's), not a copy: they must outlive it. The bicubic
// interpolating patch and the bicubic Hermite (Ferguson) patch become the
// BezierSurface of the same surface, whose net the object owns. `Surface` is
// the std::variant over the kinds; code that handles every kind uses
// std::visit, so a new kind is a compile error wherever it is missing.
//
// Thread-safe: evaluation is const.
#ifndef FREEFORM_CORE_SURFACE_H_
#define FREEFORM_CORE_SURFACE_H_

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <variant>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/types/span.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/subdivision.h"
#include "freeform/core/surface_output.h"
#include "freeform/core/tensor_surface.h"
#include "freeform/core/thread_pool.h"
#include "freeform/core/triangular.h"

namespace freeform {

// A polynomial or rational tensor-product Bezier surface on [0, 1]^2.
class BezierSurface {
 public:
  // Create validates `view` (ValidateBezierSurface).
  static absl::StatusOr<BezierSurface> Create(const BezierSurfaceView& view);
  // FromInterpolatingPatch validates a 4 x 4 net of points ("points...",
  // "points.count_u" / "points.count_v" when it is not 4 x 4) and returns
  // the bicubic patch through them at 0, 1/3, 2/3, 1 (patches.h).
  static absl::StatusOr<BezierSurface> FromInterpolatingPatch(
      const ControlNetView& points);
  // FromHermitePatch validates the 2 x 2 corner nets of a Ferguson patch
  // (each "<name>.dimension" equal to the positions', "<name>.count_u" for a
  // net that is not 2 x 2, "<name>.coordinates..."; empty twists mean zero)
  // and returns its bicubic Bezier form (patches.h).
  static absl::StatusOr<BezierSurface> FromHermitePatch(
      const ControlNetView& positions, const ControlNetView& derivatives_u,
      const ControlNetView& derivatives_v, const ControlNetView& twists);

  const BezierSurfaceView& view() const { return view_; }
  int dimension() const { return view_.control_net.dimension; }
  SurfaceDomain domain() const { return BezierSurfaceDomain(); }
  absl::Status Evaluate(const SurfaceSamples& samples, SurfaceOutput output,
                        const ExecutionContext& context = {}) const;

 private:
  BezierSurface(const BezierSurfaceView& view,
                std::shared_ptr<const std::vector<double>> owned)
      : view_(view), owned_(std::move(owned)) {}
  static BezierSurface OwnedBicubic(int dimension, std::vector<double> net);

  BezierSurfaceView view_;
  std::shared_ptr<const std::vector<double>> owned_;
};

// A B-spline or NURBS surface on its knot domain.
class BSplineSurface {
 public:
  // Create validates `view` (ValidateBSplineSurface).
  static absl::StatusOr<BSplineSurface> Create(const BSplineSurfaceView& view);

  const BSplineSurfaceView& view() const { return view_; }
  int dimension() const { return view_.control_net.dimension; }
  SurfaceDomain domain() const { return domain_; }
  absl::Status Evaluate(const SurfaceSamples& samples, SurfaceOutput output,
                        const ExecutionContext& context = {}) const;

 private:
  explicit BSplineSurface(const BSplineSurfaceView& view)
      : view_(view), domain_(BSplineSurfaceDomain(view)) {}

  BSplineSurfaceView view_;
  SurfaceDomain domain_;
};

// A triangular Bezier patch, barycentric or on a domain triangle. It takes
// (u, v) pairs only: a grid of samples is an error ("grid").
class TriangularPatch {
 public:
  // Create validates `view` (ValidateTriangularPatch).
  static absl::StatusOr<TriangularPatch> Create(
      const TriangularPatchView& view);

  const TriangularPatchView& view() const { return view_; }
  int dimension() const { return view_.control_points.dimension; }
  // The unit square; the patch checks its own triangle.
  SurfaceDomain domain() const { return BezierSurfaceDomain(); }
  absl::Status Evaluate(const SurfaceSamples& samples, SurfaceOutput output,
                        const ExecutionContext& context = {}) const;

 private:
  explicit TriangularPatch(const TriangularPatchView& view) : view_(view) {}

  TriangularPatchView view_;
};

// Every surface kind the core evaluates.
using Surface = std::variant<BezierSurface, BSplineSurface, TriangularPatch>;

// DimensionOf returns the surface's point dimension.
int DimensionOf(const Surface& surface);

// DomainOf returns the parameter rectangle of a tensor-product surface (the
// unit square for a triangular patch).
SurfaceDomain DomainOf(const Surface& surface);

// IsTriangular returns true for a triangular patch.
bool IsTriangular(const Surface& surface);

// ValidateSamples checks `samples` for `surface` before any work, as its
// evaluator would: finite values inside the domain for a tensor-product
// surface (ValidateSurfaceSamples: "uv[i]", "u[i]", "v[i]"), (u, v) pairs
// inside the triangle for a triangular patch ("uv", "uv[i]"; a grid is
// refused as "grid").
absl::Status ValidateSamples(const Surface& surface,
                             const SurfaceSamples& samples);

// EvaluateSurface writes every partial d^(k+l) S / du^k dv^l with
// k + l <= MaxOrderOf(partials) at every sample into `partials`, and, when
// `normals` is not empty, the unit normals (3 * samples.size() doubles; 3D
// surfaces only, "normals") by ComputeUnitNormals. Normals need the partials
// of order 1 and, for the limit at degenerate points, of order 2: those the
// caller did not ask for are computed in scratch memory. Fails like the
// kind's evaluator.
absl::Status EvaluateSurface(const Surface& surface,
                             const SurfaceSamples& samples,
                             SurfaceOutput partials, absl::Span<double> normals,
                             const ExecutionContext& context = {});

// The (rational) Bezier pieces of a surface of any kind, as DecomposeSurface
// returns them: pieces.patches[i * (pieces.breakpoints_v.size() - 1) + j] is
// the surface on [breakpoints_u[i], breakpoints_u[i + 1]] x
// [breakpoints_v[j], breakpoints_v[j + 1]] reparameterized to [0, 1]^2. A
// triangular patch is one piece, its degenerate tensor form, on {0, 1}^2.
struct SurfaceDecomposition {
  BezierPatchDecomposition pieces;
  bool triangular = false;
  // The triangular patch's domain triangle (6 values), or empty.
  std::vector<double> domain_triangle;
};

// DecomposeSurface returns the Bezier pieces of a valid surface: a tensor
// Bezier surface (also the bicubic interpolating and Hermite patches) is its
// own piece; a B-spline (NURBS) surface is DecomposeBSplineSurface. A
// triangular patch of degree n becomes the degenerate tensor patch of
// degrees (n, n) of S(s, (1 - s) t) on [0, 1]^2 (docs/references.md, 'A
// triangular patch as a degenerate tensor patch'): with u = s,
// v = (1 - s) t, w = (1 - s)(1 - t), row i of the net is the row
// P(i, j, n - i - j), j = 0..n - i, of the triangle raised by i degrees
// (ElevateBezierCurve), and the edge s = 1 collapses to the corner
// P(n, 0, 0). Fails only with the token's CANCELLED / DEADLINE_EXCEEDED.
absl::StatusOr<SurfaceDecomposition> DecomposeSurface(
    const Surface& surface, const CancellationToken* cancel = nullptr);

// SurfacePieceParameters returns the surface parameters, as EvaluateSurface
// takes them, of the point (s, t) in [0, 1]^2 of piece `index`: the affine
// image in the piece's span rectangle (exact at its corners), or for a
// triangular patch the barycentric (u, v) = (s, (1 - s) t), or the point
// u A + v B + w C of its domain triangle.
std::array<double, 2> SurfacePieceParameters(
    const SurfaceDecomposition& decomposition, size_t index, double s,
    double t);

// SurfacePieceValues returns an upper bound, known before any work, of the
// doubles DecomposeSurface returns (coordinates, weights and breakpoints):
// one piece per span rectangle of a B-spline surface, the net of a Bezier
// surface, the degenerate tensor net of degrees (n, n) of a triangular
// patch of degree n. The geometric queries cut the surface into these
// pieces first, so it bounds their working memory. Saturates at
// UINT64_MAX.
uint64_t SurfacePieceValues(const Surface& surface);

// SurfacePieceCount returns an upper bound, known before any work, of the
// pieces DecomposeSurface returns: one per span rectangle of a B-spline
// surface, one for the other kinds.
uint64_t SurfacePieceCount(const Surface& surface);

}  // namespace freeform

#endif  // FREEFORM_CORE_SURFACE_H_
