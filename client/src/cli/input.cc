// Reading the freeform CLI's requests and CSV points (input.h).
#include "input.h"

#include <google/protobuf/util/json_util.h>
#include <unistd.h>

#include <algorithm>
#include <iostream>
#include <iterator>
#include <sstream>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "absl/strings/strip.h"
#include "freeform/io/file.h"
#include "nlohmann/json.hpp"

namespace freeform::cli {
namespace {

// A SAX handler that keeps nothing: checking that text is JSON in constant
// memory, and where it is not.
class SyntaxCheck : public nlohmann::json_sax<nlohmann::json> {
 public:
  bool null() override { return true; }
  bool boolean(bool) override { return true; }
  bool number_integer(number_integer_t) override { return true; }
  bool number_unsigned(number_unsigned_t) override { return true; }
  bool number_float(number_float_t, const string_t&) override { return true; }
  bool string(string_t&) override { return true; }
  bool binary(binary_t&) override { return true; }
  bool start_object(std::size_t) override { return true; }
  bool key(string_t&) override { return true; }
  bool end_object() override { return true; }
  bool start_array(std::size_t) override { return true; }
  bool end_array() override { return true; }
  bool parse_error(std::size_t position, const std::string&,
                   const nlohmann::detail::exception& error) override {
    position_ = position;
    // "[json.exception.parse_error.101] parse error at line 1, column 2:
    // syntax error ...": keep what follows the position.
    const std::string what = error.what();
    const size_t colon = what.find(": ", what.find("column"));
    reason_ = colon == std::string::npos ? what : what.substr(colon + 2);
    return false;
  }

  size_t position() const { return position_; }
  const std::string& reason() const { return reason_; }

 private:
  size_t position_ = 0;
  std::string reason_;
};

}  // namespace

absl::StatusOr<std::string> ReadInput(const std::string& file,
                                      absl::string_view what) {
  if (!file.empty() && file != "-") {
    return ReadFileToString(file, kMaxInputBytes);
  }
  if (isatty(STDIN_FILENO)) {
    std::cerr << "freeform: reading " << what
              << " from stdin; pass --file FILE or pipe it in (end with "
                 "Ctrl-D)\n";
  }
  return ReadStandardInput(kMaxInputBytes);
}

std::string LineAndColumn(absl::string_view text, size_t offset) {
  offset = std::min(offset, text.size());
  const absl::string_view before = text.substr(0, offset);
  const size_t line =
      1 + static_cast<size_t>(std::count(before.begin(), before.end(), '\n'));
  const size_t line_start = before.rfind('\n');
  const size_t column =
      offset - (line_start == absl::string_view::npos ? 0 : line_start + 1) + 1;
  return absl::StrCat(line, ":", column);
}

absl::Status ParseJsonInto(const std::string& json, absl::string_view source,
                           google::protobuf::Message& message) {
  SyntaxCheck check;
  if (!nlohmann::json::sax_parse(json, &check)) {
    // nlohmann counts the offending character from 1.
    const size_t offset = check.position() > 0 ? check.position() - 1 : 0;
    return absl::InvalidArgumentError(
        absl::StrCat(source, ":", LineAndColumn(json, offset),
                     ": malformed JSON: ", check.reason()));
  }
  google::protobuf::util::JsonParseOptions options;
  options.ignore_unknown_fields = false;
  const auto status =
      google::protobuf::util::JsonStringToMessage(json, &message, options);
  if (!status.ok()) {
    return absl::InvalidArgumentError(absl::StrCat(
        source, ": the request is not valid JSON for ",
        message.GetDescriptor()->full_name(), ": ", status.ToString()));
  }
  return absl::OkStatus();
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
  absl::StatusOr<std::string> text = ReadInput(file, "the points (CSV)");
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

}  // namespace freeform::cli
