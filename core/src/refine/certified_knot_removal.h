// The engine behind knot_removal.h: knot removal (The NURBS Book A5.8) on a
// B-spline whose control points are blocks of values (a curve's points, or
// the lines of a surface's net), certified against the original geometry
// by refining every candidate back onto the original knots with the Oslo
// algorithm (docs/references.md, 'Knot removal'). Internal to the core.
#ifndef FREEFORM_CORE_SRC_REFINE_CERTIFIED_KNOT_REMOVAL_H_
#define FREEFORM_CORE_SRC_REFINE_CERTIFIED_KNOT_REMOVAL_H_

#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "freeform/core/cancellation.h"

namespace freeform::internal {

// A B-spline of degree `degree` whose control points are blocks of `block`
// values each, point after point: a curve's (homogeneous) points, or the
// lines of a surface's net, each line several sub-points one after the
// other.
struct BlockSpline {
  int degree = 0;
  int block = 0;
  std::vector<double> knots;
  std::vector<double> points;

  int count() const {
    return block > 0 ? static_cast<int>(points.size() / block) : 0;
  }
  const double* point(int i) const {
    return points.data() + static_cast<size_t>(i) * block;
  }
};

// How far one refined control point (block) of a candidate lies from the
// original's: the largest of |P - Q| (polynomial) or of
// |(w P - q Q) - (w - q) c| + rho |w - q| (rational) over its sub-points,
// and the smallest candidate weight q among them (infinite when there is
// none, as for a basis function that vanishes on the domain).
struct Deviation {
  double distance = 0.0;
  double weight = std::numeric_limits<double>::infinity();
};

// RelevantFunctions returns, for each B-spline N_{j,p} on `knots`
// (knots.size() - p - 1 of them), whether it is nonzero somewhere on the
// domain [u_p, u_{n+1}]: whether one of its spans j..j+p inside the domain
// is not empty.
std::vector<char> RelevantFunctions(absl::Span<const double> knots, int p);

// The original geometry that candidates are measured against: lines of
// `sub_count` sub-points of `width` values (homogeneous, weight last, when
// rational). Only sub-points marked in `relevant` count. With a
// refinement, a candidate's line has its sub-points on the coarse knots of
// the other direction and is refined onto the fine (original) ones before
// the comparison.
class LineReference {
 public:
  struct Refinement {
    int degree = 0;
    std::vector<double> coarse;
    std::vector<double> fine;
  };

  LineReference(std::vector<double> lines, int sub_count, int width,
                bool rational, std::vector<char> relevant,
                std::optional<Refinement> refinement);

  // Compare returns the deviation of `block` (a candidate's line) from
  // line `line` of the original.
  Deviation Compare(int line, const double* block) const;

  // PositiveWeights says whether every weight among `points` (sub-points of
  // `width` values) is positive; true when polynomial.
  bool PositiveWeights(absl::Span<const double> points) const;

  // Bound returns the certified distance of the worst deviation `distance`
  // with the smallest weight `weight`: distance / weight when rational
  // (infinite unless weight > 0), else distance.
  double Bound(double distance, double weight) const;

  // work returns the rough cost of one Compare, for cancellation polling.
  size_t work() const;

 private:
  Deviation CompareSubPoint(const double* original, const double* candidate,
                            Deviation deviation) const;

  std::vector<double> lines_;
  int sub_count_;
  int width_;
  bool rational_;
  std::vector<char> relevant_;
  std::optional<Refinement> refinement_;
  std::vector<double> centre_;  // rational: the bounding box centre c
  double radius_ = 0.0;         // rational: rho = max |P - c|
};

// A segment tree of the largest value over ranges of a fixed-size array:
// O(log n) to set a value or to query a range.
class MaxTree {
 public:
  MaxTree(size_t size, double fill);
  void Set(size_t index, double value);
  // Max returns the largest value in [begin, end) (-infinity when empty).
  double Max(size_t begin, size_t end) const;

 private:
  size_t size_;
  std::vector<double> nodes_;
};

class KnotQueue;

// Removes knots from a BlockSpline whose knots start as the original ones,
// keeping for every original (fine) basis function the deviation of the
// current spline's refined coefficient from the original's, so that every
// removal is certified against the original by looking only at the p + 1
// control points it changes.
class KnotRemover {
 public:
  // Create starts from `start`, whose knots are the original knots of this
  // direction and whose deviations `reference` measures (zero when `start`
  // is the original itself). `reference` must outlive the remover.
  static absl::StatusOr<KnotRemover> Create(BlockSpline start,
                                            const LineReference* reference,
                                            CancellationPoll& poll);

  // Remove removes the knot value `knot` (a knot inside the domain) up to
  // `times` times, while the bound stays within `tolerance`.
  absl::Status Remove(double knot, int times, double tolerance,
                      CancellationPoll& poll);

  // Simplify removes, one after the other, the knot whose removal has the
  // smallest local bound, while the bound stays within `tolerance`.
  absl::Status Simplify(double tolerance, CancellationPoll& poll);

  const BlockSpline& spline() const { return spline_; }
  int removals() const { return removals_; }
  // bound returns the certified distance of the current spline from the
  // original.
  double bound() const;

 private:
  struct Candidate;

  KnotRemover(BlockSpline start, const LineReference* reference);

  // LastIndexOf returns the index of the last copy of `knot` in the
  // current knots, -1 when there is none.
  int LastIndexOf(double knot) const;
  // Interior says whether `knot` lies strictly inside the domain.
  bool Interior(double knot) const;
  // Evaluate returns the removal of knots[index], the last copy of its
  // value: Solve's new points, certified by Certify.
  Candidate Evaluate(int index) const;
  Candidate Solve(int index) const;
  // SolveAtStep is Solve for a knot of multiplicity p + 1 (degree 0).
  Candidate SolveAtStep(int index) const;
  void Certify(Candidate& candidate) const;
  // Outside returns the worst deviation of the fine coefficients outside
  // [lo, hi].
  Deviation Outside(int lo, int hi) const;
  void Apply(Candidate& candidate);
  size_t EvaluationWork(const Candidate& candidate) const;
  // Push queues the candidate of value v of `queue`, if the value is still
  // a knot; Refresh does so for every candidate near a removal at `index`.
  absl::Status Push(KnotQueue& queue, int v, CancellationPoll& poll) const;
  absl::Status Refresh(KnotQueue& queue, int index,
                       CancellationPoll& poll) const;

  BlockSpline spline_;
  const LineReference* reference_;
  std::vector<double> fine_;
  std::vector<char> relevant_;
  MaxTree distances_;
  MaxTree weights_;  // negated weights, so that Max is the smallest weight
  int removals_ = 0;
};

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_REFINE_CERTIFIED_KNOT_REMOVAL_H_
