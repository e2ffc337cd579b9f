#include "base/zeroed_array.h"

#include <cstdint>
#include <cstdlib>
#include <limits>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace freeform::internal {
namespace {

size_t RoundUp(size_t value, size_t multiple) {
  return (value + multiple - 1) / multiple * multiple;
}

#if defined(__linux__)
// MapHugePages maps `bytes` (a multiple of kHugePageBytes) at a huge-page
// boundary: it maps one huge page more than asked, unmaps the unaligned head
// and tail, and advises the rest as huge pages. Returns null on failure.
void* MapHugePages(size_t bytes) {
  const size_t length = bytes + kHugePageBytes;
  void* mapped = mmap(nullptr, length, PROT_READ | PROT_WRITE,
                      MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (mapped == MAP_FAILED) return nullptr;
  const uintptr_t start = reinterpret_cast<uintptr_t>(mapped);
  const uintptr_t aligned = RoundUp(start, kHugePageBytes);
  if (aligned > start) munmap(mapped, aligned - start);
  const uintptr_t end = start + length;
  if (end > aligned + bytes) {
    munmap(reinterpret_cast<void*>(aligned + bytes), end - aligned - bytes);
  }
  void* data = reinterpret_cast<void*>(aligned);
  // Only advice: without huge pages the mapping still works, page by page.
  madvise(data, bytes, MADV_HUGEPAGE);
  return data;
}
#endif

}  // namespace

ZeroedBlock AllocateZeroed(size_t bytes) {
#if defined(__linux__)
  if (bytes >= kHugePageBytes &&
      bytes <= std::numeric_limits<size_t>::max() - 2 * kHugePageBytes) {
    const size_t rounded = RoundUp(bytes, kHugePageBytes);
    if (void* data = MapHugePages(rounded); data != nullptr) {
      return {.data = data, .mapped_bytes = rounded};
    }
    return {};
  }
#endif
  return {.data = std::calloc(bytes, 1), .mapped_bytes = 0};
}

void ReleaseZeroed(const ZeroedBlock& block) {
  if (block.data == nullptr) return;
#if defined(__linux__)
  if (block.mapped_bytes > 0) {
    munmap(block.data, block.mapped_bytes);
    return;
  }
#endif
  std::free(block.data);
}

}  // namespace freeform::internal
