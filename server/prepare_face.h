// The prepare step of FaceService: a TrimmedSurface message to the core's
// raw face parts (views of the request's arrays), every curve and the
// surface prepared with their full field paths, and the face validated by
// the core (TrimmedSurface::Create) under the call's token, its errors
// prefixed with where the face sits ("face.holes[1].curves[0]").
// Thread-compatible.
#ifndef FREEFORM_SERVER_PREPARE_FACE_H_
#define FREEFORM_SERVER_PREPARE_FACE_H_

#include <cstdint>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/trimmed_surface.h"
#include "freeform/v1/geometry.pb.h"
#include "service_limits.h"

namespace freeform::server {

// The closure and geometry tolerance of a face without one.
inline constexpr double kDefaultFaceTolerance = 1e-9;
// The area's absolute tolerance when a request gives none.
inline constexpr double kDefaultFaceAreaTolerance = 1e-9;

// What a face message prepares to: its parts and tolerance, validated
// together by CreateFace (the work of a call, under its token).
struct FaceRequest {
  TrimmedSurfaceParts parts;
  double tolerance = kDefaultFaceTolerance;
  // Where the face sits in the request ("face").
  std::string field;
  // The number of trim curves of all loops, for the call's plan.
  uint64_t curve_count = 0;
};

// PrepareFace prepares the surface ("<field>.surface") and every trim curve
// ("<field>.outer.curves[j]", "<field>.holes[i].curves[j]") and checks the
// tolerance ("<field>.tolerance", positive and finite when set) and the
// number of loops and curves against the server's limits.
absl::StatusOr<FaceRequest> PrepareFace(const v1::TrimmedSurface& message,
                                        const ServiceLimits& limits,
                                        absl::string_view field = "face");

// CreateFace validates the face (TrimmedSurface::Create), its errors
// prefixed with the face's field.
absl::StatusOr<TrimmedSurface> CreateFace(FaceRequest request,
                                          const CancellationToken* cancel);

// FaceWork returns the work of validating the face (an upper bound of the
// memory of its Bezier pieces, polylines and grid: TrimmedSurfaceWorkBytes),
// the errors of cutting its loops into pieces under the face's field.
absl::StatusOr<TrimmedSurfaceWork> FaceWork(const FaceRequest& request,
                                            const CancellationToken* cancel);

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_PREPARE_FACE_H_
