// Load: 64 concurrent callers mix every method of CurveService
// and SurfaceService, streams included, against the real freeformd for
// FREEFORM_LOAD_SECONDS (default 10), and every answer is checked against
// the mathematics (cases.h). The load stays within capacity (small and
// medium requests under the default memory budget), so every error counts,
// RESOURCE_EXHAUSTED included: none is expected.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>

#include "../integration/server_process.h"
#include "driver.h"

namespace freeform::reliability {
namespace {

constexpr int kCallers = 64;

TEST(Load, SixtyFourCallersGetRightAnswersFromEveryRpc) {
  ServerProcess server({"--log_level=warn"});
  ASSERT_GT(server.port(), 0) << "freeformd did not report its port";
  ClientOptions options;
  options.target = server.address();
  options.timeout = std::chrono::seconds(60);
  options.retry_unavailable = false;
  absl::StatusOr<std::unique_ptr<Client>> client = Client::Create(options);
  ASSERT_TRUE(client.ok()) << client.status();

  const std::vector<RpcCase> cases = AllCases();
  LoadDriver driver(client->get(), &cases, kCallers, LoadSeed());
  const std::chrono::seconds duration = LoadSeconds();
  driver.Start({.duration = duration});
  driver.Join();

  std::fprintf(stderr, "load: %d callers, %lld s\n%s", kCallers,
               static_cast<long long>(duration.count()),
               driver.Report().c_str());
  const Tally total = driver.Total();
  EXPECT_EQ(total.wrong, 0) << total.first_problem;
  EXPECT_EQ(total.failed, 0) << total.first_problem;
  EXPECT_EQ(total.cut, 0) << total.first_problem;
  EXPECT_EQ(total.unavailable, 0);
  EXPECT_EQ(total.refused, 0) << "the load is within capacity";
  for (size_t k = 0; k < cases.size(); ++k) {
    EXPECT_GT(driver.tallies()[k].answered, 0) << cases[k].name;
  }
  EXPECT_EQ(server.StopWith(SIGTERM, std::chrono::seconds(10)), 0);
}

}  // namespace
}  // namespace freeform::reliability
