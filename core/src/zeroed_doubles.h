// ZeroedDoubles: a fixed-size array of doubles that starts as zeros without
// writing them, for the band matrices of the solvers. Internal to the core.
//
// std::vector<double>(n, 0.0) writes every element before the constructor
// returns; for a normal-equation band of 10^8 values that is a second or
// more of page faults in which no cancellation poll can run. calloc takes
// large blocks straight from the kernel as fresh zero pages and skips the
// writes, so each page is faulted in by the first loop that touches it:
// the loops that assemble the matrix, which poll.
#ifndef FREEFORM_CORE_SRC_ZEROED_DOUBLES_H_
#define FREEFORM_CORE_SRC_ZEROED_DOUBLES_H_

#include <cstddef>
#include <cstdlib>
#include <memory>
#include <new>

namespace freeform::internal {

class ZeroedDoubles {
 public:
  // Throws std::bad_alloc when the memory is not there, as std::vector
  // would; the server reserves a request's memory before it starts.
  explicit ZeroedDoubles(size_t size)
      : data_(static_cast<double*>(std::calloc(size, sizeof(double)))) {
    if (data_ == nullptr && size > 0) throw std::bad_alloc();
  }

  double* data() { return data_.get(); }
  const double* data() const { return data_.get(); }
  double& operator[](size_t i) { return data_.get()[i]; }
  double operator[](size_t i) const { return data_.get()[i]; }

 private:
  struct Free {
    void operator()(double* data) const { std::free(data); }
  };
  std::unique_ptr<double[], Free> data_;
};

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_ZEROED_DOUBLES_H_
