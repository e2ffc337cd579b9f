// ConstrainedTriangulationMemoryBound against the measured peak: this
// binary replaces the global operator new and delete to count the bytes
// live, and triangulates the workloads whose memory grows fastest (random
// points, a long loop of segments, a segment that crosses every triangle).
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <numbers>
#include <vector>

#include "freeform/core/constrained_delaunay.h"
#include "gtest/gtest.h"

namespace {

// Each allocation carries its size in a header of 16 bytes (keeping the
// alignment of new).
constexpr size_t kHeader = 16;
std::atomic<size_t> live_bytes{0};
std::atomic<size_t> peak_bytes{0};

void* Allocate(size_t size) {
  void* block = std::malloc(size + kHeader);
  if (block == nullptr) throw std::bad_alloc();
  *static_cast<size_t*>(block) = size;
  const size_t live = live_bytes.fetch_add(size) + size;
  size_t peak = peak_bytes.load();
  while (live > peak && !peak_bytes.compare_exchange_weak(peak, live)) {
  }
  return static_cast<char*>(block) + kHeader;
}

void Free(void* pointer) {
  if (pointer == nullptr) return;
  void* block = static_cast<char*>(pointer) - kHeader;
  live_bytes.fetch_sub(*static_cast<size_t*>(block));
  std::free(block);
}

}  // namespace

void* operator new(size_t size) { return Allocate(size); }
void* operator new[](size_t size) { return Allocate(size); }
void operator delete(void* pointer) noexcept { Free(pointer); }
void operator delete[](void* pointer) noexcept { Free(pointer); }
void operator delete(void* pointer, size_t) noexcept { Free(pointer); }
void operator delete[](void* pointer, size_t) noexcept { Free(pointer); }

namespace freeform {
namespace {

using Segments = std::vector<std::array<int32_t, 2>>;

// The peak of the bytes allocated by a triangulation, beyond those live
// before it.
size_t MeasuredPeak(const std::vector<Point2>& points,
                    const Segments& segments) {
  const size_t before = live_bytes.load();
  peak_bytes.store(before);
  {
    const auto result = TriangulateConstrained(
        points, segments,
        {ConstrainedTriangulationOptions::Region::kInsideSegments}, nullptr);
    EXPECT_TRUE(result.ok()) << result.status();
  }
  return peak_bytes.load() - before;
}

void ExpectWithinBound(const char* name, const std::vector<Point2>& points,
                       const Segments& segments) {
  const size_t peak = MeasuredPeak(points, segments);
  const size_t bound =
      ConstrainedTriangulationMemoryBound(points.size(), segments.size());
  std::printf(
      "%s: %zu points, %zu segments: peak %zu bytes (%.1f per point), "
      "bound %zu\n",
      name, points.size(), segments.size(), peak,
      static_cast<double>(peak) / static_cast<double>(points.size()), bound);
  EXPECT_LE(peak, bound) << name;
}

std::vector<Point2> Uniform(int count) {
  std::vector<Point2> points;
  uint64_t state = 99;
  const auto next = [&state] {
    state = state * 6364136223846793005u + 1442695040888963407u;
    return static_cast<double>(state >> 11) * 0x1p-53;
  };
  for (int i = 0; i < count; ++i) points.push_back({next(), next()});
  return points;
}

TEST(TriangulationMemoryTest, BoundHoldsForRandomPoints) {
  for (const int count : {3, 100, 10000, 200000}) {
    ExpectWithinBound("uniform", Uniform(count), {});
  }
}

TEST(TriangulationMemoryTest, BoundHoldsForALoop) {
  std::vector<Point2> points;
  Segments segments;
  constexpr int kCount = 100000;
  for (int i = 0; i < kCount; ++i) {
    const double angle = 2 * std::numbers::pi * i / kCount;
    points.push_back({std::cos(angle), std::sin(angle)});
    segments.push_back({i, (i + 1) % kCount});
  }
  ExpectWithinBound("loop", points, segments);
}

// Two rows of points and a segment between them from end to end: the
// segment crosses every triangle, the largest cavity there is. (Its
// retriangulation takes time quadratic in the cavity's size, Anglada's
// worst case: 10^4 points here.)
TEST(TriangulationMemoryTest, BoundHoldsForASegmentAcrossEverything) {
  std::vector<Point2> points = {{-1, 0}, {2, 0}};
  constexpr int kCount = 5000;
  for (int i = 0; i < kCount; ++i) {
    const double x = (i + 0.5) / kCount;
    points.push_back({x, 1});
    points.push_back({x + 0.25 / kCount, -1});
  }
  ExpectWithinBound("across", points, {{0, 1}});
}

}  // namespace
}  // namespace freeform
