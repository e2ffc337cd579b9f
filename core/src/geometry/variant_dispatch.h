// The forwarding the core's geometry variants share (Curve, CurveBasis and
// Surface): every kind has domain() and Evaluate(...), so the free
// functions of curve.h, basis.h and surface.h visit with one generic call;
// and Overloaded (overloaded.h), for visits that handle each kind on its
// own. Internal to the core.
#ifndef FREEFORM_CORE_SRC_GEOMETRY_VARIANT_DISPATCH_H_
#define FREEFORM_CORE_SRC_GEOMETRY_VARIANT_DISPATCH_H_

#include <variant>

#include "absl/status/status.h"
#include "freeform/core/overloaded.h"

namespace freeform::internal {

// DomainOfKind returns the domain of whichever kind `geometry` holds.
template <typename Variant>
auto DomainOfKind(const Variant& geometry) {
  return std::visit([](const auto& kind) { return kind.domain(); }, geometry);
}

// EvaluateKind calls Evaluate(arguments...) on whichever kind `geometry`
// holds.
template <typename Variant, typename... Arguments>
absl::Status EvaluateKind(const Variant& geometry,
                          const Arguments&... arguments) {
  return std::visit(
      [&](const auto& kind) { return kind.Evaluate(arguments...); }, geometry);
}

// The core's visits name it internal::Overloaded (freeform/core/overloaded.h).
using ::freeform::Overloaded;

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_GEOMETRY_VARIANT_DISPATCH_H_
