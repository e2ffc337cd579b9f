// FreeformServer::Start's failures: an address it cannot listen on is an
// error naming the address, never a crash.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "server.h"

namespace freeform::server {
namespace {

using ::testing::HasSubstr;

TEST(ServerStartTest, AnAddressThatIsNotLocalIsRefused) {
  // 203.0.113.0/24 is reserved for documentation (RFC 5737): no interface
  // of the test machine has it, so binding fails.
  absl::StatusOr<std::unique_ptr<FreeformServer>> server =
      FreeformServer::Start(
          {.listen_address = "203.0.113.7:50051", .threads = 1});
  ASSERT_FALSE(server.ok());
  EXPECT_EQ(server.status().code(), absl::StatusCode::kUnavailable);
  EXPECT_THAT(std::string(server.status().message()),
              HasSubstr("cannot listen on 203.0.113.7:50051"));
}

TEST(ServerStartTest, AnAddressThatDoesNotParseIsRefused) {
  absl::StatusOr<std::unique_ptr<FreeformServer>> server =
      FreeformServer::Start({.listen_address = "no port here", .threads = 1});
  ASSERT_FALSE(server.ok());
  EXPECT_THAT(std::string(server.status().message()),
              HasSubstr("no port here"));
}

}  // namespace
}  // namespace freeform::server
