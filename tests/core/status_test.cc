#include "freeform/core/status.h"

#include <gtest/gtest.h>

namespace freeform {
namespace {

TEST(FieldErrorTest, CarriesPathAndRule) {
  const absl::Status status = InvalidFieldError("knots[4]", "must not drop");
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(status.message(), "knots[4]: must not drop");
  EXPECT_EQ(FieldPathOf(status), "knots[4]");
  EXPECT_EQ(FieldRuleOf(status), "must not drop");
}

TEST(FieldErrorTest, PrefixJoinsPaths) {
  const absl::Status status = PrefixFieldPath(
      InvalidFieldError("weights[2]", "negative"), "curve.bezier");
  EXPECT_EQ(FieldPathOf(status), "curve.bezier.weights[2]");
  EXPECT_EQ(status.message(), "curve.bezier.weights[2]: negative");
  EXPECT_EQ(FieldPathOf(PrefixFieldPath(InvalidFieldError("[3]", "x"), "v")),
            "v[3]");
  EXPECT_EQ(FieldPathOf(PrefixFieldPath(InvalidFieldError("", "x"), "v")), "v");
}

TEST(FieldErrorTest, OtherErrorsPassUnchanged) {
  const absl::Status plain = absl::ResourceExhaustedError("too big");
  EXPECT_EQ(PrefixFieldPath(plain, "curve"), plain);
  EXPECT_FALSE(FieldPathOf(plain).has_value());
  EXPECT_TRUE(PrefixFieldPath(absl::OkStatus(), "curve").ok());
}

}  // namespace
}  // namespace freeform
