// Interpolation with knots at the parameters (KnotRule::kAtParameters,
// interpolation.h), the rule of OpenCASCADE's GeomAPI_Interpolate: open
// and closed curves, with end derivatives given, scaled or estimated from
// Lagrange polynomials (docs/references.md, 'Interpolation with knots at
// the parameters (OpenCASCADE rule)'). Internal to the core; thread-safe
// (pure functions).
#ifndef FREEFORM_CORE_SRC_CONSTRUCT_INTERPOLATION_AT_PARAMETERS_H_
#define FREEFORM_CORE_SRC_CONSTRUCT_INTERPOLATION_AT_PARAMETERS_H_

#include "absl/status/statusor.h"
#include "freeform/core/interpolation.h"
#include "freeform/core/points.h"

namespace freeform::internal {

// InterpolateAtParameters returns InterpolateCurve's curve for
// options.knot_rule == KnotRule::kAtParameters, after checking the options
// that rule takes.
absl::StatusOr<CurveInterpolation> InterpolateAtParameters(
    const PointsView& points, const CurveInterpolationOptions& options);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_CONSTRUCT_INTERPOLATION_AT_PARAMETERS_H_
