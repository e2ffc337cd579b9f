// The Connect protocol's wire pieces (connectrpc.com/docs/protocol), for
// the HTTP gateway (http_gateway.h): error codes and their HTTP statuses,
// the JSON Error object with its details, the streaming envelope and its
// EndStreamResponse, and the Connect-Timeout-Ms header.
//
// Errors carry google.rpc details as the spec's {"type", "value", "debug"}
// objects: the type's full name, the detail's binary proto in unpadded
// base64, and its JSON for people reading the wire. Thread-safe.
#ifndef FREEFORM_SERVER_CONNECT_PROTOCOL_H_
#define FREEFORM_SERVER_CONNECT_PROTOCOL_H_

#include <grpcpp/support/status.h>

#include <cstdint>
#include <string>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/time/time.h"

namespace freeform::server::connect {

// Flags of an enveloped message: its payload is compressed; it is the
// stream's EndStreamResponse.
inline constexpr uint8_t kCompressedFlag = 0x01;
inline constexpr uint8_t kEndStreamFlag = 0x02;
// Flags byte plus the big-endian 32-bit length.
inline constexpr size_t kEnvelopeHeaderBytes = 5;

// HttpStatusOf returns the HTTP status of an error with `code`, as the
// spec's table of error codes maps it (200 for OK).
int HttpStatusOf(grpc::StatusCode code);

// CodeName returns the Connect name of `code` ("invalid_argument").
absl::string_view CodeName(grpc::StatusCode code);

// ErrorJson returns the Error object of the failed `status`: its code, its
// message, and the details of its google.rpc.Status (error_details).
std::string ErrorJson(const grpc::Status& status);

// EndStreamJson returns the EndStreamResponse of a stream that ended with
// `status`: {} when OK, {"error": ...} otherwise.
std::string EndStreamJson(const grpc::Status& status);

// AppendEnvelope appends `payload` with its 5-byte prefix to `out`.
void AppendEnvelope(uint8_t flags, absl::string_view payload, std::string& out);

// SingleEnvelopedMessage returns the message of a request body that is
// exactly one uncompressed enveloped message; INVALID_ARGUMENT otherwise.
absl::StatusOr<absl::string_view> SingleEnvelopedMessage(
    absl::string_view body);

// ParseTimeout reads a Connect-Timeout-Ms value: a positive integer of at
// most 10 ASCII digits; INVALID_ARGUMENT otherwise.
absl::StatusOr<absl::Duration> ParseTimeout(absl::string_view milliseconds);

}  // namespace freeform::server::connect

#endif  // FREEFORM_SERVER_CONNECT_PROTOCOL_H_
