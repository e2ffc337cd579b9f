// Translation of core errors into gRPC statuses with google.rpc details,
// and the mapping of a core error's field path into the request's.
//
// An INVALID_ARGUMENT that carries a field path (see core/status.h) becomes a
// grpc::Status whose binary details hold a google.rpc.Status with one
// google.rpc.BadRequest field violation: `field` is the path into the
// request, `description` the rule that broke. Other codes map one for one.
// Thread-safe.
#ifndef FREEFORM_SERVER_ERRORS_H_
#define FREEFORM_SERVER_ERRORS_H_

#include <grpcpp/support/status.h>

#include <initializer_list>

#include "absl/status/status.h"
#include "absl/strings/string_view.h"

namespace freeform::server {

// ToGrpcStatus converts `status`, prefixing its field path with
// `field_prefix` (for example "curve.bezier").
grpc::Status ToGrpcStatus(const absl::Status& status,
                          absl::string_view field_prefix = "");

// PrefixFieldPathExcept prefixes the field path of `status` with `prefix`
// (PrefixFieldPath) unless the path is one of `top_fields` or inside one
// ("knot", "points.coordinates[4]"): the core's errors about the request's
// own fields stay at the top, those about the geometry go under its path.
absl::Status PrefixFieldPathExcept(
    const absl::Status& status, absl::string_view prefix,
    std::initializer_list<absl::string_view> top_fields);

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_ERRORS_H_
