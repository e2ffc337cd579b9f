// The freeform CLI's shared flags, connection and error reporting
// (common.h).
#include "common.h"

#include <algorithm>
#include <chrono>
#include <iostream>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"

namespace freeform::cli {
namespace {

constexpr int kStreamWindowBytes = 4 << 20;

}  // namespace

void AddCommonFlags(CLI::App& command, CommonFlags& flags) {
  command
      .add_option("-a,--address", flags.address,
                  "Server address: HOST[:PORT] (port 50051 when left out) or "
                  "any gRPC target")
      ->capture_default_str();
  command
      .add_option("--timeout", flags.timeout_seconds,
                  "Deadline of the call in seconds")
      ->capture_default_str();
  command.add_flag("--tls", flags.use_tls, "Connect with TLS");
  command.add_option("--tls-root-ca", flags.root_ca,
                     "PEM file of the CA that signed the server");
  AddOldSpelling(command, "--tls_root_ca", flags.root_ca);
  command.add_flag("--proto-field-names", flags.proto_field_names,
                   "Print JSON with the .proto field names (snake_case) "
                   "instead of canonical proto3 JSON (lowerCamelCase)");
  command.add_flag("--no-progress", flags.no_progress,
                   "No progress bar on stderr (it shows only on a terminal)");
}

std::string WithDefaultPort(const std::string& address) {
  const std::string port = absl::StrCat(":", kDefaultPort);
  if (address.empty()) return absl::StrCat("localhost", port);
  // A gRPC target with a scheme: dns:///host:port, unix:path, ipv4:a:p, ...
  for (const char* scheme : {"dns:", "unix:", "unix-abstract:", "ipv4:",
                             "ipv6:", "vsock:", "xds:"}) {
    if (absl::StartsWith(address, scheme)) return address;
  }
  if (absl::StrContains(address, "://")) return address;
  if (address.front() == '[') {  // [IPv6] or [IPv6]:port
    return absl::StrContains(address, "]:") ? address
                                            : absl::StrCat(address, port);
  }
  const auto colons = std::count(address.begin(), address.end(), ':');
  if (colons == 0) return absl::StrCat(address, port);
  if (colons == 1) return address;
  return absl::StrCat("[", address, "]", port);  // a bare IPv6 address
}

int ReportError(const absl::Status& status) {
  std::cerr << "error: " << absl::StatusCodeToString(status.code()) << ": "
            << status.message() << "\n";
  for (const FieldViolation& violation : FieldViolationsOf(status)) {
    std::cerr << "  field " << violation.field << ": " << violation.description
              << "\n";
  }
  return absl::IsUnavailable(status) ? kExitUnavailable : kExitServerError;
}

int InputError(const absl::Status& status) {
  std::cerr << "error: " << status.message() << "\n";
  return kExitUsage;
}

std::unique_ptr<Client> Connect(const CommonFlags& flags) {
  ClientOptions options;
  options.target = WithDefaultPort(flags.address);
  options.timeout = std::chrono::milliseconds(
      static_cast<int64_t>(flags.timeout_seconds * 1000));
  options.use_tls = flags.use_tls;
  options.root_ca_file = flags.root_ca;
  // Streams are written out as they arrive: keep what gRPC buffers ahead
  // of the writer small.
  options.stream_window_bytes = kStreamWindowBytes;
  absl::StatusOr<std::unique_ptr<Client>> client = Client::Create(options);
  if (!client.ok()) {
    // Only reading the TLS files can fail here: the user's input.
    InputError(client.status());
    return nullptr;
  }
  return *std::move(client);
}

}  // namespace freeform::cli
