// The query subcommands' CSV answers (query_csv.h), built row by row.
#include "query_csv.h"

#include <iostream>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/strip.h"
#include "absl/types/span.h"
#include "google/protobuf/repeated_field.h"
#include "output.h"

namespace freeform::cli {
namespace {

using google::protobuf::RepeatedField;

// One CSV line, built field by field.
class CsvRow {
 public:
  CsvRow& Add(absl::string_view text) {
    fields_.emplace_back(text);
    return *this;
  }
  CsvRow& Add(double value) { return Add(FormatNumber(value)); }
  CsvRow& AddAll(absl::Span<const double> values) {
    for (double value : values) Add(value);
    return *this;
  }
  // Column names prefix0, prefix1, ... prefix{count - 1}.
  CsvRow& AddNames(absl::string_view prefix, size_t count) {
    for (size_t j = 0; j < count; ++j) Add(absl::StrCat(prefix, j));
    return *this;
  }
  void Print() const { std::cout << absl::StrJoin(fields_, ",") << "\n"; }

 private:
  std::vector<std::string> fields_;
};

// Values [index * width, (index + 1) * width) of `values`, or fewer when
// `values` ends before.
absl::Span<const double> Slice(const RepeatedField<double>& values,
                               size_t index, size_t width) {
  const absl::Span<const double> all(values.data(), values.size());
  if (index * width >= all.size()) return {};
  return all.subspan(index * width, width);
}

// An enum value's name without its common prefix (REGULAR, STRAIGHT, ...).
std::string ShortName(const std::string& name, absl::string_view prefix) {
  return std::string(absl::StripPrefix(name, prefix));
}

}  // namespace

// closest --format csv: one row per minimum.
int PrintClosestCsv(const v1::ClosestPointResponse& response) {
  const size_t parameters = response.parameter_count();
  const size_t dimension = response.points().dimension();
  CsvRow header;
  header.Add("query").Add("distance");
  if (parameters == 1) {
    header.Add("t");
  } else {
    header.Add("u").Add("v");
  }
  header.AddNames("x", dimension).Print();
  size_t minimum = 0;
  for (int query = 0; query < response.minima_counts_size(); ++query) {
    for (uint32_t k = 0; k < response.minima_counts(query); ++k, ++minimum) {
      CsvRow()
          .Add(absl::StrCat(query))
          .Add(response.distances(query))
          .AddAll(Slice(response.parameters(), minimum, parameters))
          .AddAll(Slice(response.points().coordinates(), minimum, dimension))
          .Print();
    }
  }
  return 0;
}

// sample-length --format csv: parameter and point per row.
int PrintSamplesCsv(const v1::SampleByArcLengthResponse& response) {
  const size_t dimension = response.points().dimension();
  CsvRow().Add("t").AddNames("x", dimension).Print();
  for (int k = 0; k < response.parameters_size(); ++k) {
    CsvRow()
        .Add(response.parameters(k))
        .AddAll(Slice(response.points().coordinates(), k, dimension))
        .Print();
  }
  return 0;
}

// curvature --format csv for a curve: one row per parameter.
int PrintCurveCurvatureCsv(const v1::CurveCurvatureResponse& response) {
  const size_t dimension = response.dimension();
  const bool spatial = !response.torsions().empty();
  CsvRow header;
  header.Add("index").Add("curvature");
  if (spatial) header.Add("torsion");
  header.Add("status").AddNames("t", dimension).AddNames("n", dimension);
  if (spatial) header.AddNames("b", 3);
  header.Print();
  for (int k = 0; k < response.curvatures_size(); ++k) {
    CsvRow row;
    row.Add(absl::StrCat(k)).Add(response.curvatures(k));
    if (spatial) row.Add(response.torsions(k));
    row.Add(ShortName(v1::CurvePointStatus_Name(response.statuses(k)),
                      "CURVE_POINT_STATUS_"))
        .AddAll(Slice(response.tangents().coordinates(), k, dimension))
        .AddAll(Slice(response.normals().coordinates(), k, dimension));
    if (spatial) row.AddAll(Slice(response.binormals().coordinates(), k, 3));
    row.Print();
  }
  return 0;
}

// curvature --surface --format csv: one row per point.
int PrintSurfaceCurvatureCsv(const v1::SurfaceCurvatureResponse& response) {
  CsvRow()
      .Add("index")
      .Add("gaussian")
      .Add("mean")
      .Add("k1")
      .Add("k2")
      .Add("status")
      .AddNames("n", 3)
      .AddNames("d1_", 3)
      .AddNames("d2_", 3)
      .Print();
  for (int k = 0; k < response.gaussian_size(); ++k) {
    CsvRow()
        .Add(absl::StrCat(k))
        .Add(response.gaussian(k))
        .Add(response.mean(k))
        .AddAll(Slice(response.principal_curvatures(), k, 2))
        .Add(ShortName(v1::SurfacePointStatus_Name(response.statuses(k)),
                       "SURFACE_POINT_STATUS_"))
        .AddAll(Slice(response.normals().coordinates(), k, 3))
        .AddAll(Slice(response.principal_directions(), k, 6))
        .Print();
  }
  return 0;
}

}  // namespace freeform::cli
