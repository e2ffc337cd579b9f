#include "freeform/core/points.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "freeform/core/status.h"

namespace freeform {
namespace {

TEST(ValidatePointsTest, AcceptsAnyDimensionUpToTheLimit) {
  for (int dimension = 1; dimension <= kMaxDimension; ++dimension) {
    std::vector<double> coordinates(static_cast<size_t>(3 * dimension), 0.5);
    EXPECT_TRUE(ValidatePoints({dimension, coordinates}, "p").ok());
  }
}

TEST(ValidatePointsTest, NamesTheBrokenField) {
  const std::vector<double> three = {1, 2, 3};
  EXPECT_EQ(FieldPathOf(ValidatePoints({2, three}, "p")), "p.coordinates");
  EXPECT_EQ(FieldPathOf(ValidatePoints({0, three}, "p")), "p.dimension");
  EXPECT_EQ(FieldPathOf(ValidatePoints({kMaxDimension + 1, three}, "p")),
            "p.dimension");
  EXPECT_EQ(FieldPathOf(ValidatePoints({3, {}}, "p")), "p.coordinates");
  EXPECT_EQ(FieldPathOf(ValidatePoints({3, three}, "p", 2)), "p.coordinates");
  const std::vector<double> bad = {1, INFINITY, 3, 4};
  EXPECT_EQ(FieldPathOf(ValidatePoints({2, bad}, "p")), "p.coordinates[1]");
}

TEST(ValidateInRangeTest, ChecksFiniteAndInside) {
  const std::vector<double> values = {0, 0.5, 1};
  EXPECT_TRUE(ValidateInRange(values, 0, 1, "t").ok());
  EXPECT_EQ(FieldPathOf(ValidateInRange(values, 0, 0.9, "t")), "t[2]");
  const std::vector<double> nan = {NAN};
  EXPECT_EQ(FieldPathOf(ValidateInRange(nan, 0, 1, "t")), "t[0]");
}

}  // namespace
}  // namespace freeform
