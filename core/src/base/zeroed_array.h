// ZeroedArray<T>: a fixed-size array of a trivial type that starts as zeros
// without writing them, for the large work arrays of the solvers (band
// matrices, factors, kept basis rows). Internal to the core.
//
// Two costs of fresh memory are avoided:
// - std::vector<double>(n, 0.0) writes every element before the constructor
//   returns; for a normal-equation band of 10^8 values that is a second or
//   more of page faults in which no cancellation poll can run. Here each
//   page is faulted in by the first loop that touches it: the loops that
//   assemble the matrix, which poll.
// - A page fault per 4 KiB: on a virtual machine a fault costs microseconds,
//   so 10 MB of fresh work arrays cost milliseconds, more than the
//   arithmetic of an interpolation of 10^5 points. Arrays of 2 MiB or more
//   are mapped on their own, aligned to 2 MiB and advised as transparent
//   huge pages (madvise(MADV_HUGEPAGE), as numpy does for large arrays), so
//   one fault brings in 2 MiB. Freeing one unmaps it, so the memory goes
//   back to the system at once. Smaller arrays come from calloc.
#ifndef FREEFORM_CORE_SRC_BASE_ZEROED_ARRAY_H_
#define FREEFORM_CORE_SRC_BASE_ZEROED_ARRAY_H_

#include <cstddef>
#include <limits>
#include <new>
#include <type_traits>

namespace freeform::internal {

// A block of zeroed memory: `data` (null when empty) and what releases it.
struct ZeroedBlock {
  void* data = nullptr;
  size_t mapped_bytes = 0;  // 0: from calloc
};

// AllocateZeroed returns `bytes` of zeroed memory, or a null block when the
// memory is not there. ReleaseZeroed frees what it returned.
ZeroedBlock AllocateZeroed(size_t bytes);
void ReleaseZeroed(const ZeroedBlock& block);

// The size from which AllocateZeroed maps huge pages (one huge page).
inline constexpr size_t kHugePageBytes = size_t{2} << 20;

template <typename T>
class ZeroedArray {
  static_assert(std::is_trivially_copyable_v<T> &&
                std::is_trivially_destructible_v<T>);

 public:
  // Throws std::bad_alloc when the memory is not there, as std::vector
  // would; the server reserves a request's memory before it starts.
  explicit ZeroedArray(size_t size) {
    if (size == 0) return;
    if (size > std::numeric_limits<size_t>::max() / sizeof(T)) {
      throw std::bad_alloc();
    }
    block_ = AllocateZeroed(size * sizeof(T));
    if (block_.data == nullptr) throw std::bad_alloc();
  }
  ZeroedArray(ZeroedArray&& other) noexcept : block_(other.block_) {
    other.block_ = {};
  }
  ZeroedArray& operator=(ZeroedArray&& other) noexcept {
    if (this != &other) {
      ReleaseZeroed(block_);
      block_ = other.block_;
      other.block_ = {};
    }
    return *this;
  }
  ZeroedArray(const ZeroedArray&) = delete;
  ZeroedArray& operator=(const ZeroedArray&) = delete;
  ~ZeroedArray() { ReleaseZeroed(block_); }

  T* data() { return static_cast<T*>(block_.data); }
  const T* data() const { return static_cast<const T*>(block_.data); }
  T& operator[](size_t i) { return data()[i]; }
  const T& operator[](size_t i) const { return data()[i]; }

 private:
  ZeroedBlock block_;
};

using ZeroedDoubles = ZeroedArray<double>;

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_BASE_ZEROED_ARRAY_H_
