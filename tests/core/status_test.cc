#include "freeform/core/status.h"

#include <gtest/gtest.h>

#include <memory>
#include <utility>

#include "freeform/core/status_macros.h"

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

// The status macros (status_macros.h): each step runs once, an error
// returns at once and later steps do not run, and a value is moved out.
absl::Status Steps(bool fail_first, int& ran) {
  auto step = [&ran](bool fail) {
    ++ran;
    return fail ? InvalidFieldError("knots", "broken") : absl::OkStatus();
  };
  RETURN_IF_ERROR(step(fail_first));
  RETURN_IF_ERROR(step(false));
  return absl::OkStatus();
}

absl::StatusOr<std::unique_ptr<int>> Boxed(bool fail) {
  if (fail) return absl::InvalidArgumentError("no value");
  return std::make_unique<int>(7);
}

absl::StatusOr<int> Unboxed(bool fail, int& after) {
  ASSIGN_OR_RETURN(std::unique_ptr<int> value, Boxed(fail));
  ASSIGN_OR_RETURN(const auto again, Boxed(false));  // a second, distinct
  after = *again;
  return *value + 1;
}

TEST(StatusMacrosTest, ReturnIfErrorStopsAtTheFirstError) {
  int ran = 0;
  EXPECT_TRUE(Steps(false, ran).ok());
  EXPECT_EQ(ran, 2);
  ran = 0;
  const absl::Status failed = Steps(true, ran);
  EXPECT_EQ(ran, 1);
  EXPECT_EQ(FieldPathOf(failed), "knots");
}

TEST(StatusMacrosTest, AssignOrReturnMovesTheValueOrReturnsTheError) {
  int after = 0;
  const absl::StatusOr<int> value = Unboxed(false, after);
  ASSERT_TRUE(value.ok()) << value.status();
  EXPECT_EQ(*value, 8);
  EXPECT_EQ(after, 7);
  after = 0;
  const absl::StatusOr<int> failed = Unboxed(true, after);
  EXPECT_EQ(failed.status().message(), "no value");
  EXPECT_EQ(after, 0);
}

}  // namespace
}  // namespace freeform
