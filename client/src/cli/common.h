// What every freeform CLI subcommand shares: the connection and output
// flags (CommonFlags), connecting, and reporting errors with the CLI's
// exit statuses.
#ifndef FREEFORM_CLIENT_CLI_COMMON_H_
#define FREEFORM_CLIENT_CLI_COMMON_H_

#include <memory>
#include <string>

#include "CLI/CLI.hpp"
#include "absl/status/status.h"
#include "freeform/client.h"

namespace freeform::cli {

// The exit statuses of `freeform` (also in `freeform --help` and the
// README).
inline constexpr int kExitOk = 0;
// The server answered with an error (printed with its field violations).
inline constexpr int kExitServerError = 1;
// Bad flags or unusable input (a file that cannot be read, malformed JSON).
inline constexpr int kExitUsage = 2;
// The server could not be reached (UNAVAILABLE).
inline constexpr int kExitUnavailable = 3;

// The port of an --address without one.
inline constexpr int kDefaultPort = 50051;

struct CommonFlags {
  std::string address = "localhost:50051";
  double timeout_seconds = 30;
  bool use_tls = false;
  std::string root_ca;
  // JSON answers with the .proto field names (snake_case) instead of the
  // canonical lowerCamelCase.
  bool proto_field_names = false;
  // No progress bar on stderr even when it is a terminal.
  bool no_progress = false;
};

// AddCommonFlags adds --address, --timeout, --tls, --tls-root-ca,
// --proto-field-names and --no-progress.
void AddCommonFlags(CLI::App& command, CommonFlags& flags);

// AddOldSpelling lets `command` accept `old_name` (a snake_case spelling of
// an earlier release) for `value`, without listing it in --help.
template <typename T>
void AddOldSpelling(CLI::App& command, const std::string& old_name, T& value) {
  command.add_option(old_name, value)->group("");
}

// WithDefaultPort returns `address` with ":50051" added when it names a
// host without a port ("127.0.0.1", "localhost", "::1", "[::1]"); gRPC
// targets with a scheme ("dns:///...", "unix:...", "ipv4:...") are kept.
std::string WithDefaultPort(const std::string& address);

// ReportError prints a server's error with its field violations and
// returns kExitUnavailable for UNAVAILABLE, kExitServerError otherwise.
int ReportError(const absl::Status& status);

// InputError prints why the input cannot be used and returns kExitUsage.
int InputError(const absl::Status& status);

// Connect makes a client for `flags`, or prints why not and returns null.
std::unique_ptr<Client> Connect(const CommonFlags& flags);

}  // namespace freeform::cli

#endif  // FREEFORM_CLIENT_CLI_COMMON_H_
