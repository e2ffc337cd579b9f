// Fault: three freeformd replicas behind one freeform::Client
// (ClientOptions::replicas, round_robin, retry_unavailable). 64 callers
// make every unary RPC for FREEFORM_LOAD_SECONDS (default 10). A third of
// the way in one replica hangs (SIGSTOP) for a quarter of a second, so
// that calls are surely in flight on it, is killed with SIGKILL and is
// restarted on its port half a second later. No call may fail after gRPC's
// retries, and the answers stay right. Retried calls are counted from the
// replicas' access logs: freeformd logs `attempt=N` for a call that
// carries gRPC's grpc-previous-rpc-attempts header (server/rpc.cc).
//
// Streams and large answers are left out: gRPC commits a call once its
// response starts to arrive, so a call whose answer the kill cuts cannot be
// retried by the channel (the drain test covers streams at shutdown).
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <thread>

#include "../integration/server_process.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "driver.h"

namespace freeform::reliability {
namespace {

constexpr int kCallers = 64;
constexpr int kReplicas = 3;

// Lines of the file at `path` from byte `offset` on that contain `text`.
int64_t CountLines(const std::string& path, const std::string& text,
                   std::streamoff offset = 0) {
  std::ifstream file(path);
  file.seekg(offset);
  int64_t count = 0;
  std::string line;
  while (std::getline(file, line)) count += absl::StrContains(line, text);
  return count;
}

std::streamoff FileSize(const std::string& path) {
  std::ifstream file(path, std::ios::ate);
  return file.tellg();
}

TEST(Fault, KillingAReplicaMidLoadFailsNoCall) {
  char directory[] = "/tmp/freeform_fault_XXXXXX";
  ASSERT_NE(mkdtemp(directory), nullptr);
  std::vector<std::string> logs;
  std::vector<std::unique_ptr<ServerProcess>> replicas;
  ClientOptions options;
  for (int r = 0; r < kReplicas; ++r) {
    logs.push_back(absl::StrCat(directory, "/replica", r, ".log"));
    replicas.push_back(std::make_unique<ServerProcess>(
        std::vector<std::string>{}, logs.back()));
    ASSERT_GT(replicas.back()->port(), 0)
        << "replica " << r << " did not start";
    options.replicas.push_back(replicas.back()->address());
  }
  options.timeout = std::chrono::seconds(60);
  options.retry_unavailable = true;
  absl::StatusOr<std::unique_ptr<Client>> client = Client::Create(options);
  ASSERT_TRUE(client.ok()) << client.status();

  std::vector<RpcCase> cases;
  for (RpcCase& c : AllCases()) {
    if (!c.streaming) cases.push_back(std::move(c));
  }

  LoadDriver driver(client->get(), &cases, kCallers, LoadSeed());
  const std::chrono::seconds duration = LoadSeconds();
  driver.Start({.duration = duration});

  std::this_thread::sleep_for(duration / 3);
  const int64_t before_kill = driver.finished();
  const int victim = 1;
  const std::string port = std::to_string(replicas[victim]->port());
  replicas[victim]->Signal(SIGSTOP);
  std::this_thread::sleep_for(std::chrono::milliseconds(250));
  replicas[victim]->Signal(SIGKILL);
  EXPECT_EQ(replicas[victim]->WaitForExit(std::chrono::seconds(10)),
            128 + SIGKILL);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  const std::streamoff restart_offset = FileSize(logs[victim]);
  replicas[victim] = std::make_unique<ServerProcess>(
      std::vector<std::string>{"--listen=127.0.0.1:" + port}, logs[victim]);
  EXPECT_EQ(std::to_string(replicas[victim]->port()), port)
      << "the replica did not come back on its port";
  driver.Join();

  for (auto& replica : replicas) {
    EXPECT_EQ(replica->StopWith(SIGTERM, std::chrono::seconds(10)), 0);
  }
  int64_t retried = 0, by_attempt[5] = {};
  for (const std::string& log : logs) {
    for (int attempt = 2; attempt <= 4; ++attempt) {
      const int64_t lines = CountLines(log, absl::StrCat(" attempt=", attempt));
      by_attempt[attempt] += lines;
      if (attempt == 2) retried += lines;  // every retried call has one
    }
  }
  const int64_t after_restart =
      CountLines(logs[victim], "rpc method=", restart_offset);
  const Tally total = driver.Total();
  std::fprintf(stderr,
               "fault: %d callers, %lld s, replica %d killed after %lld "
               "calls\n%sretried calls: %lld (attempt 2: %lld, 3: %lld, 4: "
               "%lld); calls served by the restarted replica: %lld\n",
               kCallers, static_cast<long long>(duration.count()), victim,
               static_cast<long long>(before_kill), driver.Report().c_str(),
               static_cast<long long>(retried),
               static_cast<long long>(by_attempt[2]),
               static_cast<long long>(by_attempt[3]),
               static_cast<long long>(by_attempt[4]),
               static_cast<long long>(after_restart));
  EXPECT_EQ(total.answered, total.calls) << total.first_problem;
  EXPECT_EQ(total.wrong, 0) << total.first_problem;
  EXPECT_GT(retried, 0) << "the kill hit no call: nothing was retried";
  EXPECT_GT(after_restart, 0) << "the restarted replica served no call";
  for (const std::string& log : logs) std::remove(log.c_str());
  rmdir(directory);
}

}  // namespace
}  // namespace freeform::reliability
