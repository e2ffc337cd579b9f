// The freeform CLI's shared pieces (cli_common.h).
#include "cli_common.h"

#include <google/protobuf/util/json_util.h>

#include <charconv>
#include <chrono>
#include <fstream>
#include <iostream>
#include <iterator>
#include <optional>
#include <sstream>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "absl/strings/strip.h"
#include "freeform/client/file.h"

namespace freeform::cli {

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

absl::StatusOr<std::string> ReadInput(const std::string& file) {
  if (file.empty() || file == "-") {
    return std::string(std::istreambuf_iterator<char>(std::cin), {});
  }
  return ReadFileToString(file);
}

absl::Status ParseJsonInto(const std::string& json,
                           google::protobuf::Message& message) {
  google::protobuf::util::JsonParseOptions options;
  options.ignore_unknown_fields = false;
  const auto status =
      google::protobuf::util::JsonStringToMessage(json, &message, options);
  if (!status.ok()) {
    return absl::InvalidArgumentError(absl::StrCat(
        "the request is not valid JSON for ",
        message.GetDescriptor()->full_name(), ": ", status.ToString()));
  }
  return absl::OkStatus();
}

std::string ToJson(const google::protobuf::Message& message) {
  google::protobuf::util::JsonPrintOptions options;
  options.preserve_proto_field_names = true;
  std::string json;
  (void)google::protobuf::util::MessageToJsonString(message, &json, options);
  return json + "\n";
}

int PrintJson(const google::protobuf::Message& message) {
  std::cout << ToJson(message);
  return 0;
}

int ReportError(const absl::Status& status) {
  std::cerr << "error: " << absl::StatusCodeToString(status.code()) << ": "
            << status.message() << "\n";
  for (const FieldViolation& violation : FieldViolationsOf(status)) {
    std::cerr << "  field " << violation.field << ": " << violation.description
              << "\n";
  }
  return 1;
}

int InputError(const absl::Status& status) {
  std::cerr << "error: " << status.message() << "\n";
  return 2;
}

std::unique_ptr<Client> Connect(const CommonFlags& flags) {
  ClientOptions options;
  options.target = flags.address;
  options.timeout = std::chrono::milliseconds(
      static_cast<int64_t>(flags.timeout_seconds * 1000));
  options.use_tls = flags.use_tls;
  options.root_ca_file = flags.root_ca;
  absl::StatusOr<std::unique_ptr<Client>> client = Client::Create(options);
  if (!client.ok()) {
    ReportError(client.status());
    return nullptr;
  }
  return *std::move(client);
}

std::optional<std::vector<double>> ParseCsvLine(absl::string_view line) {
  std::vector<double> row;
  for (absl::string_view field : absl::StrSplit(line, ',')) {
    double value = 0;
    if (!absl::SimpleAtod(absl::StripAsciiWhitespace(field), &value)) {
      return std::nullopt;
    }
    row.push_back(value);
  }
  return row;
}

absl::StatusOr<std::vector<std::vector<double>>> ReadCsvRows(
    const std::string& file) {
  absl::StatusOr<std::string> text = ReadInput(file);
  if (!text.ok()) return text.status();
  std::vector<std::vector<double>> rows;
  std::istringstream lines(*text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    if (line.empty() || line[0] == '#') continue;
    std::optional<std::vector<double>> row = ParseCsvLine(line);
    if (!row.has_value()) {
      if (rows.empty()) continue;  // a header
      return absl::InvalidArgumentError(
          absl::StrCat(file, ":", number, ": not a row of numbers"));
    }
    if (!rows.empty() && row->size() != rows.front().size()) {
      return absl::InvalidArgumentError(absl::StrCat(
          file, ":", number, ": ", row->size(),
          " values where earlier rows have ", rows.front().size()));
    }
    rows.push_back(*std::move(row));
  }
  if (rows.empty()) return absl::InvalidArgumentError(file + ": no points");
  return rows;
}

int WriteOutput(const std::string& path,
                absl::FunctionRef<void(std::ostream&)> write,
                const std::string& summary) {
  if (path == "-") {
    write(std::cout);
    return 0;
  }
  std::ofstream out(path);
  write(out);
  if (!out) {
    std::cerr << "error: cannot write " << path << "\n";
    return 2;
  }
  std::cerr << "wrote " << path << summary << "\n";
  return 0;
}

int WriteSvg(const SvgDrawing& drawing, const std::string& path) {
  return WriteOutput(path, [&](std::ostream& out) { drawing.Write(out); });
}

std::string FormatNumber(double value) {
  char buffer[32];
  const std::to_chars_result result =
      std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

}  // namespace freeform::cli
