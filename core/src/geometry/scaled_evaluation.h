// Evaluation of rational geometry whose homogeneous points w P would leave
// the double range: 2.5e-155 with a weight of 1e-300 underflows to 0, and
// the curve's end evaluated to the origin. Such geometry is evaluated on
// its copy rescaled by powers of two, each axis by its own
// (scaled_geometry.h, OfAxes: coordinates and weights at most 1, where w P
// underflows only for coordinates far below the largest of their axis; x
// of 2.5e304 no longer sends a y of 1e25 with weight 1e-100 to 0), and its
// derivatives are scaled back exactly: coordinate j of the k-th derivative
// by 2^(e_j - k ku), of a surface's partial d^(a+b)/du^a dv^b by
// 2^(e_j - a ku - b kv). Other geometry is evaluated as it is. Internal to
// the core.
#ifndef FREEFORM_CORE_SRC_GEOMETRY_SCALED_EVALUATION_H_
#define FREEFORM_CORE_SRC_GEOMETRY_SCALED_EVALUATION_H_

#include "absl/status/status.h"
#include "absl/types/span.h"
#include "freeform/core/curve.h"
#include "freeform/core/surface.h"

namespace freeform::internal {

// NeedsScaledEvaluation says whether the products w P of a rational curve
// or surface may underflow or overflow: on some axis, the largest
// coordinate times the smallest nonzero weight below 2^-960, or times the
// largest above 2^960.
bool NeedsScaledEvaluation(const Curve& curve);
bool NeedsScaledEvaluation(const Surface& surface);

// EvaluateScaledCurve and EvaluateScaledSurface evaluate on the rescaled
// copy (EvaluateCurve's and EvaluateSurface's contract, without normals).
absl::Status EvaluateScaledCurve(const Curve& curve,
                                 absl::Span<const double> parameters,
                                 CurveOutput output,
                                 const ExecutionContext& context);
absl::Status EvaluateScaledSurface(const Surface& surface,
                                   const SurfaceSamples& samples,
                                   SurfaceOutput output,
                                   const ExecutionContext& context);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_GEOMETRY_SCALED_EVALUATION_H_
