// The long run (label `long`, FREEFORM_LONG=1) of triangulation_test.cc's
// random segment sets: 10^5 planar straight-line graphs, each checked for
// the constrained Delaunay certificate, the hull's cover and the segments'
// presence.
#include <cstdint>
#include <cstdlib>

#include "freeform/core/constrained_delaunay.h"
#include "gtest/gtest.h"
#include "triangulation_checks.h"
#include "triangulation_segments.h"

namespace freeform {
namespace {

TEST(ConstrainedLongTest, HundredThousandRandomSegmentSets) {
  const char* enabled = std::getenv("FREEFORM_LONG");
  if (enabled == nullptr || std::string(enabled) != "1") {
    GTEST_SKIP() << "set FREEFORM_LONG=1 to run";
  }
  for (uint64_t seed = 1000; seed < 101000; ++seed) {
    const testing::SegmentSet set = testing::RandomSegmentSet(seed);
    const absl::StatusOr<PlanarTriangulation> mesh =
        TriangulateConstrained(set.points, set.segments, {}, nullptr);
    ASSERT_TRUE(mesh.ok()) << seed << ": " << mesh.status();
    ASSERT_EQ(testing::CheckTriangles(*mesh), "") << seed;
    ASSERT_EQ(testing::CheckHullCover(*mesh), "") << seed;
    ASSERT_EQ(testing::CheckSegmentsPresent(*mesh, set.segments), "") << seed;
  }
}

}  // namespace
}  // namespace freeform
