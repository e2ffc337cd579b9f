// The prepare step of FaceService (prepare_face.h).
#include "prepare_face.h"

#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "absl/strings/str_cat.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "prepare.h"
#include "prepare_options.h"

namespace freeform::server {
namespace {

// PrepareLoop prepares every curve of a loop at "<path>.curves[j]".
absl::StatusOr<TrimLoop> PrepareLoop(const v1::TrimLoop& message,
                                     const ServiceLimits& limits,
                                     const std::string& path) {
  TrimLoop loop;
  loop.curves.reserve(static_cast<size_t>(message.curves_size()));
  for (int j = 0; j < message.curves_size(); ++j) {
    ASSIGN_OR_RETURN(Curve curve,
                     PrepareCurve(message.curves(j), limits,
                                  IndexedField(absl::StrCat(path, ".curves"),
                                               static_cast<size_t>(j))));
    loop.curves.push_back(std::move(curve));
  }
  return loop;
}

}  // namespace

absl::StatusOr<FaceRequest> PrepareFace(const v1::TrimmedSurface& message,
                                        const ServiceLimits& limits,
                                        absl::string_view field) {
  ASSIGN_OR_RETURN(
      const double tolerance,
      Tolerance(message.has_tolerance(), message.tolerance(),
                kDefaultFaceTolerance, absl::StrCat(field, ".tolerance")));
  ASSIGN_OR_RETURN(Surface surface,
                   PrepareSurface(message.surface(), limits,
                                  absl::StrCat(field, ".surface")));
  FaceRequest request{.parts = {.surface = std::move(surface),
                                .outer = std::nullopt,
                                .holes = {},
                                .reversed = message.reversed()},
                      .tolerance = tolerance,
                      .field = std::string(field),
                      .curve_count = 0};
  // Every curve has at least one control point, so the curves are bounded
  // by the control-point limit like the points themselves.
  uint64_t curves = static_cast<uint64_t>(message.outer().curves_size());
  for (const v1::TrimLoop& hole : message.holes()) {
    curves += static_cast<uint64_t>(hole.curves_size());
  }
  RETURN_IF_ERROR(CheckPointLimit(curves, limits, field));
  request.curve_count = curves;
  if (message.has_outer()) {
    ASSIGN_OR_RETURN(
        TrimLoop outer,
        PrepareLoop(message.outer(), limits, absl::StrCat(field, ".outer")));
    request.parts.outer = std::move(outer);
  }
  request.parts.holes.reserve(static_cast<size_t>(message.holes_size()));
  for (int i = 0; i < message.holes_size(); ++i) {
    ASSIGN_OR_RETURN(TrimLoop hole,
                     PrepareLoop(message.holes(i), limits,
                                 IndexedField(absl::StrCat(field, ".holes"),
                                              static_cast<size_t>(i))));
    request.parts.holes.push_back(std::move(hole));
  }
  return request;
}

absl::StatusOr<TrimmedSurface> CreateFace(FaceRequest request,
                                          const CancellationToken* cancel) {
  absl::StatusOr<TrimmedSurface> face = TrimmedSurface::Create(
      std::move(request.parts), request.tolerance, cancel);
  if (!face.ok()) return PrefixFieldPath(face.status(), request.field);
  return face;
}

absl::StatusOr<TrimmedSurfaceWork> FaceWork(const FaceRequest& request,
                                            const CancellationToken* cancel) {
  absl::StatusOr<TrimmedSurfaceWork> work =
      TrimmedSurfaceWorkBytes(request.parts, request.tolerance, cancel);
  if (!work.ok()) return PrefixFieldPath(work.status(), request.field);
  return work;
}

}  // namespace freeform::server
