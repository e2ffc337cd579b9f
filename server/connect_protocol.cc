#include "connect_protocol.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/message.h>
#include <google/protobuf/util/json_util.h>

#include <algorithm>
#include <array>
#include <memory>

#include "absl/strings/ascii.h"
#include "absl/strings/escaping.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/strip.h"
#include "google/rpc/status.pb.h"
#include "proto_json.h"

namespace freeform::server::connect {
namespace {

struct CodeInfo {
  absl::string_view name;
  int http_status;
};

// The spec's table, indexed by the gRPC code (OK to UNAUTHENTICATED).
constexpr std::array<CodeInfo, 17> kCodes = {{
    {"ok", 200},
    {"canceled", 499},
    {"unknown", 500},
    {"invalid_argument", 400},
    {"deadline_exceeded", 504},
    {"not_found", 404},
    {"already_exists", 409},
    {"permission_denied", 403},
    {"resource_exhausted", 429},
    {"failed_precondition", 400},
    {"aborted", 409},
    {"out_of_range", 400},
    {"unimplemented", 501},
    {"internal", 500},
    {"unavailable", 503},
    {"data_loss", 500},
    {"unauthenticated", 401},
}};

const CodeInfo& InfoOf(grpc::StatusCode code) {
  const auto index = static_cast<size_t>(code);
  return index < kCodes.size() ? kCodes[index]
                               : kCodes[grpc::StatusCode::UNKNOWN];
}

// TypeNameOf returns the full message name of an Any's type URL
// ("type.googleapis.com/google.rpc.BadRequest" gives "google.rpc.BadRequest").
absl::string_view TypeNameOf(absl::string_view type_url) {
  const size_t slash = type_url.rfind('/');
  return slash == absl::string_view::npos ? type_url
                                          : type_url.substr(slash + 1);
}

// DebugJson returns the JSON of a detail of `type_name` whose binary proto
// is `value`, or "" when the type is not linked in or the bytes do not
// parse.
std::string DebugJson(absl::string_view type_name, const std::string& value) {
  const google::protobuf::Descriptor* type =
      google::protobuf::DescriptorPool::generated_pool()->FindMessageTypeByName(
          std::string(type_name));
  if (type == nullptr) return "";
  const google::protobuf::Message* prototype =
      google::protobuf::MessageFactory::generated_factory()->GetPrototype(type);
  if (prototype == nullptr) return "";
  std::unique_ptr<google::protobuf::Message> detail(prototype->New());
  if (!detail->ParseFromString(value)) return "";
  absl::StatusOr<std::string> json = MessageJson(*detail);
  return json.ok() ? *std::move(json) : "";
}

// AppendDetails appends `,"details":[...]` for the details of the
// serialized google.rpc.Status `details`, when it has any.
void AppendDetails(const std::string& details, std::string& out) {
  google::rpc::Status rpc_status;
  if (details.empty() || !rpc_status.ParseFromString(details) ||
      rpc_status.details_size() == 0) {
    return;
  }
  out += ",\"details\":[";
  for (int i = 0; i < rpc_status.details_size(); ++i) {
    const google::protobuf::Any& any = rpc_status.details(i);
    const absl::string_view type_name = TypeNameOf(any.type_url());
    if (i > 0) out += ',';
    out += "{\"type\":";
    AppendJsonString(type_name, out);
    std::string value = absl::Base64Escape(any.value());
    while (!value.empty() && value.back() == '=') value.pop_back();
    out += ",\"value\":";
    AppendJsonString(value, out);
    if (const std::string debug = DebugJson(type_name, any.value());
        !debug.empty()) {
      out += ",\"debug\":";
      out += debug;
    }
    out += '}';
  }
  out += ']';
}

}  // namespace

int HttpStatusOf(grpc::StatusCode code) { return InfoOf(code).http_status; }

absl::string_view CodeName(grpc::StatusCode code) { return InfoOf(code).name; }

std::string ErrorJson(const grpc::Status& status) {
  std::string out = "{\"code\":";
  AppendJsonString(CodeName(status.error_code()), out);
  if (!status.error_message().empty()) {
    out += ",\"message\":";
    AppendJsonString(status.error_message(), out);
  }
  AppendDetails(status.error_details(), out);
  out += '}';
  return out;
}

std::string EndStreamJson(const grpc::Status& status) {
  if (status.ok()) return "{}";
  return absl::StrCat("{\"error\":", ErrorJson(status), "}");
}

void AppendEnvelope(uint8_t flags, absl::string_view payload,
                    std::string& out) {
  const auto length = static_cast<uint32_t>(payload.size());
  out += static_cast<char>(flags);
  for (int shift = 24; shift >= 0; shift -= 8) {
    out += static_cast<char>((length >> shift) & 0xff);
  }
  out.append(payload.data(), payload.size());
}

absl::StatusOr<absl::string_view> SingleEnvelopedMessage(
    absl::string_view body) {
  if (body.size() < kEnvelopeHeaderBytes) {
    return absl::InvalidArgumentError(absl::StrCat(
        "the request body of ", body.size(),
        " bytes is not an enveloped message (5-byte prefix, then the "
        "message)"));
  }
  const auto flags = static_cast<uint8_t>(body[0]);
  if (flags != 0) {
    return absl::InvalidArgumentError(absl::StrCat(
        "the request's envelope has flags ", flags,
        "; a request message takes 0 (no compression, not end of stream)"));
  }
  uint32_t length = 0;
  for (size_t i = 1; i < kEnvelopeHeaderBytes; ++i) {
    length = (length << 8) | static_cast<uint8_t>(body[i]);
  }
  const absl::string_view message = body.substr(kEnvelopeHeaderBytes);
  if (message.size() != length) {
    return absl::InvalidArgumentError(absl::StrCat(
        "the request's envelope announces ", length, " bytes but ",
        message.size(),
        " follow; a server-streaming call takes exactly one message"));
  }
  return message;
}

absl::StatusOr<absl::Duration> ParseTimeout(absl::string_view milliseconds) {
  constexpr size_t kMaxDigits = 10;
  int64_t value = 0;
  if (milliseconds.empty() || milliseconds.size() > kMaxDigits ||
      !std::all_of(milliseconds.begin(), milliseconds.end(),
                   absl::ascii_isdigit) ||
      !absl::SimpleAtoi(milliseconds, &value) || value <= 0) {
    return absl::InvalidArgumentError(
        absl::StrCat("Connect-Timeout-Ms \"", absl::CHexEscape(milliseconds),
                     "\" is not a positive integer of at most 10 digits"));
  }
  return absl::Milliseconds(value);
}

}  // namespace freeform::server::connect
