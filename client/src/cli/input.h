// Reading the freeform CLI's input: a request as proto3 JSON from a file or
// stdin (with the line and column of malformed JSON), and points from CSV.
#ifndef FREEFORM_CLIENT_CLI_INPUT_H_
#define FREEFORM_CLIENT_CLI_INPUT_H_

#include <google/protobuf/message.h>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace freeform::cli {

// The most bytes of input read: four times the server's default message
// limit (64 MiB), room for any request it would accept in JSON or CSV
// (about 3 bytes of text per byte of message), so that `--file /dev/zero`
// or an endless pipe ends with an error instead of filling the memory.
inline constexpr size_t kMaxInputBytes = size_t{256} << 20;

// ReadInput returns the contents of `file`, or of stdin for "" and "-"
// (telling on stderr that it reads `what` there when stdin is a terminal).
// A file that cannot be read, or holds more than kMaxInputBytes, is an
// error naming the reason.
absl::StatusOr<std::string> ReadInput(const std::string& file,
                                      absl::string_view what = "the request");

// LineAndColumn returns "LINE:COLUMN" (both from 1) of byte `offset` of
// `text`.
std::string LineAndColumn(absl::string_view text, size_t offset);

// ParseJsonInto parses proto3 JSON into `message` (both the lowerCamelCase
// and the .proto field names; unknown fields are errors). Malformed JSON is
// an error naming `source`, the line and the column.
absl::Status ParseJsonInto(const std::string& json, absl::string_view source,
                           google::protobuf::Message& message);

// ParseJson reads a `Message` as proto3 JSON from `file` (see ReadInput).
template <typename Message>
absl::StatusOr<Message> ParseJson(const std::string& file) {
  absl::StatusOr<std::string> json = ReadInput(file);
  if (!json.ok()) return json.status();
  Message message;
  const std::string source = file.empty() || file == "-" ? "stdin" : file;
  if (absl::Status status = ParseJsonInto(*json, source, message);
      !status.ok()) {
    return status;
  }
  return message;
}

// ParseCsvLine parses comma-separated numbers; nullopt when a field is not
// a number.
std::optional<std::vector<double>> ParseCsvLine(absl::string_view line);

// ReadCsvRows reads points from CSV: one point per line, coordinates
// separated by commas; blank lines, '#' comments and a non-numeric header
// are skipped; every row has the same number of values.
absl::StatusOr<std::vector<std::vector<double>>> ReadCsvRows(
    const std::string& file);

}  // namespace freeform::cli

#endif  // FREEFORM_CLIENT_CLI_INPUT_H_
