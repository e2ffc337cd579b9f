#include "triangulation/expansion.h"

#include <algorithm>
#include <cmath>

#include "base/double_double.h"

namespace freeform::internal {
namespace {

// Appends `component` unless it is zero (zero elimination).
void AppendNonzero(double component, absl::InlinedVector<double, 8>& out) {
  if (component != 0.0) out.push_back(component);
}

bool SmallerMagnitude(double a, double b) { return std::abs(a) < std::abs(b); }

}  // namespace

Expansion Expansion::Of(double value) {
  Expansion result;
  AppendNonzero(value, result.components_);
  return result;
}

Expansion Expansion::Difference(double a, double b) {
  const DoubleDouble difference = TwoSum(a, -b);
  Expansion result;
  AppendNonzero(difference.lo, result.components_);
  AppendNonzero(difference.hi, result.components_);
  return result;
}

int Expansion::Sign() const {
  if (components_.empty()) return 0;
  return components_.back() > 0.0 ? 1 : -1;
}

double Expansion::Estimate() const {
  double sum = 0.0;
  for (const double component : components_) sum += component;
  return sum;
}

Expansion Expansion::Negated() const {
  Expansion result = *this;
  for (double& component : result.components_) component = -component;
  return result;
}

Expansion Expansion::Grown(double b) const {
  Expansion result;
  double running = b;
  for (const double component : components_) {
    const DoubleDouble sum = TwoSum(running, component);
    AppendNonzero(sum.lo, result.components_);
    running = sum.hi;
  }
  AppendNonzero(running, result.components_);
  return result;
}

Expansion Expansion::Scaled(double b) const {
  Expansion result;
  if (components_.empty() || b == 0.0) return result;
  DoubleDouble product = TwoProduct(components_[0], b);
  AppendNonzero(product.lo, result.components_);
  double running = product.hi;
  for (size_t i = 1; i < components_.size(); ++i) {
    product = TwoProduct(components_[i], b);
    const DoubleDouble sum = TwoSum(running, product.lo);
    AppendNonzero(sum.lo, result.components_);
    const DoubleDouble carried = QuickTwoSum(product.hi, sum.hi);
    AppendNonzero(carried.lo, result.components_);
    running = carried.hi;
  }
  AppendNonzero(running, result.components_);
  return result;
}

// Shewchuk's Fast-Expansion-Sum: the components of both, merged by
// magnitude, are summed from the smallest up.
Expansion operator+(const Expansion& e, const Expansion& f) {
  if (e.components_.empty()) return f;
  if (f.components_.empty()) return e;
  absl::InlinedVector<double, 16> merged(e.components_.size() +
                                         f.components_.size());
  std::merge(e.components_.begin(), e.components_.end(), f.components_.begin(),
             f.components_.end(), merged.begin(), SmallerMagnitude);
  Expansion result;
  DoubleDouble sum = QuickTwoSum(merged[1], merged[0]);
  AppendNonzero(sum.lo, result.components_);
  for (size_t i = 2; i < merged.size(); ++i) {
    sum = TwoSum(sum.hi, merged[i]);
    AppendNonzero(sum.lo, result.components_);
  }
  AppendNonzero(sum.hi, result.components_);
  return result;
}

Expansion operator*(const Expansion& e, const Expansion& f) {
  Expansion result;
  for (const double component : f.components_) {
    result = result + e.Scaled(component);
  }
  return result;
}

}  // namespace freeform::internal
