// The prepare step's options: every mapping of a request's enums and
// options from freeform.v1 to the core's types, with the defaults of the
// optional ones (CheckEnum, the ToCore overloads, the query tolerances).
//
// An enum is checked with CheckEnum before its ToCore (proto3 keeps unknown
// numbers); a mapping that can refuse a value returns StatusOr. Field paths
// are the request's ("scheme", "options.tolerance"). Thread-compatible: no
// shared state.
#ifndef FREEFORM_SERVER_PREPARE_OPTIONS_H_
#define FREEFORM_SERVER_PREPARE_OPTIONS_H_

#include <cstdint>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "freeform/core/bezier.h"
#include "freeform/core/closest_point.h"
#include "freeform/core/interpolation.h"
#include "freeform/core/intersection.h"
#include "freeform/core/knot_removal.h"
#include "freeform/core/subdivision.h"
#include "freeform/v1/curve_service.pb.h"
#include "freeform/v1/query.pb.h"
#include "freeform/v1/surface_service.pb.h"
#include "service_limits.h"

namespace freeform::server {

// CheckEnum returns INVALID_ARGUMENT naming `field` when `value` is none of
// its enum's values (`is_valid` is the generated <Enum>_IsValid): proto3
// keeps unknown numbers, which must not run as some other value.
absl::Status CheckEnum(int value, bool (*is_valid)(int),
                       absl::string_view field);

// ToCore maps the Bezier algorithm of an evaluation (checked with CheckEnum
// first): unspecified is AUTO.
BezierAlgorithm ToCore(v1::BezierAlgorithm algorithm);

// ToCore maps the interpolation enums of the curve and surface Interpolate
// RPCs (checked with CheckEnum first): unspecified is chord length and
// averaging.
Parameterization ToCore(v1::Parameterization parameterization);
KnotRule ToCore(v1::KnotRule rule);

// ToCore maps a cubic spline's end condition (checked with CheckEnum
// first): unspecified is not-a-knot.
SplineEnd ToCore(v1::SplineEndCondition end);

// ToCore maps a subdivision scheme; unspecified, or a value unknown to v1,
// is INVALID_ARGUMENT on "scheme".
absl::StatusOr<SubdivisionScheme> ToCore(v1::SubdivisionScheme scheme);

// DirectionIsU returns whether a split or a knot insertion of a tensor
// surface runs in U (true) or V (false); any other value is
// INVALID_ARGUMENT on "direction".
absl::StatusOr<bool> DirectionIsU(v1::SurfaceDirection direction);

// RemovalDirections maps the direction of a surface knot removal: U or V
// for one knot (`one_knot`); U, V or BOTH to simplify. Anything else is
// INVALID_ARGUMENT on "direction".
absl::StatusOr<KnotDirections> RemovalDirections(v1::SurfaceDirection direction,
                                                 bool one_knot);

// GivenLimit returns an optional limit of a request, 0 (no limit) when it
// is absent. Zero is the proto's default, which the core reads as no limit,
// so a limit that is there must not be zero; the core checks the rest of
// `rule`, naming the same field.
absl::StatusOr<double> GivenLimit(bool present, double value,
                                  absl::string_view field,
                                  absl::string_view rule);

// Defaults of the optional tolerances (query.proto).
inline constexpr double kDefaultQueryTolerance = 1e-9;
inline constexpr double kDefaultSeparation = 1e-7;
inline constexpr uint32_t kDefaultMaxMinima = 8;
// The default cap of intersection results (points plus overlaps).
inline constexpr uint64_t kDefaultMaxResults = 1 << 16;
// The default chordal tolerance of section polylines, and the default cap
// of their vertices (surface_service.proto).
inline constexpr double kDefaultSectionTolerance = 1e-6;
inline constexpr uint64_t kDefaultSectionPoints = uint64_t{1} << 16;

// GivenTolerance returns a tolerance the request must give (a plain
// double field): `value` when it is positive and finite, else
// INVALID_ARGUMENT naming `field`. It is the rule of every tolerance
// checked here.
absl::StatusOr<double> GivenTolerance(double value, absl::string_view field);

// Tolerance returns `value` when `has_value` (GivenTolerance), otherwise
// `fallback`.
absl::StatusOr<double> Tolerance(bool has_value, double value, double fallback,
                                 absl::string_view field);

// RequestTolerance returns the optional `tolerance` field of a query
// request (Tolerance, naming "tolerance"), or `fallback` when it is unset.
template <typename Request>
absl::StatusOr<double> RequestTolerance(
    const Request& request, double fallback = kDefaultQueryTolerance) {
  return Tolerance(request.has_tolerance(), request.tolerance(), fallback,
                   "tolerance");
}

// ToCore checks closest-point options (fields under "options.") and fills
// in their defaults; the pieces one query may examine come from the server.
absl::StatusOr<ClosestPointOptions> ToCore(
    const v1::ClosestPointOptions& options);

// ToCore checks intersection options whose answer holds `values_per_result`
// doubles per result: the cap of results is the request's (or the
// default), within the output and message limits.
absl::StatusOr<IntersectionOptions> ToCore(
    const v1::IntersectionOptions& options, uint64_t values_per_result,
    const ServiceLimits& limits);

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_PREPARE_OPTIONS_H_
