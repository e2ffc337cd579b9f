// What one reliability call returns, and the Checker that compares an
// answer with the mathematics: it counts the checks made and keeps the
// first that failed, together with the request, so a wrong answer comes
// with its reproducer.
#ifndef FREEFORM_TESTS_RELIABILITY_CHECK_H_
#define FREEFORM_TESTS_RELIABILITY_CHECK_H_

#include <google/protobuf/message.h>
#include <grpcpp/support/sync_stream.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/string_view.h"
#include "freeform/client.h"
#include "freeform/v1/geometry.pb.h"
#include "reference.h"

namespace freeform::reliability {

// The outcome of one call.
struct CallResult {
  // OK, or the error the call ended with.
  absl::Status status;
  // The first check the answer failed, with the request (empty: all held).
  std::string mismatch;
  // Checks made on the answer.
  int64_t checks = 0;
  // Streams: messages received (also when the call then failed).
  size_t chunks = 0;
};

// Relative tolerance of values computed in double precision by different
// algorithms: the reference sums against the server's recurrences.
inline constexpr double kTight = 1e-9;

class Checker {
 public:
  // `request` is quoted in the mismatch; `scale` (at least 1) multiplies
  // every tolerance, the size of the coordinates involved.
  explicit Checker(const google::protobuf::Message& request, double scale = 1);

  void set_scale(double scale);

  // True checks a fact; `what` names it in the mismatch.
  bool True(bool fact, absl::string_view what);
  // Near checks |actual - expected| <= tolerance * scale.
  bool Near(double actual, double expected, double tolerance,
            absl::string_view what);
  // NearPoint checks every coordinate with Near; `at` locates the point in
  // the mismatch (a parameter or an index).
  bool NearPoint(Coordinates actual, Coordinates expected, double tolerance,
                 absl::string_view what, double at);
  // Fail records a failed check described by `what`.
  void Fail(absl::string_view what);

  bool ok() const { return mismatch_.empty(); }
  int64_t checks() const { return checks_; }

  // Result combines the call's status with the checks (which count only
  // for an OK answer).
  CallResult Result(const absl::Status& status, size_t chunks = 0) const;

 private:
  const google::protobuf::Message& request_;
  double scale_;
  int64_t checks_ = 0;
  std::string mismatch_;
};

// Flat returns the coordinates of `points`.
Values Flat(const v1::Points& points);
// SetPoints fills `points` with `dimension` and `coordinates`.
void SetPoints(int dimension, Coordinates coordinates, v1::Points* points);
// AddValues appends `values` to a repeated double field.
void AddValues(Coordinates values,
               google::protobuf::RepeatedField<double>* field);
// Linspace returns numpy.linspace(start, end, count): start + k h, the last
// value exactly `end` (geometry.proto, UniformRange).
Values Linspace(double start, double end, uint32_t count);

// A curve (or a surface along one line) as a function of its parameter.
using PointAt = std::function<Values(double)>;

// CheckSameCurve checks that `actual` on [actual_start, actual_end] and
// `expected` on [expected_start, expected_end] trace the same points under
// the linear map between the intervals: at both ends and at `samples`
// random places in between, drawn from `rng`.
void CheckSameCurve(Checker& check, std::mt19937_64& rng, int samples,
                    const PointAt& actual, double actual_start,
                    double actual_end, const PointAt& expected,
                    double expected_start, double expected_end,
                    absl::string_view what);

// ReadStream reads every message of a server stream into `chunks` and
// returns the call's status.
template <typename Response>
absl::Status ReadStream(grpc::ClientReaderInterface<Response>& reader,
                        std::vector<Response>* chunks) {
  Response response;
  while (reader.Read(&response)) chunks->push_back(std::move(response));
  return FromGrpcStatus(reader.Finish());
}

}  // namespace freeform::reliability

#endif  // FREEFORM_TESTS_RELIABILITY_CHECK_H_
