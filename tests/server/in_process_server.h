// InProcessServerTest: the fixture of the service tests. Each test gets a
// real FreeformServer (listening on 127.0.0.1:0 with two math threads) and a
// freeform::Client on its in-process channel, plus the checks every service
// test makes on errors.
#ifndef FREEFORM_TESTS_SERVER_IN_PROCESS_SERVER_H_
#define FREEFORM_TESTS_SERVER_IN_PROCESS_SERVER_H_

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <initializer_list>
#include <memory>
#include <string>

#include "freeform/client.h"
#include "server.h"

namespace freeform::server {

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
    client_ =
        std::make_unique<Client>(server_->InProcessChannel(), ClientOptions{});
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

  std::unique_ptr<FreeformServer> server_;
  std::unique_ptr<Client> client_;
};

// Append adds `values` to a repeated double field.
inline void Append(google::protobuf::RepeatedField<double>* field,
                   std::initializer_list<double> values) {
  field->Add(values.begin(), values.end());
}

}  // namespace freeform::server

#endif  // FREEFORM_TESTS_SERVER_IN_PROCESS_SERVER_H_
