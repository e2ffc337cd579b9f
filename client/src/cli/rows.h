// RowWriter: answers that are tables of numbers (points and derivatives,
// blending functions) written row by row as they arrive, in constant
// memory: CSV (a header, then one line per row), JSON lines (one object per
// row) or one JSON document written incrementally.
#ifndef FREEFORM_CLIENT_CLI_ROWS_H_
#define FREEFORM_CLIENT_CLI_ROWS_H_

#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/types/span.h"

namespace freeform::cli {

enum class RowFormat { kCsv, kJsonLines, kJson };

// ParseRowFormat reads "csv", "jsonl" or "json".
absl::StatusOr<RowFormat> ParseRowFormat(const std::string& name);

// A group of a row's values: one vector such as a point or a derivative.
// In JSON it is "json_name": [values...]; in CSV its values are the
// columns csv_prefix + "0", csv_prefix + "1", ... (or csv_names when given).
struct ColumnGroup {
  std::string json_name;
  std::string csv_prefix;
  size_t width = 0;
  std::vector<std::string> csv_names = {};
};

// Writes rows to a stdio stream. The JSON document is
//   {HEADER FIELDS, "points": [ROW, ROW, ...], "count": ROWS}
// and a row {"index": I, "NAME": [values], ...}. Not thread-safe.
class RowWriter {
 public:
  RowWriter(RowFormat format, std::FILE* out);
  RowWriter(const RowWriter&) = delete;
  RowWriter& operator=(const RowWriter&) = delete;

  // Begin writes the CSV header or the document's opening, with the
  // integer `fields` (name, value) before "points" in JSON. Called once,
  // before the first row.
  void Begin(std::vector<ColumnGroup> groups,
             const std::vector<std::pair<std::string, int64_t>>& fields);
  bool begun() const { return begun_; }

  // Row writes row `index`: one span of values per group, in order.
  void Row(uint64_t index, absl::Span<const absl::Span<const double>> values);

  // Rows writes `count` rows from index `first_index` on out of columns of
  // values: columns[g] holds count * width values of group g, row-major.
  // An error (nothing written) when a column has another size.
  absl::Status Rows(uint64_t first_index, size_t count,
                    absl::Span<const absl::Span<const double>> columns);

  // Finish ends the document (Begin with no groups when nothing began) and
  // flushes; an error when the output could not be written.
  absl::Status Finish();

 private:
  void AppendNumber(double value);
  void FlushIfFull();

  RowFormat format_;
  std::FILE* out_;
  std::vector<ColumnGroup> groups_;
  std::string buffer_;
  uint64_t rows_ = 0;
  bool begun_ = false;
};

}  // namespace freeform::cli

#endif  // FREEFORM_CLIENT_CLI_ROWS_H_
