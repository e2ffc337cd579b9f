#include "gateway_call.h"

#include <grpcpp/client_context.h>
#include <grpcpp/completion_queue.h>
#include <grpcpp/support/byte_buffer.h>

#include <chrono>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/synchronization/notification.h"
#include "freeform_services.h"
#include "transport.h"

namespace freeform::server {
namespace {

// The services the gateway serves, by full name.
bool IsGatewayService(absl::string_view service) {
  for (const char* name : FreeformServiceNames()) {
    if (service == name) return true;
  }
  return false;
}

const google::protobuf::Message* PrototypeOf(
    const google::protobuf::Descriptor* type) {
  return google::protobuf::MessageFactory::generated_factory()->GetPrototype(
      type);
}

void Configure(const CallSettings& settings, grpc::ClientContext& context) {
  if (settings.timeout.has_value()) {
    context.set_deadline(std::chrono::system_clock::now() +
                         absl::ToChronoMilliseconds(*settings.timeout));
  }
  context.AddMetadata(kGatewayMetadataKey, GatewayToken());
  context.AddMetadata(kHttpClientMetadataKey, settings.client);
}

grpc::ByteBuffer BufferOf(const std::string& bytes) {
  grpc::Slice slice(bytes);
  return grpc::ByteBuffer(&slice, 1);
}

// BytesOf returns the contents of `buffer` in one string.
std::string BytesOf(const grpc::ByteBuffer& buffer) {
  std::vector<grpc::Slice> slices;
  std::string bytes;
  if (!buffer.Dump(&slices).ok()) return bytes;
  bytes.reserve(buffer.Length());
  for (const grpc::Slice& slice : slices) {
    bytes.append(reinterpret_cast<const char*>(slice.begin()), slice.size());
  }
  return bytes;
}

// A completion queue used by one thread for one call, step by step.
class BlockingQueue {
 public:
  ~BlockingQueue() {
    queue_.Shutdown();
    void* tag = nullptr;
    bool ok = false;
    while (queue_.Next(&tag, &ok)) {
    }
  }
  grpc::CompletionQueue* get() { return &queue_; }
  // Wait returns whether the step started with tag `this` succeeded.
  bool Wait() {
    void* tag = nullptr;
    bool ok = false;
    return queue_.Next(&tag, &ok) && ok;
  }
  void* tag() { return this; }

 private:
  grpc::CompletionQueue queue_;
};

}  // namespace

absl::StatusOr<GatewayMethod> ResolveMethod(absl::string_view path) {
  const size_t slash = path.rfind('/');
  if (path.size() < 2 || path.front() != '/' || slash == 0 ||
      !IsGatewayService(path.substr(1, slash - 1))) {
    return absl::NotFoundError(
        absl::StrCat("no freeform.v1 method at ", path,
                     "; the paths are /freeform.v1.CurveService/METHOD and "
                     "/freeform.v1.SurfaceService/METHOD"));
  }
  const google::protobuf::MethodDescriptor* descriptor =
      google::protobuf::DescriptorPool::generated_pool()->FindMethodByName(
          absl::StrCat(path.substr(1, slash - 1), ".", path.substr(slash + 1)));
  if (descriptor == nullptr || descriptor->client_streaming()) {
    return absl::NotFoundError(
        absl::StrCat("freeform.v1 has no method at ", path));
  }
  return GatewayMethod{
      .path = std::string(path),
      .name =
          absl::StrCat(descriptor->service()->name(), ".", descriptor->name()),
      .request_prototype = PrototypeOf(descriptor->input_type()),
      .response_prototype = PrototypeOf(descriptor->output_type()),
      .server_streaming = descriptor->server_streaming()};
}

InProcessCaller::InProcessCaller(std::shared_ptr<grpc::Channel> channel)
    : stub_(std::move(channel)) {}

grpc::Status InProcessCaller::Unary(const GatewayMethod& method,
                                    const CallSettings& settings,
                                    const std::string& request,
                                    std::string& response) {
  grpc::ClientContext context;
  Configure(settings, context);
  const grpc::ByteBuffer request_buffer = BufferOf(request);
  grpc::ByteBuffer response_buffer;
  grpc::Status status;
  absl::Notification done;
  stub_.UnaryCall(&context, method.path, grpc::StubOptions(), &request_buffer,
                  &response_buffer, [&](grpc::Status result) {
                    status = std::move(result);
                    done.Notify();
                  });
  done.WaitForNotification();
  if (status.ok()) response = BytesOf(response_buffer);
  return status;
}

grpc::Status InProcessCaller::Stream(
    const GatewayMethod& method, const CallSettings& settings,
    const std::string& request,
    absl::FunctionRef<bool(std::string)> on_message) {
  grpc::ClientContext context;
  Configure(settings, context);
  BlockingQueue queue;
  std::unique_ptr<grpc::GenericClientAsyncReaderWriter> call =
      stub_.PrepareCall(&context, method.path, queue.get());
  grpc::Status status;
  if (call == nullptr) {
    return grpc::Status(grpc::StatusCode::INTERNAL,
                        "the gateway could not start the call");
  }
  call->StartCall(queue.tag());
  bool open = queue.Wait();
  if (open) {
    call->Write(BufferOf(request), queue.tag());
    open = queue.Wait();
  }
  if (open) {
    call->WritesDone(queue.tag());
    open = queue.Wait();
  }
  grpc::ByteBuffer message;
  while (open) {
    call->Read(&message, queue.tag());
    if (!queue.Wait()) break;
    if (!on_message(BytesOf(message))) {
      context.TryCancel();
      open = false;
    }
  }
  call->Finish(&status, queue.tag());
  queue.Wait();
  return status;
}

}  // namespace freeform::server
