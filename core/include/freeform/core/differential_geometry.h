// Differential geometry of curves and surfaces at parameters: Frenet frames,
// curvature and torsion of curves, rotation-minimizing frames along a curve,
// and normals, Gaussian, mean and principal curvatures of surfaces
// (docs/references.md, 'Differential geometry of curves' and
// 'Differential geometry of surfaces').
//
// Curves, in any dimension d >= 1, from the derivatives r', r'', r''' of
// EvaluateCurve:
//   tangent    T = r' / |r'|;
//   curvature  kappa = |r''_perp| / |r'|^2 >= 0, with r''_perp = r'' -
//              (r'' . T) T the part of r'' across the tangent. Since
//              |r'|^2 |r''_perp|^2 = |r'|^2 |r''|^2 - (r' . r'')^2, this is
//              the formula sqrt(|r'|^2 |r''|^2 - (r' . r'')^2) / |r'|^3 of
//              every dimension, computed without its cancellation;
//   normal     N = r''_perp / |r''_perp| (towards the centre of curvature;
//              in 2-D too, so the curvature is unsigned there);
//   binormal   B = T x N (3-D only);
//   torsion    tau = (r' x r'') . r''' / |r' x r''|^2 (3-D only: the
//              buffers for B and tau must be empty in other dimensions).
// A point where the curve stands still is kSingular and one where it does
// not bend kStraight (see CurvePointStatus); what is undefined there is
// written as zeros, never NaN. "Stands still" and "does not bend" are
// relative to the size of the curve's motion over its whole domain of width
// W, M = |r'| W + |r''| W^2 / 2 + |r'''| W^3 / 6 (its Taylor terms): r' is
// negligible when |r'| W <= 1e-12 M, r''_perp when |r''_perp| W^2 / 2 <=
// 1e-12 M. A domain of width 0 (a Lagrange curve with one given node) makes
// every point singular.
//
// Rotation-minimizing frames follow the curve through the given parameters
// by the double reflection method (Wang, Juttler, Zheng and Liu, "Computation
// of rotation minimizing frames", ACM TOG 27(1), 2008): from (x_i, t_i, r_i),
// reflect r_i and t_i in the plane bisecting x_i x_{i+1}, then reflect in the
// plane that maps the reflected tangent onto t_{i+1}. Reflections are
// orthogonal, so (t, r) stays orthonormal in any dimension; the global error
// is O(h^4) in the parameter spacing h. In 3-D the third vector is
// s = t x r.
//
// Surfaces, 3-D only, from the partials of EvaluateSurface: with
// E = S_u.S_u, F = S_u.S_v, G = S_v.S_v (first fundamental form), the unit
// normal n = (S_u x S_v) / |S_u x S_v| and L = S_uu.n, M = S_uv.n,
// N = S_vv.n (second fundamental form), the shape operator in the
// orthonormal tangent basis e1 = S_u / |S_u|, e2 = n x e1 is the symmetric
// matrix of II(e_a, e_b); its eigenvalues are the principal curvatures
// k1 >= k2 and its eigenvectors the principal directions d1, d2 = n x d1;
// K = k1 k2 = (LN - M^2) / (EG - F^2), H = (k1 + k2) / 2 =
// (EN - 2FM + GL) / (2 (EG - F^2)). Sign convention: curvatures are
// positive where the surface bends towards n = S_u x S_v normalized; a
// sphere of radius r whose S_u x S_v points inwards has H = 1/r, k1 = k2 =
// 1/r, one whose normal points outwards H = -1/r; K = 1/r^2 either way.
// Where |S_u x S_v| <= 1e-10 (E + G) (the rule of normals.h) the first
// fundamental form is singular: the point is kSingular, its normal is the
// limit ComputeUnitNormals finds (or zero) and its curvatures and
// directions are zeros.
//
// Scale: curves and surfaces are evaluated as their copies rescaled by
// powers of two (coordinates at most 1, the domain's width about 1; exact)
// and every norm scales its squares (docs/references.md, 'Scale-safe
// norms'), so a circle of radius 1e-200, a curve on knots 1e170 apart and
// a cylinder of radius 1e80 have the curvatures of the unit ones over their
// size; only a value beyond the double range itself (the Gaussian
// curvature 1e400 of a sphere of radius 1e-200) is not representable. A
// Gaussian curvature below 16 epsilon of the shape operator's size squared
// is rounding and returned as 0.
//
// Output buffers have sizes known before any work (the *Sizes functions);
// a buffer may be left empty when it is not wanted (except the statuses),
// otherwise a wrong size is INVALID_ARGUMENT. Batches run in chunks on the
// context's pool; parameter errors name "parameters[i]" (curves) or
// "uv[i]", "u[i]", "v[i]" (surfaces).
//
// All functions are thread-safe and allocate per call.
#ifndef FREEFORM_CORE_DIFFERENTIAL_GEOMETRY_H_
#define FREEFORM_CORE_DIFFERENTIAL_GEOMETRY_H_

#include <cstddef>
#include <cstdint>

#include "absl/status/status.h"
#include "absl/types/span.h"
#include "freeform/core/curve.h"
#include "freeform/core/surface.h"
#include "freeform/core/thread_pool.h"

namespace freeform {

// What is defined at a curve point.
enum class CurvePointStatus : uint8_t {
  // Everything: tangent, curvature, normal (and binormal and torsion).
  kRegular = 0,
  // r' != 0 but the curve does not bend (r'' along r', e.g. a line or an
  // inflection): the tangent is defined and the curvature is 0; normal,
  // binormal and torsion are undefined and written as 0.
  kStraight = 1,
  // r' = 0 (a cusp, a stationary point, coincident control points): nothing
  // is defined; everything is written as 0.
  kSingular = 2,
};

// Where EvaluateFrenetFrames writes, per parameter r.
struct FrenetFrameOutput {
  absl::Span<double> tangents;            // [r * d + j]
  absl::Span<double> normals;             // [r * d + j]
  absl::Span<double> binormals;           // [r * 3 + j], 3-D only
  absl::Span<double> curvatures;          // [r]
  absl::Span<double> torsions;            // [r], 3-D only
  absl::Span<CurvePointStatus> statuses;  // [r], required
};

// The size of every buffer of FrenetFrameOutput (values, not bytes).
struct FrenetFrameSizes {
  size_t tangents = 0;
  size_t normals = 0;
  size_t binormals = 0;
  size_t curvatures = 0;
  size_t torsions = 0;
  size_t statuses = 0;
};

// FrenetSizes returns the buffer sizes for `count` parameters of a curve of
// `dimension`: binormals and torsions are 0 unless dimension == 3.
FrenetFrameSizes FrenetSizes(int dimension, size_t count);

// EvaluateFrenetFrames writes the Frenet frame, curvature and torsion of
// `curve` at every parameter (see the file comment). Fails with
// INVALID_ARGUMENT "parameters[i]" (not finite or outside the domain), for
// a wrongly sized buffer or a binormal or torsion buffer outside 3-D, and
// with the token's CANCELLED / DEADLINE_EXCEEDED.
absl::Status EvaluateFrenetFrames(const Curve& curve,
                                  absl::Span<const double> parameters,
                                  const FrenetFrameOutput& output,
                                  const ExecutionContext& context = {});

// Where EvaluateRotationMinimizingFrames writes, per parameter r.
struct RotationMinimizingFrameOutput {
  absl::Span<double> tangents;    // [r * d + j], t_r
  absl::Span<double> references;  // [r * d + j], r_r: unit, across t_r
  absl::Span<double> third;       // [r * 3 + j], s_r = t_r x r_r, 3-D only
};

// The size of every buffer of RotationMinimizingFrameOutput.
struct RotationMinimizingFrameSizes {
  size_t tangents = 0;
  size_t references = 0;
  size_t third = 0;
};

// RotationMinimizingSizes returns the buffer sizes for `count` parameters
// of a curve of `dimension` (third is 0 unless dimension == 3).
RotationMinimizingFrameSizes RotationMinimizingSizes(int dimension,
                                                     size_t count);

// EvaluateRotationMinimizingFrames propagates a rotation-minimizing frame
// through `parameters` in the order given (usually increasing), starting
// from `initial_reference` (d values) made orthogonal to the first tangent
// and unit, or, when it is empty, from the principal normal there (or, at a
// straight point, the coordinate axis farthest from the tangent, made
// orthogonal). The frame is defined in dimension >= 2. Fails with
// INVALID_ARGUMENT "parameters" (empty), "parameters[i]" (not finite,
// outside the domain, or a singular point, where the tangent is undefined),
// "initial_reference" (not d finite values, or along the tangent), for a
// curve of dimension 1 ("dimension") or wrongly sized buffers, and with the
// token's CANCELLED / DEADLINE_EXCEEDED.
absl::Status EvaluateRotationMinimizingFrames(
    const Curve& curve, absl::Span<const double> parameters,
    absl::Span<const double> initial_reference,
    const RotationMinimizingFrameOutput& output,
    const ExecutionContext& context = {});

// What is defined at a surface point.
enum class SurfacePointStatus : uint8_t {
  // Everything, with distinct principal curvatures.
  kRegular = 0,
  // Everything, but k1 = k2 (within 1e-10 of their size): every tangent
  // direction is principal; d1 = e1, d2 = e2 are returned.
  kUmbilic = 1,
  // The first fundamental form is singular (S_u x S_v ~ 0): curvatures and
  // directions are written as 0, the normal is the limit of normals.h.
  kSingular = 2,
};

// Where EvaluateSurfaceCurvatures writes, per sample r.
struct SurfaceCurvatureOutput {
  absl::Span<double> normals;               // [r * 3 + j]
  absl::Span<double> gaussian;              // [r]
  absl::Span<double> mean;                  // [r]
  absl::Span<double> principal_curvatures;  // [r * 2 + a]: k1, k2
  absl::Span<double> principal_directions;  // [r * 6 + 3 a + j]: d1, d2
  absl::Span<SurfacePointStatus> statuses;  // [r], required
};

// The size of every buffer of SurfaceCurvatureOutput.
struct SurfaceCurvatureSizes {
  size_t normals = 0;
  size_t gaussian = 0;
  size_t mean = 0;
  size_t principal_curvatures = 0;
  size_t principal_directions = 0;
  size_t statuses = 0;
};

// CurvatureSizes returns the buffer sizes for `count` samples.
SurfaceCurvatureSizes CurvatureSizes(size_t count);

// EvaluateSurfaceCurvatures writes the unit normal, Gaussian and mean
// curvature and principal curvatures and directions of a 3-D `surface` at
// every sample (see the file comment). Fails with INVALID_ARGUMENT for
// samples EvaluateSurface refuses, a surface that is not 3-D
// ("control_net.dimension", or "control_points.dimension" for a triangular
// patch), wrongly sized buffers, and with the token's CANCELLED /
// DEADLINE_EXCEEDED.
absl::Status EvaluateSurfaceCurvatures(const Surface& surface,
                                       const SurfaceSamples& samples,
                                       const SurfaceCurvatureOutput& output,
                                       const ExecutionContext& context = {});

}  // namespace freeform

#endif  // FREEFORM_CORE_DIFFERENTIAL_GEOMETRY_H_
