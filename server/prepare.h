// The prepare step: from a request's geometry message to one validated core
// object (curve.h, basis.h, surface.h), with every rule and every server
// limit checked once, before any work.
//
// Errors carry full field paths into the request: `field` is where the
// message sits ("curve", "basis", "tensor.u", "surfaces[2]"), so a broken
// knot reads "curve.bspline.knots[4]". Integers are checked in their own
// type before any conversion. The prepared object views the request's
// arrays (or owns a converted copy), so it must not outlive the request.
// Thread-compatible.
#ifndef FREEFORM_SERVER_PREPARE_H_
#define FREEFORM_SERVER_PREPARE_H_

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "freeform/core/basis.h"
#include "freeform/core/bezier.h"
#include "freeform/core/curve.h"
#include "freeform/core/surface.h"
#include "freeform/v1/curve_service.pb.h"
#include "freeform/v1/geometry.pb.h"
#include "service_limits.h"

namespace freeform::server {

// PrepareCurveToEvaluate validates a curve of any kind for evaluation;
// `algorithm` (the request's, ToCore in prepare_options.h) applies to
// Bezier and power forms. Power-form curves become Bezier curves.
absl::StatusOr<Curve> PrepareCurveToEvaluate(const v1::Curve& message,
                                             const ServiceLimits& limits,
                                             absl::string_view field,
                                             BezierAlgorithm algorithm);

// PrepareCurve validates a curve for every other RPC, which work on its
// Bezier pieces: as PrepareCurveToEvaluate, and a Lagrange curve must have
// a Bezier form that double precision holds (CheckLagrangeBezierForm,
// "<field>.lagrange.nodes").
absl::StatusOr<Curve> PrepareCurve(const v1::Curve& message,
                                   const ServiceLimits& limits,
                                   absl::string_view field = "curve");

// PrepareBasis validates a set of blending functions.
absl::StatusOr<CurveBasis> PrepareBasis(const v1::Basis& message,
                                        const ServiceLimits& limits,
                                        absl::string_view field = "basis");

// PrepareSurface validates a surface of any kind. Interpolating and Hermite
// patches become Bezier surfaces.
absl::StatusOr<Surface> PrepareSurface(const v1::Surface& message,
                                       const ServiceLimits& limits,
                                       absl::string_view field = "surface");

// PreparePoints checks a point set's dimension and count limits and its
// values (finite, a whole number of points), relative to `field`.
absl::StatusOr<PointsView> PreparePoints(const v1::Points& message,
                                         const ServiceLimits& limits,
                                         absl::string_view field);

// PrepareNet checks a control net's dimension and size limits (each count
// and their product in uint64) and returns its view; the net's own rules
// are the core's. With `degrees_from_counts`, count - 1 must also be within
// the degree limit.
absl::StatusOr<ControlNetView> PrepareNet(const v1::ControlNet& message,
                                          const ServiceLimits& limits,
                                          absl::string_view field,
                                          bool degrees_from_counts);

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_PREPARE_H_
