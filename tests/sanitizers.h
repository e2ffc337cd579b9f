// Which sanitizer a test binary was built with, for the tests whose
// allowances of memory or time depend on it.
#ifndef FREEFORM_TESTS_SANITIZERS_H_
#define FREEFORM_TESTS_SANITIZERS_H_

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

}  // namespace freeform

#endif  // FREEFORM_TESTS_SANITIZERS_H_
