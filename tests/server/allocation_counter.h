// The bytes a test executable has allocated and not yet freed, now and at
// their peak. allocation_counter.cc replaces the C allocator of the
// executable it is linked into (malloc, free, calloc, realloc,
// reallocarray, posix_memalign, aligned_alloc, memalign, valloc, pvalloc:
// libstdc++'s operator new and delete call them) with glibc's own
// functions plus a count, and counts the anonymous mappings made with
// mmap and given back with munmap (core/src/base/zeroed_array.cc maps large
// work arrays itself; glibc's internal mappings for large blocks are
// counted as the blocks they hold). A block counts its usable size
// (malloc_usable_size), a mapping its length in whole pages. Link it into
// one dedicated test executable only (memory_bounds_test). Sanitizer builds
// keep their own allocator: the counter is compiled out there and
// kCountingAllocations is false. Thread-safe.
#ifndef FREEFORM_TESTS_SERVER_ALLOCATION_COUNTER_H_
#define FREEFORM_TESTS_SERVER_ALLOCATION_COUNTER_H_

#include <cstdint>

namespace freeform::testing {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr bool kCountingAllocations = false;
#else
inline constexpr bool kCountingAllocations = true;
#endif

// AllocatedBytes returns the bytes allocated (or mapped) and not yet freed.
int64_t AllocatedBytes();

// PeakAllocatedBytes returns the largest AllocatedBytes() since the last
// ResetPeakAllocatedBytes().
int64_t PeakAllocatedBytes();

// ResetPeakAllocatedBytes restarts the peak at AllocatedBytes().
void ResetPeakAllocatedBytes();

// LostMappings counts the anonymous mappings the counter could not follow
// (its table of mappings was full): zero unless the counts are off.
int64_t LostMappings();

}  // namespace freeform::testing

#endif  // FREEFORM_TESTS_SERVER_ALLOCATION_COUNTER_H_
