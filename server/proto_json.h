// ProtoJson: proto3's canonical JSON of freeformd's messages, written fast
// enough for answers of millions of numbers.
//
// google::protobuf::util::MessageToJsonString takes about 0.9 us per double
// (262 ms for the 300,000 coordinates of a 10^5-point 3D evaluation, where
// the gRPC answer costs a few ms): the HTTP gateway's answers would be
// dominated by it. AppendMessageJson writes the same JSON by reflection:
// lowerCamelCase json names, fields with their default value left out,
// 64-bit integers as strings, enums by name, bytes as base64, doubles as the
// shortest text that reads back to the same double (std::to_chars), NaN and
// the infinities as "NaN", "Infinity", "-Infinity". A message of the
// well-known types (google.protobuf.*) or with a map field is handed to
// protobuf's own writer, whose special forms it keeps; freeform.v1 has
// neither. Requests are parsed with protobuf's own JsonStringToMessage.
// Thread-safe.
#ifndef FREEFORM_SERVER_PROTO_JSON_H_
#define FREEFORM_SERVER_PROTO_JSON_H_

#include <google/protobuf/message.h>

#include <string>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace freeform::server {

// AppendMessageJson appends the JSON object of `message` to `out`.
absl::Status AppendMessageJson(const google::protobuf::Message& message,
                               std::string& out);

// MessageJson returns the JSON object of `message`.
absl::StatusOr<std::string> MessageJson(
    const google::protobuf::Message& message);

// AppendJsonString appends `text` (UTF-8) as a quoted JSON string.
void AppendJsonString(absl::string_view text, std::string& out);

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_PROTO_JSON_H_
