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
#include <functional>
#include <optional>

#include "absl/status/status.h"

namespace freeform {

class CancellationToken {
 public:
  using Clock = std::chrono::steady_clock;

  CancellationToken() = default;
  CancellationToken(const CancellationToken&) = delete;
  CancellationToken& operator=(const CancellationToken&) = delete;

  // SetDeadline makes the token report DEADLINE_EXCEEDED from `deadline` on.
  void SetDeadline(Clock::time_point deadline) { deadline_ = deadline; }

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
  std::function<bool()> poll_;
};

}  // namespace freeform

#endif  // FREEFORM_CORE_CANCELLATION_H_
