#include "parse_errors.h"

#include <google/protobuf/descriptor.h>
#include <grpcpp/server_context.h>

#include <memory>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_replace.h"
#include "grpc_handoff.h"
#include "spdlog/spdlog.h"

namespace freeform::server {
namespace {

// "/freeform.v1.CurveService/Evaluate" -> "CurveService.Evaluate", the
// access log's name.
std::string ShortMethodName(const std::string& method) {
  const size_t slash = method.rfind('/');
  if (slash == std::string::npos || slash == 0) return method;
  const size_t dot = method.rfind('.', slash);
  const size_t start = dot == std::string::npos ? 1 : dot + 1;
  return absl::StrCat(method.substr(start, slash - start), ".",
                      method.substr(slash + 1));
}

class ParseErrorInterceptor : public grpc::experimental::Interceptor {
 public:
  // `served` tells whether the server serves the call's service.
  ParseErrorInterceptor(grpc::experimental::ServerRpcInfo* info, bool served)
      : info_(info), served_(served) {
    HandOffToGrpc(this);  // to the first Intercept
  }

  // gRPC calls Intercept for each batch of the call, on any of its threads,
  // one batch after another.
  void Intercept(
      grpc::experimental::InterceptorBatchMethods* methods) override {
    TakeBackFromGrpc(this);
    if (methods->QueryInterceptionHookPoint(
            grpc::experimental::InterceptionHookPoints::PRE_SEND_STATUS)) {
      const grpc::Status status = methods->GetSendStatus();
      if (served_ && IsParseFailure(status, info_->method())) {
        Rewrite(methods);
      }
    }
    HandOffToGrpc(this);  // to the next Intercept
    methods->Proceed();
  }

 private:
  void Rewrite(grpc::experimental::InterceptorBatchMethods* methods) {
    const std::string method = info_->method();
    const std::string type = RequestTypeOf(method);
    const std::string message = absl::StrCat(
        "request is not a valid ", type.empty() ? std::string("request") : type,
        ": its bytes do not parse as that message");
    methods->ModifySendStatus(
        grpc::Status(grpc::StatusCode::INVALID_ARGUMENT, message));
    spdlog::info("rpc method={} peer={} status=INVALID_ARGUMENT error=\"{}\"",
                 ShortMethodName(method), info_->server_context()->peer(),
                 message);
  }

  grpc::experimental::ServerRpcInfo* const info_;
  const bool served_;
};

}  // namespace

ParseErrorInterceptorFactory::ParseErrorInterceptorFactory(
    const std::vector<std::string>& services)
    : services_(services.begin(), services.end()) {}

grpc::experimental::Interceptor*
ParseErrorInterceptorFactory::CreateServerInterceptor(
    grpc::experimental::ServerRpcInfo* info) {
  TakeBackFromGrpc(this);  // FreeformServer::Start handed the server over
  return new ParseErrorInterceptor(
      info, services_.contains(ServiceOf(info->method())));
}

std::string ServiceOf(const std::string& method) {
  const size_t slash = method.rfind('/');
  if (method.size() < 2 || method.front() != '/' || slash == 0) return "";
  return method.substr(1, slash - 1);
}

std::string RequestTypeOf(const std::string& method) {
  // "/package.Service/Method" -> "package.Service.Method".
  if (method.size() < 2 || method.front() != '/') return "";
  const std::string name = absl::StrReplaceAll(method.substr(1), {{"/", "."}});
  const google::protobuf::MethodDescriptor* descriptor =
      google::protobuf::DescriptorPool::generated_pool()->FindMethodByName(
          name);
  if (descriptor == nullptr) return "";
  return descriptor->input_type()->full_name();
}

bool IsParseFailure(const grpc::Status& status, const std::string& method) {
  const std::string& message = status.error_message();
  switch (status.error_code()) {
    case grpc::StatusCode::INTERNAL:  // the synchronous API
      return message.empty() || message == "No payload";
    case grpc::StatusCode::UNIMPLEMENTED:  // the callback API, known methods
      return message.empty() && !RequestTypeOf(method).empty();
    default:
      return false;
  }
}

}  // namespace freeform::server
