// The rules of a trimmed face (trimmed_surface.h), each a check on the
// face's pieces (face_boundary.h) that fails with INVALID_ARGUMENT naming
// the offending loop or curve relative to the face. Internal to the core.
#ifndef FREEFORM_CORE_SRC_FACES_TRIM_VALIDATION_H_
#define FREEFORM_CORE_SRC_FACES_TRIM_VALIDATION_H_

#include <cstdint>

#include "absl/status/status.h"
#include "faces/face_boundary.h"
#include "freeform/core/cancellation.h"

namespace freeform::internal {

// CheckTrimResolution refuses a tolerance below 2^-46 of the trims' largest
// coordinate ("tolerance"): the intersection and tessellation of the trims
// could not meet it.
absl::Status CheckTrimResolution(const FaceBoundary& boundary);

// CheckClosure checks that every curve starts within the tolerance of the
// end of the curve before it in its loop (the last before the first):
// "<loop>.curves[j]" with the gap.
absl::Status CheckClosure(const FaceBoundary& boundary);

// CheckInsideDomain checks that every piece lies within the tolerance of
// the parameter rectangle: its control points' hull, halved where it pokes
// out while the curve may not ("<loop>.curves[j]").
absl::Status CheckInsideDomain(const FaceBoundary& boundary,
                               const CancellationToken* cancel);

// MonotonePartLimit is the most parts CheckCrossings cuts the pieces into
// (RESOURCE_EXHAUSTED naming the loop beyond): one per segment, 16 per
// control point of other pieces, and 64. CrossingCheckBytes bounds the memory
// of those parts.
uint64_t MonotonePartLimit(const FaceBoundary& boundary);
uint64_t CrossingCheckBytes(const FaceBoundary& boundary);

// CheckCrossings checks that no two pieces cross or touch within the
// tolerance, except neighbours in a loop at their shared end
// (IntersectCurves on pieces cut until each is monotone along its chord,
// pairs found by a sweep over their boxes): "<loop>.curves[j]" naming the
// other curve.
absl::Status CheckCrossings(const FaceBoundary& boundary,
                            const CancellationToken* cancel);

// LoopSignedArea returns the integral of u dv around a loop (positive when
// counter-clockwise): Gauss-Legendre with enough points to be exact per
// polynomial piece, adaptive Gauss-Kronrod per rational piece.
double LoopSignedArea(const FaceBoundary& boundary, int loop);

// CheckOrientation checks the outer loop's signed area is positive
// ("outer") and every hole's negative ("holes[i]").
absl::Status CheckOrientation(const FaceBoundary& boundary);

// CheckContainment checks that every hole lies inside the outer loop and
// inside no other hole ("holes[i]"); needs the polylines and grid.
absl::Status CheckContainment(const FaceBoundary& boundary,
                              const CancellationToken* cancel);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_FACES_TRIM_VALIDATION_H_
