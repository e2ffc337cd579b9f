// CheckConnectionAge refuses every age and grace gRPC would misread, naming
// the flag; ConnectionAgeArguments maps the accepted ones to gRPC's
// milliseconds; FreeformServer::Start refuses what CheckConnectionAge
// refuses.
#include "connection_age.h"

#include <gmock/gmock.h>
#include <grpc/grpc.h>
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "server.h"

namespace freeform::server {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::Pair;

TEST(ConnectionAgeTest, AnAgeAndAGraceAreGrpcsMilliseconds) {
  const ConnectionAgeOptions options = {.max_age = absl::Seconds(30),
                                        .grace = absl::Milliseconds(2500)};
  ASSERT_TRUE(CheckConnectionAge(options).ok());
  EXPECT_THAT(ConnectionAgeArguments(options),
              ElementsAre(Pair(GRPC_ARG_MAX_CONNECTION_AGE_MS, 30'000),
                          Pair(GRPC_ARG_MAX_CONNECTION_AGE_GRACE_MS, 2'500)));
}

TEST(ConnectionAgeTest, AnInfiniteGraceLeavesGrpcsDefault) {
  const ConnectionAgeOptions options = {.max_age = absl::Minutes(5)};
  ASSERT_TRUE(CheckConnectionAge(options).ok());
  EXPECT_THAT(ConnectionAgeArguments(options),
              ElementsAre(Pair(GRPC_ARG_MAX_CONNECTION_AGE_MS, 300'000)));
}

TEST(ConnectionAgeTest, ZeroOrInfiniteAgeSetsNothing) {
  for (const absl::Duration age :
       {absl::ZeroDuration(), absl::InfiniteDuration()}) {
    const ConnectionAgeOptions options = {.max_age = age};
    EXPECT_TRUE(CheckConnectionAge(options).ok()) << age;
    EXPECT_THAT(ConnectionAgeArguments(options), IsEmpty()) << age;
  }
}

TEST(ConnectionAgeTest, TheLongestAgeGrpcHoldsIsAccepted) {
  const ConnectionAgeOptions options = {
      .max_age = absl::Milliseconds(2'147'483'646),
      .grace = absl::ZeroDuration()};
  ASSERT_TRUE(CheckConnectionAge(options).ok());
  EXPECT_THAT(ConnectionAgeArguments(options),
              ElementsAre(Pair(GRPC_ARG_MAX_CONNECTION_AGE_MS, 2'147'483'646),
                          Pair(GRPC_ARG_MAX_CONNECTION_AGE_GRACE_MS, 0)));
}

TEST(ConnectionAgeTest, BadValuesAreRefusedNamingTheFlag) {
  struct Case {
    ConnectionAgeOptions options;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{.max_age = absl::Seconds(-1)}, "--max_connection_age=-1s is negative"},
      {{.max_age = -absl::InfiniteDuration()},
       "--max_connection_age=-inf is negative"},
      {{.max_age = absl::Milliseconds(999)},
       "--max_connection_age=999ms is under the shortest age, 1s"},
      {{.max_age = absl::Milliseconds(2'147'483'647)},
       "--max_connection_age=596h31m23.647s is over the longest gRPC "
       "accepts (596h31m23.646s)"},
      {{.max_age = absl::Seconds(30), .grace = absl::Milliseconds(-5)},
       "--max_connection_age_grace=-5ms is negative"},
      {{.max_age = absl::Seconds(30), .grace = absl::Hours(24 * 30)},
       "--max_connection_age_grace=720h is over the longest"},
      {{.grace = absl::Seconds(10)},
       "--max_connection_age_grace=10s needs --max_connection_age"},
      {{.max_age = absl::InfiniteDuration(), .grace = absl::Seconds(10)},
       "--max_connection_age_grace=10s needs --max_connection_age"},
  };
  for (const Case& test : cases) {
    const absl::Status status = CheckConnectionAge(test.options);
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument)
        << test.message;
    EXPECT_THAT(std::string(status.message()), HasSubstr(test.message));
  }
}

TEST(ConnectionAgeTest, TheServerRefusesToStartWithABadAge) {
  absl::StatusOr<std::unique_ptr<FreeformServer>> server =
      FreeformServer::Start(
          {.listen_address = "127.0.0.1:0",
           .threads = 1,
           .connection_age = {.max_age = absl::Milliseconds(10)}});
  ASSERT_FALSE(server.ok());
  EXPECT_EQ(server.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(std::string(server.status().message()),
              HasSubstr("--max_connection_age=10ms"));
}

}  // namespace
}  // namespace freeform::server
