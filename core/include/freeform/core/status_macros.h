// RETURN_IF_ERROR and ASSIGN_OR_RETURN: the two status macros of Abseil's
// internal code and of Draco, which Debian's Abseil does not ship.
//
//   RETURN_IF_ERROR(ValidatePoints(points, "points"));
//   ASSIGN_OR_RETURN(const BezierDecomposition pieces, DecomposeCurve(curve));
//
// RETURN_IF_ERROR(expr) returns the absl::Status `expr` from the enclosing
// function when it is not OK. ASSIGN_OR_RETURN(lhs, rexpr) evaluates the
// absl::StatusOr `rexpr`, returns its status when it is not OK, and else
// moves its value into `lhs`, a declaration ("const auto x", "Net net") or
// an lvalue; `lhs` must not hold an unparenthesized comma. Both work in
// functions that return absl::Status or any absl::StatusOr.
#ifndef FREEFORM_CORE_STATUS_MACROS_H_
#define FREEFORM_CORE_STATUS_MACROS_H_

#include <utility>

#include "absl/status/status.h"
#include "absl/status/statusor.h"

#define RETURN_IF_ERROR(expr)                          \
  do {                                                 \
    if (::absl::Status freeform_macro_status = (expr); \
        !freeform_macro_status.ok()) {                 \
      return freeform_macro_status;                    \
    }                                                  \
  } while (false)

#define FREEFORM_STATUS_MACROS_CONCAT_INNER(a, b) a##b
#define FREEFORM_STATUS_MACROS_CONCAT(a, b) \
  FREEFORM_STATUS_MACROS_CONCAT_INNER(a, b)

#define ASSIGN_OR_RETURN(lhs, rexpr)                                          \
  FREEFORM_ASSIGN_OR_RETURN_IMPL(                                             \
      FREEFORM_STATUS_MACROS_CONCAT(freeform_macro_statusor_, __LINE__), lhs, \
      rexpr)

#define FREEFORM_ASSIGN_OR_RETURN_IMPL(statusor, lhs, rexpr) \
  auto statusor = (rexpr);                                   \
  if (!statusor.ok()) return std::move(statusor).status();   \
  lhs = *std::move(statusor)

#endif  // FREEFORM_CORE_STATUS_MACROS_H_
