// ParseErrorInterceptorFactory: answers a request whose bytes do not parse
// as its method's message with INVALID_ARGUMENT naming that message, and
// logs it.
//
// gRPC parses a request before any handler runs; when parsing fails it ends
// the call itself with an empty INTERNAL or UNIMPLEMENTED status, and no
// handler sees it. This server interceptor rewrites exactly that status:
// "request is not a valid freeform.v1.EvaluateCurveRequest", with the
// access-log line the handler would have written. A method of a service
// the server does not serve (such as server reflection, turned off) keeps
// gRPC's UNIMPLEMENTED, though the descriptors know it. Thread-safe.
#ifndef FREEFORM_SERVER_PARSE_ERRORS_H_
#define FREEFORM_SERVER_PARSE_ERRORS_H_

#include <grpcpp/support/server_interceptor.h>

#include <string>
#include <vector>

#include "absl/container/flat_hash_set.h"

namespace freeform::server {

class ParseErrorInterceptorFactory
    : public grpc::experimental::ServerInterceptorFactoryInterface {
 public:
  // `services`: the full names of the services the server serves
  // ("freeform.v1.CurveService", "grpc.health.v1.Health").
  explicit ParseErrorInterceptorFactory(
      const std::vector<std::string>& services);

  grpc::experimental::Interceptor* CreateServerInterceptor(
      grpc::experimental::ServerRpcInfo* info) override;

 private:
  const absl::flat_hash_set<std::string> services_;
};

// ServiceOf returns the full name of the service of `method`
// ("/freeform.v1.CurveService/Evaluate" gives "freeform.v1.CurveService"),
// or "" when `method` is not of that form.
std::string ServiceOf(const std::string& method);

// RequestTypeOf returns the full name of the request message of `method`
// ("/freeform.v1.CurveService/Evaluate" gives
// "freeform.v1.EvaluateCurveRequest"), or "" for a method the generated
// descriptors do not know.
std::string RequestTypeOf(const std::string& method);

// IsParseFailure returns true for the status gRPC ends a call to `method`
// with when the request's bytes do not parse: INTERNAL with no message (or
// "No payload") from the synchronous API, UNIMPLEMENTED with no message from
// the callback API (which it also uses for a method no service has, so a
// method the descriptors do not know is never a parse failure).
bool IsParseFailure(const grpc::Status& status, const std::string& method);

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_PARSE_ERRORS_H_
