#include "freeform/core/cancellation.h"

#include <gtest/gtest.h>

#include <atomic>

namespace freeform {
namespace {

TEST(CancellationTokenTest, RunsUntilCancelled) {
  CancellationToken token;
  EXPECT_FALSE(token.IsCancelled());
  EXPECT_TRUE(token.status().ok());
  token.Cancel();
  EXPECT_TRUE(token.IsCancelled());
  EXPECT_EQ(token.status().code(), absl::StatusCode::kCancelled);
}

TEST(CancellationTokenTest, DeadlineTurnsIntoDeadlineExceeded) {
  CancellationToken token;
  token.SetDeadline(CancellationToken::Clock::now());
  EXPECT_TRUE(token.IsCancelled());
  EXPECT_EQ(token.status().code(), absl::StatusCode::kDeadlineExceeded);
  token.Cancel();  // the first reason sticks
  EXPECT_EQ(token.status().code(), absl::StatusCode::kDeadlineExceeded);
}

TEST(CancellationTokenTest, PollReportsClientCancellation) {
  std::atomic<bool> client_gone{false};
  CancellationToken token;
  token.SetPoll([&] { return client_gone.load(); });
  EXPECT_FALSE(token.IsCancelled());
  client_gone = true;
  EXPECT_TRUE(token.IsCancelled());
  EXPECT_EQ(token.status().code(), absl::StatusCode::kCancelled);
}

}  // namespace
}  // namespace freeform
