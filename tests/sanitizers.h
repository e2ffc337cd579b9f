// Which sanitizer a test binary was built with, for the tests whose
// allowances of memory or time depend on it, and the factor by which the
// sanitizer presets stretch the tests' timing allowances (TimeScale).
#ifndef FREEFORM_TESTS_SANITIZERS_H_
#define FREEFORM_TESTS_SANITIZERS_H_

#include <chrono>
#include <cstdint>
#include <cstdlib>

namespace freeform {

// True in an AddressSanitizer build: freed blocks wait in its quarantine
// (256 MiB by default) instead of being reused, so a process's peak
// resident memory counts short-lived allocations that a normal build
// reuses.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kAddressSanitizer = true;
#else
inline constexpr bool kAddressSanitizer = false;
#endif
#else
inline constexpr bool kAddressSanitizer = false;
#endif

// TimeScale is the factor by which the tests stretch the allowances of
// their timing checks (a call's deadline, the time a cancelled call may take
// to stop): FREEFORM_TEST_TIME_SCALE, default 1. The sanitizer presets set
// it (CMakePresets.json): their builds run several times slower, more so on
// a loaded machine. The checks stay the same checks; only their clocks are
// slower.
inline double TimeScale() {
  const char* scale = std::getenv("FREEFORM_TEST_TIME_SCALE");
  const double value = scale == nullptr ? 1.0 : std::atof(scale);
  return value >= 1.0 ? value : 1.0;
}

// Scaled returns `duration` times TimeScale().
template <typename Rep, typename Period>
std::chrono::milliseconds Scaled(std::chrono::duration<Rep, Period> duration) {
  return std::chrono::milliseconds(static_cast<int64_t>(
      std::chrono::duration<double, std::milli>(duration).count() *
      TimeScale()));
}

}  // namespace freeform

#endif  // FREEFORM_TESTS_SANITIZERS_H_
