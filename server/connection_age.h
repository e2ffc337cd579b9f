// Connection age: how long freeformd keeps a client's connection before it
// asks the client to move on (--max_connection_age), and how long the calls
// still running on it then get (--max_connection_age_grace).
//
// A client that balances over a DNS name (a Kubernetes headless Service,
// `dns:///` with round_robin) resolves the name when it connects and again
// only when a connection closes: without an age, replicas added later get
// no traffic from it until something breaks. With one, gRPC's server sends
// GOAWAY once a connection is older than the age (plus or minus 10 %
// jitter, so that clients do not reconnect all at once), the client
// re-resolves and connects to every address it now finds; calls in flight
// finish on the old connection within the grace (gRPC proposal A9).
//
// CheckConnectionAge validates the options; ConnectionAgeArguments maps
// them to gRPC's channel arguments. Both are pure functions.
#ifndef FREEFORM_SERVER_CONNECTION_AGE_H_
#define FREEFORM_SERVER_CONNECTION_AGE_H_

#include <string>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/time/time.h"

namespace freeform::server {

struct ConnectionAgeOptions {
  // The age after which a connection is asked to close; zero or infinite
  // keeps connections as long as clients do.
  absl::Duration max_age = absl::ZeroDuration();
  // The time calls in flight on a connection past its age get to finish
  // before it is closed under them; infinite waits for every one.
  absl::Duration grace = absl::InfiniteDuration();
};

// The shortest age accepted: below it clients reconnect more often than a
// name's addresses can usefully change, and each reconnect costs a
// resolution and a handshake.
inline constexpr absl::Duration kMinConnectionAge = absl::Seconds(1);

// CheckConnectionAge returns INVALID_ARGUMENT naming the flag when an age
// or a grace is negative, an age is under kMinConnectionAge, either does
// not fit gRPC's argument (whole milliseconds below 2^31, about 24.8 days),
// or a finite grace is set without an age.
absl::Status CheckConnectionAge(const ConnectionAgeOptions& options);

// ConnectionAgeArguments returns gRPC's server channel arguments for
// `options`, which CheckConnectionAge accepted, in milliseconds:
// GRPC_ARG_MAX_CONNECTION_AGE_MS and, with a finite grace,
// GRPC_ARG_MAX_CONNECTION_AGE_GRACE_MS; none without an age (gRPC's
// default: no limit).
std::vector<std::pair<std::string, int>> ConnectionAgeArguments(
    const ConnectionAgeOptions& options);

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_CONNECTION_AGE_H_
