// Conversions of core results (owning geometry) into freeform.v1 messages.
// Thread-compatible.
#ifndef FREEFORM_SERVER_GEOMETRY_OUT_H_
#define FREEFORM_SERVER_GEOMETRY_OUT_H_

#include "freeform/core/elevation.h"
#include "freeform/core/geometry_data.h"
#include "freeform/v1/geometry.pb.h"

namespace freeform::server {

// ToProto fills `out` with the given geometry.
void ToProto(const BezierCurveData& curve, v1::Curve& out);
void ToProto(const BSplineCurveData& curve, v1::Curve& out);
// A SurfaceData with empty knot vectors is a Bezier surface.
void ToProto(const SurfaceData& surface, v1::Surface& out);
void ToProto(const TriangularPatchData& patch, v1::Surface& out);

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_GEOMETRY_OUT_H_
