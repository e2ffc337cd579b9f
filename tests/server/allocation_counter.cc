#include "allocation_counter.h"

#include <errno.h>
#include <malloc.h>
#include <sys/mman.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <atomic>
#include <cstddef>
#include <cstdint>

#if !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)

// glibc's allocator under its own names: calling them never comes back
// here, so there is no recursion (as dlsym(RTLD_NEXT) could have: it
// allocates).
extern "C" {
void* __libc_malloc(size_t size);
void __libc_free(void* block);
void* __libc_calloc(size_t count, size_t size);
void* __libc_realloc(void* block, size_t size);
void* __libc_memalign(size_t alignment, size_t size);
void* __libc_valloc(size_t size);
void* __libc_pvalloc(size_t size);
}

namespace {

std::atomic<int64_t> allocated{0};
std::atomic<int64_t> peak{0};
std::atomic<int64_t> lost_mappings{0};

void Count(int64_t bytes) {
  const int64_t now =
      allocated.fetch_add(bytes, std::memory_order_relaxed) + bytes;
  int64_t highest = peak.load(std::memory_order_relaxed);
  while (now > highest &&
         !peak.compare_exchange_weak(highest, now, std::memory_order_relaxed)) {
  }
}

int64_t UsableBytes(void* block) {
  return block == nullptr ? 0 : static_cast<int64_t>(malloc_usable_size(block));
}

void* Counted(void* block) {
  Count(UsableBytes(block));
  return block;
}

// The anonymous mappings made through mmap, as [start, end) page ranges,
// so munmap gives back only what was counted (a file mapping, or the
// unaligned head and tail zeroed_array.cc unmaps, are told apart).
struct Mapping {
  uintptr_t start = 0;
  uintptr_t end = 0;
};
constexpr int kMaxMappings = 4096;
Mapping mappings[kMaxMappings];
int mapping_count = 0;
std::atomic_flag mappings_lock = ATOMIC_FLAG_INIT;

class MappingsLock {
 public:
  MappingsLock() {
    while (mappings_lock.test_and_set(std::memory_order_acquire)) {
    }
  }
  ~MappingsLock() { mappings_lock.clear(std::memory_order_release); }
};

uintptr_t PageEnd(uintptr_t end) {
  const uintptr_t page = static_cast<uintptr_t>(sysconf(_SC_PAGESIZE));
  return (end + page - 1) / page * page;
}

// AddMappingLocked records [start, end); false when the table is full.
bool AddMappingLocked(uintptr_t start, uintptr_t end) {
  if (mapping_count == kMaxMappings) return false;
  mappings[mapping_count++] = {start, end};
  return true;
}

void TrackMapping(void* address, size_t length) {
  const uintptr_t start = reinterpret_cast<uintptr_t>(address);
  const uintptr_t end = PageEnd(start + length);
  MappingsLock lock;
  if (!AddMappingLocked(start, end)) {
    lost_mappings.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  Count(static_cast<int64_t>(end - start));
}

// UntrackRange takes [start, end) out of every counted mapping it meets:
// whole mappings, their heads or tails, or a middle (which splits one).
void UntrackRange(void* address, size_t length) {
  const uintptr_t start = reinterpret_cast<uintptr_t>(address);
  const uintptr_t end = PageEnd(start + length);
  MappingsLock lock;
  for (int k = 0; k < mapping_count;) {
    Mapping& mapping = mappings[k];
    const uintptr_t cut_start = mapping.start > start ? mapping.start : start;
    const uintptr_t cut_end = mapping.end < end ? mapping.end : end;
    if (cut_start >= cut_end) {
      ++k;
      continue;
    }
    Count(-static_cast<int64_t>(cut_end - cut_start));
    const Mapping before = {mapping.start, cut_start};
    const Mapping after = {cut_end, mapping.end};
    if (before.start < before.end && after.start < after.end) {
      mapping = before;
      if (!AddMappingLocked(after.start, after.end)) {
        lost_mappings.fetch_add(1, std::memory_order_relaxed);
      }
      ++k;
    } else if (before.start < before.end) {
      mapping = before;
      ++k;
    } else if (after.start < after.end) {
      mapping = after;
      ++k;
    } else {
      mapping = mappings[--mapping_count];
    }
  }
}

void* MapAndTrack(void* address, size_t length, int protection, int flags,
                  int descriptor, off_t offset) {
  void* mapped = reinterpret_cast<void*>(syscall(
      SYS_mmap, address, length, protection, flags, descriptor, offset));
  if (mapped != MAP_FAILED && (flags & MAP_ANONYMOUS) != 0) {
    TrackMapping(mapped, length);
  }
  return mapped;
}

}  // namespace

extern "C" {

void* malloc(size_t size) { return Counted(__libc_malloc(size)); }

void free(void* block) {
  if (block == nullptr) return;
  Count(-UsableBytes(block));
  __libc_free(block);
}

void* calloc(size_t count, size_t size) {
  return Counted(__libc_calloc(count, size));
}

void* realloc(void* block, size_t size) {
  const int64_t before = UsableBytes(block);
  void* moved = __libc_realloc(block, size);
  if (moved != nullptr) {
    Count(UsableBytes(moved) - before);
  } else if (size == 0) {
    Count(-before);  // glibc frees the block and returns null
  }
  return moved;
}

void* reallocarray(void* block, size_t count, size_t size) {
  size_t bytes = 0;
  if (__builtin_mul_overflow(count, size, &bytes)) {
    errno = ENOMEM;
    return nullptr;
  }
  return realloc(block, bytes);
}

void* memalign(size_t alignment, size_t size) {
  return Counted(__libc_memalign(alignment, size));
}

void* aligned_alloc(size_t alignment, size_t size) {
  return Counted(__libc_memalign(alignment, size));
}

int posix_memalign(void** block, size_t alignment, size_t size) {
  if (alignment % sizeof(void*) != 0 || (alignment & (alignment - 1)) != 0) {
    return EINVAL;
  }
  void* aligned = Counted(__libc_memalign(alignment, size));
  if (aligned == nullptr) return ENOMEM;
  *block = aligned;
  return 0;
}

void* valloc(size_t size) { return Counted(__libc_valloc(size)); }

void* pvalloc(size_t size) { return Counted(__libc_pvalloc(size)); }

void* mmap(void* address, size_t length, int protection, int flags,
           int descriptor, off_t offset) {
  return MapAndTrack(address, length, protection, flags, descriptor, offset);
}

void* mmap64(void* address, size_t length, int protection, int flags,
             int descriptor, off_t offset) {
  return MapAndTrack(address, length, protection, flags, descriptor, offset);
}

int munmap(void* address, size_t length) {
  const long result = syscall(SYS_munmap, address, length);
  if (result == 0) UntrackRange(address, length);
  return static_cast<int>(result);
}

}  // extern "C"

namespace freeform::testing {

int64_t AllocatedBytes() { return allocated.load(std::memory_order_relaxed); }

int64_t PeakAllocatedBytes() { return peak.load(std::memory_order_relaxed); }

void ResetPeakAllocatedBytes() {
  peak.store(allocated.load(std::memory_order_relaxed),
             std::memory_order_relaxed);
}

int64_t LostMappings() { return lost_mappings.load(std::memory_order_relaxed); }

}  // namespace freeform::testing

#else  // a sanitizer's allocator

namespace freeform::testing {

int64_t AllocatedBytes() { return 0; }
int64_t PeakAllocatedBytes() { return 0; }
void ResetPeakAllocatedBytes() {}
int64_t LostMappings() { return 0; }

}  // namespace freeform::testing

#endif
