// The scalar point-by-point curve and surface evaluators, kept callable as
// the reference that the SIMD kernels across parameters (simd/curve_simd.h,
// simd/surface_simd.h) must match bit for bit. The public evaluators use the
// kernels where they exist; tests call these to compare. Internal to the core;
// thread-safe.
#ifndef FREEFORM_CORE_SRC_KINDS_SCALAR_REFERENCE_H_
#define FREEFORM_CORE_SRC_KINDS_SCALAR_REFERENCE_H_

#include "absl/status/status.h"
#include "absl/types/span.h"
#include "freeform/core/bezier.h"
#include "freeform/core/bspline.h"
#include "freeform/core/curve_output.h"
#include "freeform/core/surface_output.h"
#include "freeform/core/tensor_surface.h"

namespace freeform::internal {

// EvaluateBSplineCurveScalar is EvaluateBSplineCurve (one thread) on the
// scalar path.
absl::Status EvaluateBSplineCurveScalar(const BSplineCurveView& curve,
                                        absl::Span<const double> parameters,
                                        CurveOutput output);

// EvaluateBezierCurveScalar is EvaluateBezierCurve (one thread) on the
// scalar path.
absl::Status EvaluateBezierCurveScalar(
    const BezierCurveView& curve, absl::Span<const double> parameters,
    CurveOutput output, BezierAlgorithm algorithm = BezierAlgorithm::kAuto);

// EvaluateBSplineSurfaceScalar is EvaluateBSplineSurface (one thread) on the
// scalar path.
absl::Status EvaluateBSplineSurfaceScalar(const BSplineSurfaceView& surface,
                                          const SurfaceSamples& samples,
                                          SurfaceOutput output);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_KINDS_SCALAR_REFERENCE_H_
