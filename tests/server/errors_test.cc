#include "errors.h"

#include <gtest/gtest.h>

#include "freeform/client.h"
#include "freeform/core/status.h"

namespace freeform::server {
namespace {

TEST(ToGrpcStatusTest, FieldErrorsBecomeBadRequestDetails) {
  const grpc::Status status = ToGrpcStatus(
      InvalidFieldError("knots[4]", "knots must be non-decreasing"),
      "curve.bspline");
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(status.error_message(),
            "curve.bspline.knots[4]: knots must be non-decreasing");
  const std::vector<FieldViolation> violations =
      FieldViolationsOf(FromGrpcStatus(status));
  ASSERT_EQ(violations.size(), 1u);
  EXPECT_EQ(violations[0].field, "curve.bspline.knots[4]");
  EXPECT_EQ(violations[0].description, "knots must be non-decreasing");
}

TEST(ToGrpcStatusTest, CodesMapOneForOne) {
  EXPECT_TRUE(ToGrpcStatus(absl::OkStatus()).ok());
  const grpc::Status status =
      ToGrpcStatus(absl::ResourceExhaustedError("too big"));
  EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(status.error_message(), "too big");
  EXPECT_TRUE(status.error_details().empty());
  EXPECT_EQ(ToGrpcStatus(absl::DeadlineExceededError("late")).error_code(),
            grpc::StatusCode::DEADLINE_EXCEEDED);
}

}  // namespace
}  // namespace freeform::server
