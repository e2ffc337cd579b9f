// InProcessServerTest: the fixture of the service tests. Each test gets a
// real FreeformServer (listening on 127.0.0.1:0 with two math threads) and a
// freeform::Client on its in-process channel (on loopback TCP under
// ThreadSanitizer, see ClientChannel), plus the checks every service test
// makes on errors.
#ifndef FREEFORM_TESTS_SERVER_IN_PROCESS_SERVER_H_
#define FREEFORM_TESTS_SERVER_IN_PROCESS_SERVER_H_

#include <gmock/gmock.h>
#include <grpcpp/create_channel.h>
#include <grpcpp/security/credentials.h>
#include <grpcpp/support/channel_arguments.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <initializer_list>
#include <memory>
#include <string>
#include <thread>

#include "absl/strings/str_cat.h"
#include "freeform/client.h"
#include "grpc_handoff.h"
#include "sanitizers.h"
#include "server.h"

namespace freeform::server {

// True in a ThreadSanitizer build (FREEFORM_TSAN, grpc_handoff.h).
#ifdef FREEFORM_TSAN
inline constexpr bool kThreadSanitizer = true;
#else
inline constexpr bool kThreadSanitizer = false;
#endif

class InProcessServerTest : public ::testing::Test {
 protected:
  void SetUp() override { StartServer(ServiceLimits{}); }

  // StartServer (re)starts the server with `limits`.
  void StartServer(const ServiceLimits& limits) {
    ServerOptions options;
    options.listen_address = "127.0.0.1:0";
    options.threads = 2;
    options.limits = limits;
    auto server = FreeformServer::Start(options);
    ASSERT_TRUE(server.ok()) << server.status();
    server_ = *std::move(server);
    max_message_bytes_ = static_cast<int>(limits.max_message_bytes);
    ClientOptions client_options;
    client_options.timeout = Scaled(client_options.timeout);
    client_ = std::make_unique<Client>(ClientChannel(), client_options);
  }

  // ClientChannel returns a new channel to the server: its in-process
  // channel, or under ThreadSanitizer a loopback TCP channel. The in-process
  // transport hands each serialized message from the sender's thread to the
  // receiver's without a copy, synchronized inside libgrpc, which Debian
  // does not build with TSan: every byte the receiver parses is then a
  // (suppressed, docs/testing.md) report, and TSan's handling of millions
  // of them turns a 16 MB answer into minutes. Over TCP the bytes arrive
  // in a buffer of their own.
  std::shared_ptr<grpc::Channel> ClientChannel() {
    if (!kThreadSanitizer) return server_->InProcessChannel();
    grpc::ChannelArguments arguments;
    arguments.SetMaxReceiveMessageSize(max_message_bytes_);
    return grpc::CreateCustomChannel(
        absl::StrCat("127.0.0.1:", server_->port()),
        grpc::InsecureChannelCredentials(), arguments);
  }

  // ExpectInvalid checks INVALID_ARGUMENT with one field violation whose
  // path is `field` (or, with `prefix_only`, starts with it).
  static void ExpectInvalid(const absl::Status& status,
                            const std::string& field,
                            bool prefix_only = false) {
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << status;
    const std::vector<FieldViolation> violations = FieldViolationsOf(status);
    ASSERT_EQ(violations.size(), 1u) << status;
    if (prefix_only) {
      EXPECT_THAT(violations[0].field, ::testing::StartsWith(field)) << status;
    } else {
      EXPECT_EQ(violations[0].field, field) << status;
    }
    EXPECT_FALSE(violations[0].description.empty());
  }

  // Drains waits until no call is in flight: a call the client gave up on
  // must not keep computing.
  bool Drains(std::chrono::milliseconds within) {
    const auto until = std::chrono::steady_clock::now() + within;
    while (std::chrono::steady_clock::now() < until) {
      if (server_->calls_in_flight() == 0) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return server_->calls_in_flight() == 0;
  }

  // Hurried returns a client whose calls have the deadline `timeout`.
  std::unique_ptr<Client> Hurried(std::chrono::milliseconds timeout) {
    ClientOptions options;
    options.timeout = timeout;
    return std::make_unique<Client>(ClientChannel(), options);
  }

  std::unique_ptr<FreeformServer> server_;
  std::unique_ptr<Client> client_;
  int max_message_bytes_ = 0;
};

// Append adds `values` to a repeated double field.
inline void Append(google::protobuf::RepeatedField<double>* field,
                   std::initializer_list<double> values) {
  field->Add(values.begin(), values.end());
}

}  // namespace freeform::server

#endif  // FREEFORM_TESTS_SERVER_IN_PROCESS_SERVER_H_
