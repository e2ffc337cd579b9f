// Unit normals of 3D surfaces from their partial derivatives.
//
// The normal of a regular point is (S_u x S_v) / |S_u x S_v|. Where the
// cross product vanishes relative to |S_u|^2 + |S_v|^2 (a collapsed boundary
// row or column, as at the top of the Utah teapot lid, or a pole of a
// sphere-like patch), the normal is the limit of the normals of nearby
// points, found from the second partials. Moving by h in u,
//   S_u(u+h) x S_v(u+h) = S_u x S_v + h (S_u x S_uv + S_uu x S_v) + O(h^2),
// so with S_u x S_v = 0 the normal tends to sign(h) times the direction of
// D_u = S_u x S_uv + S_uu x S_v (at a collapsed row, S_v = 0 along the edge
// and D_u = S_u x S_uv); moving in v it tends to sign(h) times
// D_v = S_uv x S_v + S_u x S_vv. Along a collapsed row one of the two is
// zero (the surface does not move along the edge), so the larger one is the
// direction in which the point leaves the degeneracy, and the sign is that
// of the step into the domain: the limit is one-sided, and opposite on the
// two sides of the edge. Without second partials, or when that limit
// vanishes too, the normal is the zero vector.
//
// Thread-safe; no allocation.
#ifndef FREEFORM_CORE_NORMALS_H_
#define FREEFORM_CORE_NORMALS_H_

#include <cstddef>

#include "absl/status/status.h"
#include "absl/types/span.h"
#include "freeform/core/surface_output.h"
#include "freeform/core/tensor_surface.h"

namespace freeform {

// ComputeUnitNormals writes the unit normal of each of `count` points of a
// 3D surface into normals[3 r .. 3 r + 2], from `partials` (an output of
// max order >= 1 filled by a surface evaluator; with max order >= 2 the
// limit at degenerate points is used). Degenerate points are approached
// from larger parameters (u + h, v + h with h > 0), which is the limit from
// inside the domain at a collapsed edge at the start of u or v (the teapot
// lid's apex, row 0); for an edge at the end of the domain use the overload
// below. Fails with INVALID_ARGUMENT when the buffers are not 3D or not
// count * 3 doubles, or the max order is 0.
absl::Status ComputeUnitNormals(SurfaceOutput partials, size_t count,
                                absl::Span<double> normals);

// ComputeUnitNormals for the points of `samples` on `domain`: a degenerate
// point at u = u_end (v = v_end) is approached from below, all others from
// above, so the normal is the limit from inside the domain everywhere.
absl::Status ComputeUnitNormals(SurfaceOutput partials,
                                const SurfaceSamples& samples,
                                const SurfaceDomain& domain,
                                absl::Span<double> normals);

}  // namespace freeform

#endif  // FREEFORM_CORE_NORMALS_H_
