// RowWriter (rows.h): rows formatted into a buffer with std::to_chars (the
// shortest digits that read back exactly) and written in 64 KiB blocks.
#include "rows.h"

#include <cerrno>
#include <charconv>
#include <cstring>

#include "absl/strings/str_cat.h"

namespace freeform::cli {
namespace {

constexpr size_t kBlockBytes = 64 << 10;

}  // namespace

absl::StatusOr<RowFormat> ParseRowFormat(const std::string& name) {
  if (name == "csv") return RowFormat::kCsv;
  if (name == "jsonl") return RowFormat::kJsonLines;
  if (name == "json") return RowFormat::kJson;
  return absl::InvalidArgumentError(
      absl::StrCat("--format ", name, ": not csv, jsonl or json"));
}

RowWriter::RowWriter(RowFormat format, std::FILE* out)
    : format_(format), out_(out) {
  buffer_.reserve(2 * kBlockBytes);
}

void RowWriter::Begin(
    std::vector<ColumnGroup> groups,
    const std::vector<std::pair<std::string, int64_t>>& fields) {
  groups_ = std::move(groups);
  begun_ = true;
  switch (format_) {
    case RowFormat::kCsv:
      buffer_ += "index";
      for (const ColumnGroup& group : groups_) {
        for (size_t j = 0; j < group.width; ++j) {
          if (j < group.csv_names.size()) {
            absl::StrAppend(&buffer_, ",", group.csv_names[j]);
          } else {
            absl::StrAppend(&buffer_, ",", group.csv_prefix, j);
          }
        }
      }
      buffer_ += '\n';
      break;
    case RowFormat::kJsonLines:
      break;
    case RowFormat::kJson:
      buffer_ += '{';
      for (const auto& [name, value] : fields) {
        absl::StrAppend(&buffer_, "\"", name, "\":", value, ",");
      }
      buffer_ += "\"points\":[";
      break;
  }
}

void RowWriter::AppendNumber(double value) {
  char digits[32];
  const std::to_chars_result result =
      std::to_chars(digits, digits + sizeof(digits), value);
  buffer_.append(digits, result.ptr);
}

void RowWriter::Row(uint64_t index,
                    absl::Span<const absl::Span<const double>> values) {
  if (format_ == RowFormat::kCsv) {
    absl::StrAppend(&buffer_, index);
    for (absl::Span<const double> group : values) {
      for (double value : group) {
        buffer_ += ',';
        AppendNumber(value);
      }
    }
    buffer_ += '\n';
  } else {
    if (format_ == RowFormat::kJson && rows_ > 0) buffer_ += ',';
    absl::StrAppend(&buffer_, "{\"index\":", index);
    for (size_t g = 0; g < values.size() && g < groups_.size(); ++g) {
      absl::StrAppend(&buffer_, ",\"", groups_[g].json_name, "\":[");
      for (size_t j = 0; j < values[g].size(); ++j) {
        if (j > 0) buffer_ += ',';
        AppendNumber(values[g][j]);
      }
      buffer_ += ']';
    }
    buffer_ += format_ == RowFormat::kJson ? "}" : "}\n";
  }
  ++rows_;
  FlushIfFull();
}

absl::Status RowWriter::Rows(
    uint64_t first_index, size_t count,
    absl::Span<const absl::Span<const double>> columns) {
  if (columns.size() != groups_.size()) {
    return absl::DataLossError("the answer's chunks differ in shape");
  }
  for (size_t g = 0; g < columns.size(); ++g) {
    if (columns[g].size() != count * groups_[g].width) {
      return absl::DataLossError(absl::StrCat(
          "the answer's ", groups_[g].json_name, " has ", columns[g].size(),
          " values for ", count, " rows of ", groups_[g].width));
    }
  }
  std::vector<absl::Span<const double>> row(columns.size());
  for (size_t r = 0; r < count; ++r) {
    for (size_t g = 0; g < columns.size(); ++g) {
      row[g] = columns[g].subspan(r * groups_[g].width, groups_[g].width);
    }
    Row(first_index + r, row);
  }
  return absl::OkStatus();
}

void RowWriter::FlushIfFull() {
  if (buffer_.size() < kBlockBytes) return;
  std::fwrite(buffer_.data(), 1, buffer_.size(), out_);
  buffer_.clear();
}

absl::Status RowWriter::Finish() {
  if (!begun_) Begin({}, {});
  if (format_ == RowFormat::kJson) {
    absl::StrAppend(&buffer_, "],\"count\":", rows_, "}\n");
  }
  std::fwrite(buffer_.data(), 1, buffer_.size(), out_);
  buffer_.clear();
  if (std::fflush(out_) != 0 || std::ferror(out_)) {
    return absl::FailedPreconditionError(
        absl::StrCat("cannot write the answer: ", std::strerror(errno)));
  }
  return absl::OkStatus();
}

}  // namespace freeform::cli
