// Floating-point expansions (Shewchuk 1997, docs/references.md): a real
// number held exactly as an unevaluated sum of doubles, ordered by
// increasing magnitude, strongly nonoverlapping, without zero components
// (the zero expansion is empty). Sums and products of expansions are exact
// while no product overflows or falls below the normal range, and the sign
// of an expansion is the sign of its largest component. The error-free
// transformations underneath are TwoSum, QuickTwoSum (Shewchuk's
// FastTwoSum) and TwoProduct of base/double_double.h. Values are cheap for
// a few components (kept inline) and safe to share between threads for
// reading. Internal to the core.
#ifndef FREEFORM_CORE_SRC_TRIANGULATION_EXPANSION_H_
#define FREEFORM_CORE_SRC_TRIANGULATION_EXPANSION_H_

#include "absl/container/inlined_vector.h"
#include "absl/types/span.h"

namespace freeform::internal {

class Expansion {
 public:
  // The zero expansion.
  Expansion() = default;

  // Of returns `value` as an expansion.
  static Expansion Of(double value);
  // Difference returns a - b exactly.
  static Expansion Difference(double a, double b);

  absl::Span<const double> components() const { return components_; }
  // Sign returns -1, 0 or +1, the exact sign of the value.
  int Sign() const;
  // Estimate returns the value rounded roughly (the sum of the components).
  double Estimate() const;
  Expansion Negated() const;

  // Grown returns this + b exactly (Shewchuk's Grow-Expansion).
  Expansion Grown(double b) const;
  // Scaled returns this * b exactly (Scale-Expansion).
  Expansion Scaled(double b) const;

  friend Expansion operator+(const Expansion& e, const Expansion& f);
  friend Expansion operator-(const Expansion& e, const Expansion& f) {
    return e + f.Negated();
  }
  friend Expansion operator*(const Expansion& e, const Expansion& f);

 private:
  absl::InlinedVector<double, 8> components_;
};

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_TRIANGULATION_EXPANSION_H_
