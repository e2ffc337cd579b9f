// ServiceLimits: the request limits freeformd enforces, and the admission
// control that bounds concurrent heavy work.
//
// Every limit is a server flag with a safe default; a request over a limit
// gets RESOURCE_EXHAUSTED naming the limit. HeavyWorkAdmission hands out at
// most `capacity` tickets for batches that go to the thread pool, so a
// flood of big requests is refused instead of queueing without bound.
// HeavyWorkAdmission is thread-safe.
#ifndef FREEFORM_SERVER_SERVICE_LIMITS_H_
#define FREEFORM_SERVER_SERVICE_LIMITS_H_

#include <atomic>
#include <cstddef>
#include <cstdint>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

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
  // Heavy (pool) requests running at once; more get RESOURCE_EXHAUSTED.
  int max_concurrent_heavy = 64;
  // Points per streamed chunk when the request does not say.
  size_t default_stream_chunk = 65536;
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

// CheckOutputLimit returns RESOURCE_EXHAUSTED naming "parameters" when an
// answer of `values` numbers is over limits.max_output_values.
absl::Status CheckOutputLimit(uint64_t values, const ServiceLimits& limits);

// CheckMessageLimit returns RESOURCE_EXHAUSTED naming "parameters" when
// `values` doubles do not fit one message of limits.max_message_bytes;
// `hint` (e.g. "; use EvaluateStream") ends the message.
absl::Status CheckMessageLimit(uint64_t values, const ServiceLimits& limits,
                               absl::string_view hint = "");

// A ticket for one heavy request; released when destroyed.
class HeavyWorkAdmission {
 public:
  class Ticket {
   public:
    explicit Ticket(std::atomic<int>* in_flight) : in_flight_(in_flight) {}
    Ticket(Ticket&& other) noexcept : in_flight_(other.in_flight_) {
      other.in_flight_ = nullptr;
    }
    Ticket(const Ticket&) = delete;
    Ticket& operator=(const Ticket&) = delete;
    Ticket& operator=(Ticket&&) = delete;
    ~Ticket() {
      if (in_flight_ != nullptr) in_flight_->fetch_sub(1);
    }

   private:
    std::atomic<int>* in_flight_;
  };

  explicit HeavyWorkAdmission(int capacity) : capacity_(capacity) {}

  // Admit returns a ticket for a request; heavy ones get RESOURCE_EXHAUSTED
  // when `capacity` heavy requests are in flight. Light requests always get
  // an empty ticket.
  absl::StatusOr<Ticket> Admit(bool heavy) {
    if (!heavy) return Ticket(nullptr);
    if (in_flight_.fetch_add(1) >= capacity_) {
      in_flight_.fetch_sub(1);
      return absl::ResourceExhaustedError(
          "too many large requests in flight (--max_concurrent_heavy); "
          "retry later");
    }
    return Ticket(&in_flight_);
  }

 private:
  const int capacity_;
  std::atomic<int> in_flight_{0};
};

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_SERVICE_LIMITS_H_
