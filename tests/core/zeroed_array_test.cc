// ZeroedArray (core/src/base/zeroed_array.h), the solvers' work arrays: every
// element starts at zero, small arrays come from the heap, arrays of a huge
// page or more are mapped at a huge-page boundary and given back on release,
// and a move hands the block over without a copy.
#include "base/zeroed_array.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <new>
#include <string>
#include <utility>

namespace freeform::internal {
namespace {

bool AllZero(const ZeroedDoubles& array, size_t size) {
  for (size_t i = 0; i < size; ++i) {
    if (array[i] != 0.0) return false;
  }
  return true;
}

// The bytes of this process's address space that are mapped (VmSize).
int64_t MappedKiB() {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == "VmSize:") {
      int64_t kib = 0;
      status >> kib;
      return kib;
    }
  }
  return -1;
}

TEST(ZeroedArray, SmallArrayStartsAtZero) {
  ZeroedDoubles array(1000);
  ASSERT_NE(array.data(), nullptr);
  EXPECT_TRUE(AllZero(array, 1000));
  array[999] = 2.5;
  EXPECT_EQ(array[999], 2.5);
}

TEST(ZeroedArray, EmptyArrayHasNoData) {
  ZeroedDoubles array(0);
  EXPECT_EQ(array.data(), nullptr);
}

TEST(ZeroedArray, LargeArrayStartsAtZeroOnAHugePageBoundary) {
  // 3 MiB and a bit: two huge pages, the second one partly used.
  const size_t size = (size_t{3} << 20) / sizeof(double) + 7;
  ZeroedDoubles array(size);
  ASSERT_NE(array.data(), nullptr);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(array.data()) % kHugePageBytes, 0u);
  EXPECT_TRUE(AllZero(array, size));
  array[0] = 1.0;
  array[size - 1] = -1.0;
  EXPECT_EQ(array[0] + array[size - 1], 0.0);
}

TEST(ZeroedArray, ReleaseGivesTheMappingBack) {
  const int64_t before = MappedKiB();
  ASSERT_GT(before, 0);
  {
    ZeroedArray<int> array((size_t{64} << 20) / sizeof(int));  // 64 MiB
    array[12345] = 1;
    EXPECT_GE(MappedKiB(), before + (64 << 10));
  }
  EXPECT_LT(MappedKiB(), before + (1 << 10));
}

TEST(ZeroedArray, MoveHandsTheBlockOver) {
  const size_t size = kHugePageBytes / sizeof(double);
  ZeroedDoubles from(size);
  from[5] = 3.0;
  double* const data = from.data();
  ZeroedDoubles to(std::move(from));
  EXPECT_EQ(to.data(), data);
  EXPECT_EQ(to[5], 3.0);
  ZeroedDoubles other(10);
  other = std::move(to);
  EXPECT_EQ(other.data(), data);
  EXPECT_EQ(other[5], 3.0);
}

TEST(ZeroedArray, ImpossibleSizeThrowsBadAllocAsVectorWould) {
  EXPECT_THROW(ZeroedDoubles(SIZE_MAX / 4), std::bad_alloc);
}

}  // namespace
}  // namespace freeform::internal
