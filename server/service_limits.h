// ServiceLimits: the request limits freeformd enforces, and the checks that
// name them.
//
// Every limit is a server flag with a safe default; a request over a limit
// gets RESOURCE_EXHAUSTED naming the limit (or INVALID_ARGUMENT for a rule
// such as the highest degree). Thread-compatible.
#ifndef FREEFORM_SERVER_SERVICE_LIMITS_H_
#define FREEFORM_SERVER_SERVICE_LIMITS_H_

#include <cstddef>
#include <cstdint>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/time/time.h"

namespace freeform::server {

struct ServiceLimits {
  // Largest gRPC message accepted or sent.
  int64_t max_message_bytes = 64 << 20;
  // Most control points (or data points) in one request.
  size_t max_control_points = 1'000'000;
  // Highest polynomial degree accepted (and produced by elevation).
  int max_degree = 64;
  // Highest point dimension.
  int max_dimension = 64;
  // Highest derivative order.
  int max_derivative_order = 16;
  // Most parameters (evaluation points) in one request.
  size_t max_parameters = 10'000'000;
  // Most output doubles one request may produce (streams included).
  size_t max_output_values = 64'000'000;
  // Items per chunk on the thread pool; smaller batches run inline.
  size_t grain = 4096;
  // Memory all calls together may hold for their answers and work
  // (admission.h); a call that does not fit gets RESOURCE_EXHAUSTED.
  uint64_t memory_budget_bytes = 768ull << 20;
  // Points per streamed chunk when the request does not say.
  size_t default_stream_chunk = 32768;
  // Bezier pieces one closest-point call may examine over all its queries
  // (each query gets its share, between 1 and 4096): bounds the work of
  // geometry whose hull bounds prune little (extreme weights). A query
  // that runs out answers complete = false.
  uint64_t max_closest_point_pieces = uint64_t{1} << 26;
  // Most control-point values one knot simplification may move: each
  // removal shifts the values after it (the core keeps its arrays
  // contiguous), so simplifying a net of V values with R interior knots
  // moves up to R * V of them, which grows with the square of the size.
  // 2^35 bounds that part to about 14 s here: planar curves up to about
  // 130,000 control points, spatial ones up to about 107,000.
  uint64_t max_simplify_moves = uint64_t{1} << 35;
  // Most work one intersection (Intersect, IntersectCurve) or one section
  // may do, in units of about one multiply-add (the core's max_work): 2^28
  // is 0.2 to 0.9 s of one core here (query_bench Q4). A search that needs
  // more is RESOURCE_EXHAUSTED naming its tolerance.
  uint64_t max_query_work = uint64_t{1} << 28;
  // Longest time a call may run: its deadline when the client sets none or
  // a later one, so a legal but huge request cannot hold the CPU for
  // minutes. Zero means no server-side limit.
  absl::Duration max_call_time = absl::Seconds(60);
};

// CheckDimensionLimit returns INVALID_ARGUMENT on "<field>.dimension" unless
// 1 <= dimension <= limits.max_dimension.
absl::Status CheckDimensionLimit(uint64_t dimension,
                                 const ServiceLimits& limits,
                                 absl::string_view field);

// CheckDegreeLimit returns INVALID_ARGUMENT on `field` when `degree` is over
// limits.max_degree.
absl::Status CheckDegreeLimit(int64_t degree, const ServiceLimits& limits,
                              absl::string_view field);

// CheckPointLimit returns RESOURCE_EXHAUSTED naming `field` when `count`
// points are over limits.max_control_points.
absl::Status CheckPointLimit(uint64_t count, const ServiceLimits& limits,
                             absl::string_view field);

// CheckOutputLimit returns RESOURCE_EXHAUSTED naming `field` when an answer
// of `values` numbers is over limits.max_output_values.
absl::Status CheckOutputLimit(uint64_t values, const ServiceLimits& limits,
                              absl::string_view field = "parameters");

// CheckMessageLimit returns RESOURCE_EXHAUSTED naming `field` when
// `values` doubles do not fit one message of limits.max_message_bytes;
// `hint` (e.g. "; use EvaluateStream") ends the message.
absl::Status CheckMessageLimit(uint64_t values, const ServiceLimits& limits,
                               absl::string_view hint = "",
                               absl::string_view field = "parameters");

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_SERVICE_LIMITS_H_
