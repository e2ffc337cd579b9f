// Visiting the prepared geometry (the Curve, CurveBasis and Surface
// variants of the core): every RPC std::visits the variant with one handler
// per kind, and names the kinds it does not take in a Refuse. Adding a kind
// to a variant is then a compile error in every RPC until each one decides
// what to do with it; no RPC has a default branch.
#ifndef FREEFORM_SERVER_VISIT_H_
#define FREEFORM_SERVER_VISIT_H_

#include <concepts>
#include <string>
#include <utility>

#include "absl/status/status.h"
#include "absl/strings/string_view.h"
#include "freeform/core/overloaded.h"  // Overloaded{handler...}
#include "freeform/core/status.h"

namespace freeform::server {

// Refuse<Kind...>{field, reason}: the handler of the kinds an RPC does not
// take. Each answers INVALID_ARGUMENT naming `field`. Visit with
// std::visit<Result> so its status converts to the RPC's result type.
template <typename... Kinds>
struct Refuse {
  std::string field;
  std::string reason;

  template <typename Kind>
  requires(std::same_as<Kind, Kinds> || ...) absl::Status operator()(
      const Kind&) const {
    return InvalidFieldError(field, reason);
  }
};

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_VISIT_H_
