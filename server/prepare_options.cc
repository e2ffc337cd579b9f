#include "prepare_options.h"

#include <cmath>

#include "absl/strings/str_cat.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "plan.h"

namespace freeform::server {
namespace {

absl::StatusOr<double> Separation(bool has_value, double value,
                                  absl::string_view field) {
  if (!has_value) return kDefaultSeparation;
  if (std::isfinite(value) && value >= 0.0) return value;
  return InvalidFieldError(
      field, absl::StrCat("must be non-negative and finite, got ", value));
}

}  // namespace

absl::Status CheckEnum(int value, bool (*is_valid)(int),
                       absl::string_view field) {
  if (is_valid(value)) return absl::OkStatus();
  return InvalidFieldError(field,
                           absl::StrCat(value, " is not one of its values"));
}

BezierAlgorithm ToCore(v1::BezierAlgorithm algorithm) {
  switch (algorithm) {
    case v1::BEZIER_ALGORITHM_DE_CASTELJAU:
      return BezierAlgorithm::kDeCasteljau;
    case v1::BEZIER_ALGORITHM_HORNER:
      return BezierAlgorithm::kHorner;
    case v1::BEZIER_ALGORITHM_LADDER:
      return BezierAlgorithm::kLadder;
    case v1::BEZIER_ALGORITHM_AUTO:
    case v1::BezierAlgorithm_INT_MIN_SENTINEL_DO_NOT_USE_:
    case v1::BezierAlgorithm_INT_MAX_SENTINEL_DO_NOT_USE_:
      break;
  }
  // AUTO; an unknown value was refused by CheckEnum before.
  return BezierAlgorithm::kAuto;
}

Parameterization ToCore(v1::Parameterization parameterization) {
  switch (parameterization) {
    case v1::PARAMETERIZATION_UNIFORM:
      return Parameterization::kUniform;
    case v1::PARAMETERIZATION_CENTRIPETAL:
      return Parameterization::kCentripetal;
    case v1::PARAMETERIZATION_UNIVERSAL:
      return Parameterization::kUniversal;
    case v1::PARAMETERIZATION_UNSPECIFIED:
    case v1::PARAMETERIZATION_CHORD_LENGTH:
    case v1::Parameterization_INT_MIN_SENTINEL_DO_NOT_USE_:
    case v1::Parameterization_INT_MAX_SENTINEL_DO_NOT_USE_:
      break;
  }
  // Chord length, the default; an unknown value was refused before.
  return Parameterization::kChordLength;
}

KnotRule ToCore(v1::KnotRule rule) {
  switch (rule) {
    case v1::KNOT_RULE_UNIFORM:
      return KnotRule::kUniform;
    case v1::KNOT_RULE_AT_PARAMETERS:
      return KnotRule::kAtParameters;
    case v1::KNOT_RULE_UNSPECIFIED:
    case v1::KNOT_RULE_AVERAGING:
    case v1::KnotRule_INT_MIN_SENTINEL_DO_NOT_USE_:
    case v1::KnotRule_INT_MAX_SENTINEL_DO_NOT_USE_:
      break;
  }
  // Averaging, the default; an unknown value was refused before.
  return KnotRule::kAveraging;
}

SplineEnd ToCore(v1::SplineEndCondition end) {
  switch (end) {
    case v1::SPLINE_END_CONDITION_NATURAL:
      return SplineEnd::kNatural;
    case v1::SPLINE_END_CONDITION_CLAMPED:
      return SplineEnd::kClamped;
    case v1::SPLINE_END_CONDITION_PERIODIC:
      return SplineEnd::kPeriodic;
    case v1::SPLINE_END_CONDITION_UNSPECIFIED:
    case v1::SPLINE_END_CONDITION_NOT_A_KNOT:
    case v1::SplineEndCondition_INT_MIN_SENTINEL_DO_NOT_USE_:
    case v1::SplineEndCondition_INT_MAX_SENTINEL_DO_NOT_USE_:
      break;
  }
  // Not-a-knot, the default; an unknown value was refused before.
  return SplineEnd::kNotAKnot;
}

absl::StatusOr<SubdivisionScheme> ToCore(v1::SubdivisionScheme scheme) {
  switch (scheme) {
    case v1::SUBDIVISION_SCHEME_CHAIKIN:
      return SubdivisionScheme::kChaikin;
    case v1::SUBDIVISION_SCHEME_UNIFORM_BSPLINE:
      return SubdivisionScheme::kUniformBSpline;
    case v1::SUBDIVISION_SCHEME_UNSPECIFIED:
    case v1::SubdivisionScheme_INT_MIN_SENTINEL_DO_NOT_USE_:
    case v1::SubdivisionScheme_INT_MAX_SENTINEL_DO_NOT_USE_:
      break;
  }
  // Unspecified, or a value unknown to v1.
  return InvalidFieldError(
      "scheme",
      absl::StrCat("choose CHAIKIN or UNIFORM_BSPLINE, got ", scheme));
}

absl::StatusOr<bool> DirectionIsU(v1::SurfaceDirection direction) {
  if (direction != v1::SURFACE_DIRECTION_U &&
      direction != v1::SURFACE_DIRECTION_V) {
    return InvalidFieldError("direction",
                             absl::StrCat("choose U or V, got ", direction));
  }
  return direction == v1::SURFACE_DIRECTION_U;
}

absl::StatusOr<KnotDirections> RemovalDirections(v1::SurfaceDirection direction,
                                                 bool one_knot) {
  RETURN_IF_ERROR(
      CheckEnum(direction, v1::SurfaceDirection_IsValid, "direction"));
  switch (direction) {
    case v1::SURFACE_DIRECTION_U:
      return KnotDirections::kU;
    case v1::SURFACE_DIRECTION_V:
      return KnotDirections::kV;
    case v1::SURFACE_DIRECTION_BOTH:
      if (!one_knot) return KnotDirections::kBoth;
      return InvalidFieldError("direction",
                               "a knot is removed in U or V, not BOTH");
    case v1::SURFACE_DIRECTION_UNSPECIFIED:
    case v1::SurfaceDirection_INT_MIN_SENTINEL_DO_NOT_USE_:
    case v1::SurfaceDirection_INT_MAX_SENTINEL_DO_NOT_USE_:
      break;
  }
  return InvalidFieldError(
      "direction",
      one_knot ? "choose U or V" : "choose U, V or BOTH (simplify both)");
}

absl::StatusOr<double> GivenLimit(bool present, double value,
                                  absl::string_view field,
                                  absl::string_view rule) {
  if (!present) return 0.0;
  if (value == 0.0) return InvalidFieldError(field, rule);
  return value;
}

absl::StatusOr<double> GivenTolerance(double value, absl::string_view field) {
  if (std::isfinite(value) && value > 0.0) return value;
  return InvalidFieldError(
      field, absl::StrCat("must be positive and finite, got ", value));
}

absl::StatusOr<double> Tolerance(bool has_value, double value, double fallback,
                                 absl::string_view field) {
  if (!has_value) return fallback;
  return GivenTolerance(value, field);
}

absl::StatusOr<ClosestPointOptions> ToCore(
    const v1::ClosestPointOptions& options) {
  absl::StatusOr<double> tolerance =
      Tolerance(options.has_tolerance(), options.tolerance(),
                kDefaultQueryTolerance, "options.tolerance");
  if (!tolerance.ok()) return tolerance.status();
  absl::StatusOr<double> separation = Separation(
      options.has_separation(), options.separation(), "options.separation");
  if (!separation.ok()) return separation.status();
  const uint32_t max_minima =
      options.max_minima() == 0 ? kDefaultMaxMinima : options.max_minima();
  if (max_minima > static_cast<uint32_t>(kMaxMinimaPerQuery)) {
    return InvalidFieldError(
        "options.max_minima",
        absl::StrCat("must be at most ", kMaxMinimaPerQuery, ", got ",
                     max_minima));
  }
  return ClosestPointOptions{.tolerance = *tolerance,
                             .separation = *separation,
                             .max_minima = static_cast<int>(max_minima)};
}

absl::StatusOr<IntersectionOptions> ToCore(
    const v1::IntersectionOptions& options, uint64_t values_per_result,
    const ServiceLimits& limits) {
  absl::StatusOr<double> tolerance =
      Tolerance(options.has_tolerance(), options.tolerance(),
                kDefaultQueryTolerance, "options.tolerance");
  if (!tolerance.ok()) return tolerance.status();
  absl::StatusOr<double> separation = Separation(
      options.has_separation(), options.separation(), "options.separation");
  if (!separation.ok()) return separation.status();
  const uint64_t max_results = options.max_results() == 0
                                   ? kDefaultMaxResults
                                   : uint64_t{options.max_results()};
  RETURN_IF_ERROR(
      UnaryAnswerCheck(SaturatingProduct(max_results, values_per_result),
                       limits, "options.max_results"));
  return IntersectionOptions{.tolerance = *tolerance,
                             .separation = *separation,
                             .max_results = static_cast<size_t>(max_results),
                             .max_work = limits.max_query_work};
}

}  // namespace freeform::server
