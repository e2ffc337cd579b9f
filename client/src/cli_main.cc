// freeform: command-line client of freeformd.
//
//   freeform eval   [--address HOST:PORT] [--file REQUEST.json] [--stream]
//                   [--format json|csv]
//   freeform basis  [--address HOST:PORT] [--file REQUEST.json]
//                   [--format json|csv]
//   freeform health [--address HOST:PORT] [--service NAME]
//
// Requests are the canonical proto3 JSON of the request message (from a file
// or stdin); answers are printed as proto3 JSON or CSV. Exit status: 0 on
// success, 1 when the server answers with an error (printed on stderr with
// its field violations), 2 for unusable input.
#include <google/protobuf/util/json_util.h>

#include <iostream>
#include <iterator>
#include <string>

#include "CLI/CLI.hpp"
#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "freeform/client.h"
#include "freeform/core/file.h"

namespace {

struct CommonFlags {
  std::string address = "localhost:50051";
  double timeout_seconds = 30;
  bool use_tls = false;
  std::string root_ca;
};

absl::StatusOr<std::string> ReadInput(const std::string& file) {
  if (file.empty() || file == "-") {
    return std::string(std::istreambuf_iterator<char>(std::cin), {});
  }
  return freeform::ReadFileToString(file);
}

template <typename Message>
absl::StatusOr<Message> ParseJson(const std::string& file) {
  absl::StatusOr<std::string> json = ReadInput(file);
  if (!json.ok()) return json.status();
  Message message;
  google::protobuf::util::JsonParseOptions options;
  options.ignore_unknown_fields = false;
  const auto status =
      google::protobuf::util::JsonStringToMessage(*json, &message, options);
  if (!status.ok()) {
    return absl::InvalidArgumentError(absl::StrCat(
        "the request is not valid JSON for ",
        Message::descriptor()->full_name(), ": ", status.ToString()));
  }
  return message;
}

std::string ToJson(const google::protobuf::Message& message) {
  google::protobuf::util::JsonPrintOptions options;
  options.preserve_proto_field_names = true;
  std::string json;
  (void)google::protobuf::util::MessageToJsonString(message, &json, options);
  return json + "\n";
}

int ReportError(const absl::Status& status) {
  std::cerr << "error: " << absl::StatusCodeToString(status.code()) << ": "
            << status.message() << "\n";
  for (const freeform::FieldViolation& violation :
       freeform::FieldViolationsOf(status)) {
    std::cerr << "  field " << violation.field << ": " << violation.description
              << "\n";
  }
  return 1;
}

std::unique_ptr<freeform::Client> Connect(const CommonFlags& flags) {
  freeform::ClientOptions options;
  options.target = flags.address;
  options.timeout = std::chrono::milliseconds(
      static_cast<int64_t>(flags.timeout_seconds * 1000));
  options.use_tls = flags.use_tls;
  options.root_ca_file = flags.root_ca;
  absl::StatusOr<std::unique_ptr<freeform::Client>> client =
      freeform::Client::Create(options);
  if (!client.ok()) {
    ReportError(client.status());
    return nullptr;
  }
  return *std::move(client);
}

// One CSV row per parameter: index, then each derivative's coordinates.
void PrintCsv(const freeform::CurveSamples& samples) {
  std::cout << "index";
  for (size_t k = 0; k < samples.derivatives.size(); ++k) {
    for (int j = 0; j < samples.dimension; ++j) {
      std::cout << "," << (k == 0 ? "x" : absl::StrCat("d", k, "x")) << j;
    }
  }
  std::cout << "\n";
  std::cout.precision(17);
  for (size_t r = 0; r < samples.count; ++r) {
    std::cout << r;
    for (size_t k = 0; k < samples.derivatives.size(); ++k) {
      for (double value : samples.Point(k, r)) std::cout << "," << value;
    }
    std::cout << "\n";
  }
}

// Rebuilds one response message from joined samples, for JSON output.
freeform::v1::EvaluateCurveResponse ToResponse(
    const freeform::CurveSamples& samples) {
  freeform::v1::EvaluateCurveResponse response;
  response.set_dimension(static_cast<uint32_t>(samples.dimension));
  response.set_count(static_cast<uint32_t>(samples.count));
  for (const std::vector<double>& values : samples.derivatives) {
    freeform::v1::Points* points = response.add_derivatives();
    points->set_dimension(static_cast<uint32_t>(samples.dimension));
    points->mutable_coordinates()->Add(values.begin(), values.end());
  }
  return response;
}

int RunEval(const CommonFlags& flags, const std::string& file, bool stream,
            const std::string& format) {
  absl::StatusOr<freeform::v1::EvaluateCurveRequest> request =
      ParseJson<freeform::v1::EvaluateCurveRequest>(file);
  if (!request.ok()) {
    std::cerr << "error: " << request.status().message() << "\n";
    return 2;
  }
  std::unique_ptr<freeform::Client> client = Connect(flags);
  if (client == nullptr) return 2;
  absl::StatusOr<freeform::CurveSamples> samples =
      stream ? client->EvaluateCurveStreamed(*request)
             : client->EvaluateCurve(*request);
  if (!samples.ok()) return ReportError(samples.status());
  if (format == "csv") {
    PrintCsv(*samples);
  } else {
    std::cout << ToJson(ToResponse(*samples));
  }
  return 0;
}

// One CSV row per parameter: index, then each derivative's function values.
void PrintBasisCsv(const freeform::BasisSamples& samples) {
  std::cout << "index";
  for (size_t k = 0; k < samples.derivatives.size(); ++k) {
    for (size_t i = 0; i < samples.function_count; ++i) {
      std::cout << "," << (k == 0 ? "" : absl::StrCat("d", k)) << "f" << i;
    }
  }
  std::cout << "\n";
  std::cout.precision(17);
  for (size_t r = 0; r < samples.count; ++r) {
    std::cout << r;
    for (size_t k = 0; k < samples.derivatives.size(); ++k) {
      for (size_t i = 0; i < samples.function_count; ++i) {
        std::cout << "," << samples.Value(k, r, i);
      }
    }
    std::cout << "\n";
  }
}

int RunBasis(const CommonFlags& flags, const std::string& file,
             const std::string& format) {
  absl::StatusOr<freeform::v1::EvaluateBasisRequest> request =
      ParseJson<freeform::v1::EvaluateBasisRequest>(file);
  if (!request.ok()) {
    std::cerr << "error: " << request.status().message() << "\n";
    return 2;
  }
  std::unique_ptr<freeform::Client> client = Connect(flags);
  if (client == nullptr) return 2;
  absl::StatusOr<freeform::BasisSamples> samples =
      client->EvaluateBasis(*request);
  if (!samples.ok()) return ReportError(samples.status());
  if (format == "csv") {
    PrintBasisCsv(*samples);
    return 0;
  }
  freeform::v1::EvaluateBasisResponse response;
  response.set_function_count(static_cast<uint32_t>(samples->function_count));
  response.set_count(static_cast<uint32_t>(samples->count));
  for (const std::vector<double>& values : samples->derivatives) {
    response.add_derivatives()->mutable_values()->Add(values.begin(),
                                                      values.end());
  }
  std::cout << ToJson(response);
  return 0;
}

int RunHealth(const CommonFlags& flags, const std::string& service) {
  std::unique_ptr<freeform::Client> client = Connect(flags);
  if (client == nullptr) return 2;
  absl::Status status = client->CheckHealth(service);
  if (!status.ok()) return ReportError(status);
  std::cout << "SERVING\n";
  return 0;
}

void AddCommonFlags(CLI::App& command, CommonFlags& flags) {
  command
      .add_option("-a,--address", flags.address,
                  "Server address (host:port or any gRPC target)")
      ->capture_default_str();
  command
      .add_option("--timeout", flags.timeout_seconds,
                  "Deadline of the call in seconds")
      ->capture_default_str();
  command.add_flag("--tls", flags.use_tls, "Connect with TLS");
  command.add_option("--tls_root_ca", flags.root_ca,
                     "PEM file of the CA that signed the server");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"freeform: command-line client of the freeform gRPC service"};
  app.require_subcommand(1);
  CommonFlags flags;

  CLI::App* eval =
      app.add_subcommand("eval", "Evaluate a curve: CurveService.Evaluate");
  std::string file;
  bool stream = false;
  std::string format = "json";
  AddCommonFlags(*eval, flags);
  eval->add_option("-f,--file", file,
                   "EvaluateCurveRequest as proto3 JSON (default: stdin)");
  eval->add_flag("--stream", stream, "Use EvaluateStream (large batches)");
  eval->add_option("--format", format, "Output: json or csv")
      ->check(CLI::IsMember({"json", "csv"}))
      ->capture_default_str();

  CLI::App* basis = app.add_subcommand(
      "basis", "Evaluate blending functions: CurveService.EvaluateBasis");
  AddCommonFlags(*basis, flags);
  basis->add_option("-f,--file", file,
                    "EvaluateBasisRequest as proto3 JSON (default: stdin)");
  basis->add_option("--format", format, "Output: json or csv")
      ->check(CLI::IsMember({"json", "csv"}))
      ->capture_default_str();

  CLI::App* health =
      app.add_subcommand("health", "Ask the server's health service");
  std::string service;
  AddCommonFlags(*health, flags);
  health->add_option("--service", service,
                     "Service name (empty: the whole server)");

  CLI11_PARSE(app, argc, argv);
  if (eval->parsed()) return RunEval(flags, file, stream, format);
  if (basis->parsed()) return RunBasis(flags, file, format);
  return RunHealth(flags, service);
}
