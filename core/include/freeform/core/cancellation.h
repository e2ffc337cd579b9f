// CancellationToken: tells long computations to stop early.
//
// A server creates one token per RPC, gives it the RPC's deadline and a poll
// function that reports client cancellation, and passes it down with the
// work. Core loops call IsCancelled() between chunks of work (never per
// point) and return status() when it turns true. Once a token is cancelled it
// stays cancelled.
//
// Thread safety: set the deadline and the poll function before sharing the
// token; after that Cancel(), IsCancelled() and status() may be called from
// any thread.
#ifndef FREEFORM_CORE_CANCELLATION_H_
#define FREEFORM_CORE_CANCELLATION_H_

#include <atomic>
#include <chrono>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <utility>

#include "absl/status/status.h"

namespace freeform {

class CancellationToken {
 public:
  using Clock = std::chrono::steady_clock;

  CancellationToken() = default;
  CancellationToken(const CancellationToken&) = delete;
  CancellationToken& operator=(const CancellationToken&) = delete;

  // SetDeadline makes the token report DEADLINE_EXCEEDED from `deadline` on,
  // with `why` as the status message when it is not empty (e.g. whose
  // deadline it was).
  void SetDeadline(Clock::time_point deadline, std::string why = {}) {
    deadline_ = deadline;
    deadline_why_ = std::move(why);
  }

  // SetPoll installs a function asked on every IsCancelled() call; when it
  // returns true the token turns CANCELLED. It must be thread-safe and cheap.
  void SetPoll(std::function<bool()> poll) { poll_ = std::move(poll); }

  // Cancel turns the token CANCELLED (unless it already stopped).
  void Cancel() { Stop(kCancelled); }

  // IsCancelled returns true once the token was cancelled, its poll function
  // said so, or its deadline passed.
  bool IsCancelled() const;

  // status returns OK while running, else CANCELLED or DEADLINE_EXCEEDED.
  absl::Status status() const;

 private:
  enum State : int { kRunning = 0, kCancelled = 1, kDeadlineExceeded = 2 };
  void Stop(State reason) const;

  mutable std::atomic<int> state_{kRunning};
  std::optional<Clock::time_point> deadline_;
  std::string deadline_why_;
  std::function<bool()> poll_;
};

// CheckCancelled returns OK while `cancel` runs (a null token always runs),
// else its CANCELLED or DEADLINE_EXCEEDED status.
absl::Status CheckCancelled(const CancellationToken* cancel);

// CancellationPoll polls a token from a sequential loop whose iterations
// may differ widely in cost: the loop reports the work each iteration did
// (in arithmetic operations, roughly), and the token is asked once per
// `work_per_poll` units, so the loop stops within about a tenth of a
// millisecond of the deadline and the polls cost nothing next to the work.
//   CancellationPoll poll(cancel);
//   for (...) {
//     ...;
//     if (absl::Status status = poll.Done(p * dim); !status.ok()) return
//     status;
//   }
class CancellationPoll {
 public:
  static constexpr size_t kDefaultWorkPerPoll = size_t{1} << 16;

  explicit CancellationPoll(const CancellationToken* cancel,
                            size_t work_per_poll = kDefaultWorkPerPoll)
      : cancel_(cancel), work_per_poll_(work_per_poll) {}

  // Done counts `work` units and returns the token's status when it is
  // time to ask and the token stopped; OK otherwise.
  absl::Status Done(size_t work) {
    if (cancel_ == nullptr) return absl::OkStatus();
    pending_ += work;
    if (pending_ < work_per_poll_) return absl::OkStatus();
    pending_ = 0;
    return CheckCancelled(cancel_);
  }

 private:
  const CancellationToken* const cancel_;
  const size_t work_per_poll_;
  size_t pending_ = 0;
};

}  // namespace freeform

#endif  // FREEFORM_CORE_CANCELLATION_H_
