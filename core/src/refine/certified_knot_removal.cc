#include "refine/certified_knot_removal.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <queue>
#include <utility>
#include <vector>

#include "freeform/core/status_macros.h"

namespace freeform::internal {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// SpanOf returns the index mu of the non-empty span [knot(mu), knot(mu + 1))
// holding t, the last index with knot(mu) <= t, among `size` sorted knots
// read through `knot`, with knot(0) <= t. Given the span of a smaller t as
// `hint` (-1: none), it walks on from there: a sorted batch costs O(1) per
// value after the first binary search.
template <typename Knot>
int SpanOf(const Knot& knot, int size, double t, int hint) {
  if (hint >= 0) {
    while (hint + 1 < size && knot(hint + 1) <= t) ++hint;
    return hint;
  }
  int lo = 0;
  int hi = size;
  while (hi - lo > 1) {
    const int mid = lo + (hi - lo) / 2;
    if (knot(mid) <= t) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return lo;
}

// OsloRow writes alpha[k], k = 0..p, the coefficient of the coarse B-spline
// N_{mu-p+k,p} (knots read through `knot`) in the fine B-spline with knots
// fine[0..p+1], by the discrete B-spline recurrence of the Oslo algorithm
// (Cohen, Lyche and Riesenfeld 1980; docs/references.md, 'Knot removal'):
// with the coarse knots u_i = knot(i) and x = fine[k] at level k,
//   a_{i,k} = (x - u_i) / (u_{i+k} - u_i) a_{i,k-1}
//           + (u_{i+k+1} - x) / (u_{i+k+1} - u_{i+1}) a_{i+1,k-1},
// starting from a_{mu,0} = 1 for the coarse span mu holding fine[0]. Every
// term is nonnegative where its factor a is not 0, so the fine coefficient
// sum_k alpha[k] P_{mu-p+k} is a convex combination. Functions with a
// negative index (before an unclamped start) get 0.
template <typename Knot>
void OsloRow(const Knot& knot, int mu, int p, const double* fine,
             double* alpha) {
  std::fill(alpha, alpha + p + 1, 0.0);
  alpha[p] = 1.0;
  for (int k = 1; k <= p; ++k) {
    const double x = fine[k];
    for (int i = std::max(mu - k, 0); i <= mu; ++i) {
      const int slot = p - mu + i;
      double value = 0.0;
      if (i > mu - k) {
        const double left = knot(i);
        value += (x - left) / (knot(i + k) - left) * alpha[slot];
      }
      if (i < mu) {
        const double right = knot(i + k + 1);
        value += (right - x) / (right - knot(i + 1)) * alpha[slot + 1];
      }
      alpha[slot] = value;
    }
  }
}

// FineCoefficient writes into `out` (`width` values) the coefficient of
// the fine B-spline with knots fine[0..p+1] of the spline whose knots and
// points (`width` values each) are read through `knot` and `point`; mu is
// the coarse span holding fine[0] (SpanOf). `alpha` holds p + 1 doubles.
template <typename Knot, typename Point>
void FineCoefficient(const Knot& knot, const Point& point, int mu, int p,
                     const double* fine, int width, double* alpha,
                     double* out) {
  OsloRow(knot, mu, p, fine, alpha);
  std::fill(out, out + width, 0.0);
  for (int k = 0; k <= p; ++k) {
    if (alpha[k] == 0.0) continue;
    const double* source = point(mu - p + k);
    for (int x = 0; x < width; ++x) out[x] += alpha[k] * source[x];
  }
}

// SolveFor writes q = (b - known_weight * known) / own_weight: one control
// point of a removal from the equation b = own_weight q + known_weight
// known (The NURBS Book, section 5.4).
void SolveFor(const double* b, const double* known, double own_weight,
              double known_weight, int block, double* q) {
  for (int x = 0; x < block; ++x) {
    q[x] = (b[x] - known_weight * known[x]) / own_weight;
  }
}

// Worse returns the deviation that combines both: the larger distance and
// the smaller weight.
Deviation Worse(Deviation a, Deviation b) {
  return {std::max(a.distance, b.distance), std::min(a.weight, b.weight)};
}

}  // namespace

std::vector<char> RelevantFunctions(absl::Span<const double> knots, int p) {
  const int n = static_cast<int>(knots.size()) - p - 2;
  std::vector<char> relevant(static_cast<size_t>(n) + 1);
  for (int j = 0; j <= n; ++j) {
    const int first = std::max(j, p);
    const int last = std::min(j + p, n);
    relevant[static_cast<size_t>(j)] = knots[static_cast<size_t>(first)] <
                                       knots[static_cast<size_t>(last) + 1];
  }
  return relevant;
}

// ---------------------------------------------------------------------------
// LineReference.

LineReference::LineReference(std::vector<double> lines, int sub_count,
                             int width, bool rational,
                             std::vector<char> relevant,
                             std::optional<Refinement> refinement)
    : lines_(std::move(lines)),
      sub_count_(sub_count),
      width_(width),
      rational_(rational),
      relevant_(std::move(relevant)),
      refinement_(std::move(refinement)) {
  if (!rational_) return;
  const int dim = width_ - 1;
  std::vector<double> lo(static_cast<size_t>(dim), kInfinity);
  std::vector<double> hi(static_cast<size_t>(dim), -kInfinity);
  for (size_t k = 0; k < lines_.size(); k += static_cast<size_t>(width_)) {
    for (int x = 0; x < dim; ++x) {
      const double value = lines_[k + x] / lines_[k + dim];
      lo[x] = std::min(lo[x], value);
      hi[x] = std::max(hi[x], value);
    }
  }
  centre_.resize(static_cast<size_t>(dim));
  for (int x = 0; x < dim; ++x) centre_[x] = 0.5 * (lo[x] + hi[x]);
  for (size_t k = 0; k < lines_.size(); k += static_cast<size_t>(width_)) {
    double squared = 0.0;
    for (int x = 0; x < dim; ++x) {
      const double d = lines_[k + x] / lines_[k + dim] - centre_[x];
      squared += d * d;
    }
    radius_ = std::max(radius_, std::sqrt(squared));
  }
}

Deviation LineReference::CompareSubPoint(const double* original,
                                         const double* candidate,
                                         Deviation deviation) const {
  const int dim = rational_ ? width_ - 1 : width_;
  const double weight_change = rational_ ? original[dim] - candidate[dim] : 0.0;
  double squared = 0.0;
  for (int x = 0; x < dim; ++x) {
    const double centred = rational_ ? weight_change * centre_[x] : 0.0;
    const double d = original[x] - candidate[x] - centred;
    squared += d * d;
  }
  double distance = std::sqrt(squared);
  if (rational_) {
    distance += radius_ * std::abs(weight_change);
    deviation.weight = std::min(deviation.weight, candidate[dim]);
  }
  deviation.distance = std::max(deviation.distance, distance);
  return deviation;
}

Deviation LineReference::Compare(int line, const double* block) const {
  const double* original =
      lines_.data() + static_cast<size_t>(line) * sub_count_ * width_;
  Deviation deviation;
  if (!refinement_.has_value()) {
    for (int k = 0; k < sub_count_; ++k) {
      if (!relevant_[static_cast<size_t>(k)]) continue;
      const size_t offset = static_cast<size_t>(k) * width_;
      deviation = CompareSubPoint(original + offset, block + offset, deviation);
    }
    return deviation;
  }
  const Refinement& refinement = *refinement_;
  const int p = refinement.degree;
  const auto knot = [&](int i) {
    return refinement.coarse[static_cast<size_t>(i)];
  };
  const auto point = [&](int i) {
    return block + static_cast<size_t>(i) * width_;
  };
  std::vector<double> alpha(static_cast<size_t>(p) + 1);
  std::vector<double> refined(static_cast<size_t>(width_));
  int mu = -1;
  for (int k = 0; k < sub_count_; ++k) {
    if (!relevant_[static_cast<size_t>(k)]) continue;
    const double* fine = &refinement.fine[static_cast<size_t>(k)];
    mu = SpanOf(knot, static_cast<int>(refinement.coarse.size()), fine[0], mu);
    FineCoefficient(knot, point, mu, p, fine, width_, alpha.data(),
                    refined.data());
    deviation = CompareSubPoint(original + static_cast<size_t>(k) * width_,
                                refined.data(), deviation);
  }
  return deviation;
}

bool LineReference::PositiveWeights(absl::Span<const double> points) const {
  if (!rational_) return true;
  for (size_t k = static_cast<size_t>(width_) - 1; k < points.size();
       k += static_cast<size_t>(width_)) {
    if (!(points[k] > 0.0)) return false;
  }
  return true;
}

double LineReference::Bound(double distance, double weight) const {
  if (!rational_) return distance;
  if (distance == 0.0) return 0.0;
  return weight > 0.0 ? distance / weight : kInfinity;
}

size_t LineReference::work() const {
  const size_t per_point = refinement_.has_value()
                               ? static_cast<size_t>(refinement_->degree + 1) *
                                     (width_ + 4) * (refinement_->degree + 1)
                               : static_cast<size_t>(width_) + 1;
  return static_cast<size_t>(sub_count_) * per_point + 1;
}

// ---------------------------------------------------------------------------
// MaxTree.

MaxTree::MaxTree(size_t size, double fill)
    : size_(size), nodes_(2 * size, fill) {}

void MaxTree::Set(size_t index, double value) {
  size_t node = index + size_;
  nodes_[node] = value;
  for (node /= 2; node >= 1; node /= 2) {
    nodes_[node] = std::max(nodes_[2 * node], nodes_[2 * node + 1]);
  }
}

double MaxTree::Max(size_t begin, size_t end) const {
  double result = -kInfinity;
  for (begin += size_, end += size_; begin < end; begin /= 2, end /= 2) {
    if (begin % 2 == 1) result = std::max(result, nodes_[begin++]);
    if (end % 2 == 1) result = std::max(result, nodes_[--end]);
  }
  return result;
}

// ---------------------------------------------------------------------------
// KnotRemover.

// The removal of one copy of knots[index] (multiplicity s) from the current
// spline: the points first..last (first = index - p, last = index - s)
// become last - first points, and the fine (original) coefficients
// fine_lo..fine_hi, those of the fine B-splines inside the support of the
// change, get new deviations.
struct KnotRemover::Candidate {
  int index = 0;
  int first = 0;
  int last = 0;
  std::vector<double> replacement;
  int fine_lo = 0;
  int fine_hi = -1;
  std::vector<Deviation> deviations;
  // The bound from the changed coefficients alone (the greedy order), and
  // from all of them (the certificate).
  double local_bound = 0.0;
  double bound = 0.0;

  double* point(int k, int block) {
    return replacement.data() + static_cast<size_t>(k) * block;
  }
};

KnotRemover::KnotRemover(BlockSpline start, const LineReference* reference)
    : spline_(std::move(start)),
      reference_(reference),
      fine_(spline_.knots),
      relevant_(RelevantFunctions(fine_, spline_.degree)),
      distances_(relevant_.size(), 0.0),
      weights_(relevant_.size(), -kInfinity) {}

absl::StatusOr<KnotRemover> KnotRemover::Create(BlockSpline start,
                                                const LineReference* reference,
                                                CancellationPoll& poll) {
  KnotRemover remover(std::move(start), reference);
  for (size_t j = 0; j < remover.relevant_.size(); ++j) {
    if (!remover.relevant_[j]) continue;
    RETURN_IF_ERROR(poll.Done(reference->work()));
    const Deviation deviation = reference->Compare(
        static_cast<int>(j), remover.spline_.point(static_cast<int>(j)));
    remover.distances_.Set(j, deviation.distance);
    remover.weights_.Set(j, -deviation.weight);
  }
  return remover;
}

double KnotRemover::bound() const {
  const size_t size = relevant_.size();
  return reference_->Bound(std::max(distances_.Max(0, size), 0.0),
                           -weights_.Max(0, size));
}

int KnotRemover::LastIndexOf(double knot) const {
  const auto it =
      std::upper_bound(spline_.knots.begin(), spline_.knots.end(), knot);
  if (it == spline_.knots.begin() || *(it - 1) != knot) return -1;
  return static_cast<int>(it - spline_.knots.begin()) - 1;
}

bool KnotRemover::Interior(double knot) const {
  const size_t p = static_cast<size_t>(spline_.degree);
  return knot > fine_[p] && knot < fine_[fine_.size() - p - 1];
}

KnotRemover::Candidate KnotRemover::Evaluate(int index) const {
  Candidate candidate = Solve(index);
  Certify(candidate);
  return candidate;
}

KnotRemover::Candidate KnotRemover::Solve(int index) const {
  const int p = spline_.degree;
  const int block = spline_.block;
  const std::vector<double>& knots = spline_.knots;
  const double u = knots[static_cast<size_t>(index)];
  int s = 1;
  while (knots[static_cast<size_t>(index - s)] == u) ++s;
  if (s == p + 1) return SolveAtStep(index);
  Candidate c{.index = index, .first = index - p, .last = index - s};
  // The new points from both ends of the run (The NURBS Book A5.8): the
  // left half from the equations first.., the right half from ..last; the
  // middle equation is left over.
  const int count = c.last - c.first;
  c.replacement.resize(static_cast<size_t>(count) * block);
  const auto alpha = [&](int i) {
    const double start = knots[static_cast<size_t>(i)];
    return (u - start) / (knots[static_cast<size_t>(i + p + 1)] - start);
  };
  const int left = count / 2;
  for (int k = 0; k < left; ++k) {
    const double a = alpha(c.first + k);
    SolveFor(spline_.point(c.first + k),
             k == 0 ? spline_.point(c.first - 1) : c.point(k - 1, block), a,
             1.0 - a, block, c.point(k, block));
  }
  for (int k = count - 1; k >= left; --k) {
    const double a = alpha(c.first + k + 1);
    SolveFor(spline_.point(c.first + k + 1),
             k == count - 1 ? spline_.point(c.last + 1) : c.point(k + 1, block),
             1.0 - a, a, block, c.point(k, block));
  }
  return c;
}

KnotRemover::Candidate KnotRemover::SolveAtStep(int index) const {
  // Knot u = knots[index] of multiplicity p + 1 (a degree-0 step): the
  // B-splines first and first + 1 meet at u with a jump from one point to
  // the next, and removing one copy joins them into one B-spline over both
  // spans. Its point is their midpoint, which halves the larger deviation;
  // Certify measures what that costs.
  const int block = spline_.block;
  Candidate c{.index = index,
              .first = index - spline_.degree - 1,
              .last = index - spline_.degree};
  c.replacement.resize(static_cast<size_t>(block));
  const double* left = spline_.point(c.first);
  const double* right = spline_.point(c.last);
  for (int x = 0; x < block; ++x) {
    c.replacement[static_cast<size_t>(x)] = 0.5 * left[x] + 0.5 * right[x];
  }
  return c;
}

void KnotRemover::Certify(Candidate& c) const {
  const int p = spline_.degree;
  const int block = spline_.block;
  const std::vector<double>& knots = spline_.knots;
  // The candidate's knots and points, read without building it.
  const auto knot = [&](int g) {
    return knots[static_cast<size_t>(g < c.index ? g : g + 1)];
  };
  const auto point = [&](int g) -> const double* {
    if (g < c.first) return spline_.point(g);
    if (g < c.last) return c.point(g - c.first, block);
    return spline_.point(g + 1);
  };
  // The change lies in [knots[first], knots[last + p + 1]]; the fine
  // B-splines inside it are those whose coefficients change.
  const double a = knots[static_cast<size_t>(c.first)];
  const double b = knots[static_cast<size_t>(c.last + p + 1)];
  c.fine_lo = static_cast<int>(std::lower_bound(fine_.begin(), fine_.end(), a) -
                               fine_.begin());
  c.fine_hi = std::min(
      static_cast<int>(std::upper_bound(fine_.begin(), fine_.end(), b) -
                       fine_.begin()) -
          p - 2,
      static_cast<int>(relevant_.size()) - 1);
  std::vector<double> alpha(static_cast<size_t>(p) + 1);
  std::vector<double> refined(static_cast<size_t>(block));
  Deviation local;
  int mu = -1;
  for (int j = c.fine_lo; j <= c.fine_hi; ++j) {
    Deviation deviation;
    if (relevant_[static_cast<size_t>(j)]) {
      const double* fine = &fine_[static_cast<size_t>(j)];
      mu = SpanOf(knot, static_cast<int>(knots.size()) - 1, fine[0], mu);
      FineCoefficient(knot, point, mu, p, fine, block, alpha.data(),
                      refined.data());
      deviation = reference_->Compare(j, refined.data());
    }
    c.deviations.push_back(deviation);
    local = Worse(local, deviation);
  }
  const Deviation all = Worse(local, Outside(c.fine_lo, c.fine_hi));
  c.local_bound = reference_->Bound(local.distance, local.weight);
  c.bound = reference_->Bound(all.distance, all.weight);
  // A NaN, or a new weight that is not positive (the result would not be a
  // valid curve even where its refinement is), cannot go.
  if (!(c.local_bound >= 0.0) || !reference_->PositiveWeights(c.replacement)) {
    c.local_bound = kInfinity;
    c.bound = kInfinity;
  }
}

Deviation KnotRemover::Outside(int lo, int hi) const {
  const size_t begin = static_cast<size_t>(std::max(lo, 0));
  const size_t end = static_cast<size_t>(std::max(hi + 1, lo));
  const size_t size = relevant_.size();
  return {std::max({distances_.Max(0, begin), distances_.Max(end, size), 0.0}),
          -std::max(weights_.Max(0, begin), weights_.Max(end, size))};
}

size_t KnotRemover::EvaluationWork(const Candidate& candidate) const {
  const size_t window = candidate.deviations.size() + 1;
  const size_t p = static_cast<size_t>(spline_.degree) + 1;
  return window * (reference_->work() + p * (p + spline_.block));
}

void KnotRemover::Apply(Candidate& c) {
  BlockSpline& s = spline_;
  const size_t block = static_cast<size_t>(s.block);
  s.knots.erase(s.knots.begin() + c.index);
  std::copy(c.replacement.begin(), c.replacement.end(),
            s.points.begin() + static_cast<std::ptrdiff_t>(c.first * block));
  const auto removed =
      s.points.begin() + static_cast<std::ptrdiff_t>(c.last * block);
  s.points.erase(removed, removed + static_cast<std::ptrdiff_t>(block));
  for (int j = c.fine_lo; j <= c.fine_hi; ++j) {
    const Deviation& deviation =
        c.deviations[static_cast<size_t>(j - c.fine_lo)];
    distances_.Set(static_cast<size_t>(j), deviation.distance);
    weights_.Set(static_cast<size_t>(j), -deviation.weight);
  }
  ++removals_;
}

absl::Status KnotRemover::Remove(double knot, int times, double tolerance,
                                 CancellationPoll& poll) {
  for (int t = 0; t < times; ++t) {
    const int index = LastIndexOf(knot);
    if (index < 0) break;
    Candidate candidate = Evaluate(index);
    RETURN_IF_ERROR(poll.Done(EvaluationWork(candidate)));
    if (!(candidate.bound <= tolerance)) break;
    Apply(candidate);
  }
  return absl::OkStatus();
}

// The greedy order of Simplify: the distinct interior knot values, each
// with its latest key in a min-queue. Every push of a value gets a new
// stamp, so its older entries are stale and skipped.
class KnotQueue {
 public:
  struct Entry {
    double key = 0.0;
    int value = 0;
    int stamp = 0;
    bool operator>(const Entry& other) const {
      return key != other.key ? key > other.key : value > other.value;
    }
  };

  explicit KnotQueue(std::vector<double> values)
      : values_(std::move(values)), stamps_(values_.size(), 0) {}

  int size() const { return static_cast<int>(values_.size()); }
  double value(int v) const { return values_[static_cast<size_t>(v)]; }
  // IndexOf returns the index of a value of the queue.
  int IndexOf(double u) const {
    return static_cast<int>(
        std::lower_bound(values_.begin(), values_.end(), u) - values_.begin());
  }
  void Push(int v, double key) {
    queue_.push({key, v, ++stamps_[static_cast<size_t>(v)]});
  }
  // Requeue puts a fresh entry back with a new key and its stamp.
  void Requeue(const Entry& entry, double key) {
    queue_.push({key, entry.value, entry.stamp});
  }
  // Pop returns the fresh entry with the smallest key, if any.
  std::optional<Entry> Pop() {
    while (!queue_.empty()) {
      const Entry entry = queue_.top();
      queue_.pop();
      if (entry.stamp == stamps_[static_cast<size_t>(entry.value)]) {
        return entry;
      }
    }
    return std::nullopt;
  }

 private:
  std::vector<double> values_;
  std::vector<int> stamps_;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue_;
};

absl::Status KnotRemover::Push(KnotQueue& queue, int v,
                               CancellationPoll& poll) const {
  const int index = LastIndexOf(queue.value(v));
  if (index < 0) return absl::OkStatus();
  const Candidate candidate = Evaluate(index);
  queue.Push(v, candidate.local_bound);
  return poll.Done(EvaluationWork(candidate));
}

absl::Status KnotRemover::Refresh(KnotQueue& queue, int index,
                                  CancellationPoll& poll) const {
  // The candidates whose last copy lies within [index - 2p, index + 2p - 1]
  // read points or knots that the removal at `index` changed; for degree 0,
  // whose removals join two neighbouring points, [index - 1, index]
  // (docs/references.md, 'Knot removal'): evaluate them again.
  const int p = spline_.degree;
  const int size = static_cast<int>(spline_.knots.size());
  const int before = p == 0 ? 1 : 2 * p;
  const int after = p == 0 ? 0 : 2 * p - 1;
  double previous = std::nan("");
  for (int g = std::max(index - before, 0);
       g <= std::min(index + after, size - 1); ++g) {
    const double u = spline_.knots[static_cast<size_t>(g)];
    if (u == previous || !Interior(u)) continue;
    previous = u;
    RETURN_IF_ERROR(Push(queue, queue.IndexOf(u), poll));
  }
  return absl::OkStatus();
}

absl::Status KnotRemover::Simplify(double tolerance, CancellationPoll& poll) {
  std::vector<double> values;
  for (const double u : spline_.knots) {
    if (Interior(u) && (values.empty() || values.back() != u)) {
      values.push_back(u);
    }
  }
  KnotQueue queue(std::move(values));
  for (int v = 0; v < queue.size(); ++v) {
    RETURN_IF_ERROR(Push(queue, v, poll));
  }
  // Keys are local bounds, never above the full bound: once the smallest
  // exceeds the tolerance, nothing more can go.
  for (std::optional<KnotQueue::Entry> entry = queue.Pop();
       entry.has_value() && entry->key <= tolerance; entry = queue.Pop()) {
    const int index = LastIndexOf(queue.value(entry->value));
    if (index < 0) continue;
    Candidate candidate = Evaluate(index);
    RETURN_IF_ERROR(poll.Done(EvaluationWork(candidate)));
    if (candidate.local_bound != entry->key) {
      queue.Requeue(*entry, candidate.local_bound);  // changed nearby
      continue;
    }
    if (!(candidate.bound <= tolerance)) continue;
    Apply(candidate);
    RETURN_IF_ERROR(Refresh(queue, index, poll));
  }
  return absl::OkStatus();
}

}  // namespace freeform::internal
