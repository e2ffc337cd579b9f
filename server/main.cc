// freeformd: the freeform gRPC server.
//
//   freeformd --listen=0.0.0.0:50051 --threads=0 --log_level=info
//
// Prints "freeformd listening on HOST:PORT" on stdout once it serves (with
// --listen=127.0.0.1:0 the kernel picks the port), with --metrics_listen
// a line "freeformd metrics on HOST:PORT" after it, and with --http_listen
// (the HTTP/JSON gateway, docs/http.md) a line "freeformd http listening on
// HOST:PORT" after those. SIGTERM or SIGINT: health turns NOT_SERVING,
// in-flight RPCs and HTTP requests get --grace_period to finish, exit 0.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "absl/flags/commandlineflag.h"
#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "absl/flags/reflection.h"
#include "absl/flags/usage.h"
#include "absl/functional/function_ref.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"
#include "absl/synchronization/mutex.h"
#include "absl/time/time.h"
#include "log_format.h"
#include "memory_trimmer.h"
#include "server.h"
#include "spdlog/sinks/stdout_sinks.h"
#include "spdlog/spdlog.h"

ABSL_FLAG(std::string, listen, "0.0.0.0:50051",
          "Address to listen on; port 0 picks a free port (printed on stdout)");
ABSL_FLAG(std::string, metrics_listen, "",
          "Address of the Prometheus metrics, http://HOST:PORT/metrics (HOST "
          "numeric, e.g. 127.0.0.1:9464; port 0 picks a free port, printed "
          "on stdout); empty serves none");
ABSL_FLAG(std::string, http_listen, "",
          "Address of the HTTP/JSON gateway (the Connect protocol, "
          "docs/http.md), HOST:PORT with a numeric host; port 0 picks a free "
          "port, printed on stdout; empty serves none. Plaintext: with "
          "--tls_cert only a loopback address, with --tls_client_ca none");
ABSL_FLAG(std::vector<std::string>, http_cors_origins, {},
          "Comma-separated origins whose browser pages may call the HTTP "
          "gateway (https://app.example:8443), or * for any; empty sends no "
          "CORS headers");
ABSL_FLAG(uint64_t, http_max_request_bytes, 0,
          "Largest HTTP request body; a larger Content-Length is refused "
          "before the body is read (0 = --max_message_bytes)");
ABSL_FLAG(int, threads, 0, "Math threads; 0 = one per hardware thread");
ABSL_FLAG(std::string, log_level, "info",
          "trace, debug, info, warn, error, critical or off");
ABSL_FLAG(std::string, log_format, "text", "text or json");
ABSL_FLAG(absl::Duration, grace_period, absl::Seconds(10),
          "Time in-flight RPCs get to finish on SIGTERM/SIGINT");
ABSL_FLAG(absl::Duration, max_connection_age, absl::ZeroDuration(),
          "Age after which a client connection is sent GOAWAY (+-10% "
          "jitter), so that clients reconnect and re-resolve the server's "
          "name, and new replicas behind it get traffic (e.g. 30s; at least "
          "1s; 0 = connections live as long as clients keep them; "
          "docs/operations.md)");
ABSL_FLAG(absl::Duration, max_connection_age_grace, absl::InfiniteDuration(),
          "Time calls in flight on a connection past --max_connection_age "
          "get to finish before it is closed (inf = as long as they take; "
          "needs --max_connection_age)");
ABSL_FLAG(std::string, tls_cert, "",
          "PEM certificate chain (enables TLS; needs --tls_key)");
ABSL_FLAG(std::string, tls_key, "",
          "PEM private key of --tls_cert's certificate (unencrypted)");
ABSL_FLAG(std::string, tls_client_ca, "",
          "PEM CA that must sign client certificates (mutual TLS; needs "
          "--tls_cert and --tls_key)");
ABSL_FLAG(std::vector<std::string>, tls_allowed_clients, {},
          "Comma-separated client identities allowed with --tls_client_ca: "
          "a DNS name or URI (e.g. spiffe://...) of the client certificate's "
          "subject alternative names, or its common name; other clients get "
          "PERMISSION_DENIED. Empty allows every certificate the CA signed");
ABSL_FLAG(bool, reflection, true,
          "Serve gRPC server reflection (lists the services and their "
          "protos to any client)");
ABSL_FLAG(int64_t, max_message_bytes, 64 << 20, "Largest gRPC message");
ABSL_FLAG(uint64_t, max_control_points, 1'000'000,
          "Most control or data points per request");
ABSL_FLAG(int, max_degree, 64, "Highest polynomial degree");
ABSL_FLAG(int, max_dimension, 64, "Highest point dimension (at least 16)");
ABSL_FLAG(int, max_derivative_order, 16, "Highest derivative order");
ABSL_FLAG(uint64_t, max_parameters, 10'000'000,
          "Most evaluation parameters per request");
ABSL_FLAG(uint64_t, max_output_values, 64'000'000,
          "Most output numbers per request (streams included)");
ABSL_FLAG(uint64_t, max_closest_point_pieces, uint64_t{1} << 26,
          "Bezier pieces one ClosestPoint call may examine over all its "
          "queries (each query its share, 1 to 4096)");
ABSL_FLAG(uint64_t, max_query_work, uint64_t{1} << 28,
          "Work one intersection or section may do (units of about one "
          "multiply-add; 2^28 is under a second of one core)");
ABSL_FLAG(uint64_t, max_simplify_moves, uint64_t{1} << 35,
          "Control-point values one knot simplification may move (interior "
          "knots times the net's values; its array moves grow with the "
          "square of the size)");
ABSL_FLAG(absl::Duration, max_call_time, absl::Seconds(60),
          "Longest time a call may run: its deadline when the client sets "
          "none or a later one (0 = no server-side limit)");
ABSL_FLAG(uint64_t, memory_budget, 768ull << 20,
          "Bytes the process may use: calls together may reserve 3/4 of it "
          "for their answers and work (a call that does not fit gets "
          "RESOURCE_EXHAUSTED), the rest covers gRPC and the allocator. Keep "
          "it below the container's memory limit");

namespace {

// ConfigureLogging sets up the log on stderr and returns the logger of the
// lines announced on stdout, both in --log_format; exits 2 on a bad format.
std::shared_ptr<spdlog::logger> ConfigureLogging() {
  const absl::StatusOr<freeform::server::LogFormat> format =
      freeform::server::ParseLogFormat(absl::GetFlag(FLAGS_log_format));
  if (!format.ok()) {
    std::cerr << "freeformd: " << format.status().message() << "\n";
    std::exit(2);
  }
  auto logger = spdlog::stderr_logger_mt("freeformd");
  logger->set_formatter(freeform::server::LogFormatter(*format));
  logger->set_level(spdlog::level::from_str(absl::GetFlag(FLAGS_log_level)));
  spdlog::set_default_logger(logger);
  auto announcer = spdlog::stdout_logger_mt("freeformd-stdout");
  announcer->set_formatter(freeform::server::AnnouncementFormatter(*format));
  announcer->flush_on(spdlog::level::info);
  return announcer;
}

freeform::server::ServerOptions OptionsFromFlags() {
  freeform::server::ServerOptions options;
  options.listen_address = absl::GetFlag(FLAGS_listen);
  options.threads = absl::GetFlag(FLAGS_threads);
  options.metrics_listen_address = absl::GetFlag(FLAGS_metrics_listen);
  options.tls = {.cert_file = absl::GetFlag(FLAGS_tls_cert),
                 .key_file = absl::GetFlag(FLAGS_tls_key),
                 .client_ca_file = absl::GetFlag(FLAGS_tls_client_ca),
                 .allowed_clients = absl::GetFlag(FLAGS_tls_allowed_clients)};
  options.reflection = absl::GetFlag(FLAGS_reflection);
  options.connection_age = {
      .max_age = absl::GetFlag(FLAGS_max_connection_age),
      .grace = absl::GetFlag(FLAGS_max_connection_age_grace)};
  const uint64_t http_max_request_bytes =
      absl::GetFlag(FLAGS_http_max_request_bytes);
  options.http = {.listen_address = absl::GetFlag(FLAGS_http_listen),
                  .cors_origins = absl::GetFlag(FLAGS_http_cors_origins),
                  .max_request_bytes =
                      http_max_request_bytes != 0
                          ? http_max_request_bytes
                          : static_cast<uint64_t>(std::max<int64_t>(
                                0, absl::GetFlag(FLAGS_max_message_bytes)))};
  freeform::server::ServiceLimits& limits = options.limits;
  limits.max_message_bytes = absl::GetFlag(FLAGS_max_message_bytes);
  limits.max_control_points = absl::GetFlag(FLAGS_max_control_points);
  limits.max_degree = absl::GetFlag(FLAGS_max_degree);
  limits.max_dimension = absl::GetFlag(FLAGS_max_dimension);
  limits.max_derivative_order = absl::GetFlag(FLAGS_max_derivative_order);
  limits.max_parameters = absl::GetFlag(FLAGS_max_parameters);
  limits.max_output_values = absl::GetFlag(FLAGS_max_output_values);
  limits.max_closest_point_pieces =
      absl::GetFlag(FLAGS_max_closest_point_pieces);
  limits.max_simplify_moves = absl::GetFlag(FLAGS_max_simplify_moves);
  limits.max_query_work = absl::GetFlag(FLAGS_max_query_work);
  limits.memory_budget_bytes = absl::GetFlag(FLAGS_memory_budget);
  limits.max_call_time = absl::GetFlag(FLAGS_max_call_time);
  return options;
}

// The drain (ExitWhenDrained), the watchdog (StopWithin) and the normal
// stop at the end of main may each end the process, and two of them can
// get there at the same moment. ClaimExit returns true for the first caller
// only: it alone logs why the process ends. The default logger stays alive
// to the end (flushed, never shut down): a thread that still logs, such as
// a call answered UNAVAILABLE while draining, must not find it destroyed.
std::atomic<bool> exit_claimed{false};

bool ClaimExit() { return !exit_claimed.exchange(true); }

// WaitForTheEnd blocks a caller that lost ClaimExit until the winner ends
// the process.
[[noreturn]] void WaitForTheEnd() {
  while (true) absl::SleepFor(absl::Hours(1));
}

// ExitNow logs `message` and exits 0 at once, unless another thread already
// claimed the exit.
[[noreturn]] void ExitNow(spdlog::level::level_enum level,
                          const std::string& message) {
  if (!ClaimExit()) WaitForTheEnd();
  spdlog::log(level, "{}", message);
  spdlog::default_logger()->flush();
  _exit(0);
}

}  // namespace

// StopWithin makes sure the process is gone `limit` after the signal even
// when a call or a connection would hold the drain longer: the graceful
// path normally ends well before.
void StopWithin(absl::Duration limit) {
  std::thread([limit] {
    absl::SleepFor(limit);
    ExitNow(spdlog::level::warn,
            absl::StrCat("drain did not end within ",
                         absl::FormatDuration(limit), "; exiting"));
  }).detach();
}

// PollUntilQuiet polls the server every `interval` until `checks` polls in
// a row find no call in flight and none started since the poll before
// (returns true), or until `give_up()` (returns false).
bool PollUntilQuiet(const freeform::server::FreeformServer& server,
                    absl::Duration interval, int checks,
                    absl::FunctionRef<bool()> give_up) {
  int64_t started = server.calls_started();
  int quiet_checks = 0;
  while (!give_up()) {
    absl::SleepFor(interval);
    const int64_t now_started = server.calls_started();
    quiet_checks = server.calls_in_flight() == 0 && now_started == started
                       ? quiet_checks + 1
                       : 0;
    started = now_started;
    if (quiet_checks == checks) return true;
  }
  return false;
}

// ExitWhenDrained waits while gRPC drains. gRPC's shutdown also waits, up
// to the whole grace period, for idle client connections to go away; once
// the listener is closed and no call is in flight there is nothing left to
// wait for, so the process exits 0 at once. Two quiet polls 20 ms apart:
// the first also lets Shutdown close the listener, after which no new call
// can start. Returns when the shutdown ended by itself first.
void ExitWhenDrained(const freeform::server::FreeformServer& server,
                     const std::atomic<bool>& stopped) {
  if (PollUntilQuiet(server, absl::Milliseconds(20), 2,
                     [&] { return stopped.load(); }) &&
      !stopped) {
    ExitNow(spdlog::level::info, "drained: no call in flight; exiting");
  }
}

// WaitUntilQuiet returns once no call is in flight and none has started for
// 250 ms (the server answers new calls UNAVAILABLE while it drains), or at
// `deadline`. gRPC's Shutdown cancels the calls its transport has accepted
// but not yet handed to a handler; starting it only when the server is
// quiet leaves it none. 50 ms was not enough on a starved machine (load 8
// on 2 cores): a call still on its way to a handler got CANCELLED.
void WaitUntilQuiet(const freeform::server::FreeformServer& server,
                    absl::Time deadline) {
  PollUntilQuiet(server, absl::Milliseconds(10), 25,
                 [&] { return absl::Now() >= deadline; });
}

// The version of freeformd, set by the build (CMakeLists.txt).
#ifndef FREEFORM_VERSION
#define FREEFORM_VERSION "unknown"
#endif

namespace {

constexpr char kUsage[] = "freeform curve and surface gRPC server";

// HostOf returns the host of a HOST:PORT address.
std::string HostOf(const std::string& address) {
  return address.substr(0, address.rfind(':'));
}

// PrintHelp lists the server's own flags (those of this file), sorted, with
// their help and default values.
void PrintHelp() {
  std::vector<const absl::CommandLineFlag*> flags;
  for (const auto& [name, flag] : absl::GetAllFlags()) {
    if (absl::EndsWith(flag->Filename(), "server/main.cc")) {
      flags.push_back(flag);
    }
  }
  std::sort(flags.begin(), flags.end(),
            [](const auto* a, const auto* b) { return a->Name() < b->Name(); });
  std::cout << "freeformd " << FREEFORM_VERSION << ": " << kUsage
            << "\n\nUsage: freeformd [--flag=value ...]\n\nFlags:\n";
  for (const absl::CommandLineFlag* flag : flags) {
    std::cout << "  --" << flag->Name() << "  " << flag->Help()
              << " (default: " << flag->DefaultValue() << ")\n";
  }
  std::cout << "\n--helpfull also lists the flags of the libraries.\n";
}

// HandleHelpAndVersion answers --help / -h (the server's flags) and
// --version on stdout and exits 0; other arguments are left to Abseil.
void HandleHelpAndVersion(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const absl::string_view argument = argv[i];
    if (argument == "--help" || argument == "-h" || argument == "-help") {
      PrintHelp();
      std::exit(0);
    }
    if (argument == "--version") {
      std::cout << "freeformd " << FREEFORM_VERSION << "\n";
      std::exit(0);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  // Before any thread exists (memory_trimmer.h says why).
  const bool allocator_configured =
      freeform::server::ConfigureAllocatorForTrimming();
  HandleHelpAndVersion(argc, argv);
  absl::SetProgramUsageMessage(kUsage);
  absl::ParseCommandLine(argc, argv);
  // Abseil's mutex deadlock detection is a debugging aid that costs every
  // lock (gRPC's included) a graph update; the server runs without it.
  absl::SetMutexDeadlockDetectionMode(absl::OnDeadlockCycle::kIgnore);
  const std::shared_ptr<spdlog::logger> announcer = ConfigureLogging();
  if (!allocator_configured) {
    spdlog::info("malloc left as the environment set it");
  }

  // Block the stop signals in every thread; this thread waits for them.
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGTERM);
  sigaddset(&stop_signals, SIGINT);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);

  auto server = freeform::server::FreeformServer::Start(OptionsFromFlags());
  if (!server.ok()) {
    spdlog::critical("cannot start: {}", server.status().ToString());
    return 1;
  }
  const std::string host = HostOf(absl::GetFlag(FLAGS_listen));
  announcer->info("freeformd listening on {}:{}", host, (*server)->port());
  if ((*server)->metrics_port() != 0) {
    announcer->info("freeformd metrics on {}:{}",
                    HostOf(absl::GetFlag(FLAGS_metrics_listen)),
                    (*server)->metrics_port());
  }
  if ((*server)->http_port() != 0) {
    announcer->info("freeformd http listening on {}:{}",
                    HostOf(absl::GetFlag(FLAGS_http_listen)),
                    (*server)->http_port());
  }
  spdlog::info("serving on {}:{} with {} math threads", host, (*server)->port(),
               (*server)->pool_size());

  int signal_number = 0;
  sigwait(&stop_signals, &signal_number);
  const absl::Duration grace = absl::GetFlag(FLAGS_grace_period);
  spdlog::info("signal {}: draining for up to {}", signal_number,
               absl::FormatDuration(grace));
  StopWithin(grace + absl::Milliseconds(900));
  const absl::Time deadline = absl::Now() + grace;
  (*server)->BeginDrain();
  WaitUntilQuiet(**server, deadline);
  std::atomic<bool> stopped{false};
  std::thread drain([&] {
    (*server)->Shutdown(absl::ToChronoMilliseconds(
        std::max(absl::ZeroDuration(), deadline - absl::Now())));
    (*server)->Wait();
    stopped = true;
  });
  ExitWhenDrained(**server, stopped);
  drain.join();
  // Everything is answered and logged: nothing is left for the destructors
  // (the server's, the pool's) to do but take time. On a starved machine
  // they held the exit for over a second after "stopped".
  ExitNow(spdlog::level::info, "stopped");
}
