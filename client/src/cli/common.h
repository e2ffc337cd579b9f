// What the freeform CLI's subcommands share: the connection flags, reading
// proto3 JSON requests and CSV points, printing answers and errors, and
// RunCall, which sends any unary RPC with a request read from JSON.
//
// Exit statuses: 0 on success, 1 when the server answers with an error
// (printed with its field violations), 2 for unusable input.
#ifndef FREEFORM_CLIENT_CLI_COMMON_H_
#define FREEFORM_CLIENT_CLI_COMMON_H_

#include <google/protobuf/message.h>

#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <type_traits>
#include <vector>

#include "CLI/CLI.hpp"
#include "absl/functional/function_ref.h"
#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "freeform/client.h"
#include "svg_drawing.h"

namespace freeform::cli {

struct CommonFlags {
  std::string address = "localhost:50051";
  double timeout_seconds = 30;
  bool use_tls = false;
  std::string root_ca;
};

// AddCommonFlags adds --address, --timeout, --tls and --tls_root_ca.
void AddCommonFlags(CLI::App& command, CommonFlags& flags);

// ReadInput returns the contents of `file`, or of stdin for "" and "-".
absl::StatusOr<std::string> ReadInput(const std::string& file);

// ParseJsonInto parses proto3 JSON (unknown fields are errors).
absl::Status ParseJsonInto(const std::string& json,
                           google::protobuf::Message& message);

// ParseJson reads a `Message` as proto3 JSON from `file` (see ReadInput).
template <typename Message>
absl::StatusOr<Message> ParseJson(const std::string& file) {
  absl::StatusOr<std::string> json = ReadInput(file);
  if (!json.ok()) return json.status();
  Message message;
  if (absl::Status status = ParseJsonInto(*json, message); !status.ok()) {
    return status;
  }
  return message;
}

// ToJson prints a message as one line of proto3 JSON with the .proto field
// names.
std::string ToJson(const google::protobuf::Message& message);

// PrintJson writes ToJson(message) to stdout and returns 0.
int PrintJson(const google::protobuf::Message& message);

// ReportError prints a server's error with its field violations and
// returns 1.
int ReportError(const absl::Status& status);

// InputError prints why the input cannot be used and returns 2.
int InputError(const absl::Status& status);

// Connect makes a client for `flags`, or prints why not and returns null.
std::unique_ptr<Client> Connect(const CommonFlags& flags);

// ParseCsvLine parses comma-separated numbers; nullopt when a field is not
// a number.
std::optional<std::vector<double>> ParseCsvLine(absl::string_view line);

// ReadCsvRows reads points from CSV: one point per line, coordinates
// separated by commas; blank lines, '#' comments and a non-numeric header
// are skipped; every row has the same number of values.
absl::StatusOr<std::vector<std::vector<double>>> ReadCsvRows(
    const std::string& file);

// WriteOutput writes with `write` to `path` ('-': stdout), tells on stderr
// what it wrote (the path, then `summary`) and returns the exit status.
int WriteOutput(const std::string& path,
                absl::FunctionRef<void(std::ostream&)> write,
                const std::string& summary = "");

// WriteSvg writes the drawing to `path` ('-': stdout) and returns the exit
// status.
int WriteSvg(const SvgDrawing& drawing, const std::string& path);

// FormatNumber prints a double with the fewest digits that read back to
// it.
std::string FormatNumber(double value);

// A unary RPC of a generated stub, e.g. &v1::CurveService::Stub::ArcLength.
template <typename Stub, typename Request, typename Response>
using RpcMethod = grpc::Status (Stub::*)(grpc::ClientContext*, const Request&,
                                         Response*);

// Changes a request read from JSON before it is sent (from flags); an
// error is the user's (exit status 2).
template <typename Request>
using Amend = std::type_identity_t<absl::FunctionRef<absl::Status(Request&)>>;

// Prints an answer and returns the exit status; the client is there for
// follow-up calls.
template <typename Request, typename Response>
using Output = std::type_identity_t<
    absl::FunctionRef<int(Client&, const Request&, const Response&)>>;

// RunCall reads the request from `file` as proto3 JSON, lets `amend` change
// it, calls `method` and hands the answer to `output`. Returns the exit
// status.
template <typename Stub, typename Request, typename Response>
int RunCall(const CommonFlags& flags, const std::string& file,
            RpcMethod<Stub, Request, Response> method, Amend<Request> amend,
            Output<Request, Response> output) {
  absl::StatusOr<Request> request = ParseJson<Request>(file);
  if (!request.ok()) return InputError(request.status());
  if (absl::Status amended = amend(*request); !amended.ok()) {
    return InputError(amended);
  }
  std::unique_ptr<Client> client = Connect(flags);
  if (client == nullptr) return 2;
  absl::StatusOr<Response> response = client->Unary(method, *request);
  if (!response.ok()) return ReportError(response.status());
  return output(*client, *request, *response);
}

// RunJsonCall is RunCall that sends the request as read and prints the
// answer as JSON.
template <typename Stub, typename Request, typename Response>
int RunJsonCall(const CommonFlags& flags, const std::string& file,
                RpcMethod<Stub, Request, Response> method) {
  return RunCall(
      flags, file, method, [](Request&) { return absl::OkStatus(); },
      [](Client&, const Request&, const Response& response) {
        return PrintJson(response);
      });
}

}  // namespace freeform::cli

#endif  // FREEFORM_CLIENT_CLI_COMMON_H_
