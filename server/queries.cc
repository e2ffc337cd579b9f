#include "queries.h"

#include <algorithm>
#include <optional>
#include <string>
#include <utility>

#include "absl/strings/str_cat.h"
#include "convert.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "plan.h"
#include "prepare.h"
#include "prepare_options.h"

namespace freeform::server {
namespace {

// The most pieces one closest-point query examines (at least one, and its
// share of limits.max_closest_point_pieces): a query that needs more
// answers complete = false.
constexpr uint64_t kMaxPiecesPerQuery = 4096;

// WriteClosestPoints copies the minima of every query, without the unused
// slots of the core's layout.
void WriteClosestPoints(const ClosestPoints& minima,
                        v1::ClosestPointResponse& response) {
  const size_t queries = minima.counts.size();
  const size_t dimension = static_cast<size_t>(minima.dimension);
  const size_t parameter_count = static_cast<size_t>(minima.parameter_count);
  const size_t slots = static_cast<size_t>(minima.max_minima);
  response.set_parameter_count(static_cast<uint32_t>(parameter_count));
  response.mutable_distances()->Add(minima.distances.begin(),
                                    minima.distances.end());
  response.mutable_lower_bounds()->Add(minima.lower_bounds.begin(),
                                       minima.lower_bounds.end());
  size_t total = 0;
  for (size_t r = 0; r < queries; ++r) {
    response.add_minima_counts(static_cast<uint32_t>(minima.counts[r]));
    response.add_complete(minima.complete[r] != 0);
    total += static_cast<size_t>(minima.counts[r]);
  }
  absl::Span<double> parameters = UninitializedArray(
      *response.mutable_parameters(), total * parameter_count);
  v1::Points& points = *response.mutable_points();
  points.set_dimension(static_cast<uint32_t>(dimension));
  absl::Span<double> coordinates =
      UninitializedArray(*points.mutable_coordinates(), total * dimension);
  size_t at = 0;
  for (size_t r = 0; r < queries; ++r) {
    const size_t count = static_cast<size_t>(minima.counts[r]);
    std::copy_n(minima.parameters.begin() + r * slots * parameter_count,
                count * parameter_count,
                parameters.begin() + at * parameter_count);
    std::copy_n(minima.points.begin() + r * slots * dimension,
                count * dimension, coordinates.begin() + at * dimension);
    at += count;
  }
}

}  // namespace

absl::StatusOr<uint64_t> PieceWorkBytes(uint64_t piece_values,
                                        const ServiceLimits& limits,
                                        absl::string_view field) {
  return CheckWorkBytes(SaturatingProduct(piece_values, 3 * 8), limits, field);
}

absl::StatusOr<uint64_t> PieceWorkBytes(uint64_t piece_values, uint64_t pieces,
                                        uint64_t records,
                                        const ServiceLimits& limits,
                                        absl::string_view field) {
  const uint64_t values = SaturatingProduct(piece_values, 3 * 8);
  const uint64_t bookkeeping = SaturatingProduct(pieces, records);
  return CheckWorkBytes(
      values > UINT64_MAX - bookkeeping ? UINT64_MAX : values + bookkeeping,
      limits, field);
}

absl::StatusOr<uint64_t> CheckWorkBytes(uint64_t bytes,
                                        const ServiceLimits& limits,
                                        absl::string_view field) {
  if (bytes <= limits.memory_budget_bytes) return bytes;
  return ExhaustedFieldError(
      field, absl::StrCat("its Bezier pieces would take ", bytes >> 20,
                          " MiB, over the server's memory budget of ",
                          limits.memory_budget_bytes >> 20, " MiB"));
}

absl::Status IntersectionError(const absl::Status& status) {
  const std::optional<std::string> field = FieldPathOf(status);
  if (field == "max_results" || field == "tolerance" || field == "separation") {
    return PrefixFieldPath(status, "options");
  }
  if (field == "max_work") {
    return ExhaustedFieldError(
        "options.tolerance",
        absl::StrCat("the search would do more work than the server's limit "
                     "(--max_query_work): the inputs stay within the "
                     "tolerance of each "
                     "other along stretches it cannot resolve at this "
                     "tolerance, or meet too often; ",
                     FieldRuleOf(status)));
  }
  return status;
}

absl::Status QueryError(const absl::Status& status, absl::string_view geometry,
                        absl::string_view tolerance) {
  const std::optional<std::string> field = FieldPathOf(status);
  if (field == "weights") return PrefixFieldPath(status, geometry);
  if (field == "tolerance") {
    return InvalidFieldError(tolerance, FieldRuleOf(status));
  }
  return status;
}

absl::StatusOr<UnaryWork> PlanClosestPoints(
    std::string geometry, int dimension, int parameter_count,
    uint64_t work_bytes, const v1::Points& queries,
    const v1::ClosestPointOptions& options, ClosestPointSearch search,
    const ServiceLimits& limits, v1::ClosestPointResponse& response) {
  absl::StatusOr<PointsView> points = PreparePoints(queries, limits, "queries");
  if (!points.ok()) return points.status();
  if (points->dimension != dimension) {
    return InvalidFieldError(
        "queries.dimension",
        absl::StrCat("must be the geometry's dimension ", dimension, ", got ",
                     points->dimension));
  }
  absl::StatusOr<ClosestPointOptions> core_options = ToCore(options);
  if (!core_options.ok()) return core_options.status();
  core_options->max_pieces = static_cast<size_t>(std::clamp<uint64_t>(
      limits.max_closest_point_pieces / points->size(), 1, kMaxPiecesPerQuery));
  // The core's answer keeps max_minima slots per query; the response at
  // most as many.
  const uint64_t values = ClosestPointsValues(
      points->size(), dimension, parameter_count, core_options->max_minima);
  RETURN_IF_ERROR(UnaryAnswerCheck(values, limits, "queries"));
  // The search works on a copy of the geometry rescaled by powers of two
  // (a third of the pieces' share) and of the queries.
  const uint64_t copies =
      work_bytes / 3 + 8 * uint64_t{points->coordinates.size()};
  return UnaryWork{
      .plan = {.memory_bytes =
                   AnswerPlan(values, 8 * values + work_bytes + copies, limits)
                       .memory_bytes,
               .heavy = true},
      .run = [points = *points, options = *core_options,
              search = std::move(search), geometry = std::move(geometry),
              &response](const ExecutionContext& execution) -> absl::Status {
        absl::StatusOr<ClosestPoints> minima =
            search(points, options, execution);
        if (!minima.ok()) {
          return QueryError(minima.status(), geometry, "options.tolerance");
        }
        WriteClosestPoints(*minima, response);
        return absl::OkStatus();
      }};
}

UnaryWork PlanBoundingBox(int dimension, uint64_t work_bytes, double tolerance,
                          BoxComputation compute, const ServiceLimits& limits,
                          v1::BoundingBoxResponse& response) {
  const uint64_t values = BoundingBoxValues(dimension);
  return UnaryWork{
      // The search is heavy whatever the answer's size.
      .plan = {.memory_bytes =
                   AnswerPlan(values, work_bytes, limits).memory_bytes,
               .heavy = true},
      .run = [tolerance, compute = std::move(compute),
              &response](const ExecutionContext& execution) -> absl::Status {
        absl::StatusOr<BoundingBox> box =
            compute(tolerance, execution.cancellation);
        if (!box.ok()) return box.status();
        response.set_dimension(static_cast<uint32_t>(box->lower.size()));
        response.mutable_lower()->Add(box->lower.begin(), box->lower.end());
        response.mutable_upper()->Add(box->upper.begin(), box->upper.end());
        return absl::OkStatus();
      }};
}

}  // namespace freeform::server
