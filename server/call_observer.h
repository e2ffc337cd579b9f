// CallObserver: what the RPC frame (rpc.h) reports about the calls it
// serves, for metrics (metrics.h implements it with Prometheus).
//
// The frame holds a nullable CallObserver*: a server without one (tests,
// fuzzers, freeformd without --metrics_listen) reports nothing and pays a
// null check per call. With one, the frame asks for the call's
// MethodObserver (by method and transport, transport.h) once when the call
// starts and reports to it once when the
// call is done, so an implementation keeps each method's state ready
// instead of looking it up by name per report. Implementations are
// thread-safe: calls report from any gRPC or pool thread.
#ifndef FREEFORM_SERVER_CALL_OBSERVER_H_
#define FREEFORM_SERVER_CALL_OBSERVER_H_

#include <chrono>
#include <cstddef>

#include "absl/status/status.h"
#include "absl/strings/string_view.h"
#include "transport.h"

namespace freeform::server {

// Why admission refused a call before its work ran.
enum class Refusal {
  kMemoryBudget,  // its plan did not fit in --memory_budget (MemoryBudget)
  kQueueFull,     // the thread pool's queue was full (QueueFullError)
  kDraining,      // the server was draining before it stops (DrainingError)
};

// The reports about the calls of one method.
class MethodObserver {
 public:
  virtual ~MethodObserver() = default;

  // CallDone reports a call's final status, its time from start until its
  // answer was sent, and the bytes of its request and of its answer (every
  // streamed message of it), as serialized messages.
  virtual void CallDone(absl::StatusCode code,
                        std::chrono::steady_clock::duration elapsed,
                        size_t request_bytes, size_t response_bytes) = 0;
};

class CallObserver {
 public:
  virtual ~CallObserver() = default;

  // ForMethod returns the observer of the calls of `method`, the access
  // log's name of the RPC ("CurveService.Evaluate"), that came in by
  // `transport`; it lives as long as this observer.
  virtual MethodObserver& ForMethod(absl::string_view method,
                                    Transport transport) = 0;

  // Refused reports a call that admission refused (once per call).
  virtual void Refused(Refusal reason) = 0;
};

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_CALL_OBSERVER_H_
