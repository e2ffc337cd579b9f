// Memory: one admitted call stays within the budget, and after a burst of
// maximal calls freeformd's resident memory returns to within 20% of its
// baseline.
//
// LargestAdmittedMeshStaysWithinTheBudget: freeformd with a memory budget
// of 400 MiB, one TessellateStream of the largest mesh the budget admits
// (found by probing: a call over the budget is refused at once, an
// admitted probe stops at its short deadline), read whole: the process's
// peak resident memory (VmHWM, its code and idle state included) stays
// below the budget. Every call's reservation is an upper bound of its
// memory (tests/server/memory_bounds_test.cc measures each RPC).
//
// ResidentMemoryReturnsToBaselineAfterABurstOfMaximalCalls: The baseline is
// VmRSS after a warm-up of every RPC and of maximal calls, and an idle pause
// (the MemoryTrimmer hands freed memory back once idle, every second); the
// check polls VmRSS for up to 10 s after the burst. The burst: 64 callers for
// half of FREEFORM_LOAD_SECONDS, each asking for a cubic B-spline at
// 2.6 10^6 points in one unary answer (62 MB, just under the 64 MiB
// message limit; bench/service_load.cc --workload=s2 with larger calls).
// That is deliberately above capacity: the default memory budget admits a
// few such calls at once and refuses the others with RESOURCE_EXHAUSTED,
// counted as refused; a refused caller pauses 20 ms. Answers are checked at
// every 10007th point. Skipped under the sanitizers.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <thread>

#include "../integration/server_process.h"
#include "../metrics_scrape.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "driver.h"

namespace freeform::reliability {
namespace {

constexpr int kCallers = 64;
constexpr uint32_t kPoints = 2'600'000;
constexpr double kAllowedGrowth = 1.2;
// A refused caller retries after this pause, as RESOURCE_EXHAUSTED asks.
constexpr auto kRefusalPause = std::chrono::milliseconds(20);

std::unique_ptr<Client> Connect(const ServerProcess& server) {
  ClientOptions options;
  options.target = server.address();
  options.timeout = std::chrono::seconds(120);
  options.retry_unavailable = false;
  absl::StatusOr<std::unique_ptr<Client>> client = Client::Create(options);
  EXPECT_TRUE(client.ok()) << client.status();
  return client.ok() ? *std::move(client) : nullptr;
}

// A mesh stream's outcome: its status and the vertices it sent.
struct MeshStream {
  grpc::Status status;
  uint64_t vertices = 0;
};

MeshStream StreamMesh(Client& client,
                      const v1::TessellateSurfaceRequest& request,
                      std::chrono::milliseconds deadline) {
  std::unique_ptr<grpc::ClientContext> context = client.NewContext();
  context->set_deadline(std::chrono::system_clock::now() + deadline);
  std::unique_ptr<grpc::ClientReader<v1::TessellateSurfaceResponse>> reader =
      client.surfaces().TessellateStream(context.get(), request);
  MeshStream stream;
  v1::TessellateSurfaceResponse chunk;
  while (reader->Read(&chunk)) {
    stream.vertices += chunk.vertices().coordinates_size() / 3;
  }
  stream.status = reader->Finish();
  return stream;
}

// NothingReserved waits until no call of `server` holds any of its memory
// budget (a probe stopped by its deadline may still be stopping there).
bool NothingReserved(const ServerProcess& server) {
  const auto give_up =
      std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (std::chrono::steady_clock::now() < give_up) {
    const absl::StatusOr<std::string> metrics =
        HttpGet(server.metrics_port(), "/metrics");
    if (metrics.ok() &&
        MetricValue(*metrics, "freeform_memory_reserved_bytes") == 0.0) {
      return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

TEST(Memory, LargestAdmittedMeshStaysWithinTheBudget) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  GTEST_SKIP() << "the sanitizers keep freed memory in their own allocator";
#endif
  constexpr uint64_t kBudget = uint64_t{400} << 20;
  ServerProcess server({"--log_level=warn",
                        absl::StrCat("--memory_budget=", kBudget),
                        "--metrics_listen=127.0.0.1:0"});
  ASSERT_GT(server.port(), 0) << "freeformd did not report its port";
  ASSERT_GT(server.metrics_port(), 0) << "freeformd did not report metrics";
  std::unique_ptr<Client> client = Connect(server);
  ASSERT_NE(client, nullptr);
  Rng rng(30);  // one fixed surface: the probes and the call share it
  v1::TessellateSurfaceRequest request;
  *request.add_surfaces() =
      RandomBSplinePatch(rng, 3, 3, 40, 40, /*rational=*/false).ToSurface();
  request.set_tolerance(1e-3);
  request.set_normals(true);
  // Admitted says whether a mesh of longest edge `edge` fits the budget
  // (or the server's cap of vertices, 4 M for a stream).
  auto admitted = [&](double edge) {
    EXPECT_TRUE(NothingReserved(server));
    request.set_max_edge_length(edge);
    const MeshStream probe =
        StreamMesh(*client, request, std::chrono::milliseconds(300));
    const bool refused =
        probe.status.error_code() == grpc::StatusCode::RESOURCE_EXHAUSTED;
    EXPECT_TRUE(refused || probe.status.ok() ||
                probe.status.error_code() ==
                    grpc::StatusCode::DEADLINE_EXCEEDED)
        << probe.status.error_message();
    if (refused) {
      EXPECT_TRUE(
          absl::StrContains(probe.status.error_message(), "--memory_budget") ||
          absl::StrContains(probe.status.error_message(), "vertices"))
          << probe.status.error_message();
    }
    return !refused;
  };
  // The largest admitted mesh: its edge to 1/4096 of the search's range
  // (in log scale) between an edge the budget admits and one it refuses.
  double fits = 0.02, refused = 0.0002;
  ASSERT_TRUE(admitted(fits));
  ASSERT_FALSE(admitted(refused));
  for (int step = 0; step < 12; ++step) {
    const double middle = std::sqrt(fits * refused);
    (admitted(middle) ? fits : refused) = middle;
  }
  request.set_max_edge_length(fits);
  ASSERT_TRUE(NothingReserved(server));
  const long before = server.ResidentKiB("VmHWM");
  const MeshStream mesh =
      StreamMesh(*client, request, std::chrono::seconds(120));
  ASSERT_TRUE(mesh.status.ok()) << mesh.status.error_message();
  const long peak = server.ResidentKiB("VmHWM");
  std::fprintf(stderr,
               "memory: the largest mesh a %llu MiB budget admits (longest "
               "edge %.6g): %llu vertices; VmHWM %ld KiB before it, %ld KiB "
               "after\n",
               static_cast<unsigned long long>(kBudget >> 20), fits,
               static_cast<unsigned long long>(mesh.vertices), before, peak);
  EXPECT_GT(mesh.vertices, 1'000'000u);
  EXPECT_LT(static_cast<uint64_t>(peak) * 1024, kBudget);
  EXPECT_EQ(server.StopWith(SIGTERM, std::chrono::seconds(10)), 0);
}

TEST(Memory, ResidentMemoryReturnsToBaselineAfterABurstOfMaximalCalls) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  GTEST_SKIP() << "the sanitizers keep freed memory in their own allocator";
#endif

  ServerProcess server({"--log_level=warn"});
  ASSERT_GT(server.port(), 0) << "freeformd did not report its port";
  std::unique_ptr<Client> client = Connect(server);
  ASSERT_NE(client, nullptr);

  // Warm-up: every RPC, then maximal calls from as many callers as the
  // burst, then idle long enough to be trimmed. This pages in the code of
  // both (most of freeformd's idle VmRSS is code, RssFile) and creates the
  // threads the burst's concurrency needs, whose stacks and caches stay
  // once they exist: the test asks that a burst leaves nothing behind
  // beyond the server's steady state.
  const std::vector<RpcCase> every_rpc = AllCases();
  const std::vector<RpcCase> maximal = {LargeCurveEvaluation(kPoints, 10007)};
  for (const auto& [cases, callers] :
       {std::pair(&every_rpc, 8), std::pair(&maximal, kCallers)}) {
    LoadDriver warm_up(client.get(), cases, callers, LoadSeed());
    warm_up.Start(
        {.duration = std::chrono::seconds(2), .refusal_pause = kRefusalPause});
    warm_up.Join();
    ASSERT_EQ(warm_up.Total().answered + warm_up.Total().refused,
              warm_up.Total().calls)
        << warm_up.Total().first_problem;
  }
  std::this_thread::sleep_for(std::chrono::seconds(3));
  const long baseline = server.ResidentKiB();
  const long baseline_anonymous = server.ResidentKiB("RssAnon");
  ASSERT_GT(baseline, 0);
  const auto allowed =
      static_cast<long>(static_cast<double>(baseline) * kAllowedGrowth);

  LoadDriver burst(client.get(), &maximal, kCallers, LoadSeed());
  const std::chrono::milliseconds length = std::max<std::chrono::milliseconds>(
      LoadSeconds() / 2, std::chrono::seconds(3));
  const auto end = std::chrono::steady_clock::now() + length;
  burst.Start({.duration = length, .refusal_pause = kRefusalPause});
  long peak = baseline;
  while (std::chrono::steady_clock::now() < end || burst.in_flight() > 0) {
    peak = std::max(peak, server.ResidentKiB());
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  burst.Join();
  peak = std::max(peak, server.ResidentKiB("VmHWM"));

  // The trimmer runs every second once no call holds a reservation.
  const auto idle = std::chrono::steady_clock::now();
  long after = server.ResidentKiB();
  while (after > allowed &&
         std::chrono::steady_clock::now() - idle < std::chrono::seconds(10)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    after = server.ResidentKiB();
  }
  const auto waited = std::chrono::duration_cast<std::chrono::milliseconds>(
      std::chrono::steady_clock::now() - idle);

  const Tally total = burst.Total();
  std::fprintf(
      stderr,
      "memory: %d callers, %u points per call for %lld s: %lld calls, "
      "%lld answered, %lld refused (RESOURCE_EXHAUSTED); VmRSS baseline "
      "%ld KiB, peak %ld KiB, after %ld KiB (%.0f%% of baseline, "
      "%lld ms after the burst); of which anonymous: baseline %ld KiB, "
      "after %ld KiB\n%s",
      kCallers, kPoints, static_cast<long long>(length.count() / 1000),
      static_cast<long long>(total.calls),
      static_cast<long long>(total.answered),
      static_cast<long long>(total.refused), baseline, peak, after,
      100.0 * static_cast<double>(after) / static_cast<double>(baseline),
      static_cast<long long>(waited.count()), baseline_anonymous,
      server.ResidentKiB("RssAnon"), burst.Report().c_str());
  EXPECT_GT(total.answered, 0);
  EXPECT_EQ(total.answered + total.refused, total.calls) << total.first_problem;
  EXPECT_LE(after, allowed);
  EXPECT_EQ(server.StopWith(SIGTERM, std::chrono::seconds(10)), 0);
}

}  // namespace
}  // namespace freeform::reliability
