#include "queries/speed_minima.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "base/binomial.h"
#include "base/scaled.h"
#include "refine/bezier_halving.h"

namespace freeform::internal {
namespace {

// Halvings that locate a minimum of the speed: to 2^-32 of its net's
// parameter, where the kink it leaves costs the rule about the speed's
// slope times (2^-32)^2.
constexpr int kMinimumDepth = 32;

// Halvings of one net's slope at most: a polynomial of degree k has at most
// k roots, each located in kMinimumDepth halvings, so this is reached only
// when rounding beyond the noise flips signs everywhere; the cuts found by
// then are kept (a cut refines the integration, it is never needed for
// correctness: the error estimate still decides).
constexpr int kMaxMinimumHalvings = 1 << 12;

// A minimum is cut at only where the speed falls below this ratio of the
// bound of its largest over the net (KeepSharpMinima).
constexpr double kSmoothSpeedRatio = 0.25;

// Bernstein coefficients of a polynomial on [0, 1] (degree size() - 1), for
// the slope of a rational net.
using Bernstein = std::vector<double>;

// Product returns the Bernstein coefficients of a b.
Bernstein Product(const Bernstein& a, const Bernstein& b) {
  const int p = static_cast<int>(a.size()) - 1;
  const int q = static_cast<int>(b.size()) - 1;
  Bernstein c(a.size() + b.size() - 1, 0.0);
  for (int i = 0; i <= p; ++i) {
    for (int j = 0; j <= q; ++j) {
      c[i + j] += Binomial(p, i) * Binomial(q, j) * a[i] * b[j];
    }
  }
  for (int k = 0; k <= p + q; ++k) c[k] /= Binomial(p + q, k);
  return c;
}

// Derivative returns the Bernstein coefficients of a' (of degree one less;
// 0 for a constant).
Bernstein Derivative(const Bernstein& a) {
  const int n = static_cast<int>(a.size()) - 1;
  if (n <= 0) return {0.0};
  Bernstein d(a.size() - 1);
  for (int i = 0; i < n; ++i) d[i] = n * (a[i + 1] - a[i]);
  return d;
}

// Add adds `scale` b to a (of the same degree).
void Add(Bernstein& a, double scale, const Bernstein& b) {
  for (size_t i = 0; i < a.size(); ++i) a[i] += scale * b[i];
}

double Largest(absl::Span<const double> a) {
  double largest = 0.0;
  for (const double x : a) largest = std::max(largest, std::abs(x));
  return largest;
}

// HodographBound returns n max_i |P_{i+1} - P_i| of a polynomial curve net
// of degree n, a bound of its speed: C' is n times a convex combination of
// those differences.
double HodographBound(const Net& net) {
  const size_t stride = static_cast<size_t>(net.stride());
  const size_t d = static_cast<size_t>(net.dimension);
  std::vector<double> difference(d);
  double largest = 0.0;
  for (size_t i = 0; i + 1 < static_cast<size_t>(net.count_u); ++i) {
    for (size_t x = 0; x < d; ++x) {
      difference[x] =
          net.values[(i + 1) * stride + x] - net.values[i * stride + x];
    }
    largest = std::max(largest, ScaledNorm(difference.data(), net.dimension));
  }
  return (net.count_u - 1) * largest;
}

}  // namespace

// PolynomialSlope writes the slope of a polynomial net of degree n >= 2,
// the differences of the Bernstein coefficients of |H|^2 where H, of
// degree m = n - 1, has the control points D_i = P_{i+1} - P_i (C' = n H):
// (|C'|^2)' = n^2 2m times it. |H|^2 = sum_k c_k B_k^{2m} with c_k =
// sum_{i+j=k} C(m,i) C(m,j) / C(2m,k) D_i . D_j, so min_k c_k bounds |H|^2
// below: when even that is above (sharp / n)^2, no speed falls below
// `sharp`, no minimum is sharp, and it returns false without a slope.
bool SpeedMinimaSearch::PolynomialSlope(const Net& net, double sharp) {
  const size_t stride = static_cast<size_t>(net.stride());
  const size_t d = static_cast<size_t>(net.dimension);
  const int m = net.count_u - 2;
  const size_t points = static_cast<size_t>(m) + 1;
  hodograph_.resize(points * d);
  double sizes = 0.0;  // sum over x of max_i D_i,x^2
  for (size_t x = 0; x < d; ++x) {
    double largest = 0.0;
    for (size_t i = 0; i < points; ++i) {
      const double difference =
          net.values[(i + 1) * stride + x] - net.values[i * stride + x];
      hodograph_[i * d + x] = difference;
      largest = std::max(largest, std::abs(difference));
    }
    sizes += largest * largest;
  }
  binomials_.resize(points);
  for (int i = 0; i <= m; ++i) binomials_[i] = Binomial(m, i);
  squared_speed_.assign(2 * points - 1, 0.0);
  for (size_t i = 0; i < points; ++i) {
    const double* a = hodograph_.data() + i * d;
    double dot = 0.0;
    for (size_t x = 0; x < d; ++x) dot += a[x] * a[x];
    squared_speed_[2 * i] += binomials_[i] * binomials_[i] * dot;
    for (size_t j = i + 1; j < points; ++j) {
      const double* b = hodograph_.data() + j * d;
      dot = 0.0;
      for (size_t x = 0; x < d; ++x) dot += a[x] * b[x];
      squared_speed_[i + j] += 2 * binomials_[i] * binomials_[j] * dot;
    }
  }
  double floor = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < squared_speed_.size(); ++k) {
    squared_speed_[k] /= Binomial(2 * m, static_cast<int>(k));
    floor = std::min(floor, squared_speed_[k]);
  }
  // What rounding may put in a coefficient of |H|^2 (and twice that in a
  // difference): (|C'|^2)' = 2 C' . C'', whose coefficients are off by
  // about their count times the products |C'| |C''| of each coordinate.
  noise_ = kRoundingAgreement * 2.0 * static_cast<double>(points) * sizes;
  const double floor_needed = (sharp / (m + 1)) * (sharp / (m + 1));
  if (std::isfinite(floor) && std::isfinite(floor_needed) &&
      floor - noise_ > floor_needed) {
    return false;
  }
  slope_.resize(squared_speed_.size() - 1);
  for (size_t k = 0; k < slope_.size(); ++k) {
    slope_[k] = squared_speed_[k + 1] - squared_speed_[k];
  }
  return true;
}

// RationalSlope writes a polynomial of the sign of the derivative of
// |C'|^2 of a rational net, and its noise: C = A / w, C' = N / w^2 with
// N = A' w - A w', and d|C'|^2 / ds = 2 (N . N' w - 2 |N|^2 w') / w^5, of
// the sign of N . N' w - 2 |N|^2 w' where w > 0.
void SpeedMinimaSearch::RationalSlope(const Net& net) {
  const size_t stride = static_cast<size_t>(net.stride());
  const size_t points = static_cast<size_t>(net.count_u);
  auto coordinate = [&](size_t x) {
    Bernstein c(points);
    for (size_t i = 0; i < points; ++i) c[i] = net.values[i * stride + x];
    return c;
  };
  const Bernstein w = coordinate(stride - 1);
  const Bernstein dw = Derivative(w);
  slope_.clear();
  double magnitude = 0.0;
  for (int x = 0; x < net.dimension; ++x) {
    const Bernstein a = coordinate(static_cast<size_t>(x));
    const Bernstein da = Derivative(a);
    Bernstein n = Product(da, w);
    Add(n, -1.0, Product(a, dw));
    const Bernstein dn = Derivative(n);
    Bernstein term = Product(Product(n, dn), w);
    Add(term, -2.0, Product(Product(n, n), dw));
    if (slope_.empty()) slope_.assign(term.size(), 0.0);
    Add(slope_, 1.0, term);
    // N's rounding is that of its products, |A'| |w| + |A| |w'|, whatever
    // N itself is (a curve that stands still has N = 0 but for rounding),
    // and N' is off by its degree times as much.
    const double n_size = std::max(
        Largest(n), Largest(da) * Largest(w) + Largest(a) * Largest(dw));
    const double dn_size =
        std::max(Largest(dn), static_cast<double>(n.size()) * n_size);
    magnitude += n_size * (dn_size * Largest(w) + 2 * n_size * Largest(dw));
  }
  noise_ = kRoundingAgreement * static_cast<double>(slope_.size()) * magnitude;
}

// BisectRoot returns the root in (0, 1) of a polynomial negative at 0 and
// positive at 1, to 2^-steps.
double SpeedMinimaSearch::BisectRoot(const double* slope, int steps) {
  const int count = static_cast<int>(slope_.size());
  scratch_.resize(slope_.size());
  double a = 0.0;
  double b = 1.0;
  for (int k = 0; k < steps; ++k) {
    const double mid = 0.5 * (a + b);
    std::copy_n(slope, count, scratch_.data());
    (*Reduce(scratch_.data(), count, 1, mid) < 0.0 ? a : b) = mid;
  }
  return 0.5 * (a + b);
}

// AppendMinima appends, in increasing order, the parameters in (lo, hi)
// where the part of the slope at `depth` (over [lo, hi]; coefficients
// within the noise of 0 count as 0) rises through 0: halving it by de
// Casteljau until a part has no sign change or is 2^-kMinimumDepth wide,
// while the halvings last.
void SpeedMinimaSearch::AppendMinima(int depth, double lo, double hi) {
  const size_t count = slope_.size();
  double* part = parts_.data() + static_cast<size_t>(depth) * count;
  const double noise = noise_;
  auto sign = [noise](double c) { return c < -noise ? -1 : (c > noise); };
  int changes = 0;
  int first = 0;
  int last = 0;
  for (size_t i = 0; i < count; ++i) {
    const int s = sign(part[i]);
    if (s == 0) continue;
    changes += last != 0 && s != last ? 1 : 0;
    if (first == 0) first = s;
    last = s;
  }
  // One change from + to -: a maximum of the speed, no minimum.
  if (changes == 0 || (changes == 1 && first > 0) || halvings_ <= 0) return;
  if (changes == 1 && part[0] < 0.0 && part[count - 1] > 0.0) {
    // One sign change, from - at lo to + at hi: exactly one root, rising
    // (the Bernstein form changes sign at least as often as the
    // polynomial), found by bisection instead of halving.
    const double root = BisectRoot(part, kMinimumDepth - depth);
    cuts_.push_back(lo + root * (hi - lo));
    return;
  }
  if (depth >= kMinimumDepth) {
    if (sign(part[0]) < 0 && sign(part[count - 1]) > 0) {
      cuts_.push_back(0.5 * (lo + hi));
    }
    return;
  }
  // The lower half into the next depth's part, the upper half waiting at
  // the next depth until the lower one is searched.
  --halvings_;
  double* low = part + count;
  double* high = waiting_.data() + static_cast<size_t>(depth + 1) * count;
  HalveNet(part, static_cast<int>(count), 1, 1, true, low, high);
  // A root at the midpoint itself (within the noise), rising from the
  // lower half's last sign to the upper half's first, is neither half's
  // sign change.
  auto first_sign = [&](const double* c) {
    for (size_t i = 0; i < count; ++i) {
      if (sign(c[i]) != 0) return sign(c[i]);
    }
    return 0;
  };
  auto last_sign = [&](const double* c) {
    for (size_t i = count; i-- > 0;) {
      if (sign(c[i]) != 0) return sign(c[i]);
    }
    return 0;
  };
  const bool rises_at_mid =
      sign(low[count - 1]) == 0 && last_sign(low) < 0 && first_sign(high) > 0;
  const double mid = 0.5 * (lo + hi);
  AppendMinima(depth + 1, lo, mid);
  if (rises_at_mid) cuts_.push_back(mid);
  std::copy_n(high, count, low);
  AppendMinima(depth + 1, mid, hi);
}

// KeepSharpMinima keeps the cuts (strictly inside, between the 0 and the 1)
// where the speed of a polynomial net falls below kSmoothSpeedRatio of the
// bound of its largest: elsewhere |C'|^2 stays within 1/16 of its largest
// near the minimum, its square root is smooth there (its nearest complex
// singularity is far), and the rule's error estimate sees its error fall
// as it halves. A rational net keeps every cut.
void SpeedMinimaSearch::KeepSharpMinima(const Net& net, double sharp,
                                        SpeedIntegrator& integrator) {
  if (net.rational || cuts_.size() <= 2) return;
  size_t kept = 1;
  for (size_t k = 1; k + 1 < cuts_.size(); ++k) {
    if (integrator.Speed(net, cuts_[k]) < sharp) cuts_[kept++] = cuts_[k];
  }
  cuts_[kept++] = 1.0;
  cuts_.resize(kept);
}

absl::Span<const double> SpeedMinimaSearch::Cuts(const Net& net,
                                                 SpeedIntegrator& integrator) {
  cuts_.assign(1, 0.0);
  // Where a polynomial net's speed must fall for a minimum to be cut.
  const double sharp = net.rational || net.count_u < 3
                           ? 0.0
                           : kSmoothSpeedRatio * HodographBound(net);
  if (net.count_u >= 3) {
    bool search = true;
    if (net.rational) {
      RationalSlope(net);
    } else {
      search = PolynomialSlope(net, sharp);
    }
    if (search) {
      const size_t levels = static_cast<size_t>(kMinimumDepth) + 2;
      parts_.resize(levels * slope_.size());
      waiting_.resize(levels * slope_.size());
      std::copy(slope_.begin(), slope_.end(), parts_.begin());
      halvings_ = kMaxMinimumHalvings;
      AppendMinima(0, 0.0, 1.0);
    }
  }
  cuts_.push_back(1.0);
  KeepSharpMinima(net, sharp, integrator);
  return cuts_;
}

}  // namespace freeform::internal
