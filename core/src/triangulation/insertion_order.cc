#include "triangulation/insertion_order.h"

#include <algorithm>
#include <numeric>
#include <utility>

namespace freeform::internal {
namespace {

constexpr int kHilbertBits = 16;
constexpr uint32_t kLastCell = (1u << kHilbertBits) - 1;
// A round of fewer points is not split further.
constexpr size_t kSmallestRound = 64;

uint64_t SplitMix64(uint64_t& state) {
  uint64_t z = (state += 0x9E3779B97F4A7C15u);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9u;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBu;
  return z ^ (z >> 31);
}

// Fisher-Yates with a fixed seed (std::shuffle's sequence depends on the
// standard library).
void Shuffle(std::vector<int32_t>& order) {
  uint64_t state = 0x5EEDu;
  for (size_t i = order.size(); i > 1; --i) {
    const size_t j = SplitMix64(state) % i;
    std::swap(order[i - 1], order[j]);
  }
}

// The grid cell of `value` within [low, low + extent].
uint32_t GridCell(double value, double low, double extent) {
  constexpr auto kCells = static_cast<double>(kLastCell);
  if (!(extent > 0.0)) return 0;
  const double scaled = (value - low) / extent * kCells;
  return static_cast<uint32_t>(std::clamp(scaled, 0.0, kCells));
}

std::vector<uint64_t> HilbertKeys(absl::Span<const Point2> points) {
  double low_x = points[0].x, high_x = points[0].x;
  double low_y = points[0].y, high_y = points[0].y;
  for (const Point2& p : points) {
    low_x = std::min(low_x, p.x), high_x = std::max(high_x, p.x);
    low_y = std::min(low_y, p.y), high_y = std::max(high_y, p.y);
  }
  // Halved first: the extent of coordinates up to 2^200 does not overflow.
  const double extent_x = high_x / 2 - low_x / 2;
  const double extent_y = high_y / 2 - low_y / 2;
  std::vector<uint64_t> keys(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    keys[i] = HilbertIndex(GridCell(points[i].x / 2, low_x / 2, extent_x),
                           GridCell(points[i].y / 2, low_y / 2, extent_y));
  }
  return keys;
}

}  // namespace

uint64_t HilbertIndex(uint32_t x, uint32_t y) {
  uint64_t index = 0;
  for (uint32_t half = 1u << (kHilbertBits - 1); half > 0; half >>= 1) {
    const uint32_t right = (x & half) != 0 ? 1 : 0;
    const uint32_t up = (y & half) != 0 ? 1 : 0;
    index += static_cast<uint64_t>(half) * half * ((3 * right) ^ up);
    if (up == 0) {  // Rotate the quadrant.
      if (right == 1) {
        x = kLastCell - x;
        y = kLastCell - y;
      }
      std::swap(x, y);
    }
  }
  return index;
}

std::vector<int32_t> BiasedRandomizedOrder(absl::Span<const Point2> points) {
  std::vector<int32_t> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  if (points.empty()) return order;
  Shuffle(order);
  const std::vector<uint64_t> keys = HilbertKeys(points);
  const auto along_curve = [&keys](int32_t a, int32_t b) {
    return std::pair(keys[a], a) < std::pair(keys[b], b);
  };
  size_t end = order.size();
  while (end > 0) {
    const size_t begin = end >= 2 * kSmallestRound ? end / 2 : 0;
    std::sort(order.begin() + begin, order.begin() + end, along_curve);
    end = begin;
  }
  return order;
}

}  // namespace freeform::internal
