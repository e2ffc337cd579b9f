#include "freeform/core/intersection.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"
#include "base/scaled.h"
#include "base/vectors.h"
#include "freeform/core/points.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "queries/bezier_net.h"

namespace freeform {
namespace {

using internal::LocalModel;
using internal::Net;
using internal::NetEvaluator;
using internal::Pieces;

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Curve parts whose tangent cones are narrower than this (half-angle,
// radians) are checked for an overlap.
constexpr double kNarrowCone = 0.5;
// A parameter difference below this fraction of a domain is no difference
// when stretches are merged and points matched against them.
constexpr double kParameterSlack = 1e-6;
// The most Newton steps refining the nearest sample of a stretch of
// contact.
constexpr int kRefineContactSteps = 8;
// Halving rounds control points by about one unit in the last place of the
// coordinates per level: pairs are pruned only when they are apart by more
// than the tolerance plus this fraction of the largest coordinate, so that
// rounding never prunes a pair within tolerance.
constexpr double kPruneSlack = 64 * std::numeric_limits<double>::epsilon();

using internal::Dot;

// A cone of directions: every tangent of a part is within `angle` of
// `axis` (a unit vector).
struct Cone {
  bool valid = false;
  std::vector<double> axis;
  double angle = 0.0;
};

// AngleTo returns the angle between `vector` and the unit `axis`.
double AngleTo(const double* vector, const double* axis, int dimension) {
  const double along = Dot(vector, axis, dimension);
  double across = 0.0;
  for (int x = 0; x < dimension; ++x) {
    const double r = vector[x] - along * axis[x];
    across += r * r;
  }
  return std::atan2(std::sqrt(across), along);
}

// EdgeCone returns the cone of a curve part's control polygon edges about
// its chord; it holds every tangent of the part (docs/references.md,
// 'Intersections by subdivision'). Invalid when wider than a half-space.
Cone EdgeCone(const std::vector<double>& points, int dimension) {
  Cone cone;
  const int count = static_cast<int>(points.size()) / dimension;
  const double* first = points.data();
  const double* last =
      points.data() + static_cast<size_t>(count - 1) * dimension;
  std::vector<double> edge(static_cast<size_t>(dimension));
  cone.axis.resize(static_cast<size_t>(dimension));
  for (int x = 0; x < dimension; ++x) cone.axis[x] = last[x] - first[x];
  const double length =
      std::sqrt(Dot(cone.axis.data(), cone.axis.data(), dimension));
  if (!(length > 0.0)) return cone;
  for (double& a : cone.axis) a /= length;
  for (int i = 0; i + 1 < count; ++i) {
    const double* p = points.data() + static_cast<size_t>(i) * dimension;
    for (int x = 0; x < dimension; ++x) edge[x] = p[dimension + x] - p[x];
    if (Dot(edge.data(), edge.data(), dimension) == 0.0) continue;
    cone.angle =
        std::max(cone.angle, AngleTo(edge.data(), cone.axis.data(), dimension));
  }
  cone.valid = cone.angle < 0.5 * std::numbers::pi - 1e-9;
  return cone;
}

// ConesApart returns true when no line lies in both double cones (each
// cone and its negative): then two parts meet at most once, since a chord
// between two common points would be in both.
bool ConesApart(const Cone& a, const Cone& b, int dimension) {
  if (!a.valid || !b.valid) return false;
  const double angle = AngleTo(b.axis.data(), a.axis.data(), dimension);
  const double between = std::min(angle, std::numbers::pi - angle);
  return between > a.angle + b.angle + 1e-12;
}

// A part of a Bezier piece over the box [lo, hi] of the piece's
// parameters, with its projected control points and their bounds.
struct Part {
  size_t piece = 0;
  double lo[2] = {0.0, 0.0};
  double hi[2] = {1.0, 1.0};
  Net net;
  std::vector<double> points;
  bool hull = false;
  std::vector<double> box_lo;
  std::vector<double> box_hi;
  double diameter = kInfinity;
  Cone cone;  // curves only

  bool curve() const { return net.count_v == 1; }
};
using PartPtr = std::shared_ptr<const Part>;

PartPtr MakePart(size_t piece, const double* lo, const double* hi, Net net) {
  auto part = std::make_shared<Part>();
  part->piece = piece;
  std::copy_n(lo, 2, part->lo);
  std::copy_n(hi, 2, part->hi);
  part->net = std::move(net);
  const int dim = part->net.dimension;
  part->hull = internal::Project(part->net, part->points);
  part->box_lo.assign(static_cast<size_t>(dim), kInfinity);
  part->box_hi.assign(static_cast<size_t>(dim), -kInfinity);
  for (size_t k = 0; k < part->points.size(); ++k) {
    const size_t x = k % static_cast<size_t>(dim);
    part->box_lo[x] = std::min(part->box_lo[x], part->points[k]);
    part->box_hi[x] = std::max(part->box_hi[x], part->points[k]);
  }
  if (part->hull) {
    part->diameter =
        PointDistance(part->box_lo.data(), part->box_hi.data(), dim);
    if (part->curve()) part->cone = EdgeCone(part->points, dim);
  }
  return part;
}

std::pair<PartPtr, PartPtr> Split(const Part& part) {
  bool in_u = true;
  if (!part.curve()) {
    double along_u = 0.0;
    double along_v = 0.0;
    internal::PolygonLengths(part.points, part.net.dimension, part.net.count_u,
                             part.net.count_v, along_u, along_v);
    in_u = along_u >= along_v;
  }
  Net low, high;
  internal::Halve(part.net, in_u, low, high);
  const int axis = in_u ? 0 : 1;
  const double middle = 0.5 * (part.lo[axis] + part.hi[axis]);
  double lo_high[2] = {part.lo[0], part.lo[1]};
  double hi_low[2] = {part.hi[0], part.hi[1]};
  lo_high[axis] = middle;
  hi_low[axis] = middle;
  return {MakePart(part.piece, part.lo, hi_low, std::move(low)),
          MakePart(part.piece, lo_high, part.hi, std::move(high))};
}

bool BoxesApart(const Part& a, const Part& b, double tolerance) {
  for (size_t x = 0; x < a.box_lo.size(); ++x) {
    if (a.box_lo[x] > b.box_hi[x] + tolerance ||
        b.box_lo[x] > a.box_hi[x] + tolerance) {
      return true;
    }
  }
  return false;
}

// SlabApart returns true when the control points of a and b project onto
// the unit `normal` in intervals more than `tolerance` apart.
bool SlabApart(const double* normal, const Part& a, const Part& b,
               double tolerance) {
  const int dim = a.net.dimension;
  auto range = [&](const Part& part, double& lo, double& hi) {
    lo = kInfinity;
    hi = -kInfinity;
    for (size_t k = 0; k < part.points.size(); k += static_cast<size_t>(dim)) {
      const double d = Dot(normal, part.points.data() + k, dim);
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
  };
  double a_lo, a_hi, b_lo, b_hi;
  range(a, a_lo, a_hi);
  range(b, b_lo, b_hi);
  return b_lo > a_hi + tolerance || a_lo > b_hi + tolerance;
}

// ChordSlabApart is the fat-line test of curve part a against b: the
// normal is the part of (b's centroid - a's first point) across a's chord.
bool ChordSlabApart(const Part& a, const Part& b, double tolerance) {
  const int dim = a.net.dimension;
  if (!a.cone.valid) return false;
  std::vector<double> normal(static_cast<size_t>(dim), 0.0);
  const size_t count = b.points.size() / static_cast<size_t>(dim);
  for (size_t k = 0; k < b.points.size(); ++k) {
    normal[k % static_cast<size_t>(dim)] +=
        b.points[k] / static_cast<double>(count);
  }
  for (int x = 0; x < dim; ++x) normal[x] -= a.points[x];
  const double along = Dot(normal.data(), a.cone.axis.data(), dim);
  for (int x = 0; x < dim; ++x) normal[x] -= along * a.cone.axis[x];
  const double length = std::sqrt(Dot(normal.data(), normal.data(), dim));
  if (!(length > 0.0)) return false;
  for (double& n : normal) n /= length;
  return SlabApart(normal.data(), a, b, tolerance);
}

// CornerNormal writes the unit cross product of a 3D surface part's corner
// diagonals; false when the part is not 3D or the product vanishes.
bool CornerNormal(const Part& surface, double* normal) {
  if (surface.net.dimension != 3) return false;
  const int nu = surface.net.count_u;
  const int nv = surface.net.count_v;
  auto corner = [&](int i, int j) {
    return surface.points.data() + (static_cast<size_t>(i) * nv + j) * 3;
  };
  double d1[3], d2[3];
  for (int x = 0; x < 3; ++x) {
    d1[x] = corner(nu - 1, nv - 1)[x] - corner(0, 0)[x];
    d2[x] = corner(nu - 1, 0)[x] - corner(0, nv - 1)[x];
  }
  normal[0] = d1[1] * d2[2] - d1[2] * d2[1];
  normal[1] = d1[2] * d2[0] - d1[0] * d2[2];
  normal[2] = d1[0] * d2[1] - d1[1] * d2[0];
  const double length = std::sqrt(Dot(normal, normal, 3));
  if (!(length > 0.0)) return false;
  for (int x = 0; x < 3; ++x) normal[x] /= length;
  return true;
}

// NormalSlabApart is the slab test of a 3D surface part across the cross
// product of its corner diagonals.
bool NormalSlabApart(const Part& surface, const Part& other, double tolerance) {
  double normal[3];
  return CornerNormal(surface, normal) &&
         SlabApart(normal, surface, other, tolerance);
}

// Steep returns true when the chord of curve part a rises out of the plane
// of 3D surface part b (across its corner normal) by more than kNarrowCone:
// a curve lying along the surface there would be nearly tangent to it, so
// such a pair is only halved, never sampled for a stretch. (The normal of a
// large, curved part is rough; its halves are tested again.)
bool Steep(const Part& a, const Part& b) {
  double normal[3];
  if (!a.cone.valid || !CornerNormal(b, normal)) return false;
  return std::abs(Dot(a.cone.axis.data(), normal, 3)) > std::sin(kNarrowCone);
}

bool Pruned(const Part& a, const Part& b, double tolerance) {
  if (!a.hull || !b.hull) return false;
  if (BoxesApart(a, b, tolerance)) return true;
  if (a.curve() ? ChordSlabApart(a, b, tolerance)
                : NormalSlabApart(a, b, tolerance)) {
    return true;
  }
  return b.curve() ? ChordSlabApart(b, a, tolerance)
                   : NormalSlabApart(b, a, tolerance);
}

// Extent returns the diagonal of the box of all pieces' finite control
// points.
double Extent(const Pieces& a, const Pieces& b) {
  std::vector<double> lo(static_cast<size_t>(a.dimension), kInfinity);
  std::vector<double> hi(static_cast<size_t>(a.dimension), -kInfinity);
  std::vector<double> point(static_cast<size_t>(a.dimension));
  for (const Pieces* pieces : {&a, &b}) {
    for (const Net& net : pieces->nets) {
      for (int i = 0; i < net.count_u; ++i) {
        for (int j = 0; j < net.count_v; ++j) {
          if (!internal::Point(net, i, j, point.data())) continue;
          for (size_t x = 0; x < point.size(); ++x) {
            lo[x] = std::min(lo[x], point[x]);
            hi[x] = std::max(hi[x], point[x]);
          }
        }
      }
    }
  }
  const double extent = PointDistance(lo.data(), hi.data(), a.dimension);
  return std::isfinite(extent) ? extent : 0.0;
}

// The work (IntersectionOptions::max_work) charged for examining a pair,
// halving a part and evaluating a piece with its partials.
uint64_t ExamineCost(const Part& a, const Part& b) {
  return 4 * (a.net.values.size() + b.net.values.size()) + 16;
}
uint64_t SplitCost(const Part& part) {
  return part.net.values.size() *
             static_cast<uint64_t>(
                 std::max(part.net.count_u, part.net.count_v) + 4) +
         16;
}
uint64_t EvaluationCost(const Net& net) {
  return 6 * net.values.size() + 3 * static_cast<uint64_t>(net.count_u) +
         3 * static_cast<uint64_t>(net.count_v) + 16;
}

// A place on both inputs: the first's piece and parameter x[0] in it, the
// second's piece and parameters x[1] (t) or x[1], x[2] (u, v) in it.
struct Anchor {
  size_t first_piece = 0;
  size_t second_piece = 0;
  double x[3] = {0.0, 0.0, 0.0};
};

// A candidate: the first input from `start` to `end` (its parameters from
// <= to) is within tolerance of the second, whose parameters there lie in
// the box [low, high]. A point found by Newton has start = end; a stretch
// found by sampling is `parallel` when the tangents agree along it. A run
// (merged candidates) keeps its extent and the nearest of its points.
struct Candidate {
  Anchor start;
  Anchor end;
  double from = 0.0;
  double to = 0.0;
  double low[2] = {0.0, 0.0};
  double high[2] = {0.0, 0.0};
  bool parallel = false;
  bool stretch = false;
  bool has_point = false;
  Anchor point;
  double distance = kInfinity;
};

// The pair search shared by curve-curve and curve-surface: parts of the
// first input (a curve) against parts of the second, then the candidates
// found merged into runs.
class PairSearch {
 public:
  // `options` are in the pieces' (scaled) units.
  PairSearch(const Pieces& first, const Pieces& second,
             const IntersectionOptions& options, double slack_s,
             const double* slack_second, double prune_tolerance,
             const CancellationToken* cancel)
      : first_(first),
        second_(second),
        options_(options),
        slack_s_(slack_s),
        slack_second_{slack_second[0], slack_second[1]},
        prune_tolerance_(prune_tolerance),
        rounding_(prune_tolerance - options.tolerance),
        leaf_(std::max(options.tolerance, 1e-7 * Extent(first, second))),
        cancel_(cancel),
        budget_(options.max_work, "max_work", "the intersection search",
                cancel),
        scratch_a_(6 * static_cast<size_t>(first.dimension)),
        scratch_b_(6 * static_cast<size_t>(first.dimension)),
        partials_(6 * static_cast<size_t>(first.dimension)) {}

  // Run examines every pair of pieces and merges what it found.
  absl::Status Run();

  // The merged candidates, in the order of the first parameter: each is an
  // overlap (parallel) or gives its point.
  const std::vector<Candidate>& runs() const { return candidates_; }
  // How much the search's evaluations may differ by rounding alone.
  double rounding() const { return rounding_; }
  // SecondPointOf returns the second input's point at an anchor (valid
  // until the next call).
  const double* SecondPointOf(const Anchor& at);
  // PointOf returns the first input's point at an anchor (valid until the
  // next evaluation).
  const double* PointOf(const Anchor& at);

 private:
  bool Examine(const PartPtr& a, const PartPtr& b);
  // Solve returns the nearest points of the pair found by Newton from the
  // middle of its box, with their distance.
  std::pair<Anchor, double> Solve(const Part& a, const Part& b);
  // Refine runs Newton (at most `max_iterations` steps) from `at` on the box
  // of part a times [lo, hi] of the second's piece; returns the distance.
  double Refine(const Part& a, const double* lo, const double* hi, Anchor& at,
                int max_iterations = 60);
  void Model(const Anchor& at, LocalModel& model);
  // ProjectOnSecond moves at.x[1..] to the point of the second's piece
  // at.second_piece nearest the first's point `point` (within [lo, hi] of
  // that piece, from at.x[1..]); returns the distance.
  double ProjectOnSecond(const double* point, const double* lo,
                         const double* hi, Anchor& at);
  // ProjectOnFirst likewise moves at.x[0] within [lo, hi].
  double ProjectOnFirst(const double* point, double lo, double hi, Anchor& at);
  bool Parallel(const Anchor& at);
  bool FindCurveStretch(const Part& a, const Part& b);
  bool FindSurfaceStretch(const Part& a, const Part& b);
  // SampleStretch checks the first input from `start` to `end` (in the
  // pieces of a and b) against [lo, hi] of the second's piece at samples
  // and records it.
  bool SampleStretch(const Part& a, const Part& b, const Anchor& start,
                     const Anchor& end, const double* lo, const double* hi);
  void AddPoint(const Anchor& at, double distance);
  // AddCandidate records a candidate whose second's parameters lie in
  // [lo, hi] of its piece (at its point when lo is null).
  void AddCandidate(Candidate candidate, const double* lo, const double* hi);
  absl::Status Compact();
  absl::Status Merge();
  absl::Status Finish();
  void Extend(Anchor& anchor, double direction);
  bool OnOverlap(Anchor& at);
  Anchor Walk(Anchor from, double direction, bool on);
  // Inside returns true when the point of `run` lies inside one of the
  // overlaps (sorted by their start, reach[i] the farthest end of the
  // first i + 1).
  bool Inside(const Candidate& run, const std::vector<size_t>& overlaps,
              const std::vector<double>& reach) const;
  bool Joined(const Candidate& run, const Candidate& next);
  bool Connected(const Anchor& first, const Anchor& second);
  bool Near(Anchor& at);
  double DistanceToSecond(Anchor& at);
  double Global(const Anchor& at) const;
  void SecondGlobal(size_t piece, double s, double t, double* uv) const;

  const Pieces& first_;
  const Pieces& second_;
  const IntersectionOptions& options_;
  const double slack_s_;
  const double slack_second_[2];
  const double prune_tolerance_;
  const double rounding_;
  const double leaf_;
  const CancellationToken* const cancel_;
  internal::WorkBudget budget_;
  NetEvaluator evaluator_;
  std::vector<double> scratch_a_;
  std::vector<double> scratch_b_;
  std::vector<double> partials_;
  std::vector<double> residual_;
  std::vector<double> point_;
  std::vector<Candidate> candidates_;
};

void Absorb(Candidate& run, const Candidate& next);

// RunLimit returns the most runs a search keeps: those of the answer and a
// margin for the points that merge at the end.
size_t RunLimit(size_t max_results) { return max_results + 1024; }

// CompactionSize returns the number of candidates at which they are merged.
size_t CompactionSize(size_t max_results) {
  return RunLimit(max_results) + RunLimit(max_results) / 4;
}

int SecondCount(const Pieces& second) {
  return second.parameter_count == 1 ? 1 : 2;
}

double PairSearch::Global(const Anchor& at) const {
  double s = 0.0;
  first_.parameters(at.first_piece, at.x[0], 0.0, &s);
  return s;
}

void PairSearch::SecondGlobal(size_t piece, double s, double t,
                              double* uv) const {
  second_.parameters(piece, s, t, uv);
  if (second_.parameter_count == 1) uv[1] = 0.0;
}

void PairSearch::Model(const Anchor& at, LocalModel& model) {
  const int dim = first_.dimension;
  const bool curves = second_.parameter_count == 1;
  const Net& a = first_.nets[at.first_piece];
  const Net& b = second_.nets[at.second_piece];
  budget_.Add(EvaluationCost(a) + EvaluationCost(b));
  evaluator_.Evaluate(a, at.x[0], 0.0, scratch_a_.data());
  evaluator_.Evaluate(b, at.x[1], curves ? 0.0 : at.x[2], scratch_b_.data());
  // Gauss-Newton on F = A(x0) - B(x1, x2): columns A', -B_u, -B_v.
  const int count = curves ? 2 : 3;
  const double* columns[3] = {scratch_a_.data() + dim, scratch_b_.data() + dim,
                              scratch_b_.data() + 2 * dim};
  const double sign[3] = {1.0, -1.0, -1.0};
  std::vector<double>& f = residual_;
  f.resize(static_cast<size_t>(dim));
  for (int k = 0; k < dim; ++k) f[k] = scratch_a_[k] - scratch_b_[k];
  model = LocalModel{};
  model.value = 0.5 * Dot(f.data(), f.data(), dim);
  for (int i = 0; i < count; ++i) {
    model.gradient[i] = sign[i] * Dot(f.data(), columns[i], dim);
    for (int j = 0; j < count; ++j) {
      model.hessian[i * 3 + j] =
          sign[i] * sign[j] * Dot(columns[i], columns[j], dim);
    }
  }
}

double PairSearch::Refine(const Part& a, const double* lo, const double* hi,
                          Anchor& at, int max_iterations) {
  const int count = 1 + SecondCount(second_);
  const double lower[3] = {a.lo[0], lo[0], lo[1]};
  const double upper[3] = {a.hi[0], hi[0], hi[1]};
  const double value = internal::MinimizeInBox(
      count, lower, upper, at.x,
      [&](const double* x, LocalModel& model) {
        Anchor trial = at;
        std::copy_n(x, 3, trial.x);
        Model(trial, model);
      },
      max_iterations);
  return std::sqrt(2.0 * value);
}

std::pair<Anchor, double> PairSearch::Solve(const Part& a, const Part& b) {
  Anchor at{.first_piece = a.piece, .second_piece = b.piece};
  at.x[0] = 0.5 * (a.lo[0] + a.hi[0]);
  at.x[1] = 0.5 * (b.lo[0] + b.hi[0]);
  at.x[2] = 0.5 * (b.lo[1] + b.hi[1]);
  const double distance = Refine(a, b.lo, b.hi, at);
  return {at, distance};
}

double PairSearch::ProjectOnSecond(const double* point, const double* lo,
                                   const double* hi, Anchor& at) {
  const Net& net = second_.nets[at.second_piece];
  const int count = SecondCount(second_);
  const std::vector<double> query(point, point + first_.dimension);
  double x[2] = {std::clamp(at.x[1], lo[0], hi[0]),
                 count == 2 ? std::clamp(at.x[2], lo[1], hi[1]) : 0.0};
  const double value = internal::MinimizeInBox(
      count, lo, hi, x, [&](const double* y, LocalModel& model) {
        budget_.Add(EvaluationCost(net));
        internal::DistanceModel(evaluator_, net, count, query.data(), y,
                                partials_.data(), model);
      });
  at.x[1] = x[0];
  if (count == 2) at.x[2] = x[1];
  return std::sqrt(2.0 * value);
}

double PairSearch::ProjectOnFirst(const double* point, double lo, double hi,
                                  Anchor& at) {
  const Net& net = first_.nets[at.first_piece];
  const std::vector<double> query(point, point + first_.dimension);
  double x = std::clamp(at.x[0], lo, hi);
  const double value = internal::MinimizeInBox(
      1, &lo, &hi, &x, [&](const double* y, LocalModel& model) {
        budget_.Add(EvaluationCost(net));
        internal::DistanceModel(evaluator_, net, 1, query.data(), y,
                                partials_.data(), model);
      });
  at.x[0] = x;
  return std::sqrt(2.0 * value);
}

// SinToSpan returns the sine of the angle between `tangent` and the span of
// the `count` vectors `span` (1 or 2; 0 where a vector vanishes).
double SinToSpan(const double* tangent, const double* const* span, int count,
                 int dimension) {
  std::vector<double> basis[2];
  int rank = 0;
  for (int k = 0; k < count; ++k) {
    std::vector<double> e(span[k], span[k] + dimension);
    for (int b = 0; b < rank; ++b) {
      const double along = Dot(e.data(), basis[b].data(), dimension);
      for (int x = 0; x < dimension; ++x) e[x] -= along * basis[b][x];
    }
    const double length = std::sqrt(Dot(e.data(), e.data(), dimension));
    if (!(length > 0.0)) return 0.0;
    for (double& v : e) v /= length;
    basis[rank++] = std::move(e);
  }
  const double length = std::sqrt(Dot(tangent, tangent, dimension));
  if (!(length > 0.0)) return 0.0;
  std::vector<double> r(tangent, tangent + dimension);
  for (int b = 0; b < rank; ++b) {
    const double along = Dot(r.data(), basis[b].data(), dimension);
    for (int x = 0; x < dimension; ++x) r[x] -= along * basis[b][x];
  }
  return std::sqrt(Dot(r.data(), r.data(), dimension)) / length;
}

// Parallel returns true when the first input's tangent at `at` lies within
// kOverlapAngle of the second's tangent (line or plane) there.
bool PairSearch::Parallel(const Anchor& at) {
  const int dim = first_.dimension;
  const int count = SecondCount(second_);
  const Net& a = first_.nets[at.first_piece];
  const Net& b = second_.nets[at.second_piece];
  budget_.Add(EvaluationCost(a) + EvaluationCost(b));
  evaluator_.Evaluate(a, at.x[0], 0.0, scratch_a_.data());
  evaluator_.Evaluate(b, at.x[1], count == 2 ? at.x[2] : 0.0,
                      scratch_b_.data());
  const double* span[2] = {scratch_b_.data() + dim,
                           scratch_b_.data() + 2 * dim};
  return SinToSpan(scratch_a_.data() + dim, span, count, dim) <= kOverlapAngle;
}

void PairSearch::AddCandidate(Candidate candidate, const double* lo,
                              const double* hi) {
  candidate.from = Global(candidate.start);
  candidate.to = Global(candidate.end);
  if (candidate.to < candidate.from) {
    std::swap(candidate.from, candidate.to);
    std::swap(candidate.start, candidate.end);
  }
  // The second's parameters: the box given, else the point's.
  const size_t piece = candidate.start.second_piece;
  const double* point = candidate.start.x + 1;
  const double* box_lo = lo != nullptr ? lo : point;
  const double* box_hi = hi != nullptr ? hi : point;
  for (int c = 0; c < 2; ++c) {
    candidate.low[c] = kInfinity;
    candidate.high[c] = -kInfinity;
  }
  for (const double s : {box_lo[0], box_hi[0]}) {
    for (const double t : {box_lo[1], box_hi[1]}) {
      double uv[2];
      SecondGlobal(piece, s, t, uv);
      for (int c = 0; c < 2; ++c) {
        candidate.low[c] = std::min(candidate.low[c], uv[c]);
        candidate.high[c] = std::max(candidate.high[c], uv[c]);
      }
    }
  }
  // Compact keeps the candidates under CompactionSize; one pair adds at most
  // two more. The capacity grows to that, no more.
  if (candidates_.size() == candidates_.capacity()) {
    candidates_.reserve(std::min(2 * candidates_.capacity() + 16,
                                 CompactionSize(options_.max_results) + 2));
  }
  candidates_.push_back(std::move(candidate));
}

void PairSearch::AddPoint(const Anchor& at, double distance) {
  AddCandidate(Candidate{.start = at,
                         .end = at,
                         .has_point = true,
                         .point = at,
                         .distance = distance},
               nullptr, nullptr);
}

bool PairSearch::SampleStretch(const Part& a, const Part& b,
                               const Anchor& start, const Anchor& end,
                               const double* lo, const double* hi) {
  const int dim = first_.dimension;
  const int count = SecondCount(second_);
  std::vector<double> from(static_cast<size_t>(dim));
  std::copy_n(PointOf(start), dim, from.data());
  if (PointDistance(from.data(), PointOf(end), dim) <=
      std::max(options_.separation, 10.0 * options_.tolerance)) {
    return false;
  }
  const int samples =
      2 * (a.net.count_u + b.net.count_u + (count == 2 ? b.net.count_v : 0)) +
      1;
  // Whether the tangents agree at every sample, and at any: where they agree
  // somewhere but not everywhere, an overlap may lie inside and the pair is
  // halved (as soon as that shows: the ends, then the middle, then the
  // rest).
  bool all = Parallel(start);
  bool any = all;
  const bool end_parallel = Parallel(end);
  all = all && end_parallel;
  any = any || end_parallel;
  if (any && !all) return false;
  Anchor nearest = start;
  double nearest_distance = kInfinity;
  // The box of the second's parameters along the stretch.
  double low[2], high[2];
  for (int c = 0; c < 2; ++c) {
    low[c] = std::min(start.x[c + 1], end.x[c + 1]);
    high[c] = std::max(start.x[c + 1], end.x[c + 1]);
  }
  const int middle = (samples + 1) / 2;
  for (int step = 0; step < samples; ++step) {
    if (budget_.exhausted()) return false;
    const int k = step == 0 ? middle : (step <= middle - 1 ? step : step + 1);
    const double f = static_cast<double>(k) / (samples + 1);
    Anchor at = start;
    at.x[0] = start.x[0] + f * (end.x[0] - start.x[0]);
    for (int c = 1; c <= count; ++c) {
      at.x[c] = start.x[c] + f * (end.x[c] - start.x[c]);
    }
    std::copy_n(PointOf(at), dim, from.data());
    const double d = ProjectOnSecond(from.data(), lo, hi, at);
    if (d > options_.tolerance) return false;
    for (int c = 0; c < 2; ++c) {
      low[c] = std::min(low[c], at.x[c + 1]);
      high[c] = std::max(high[c], at.x[c + 1]);
    }
    const bool parallel = Parallel(at);
    all = all && parallel;
    any = any || parallel;
    if (any && !all) return false;
    if (d < nearest_distance) {
      nearest = at;
      nearest_distance = d;
    }
  }
  Candidate stretch{
      .start = start, .end = end, .parallel = all, .stretch = true};
  // A stretch of contact that is not an overlap has its nearest point.
  if (!all) {
    stretch.has_point = true;
    stretch.point = nearest;
    // From within tolerance already: a crossing converges in a few steps,
    // and a flat contact does not improve much with more.
    stretch.distance = Refine(a, lo, hi, stretch.point, kRefineContactSteps);
  }
  AddCandidate(std::move(stretch), low, high);
  return true;
}

// FindCurveStretch checks whether parts a and b of two curves run along
// each other between the end points of either that lie on the other.
bool PairSearch::FindCurveStretch(const Part& a, const Part& b) {
  const int dim = first_.dimension;
  const double tolerance = options_.tolerance;
  std::vector<Anchor> ends;
  const size_t last_a = a.points.size() - static_cast<size_t>(dim);
  const size_t last_b = b.points.size() - static_cast<size_t>(dim);
  for (int side = 0; side < 2; ++side) {
    Anchor at{.first_piece = a.piece, .second_piece = b.piece};
    at.x[0] = side == 0 ? a.lo[0] : a.hi[0];
    at.x[1] = 0.5 * (b.lo[0] + b.hi[0]);
    const double* point = a.points.data() + (side == 0 ? 0 : last_a);
    if (ProjectOnSecond(point, b.lo, b.hi, at) <= tolerance) {
      ends.push_back(at);
    }
  }
  for (int side = 0; side < 2; ++side) {
    Anchor at{.first_piece = a.piece, .second_piece = b.piece};
    at.x[0] = 0.5 * (a.lo[0] + a.hi[0]);
    at.x[1] = side == 0 ? b.lo[0] : b.hi[0];
    const double* point = b.points.data() + (side == 0 ? 0 : last_b);
    if (ProjectOnFirst(point, a.lo[0], a.hi[0], at) <= tolerance) {
      ends.push_back(at);
    }
  }
  if (ends.size() < 2) return false;
  std::sort(ends.begin(), ends.end(),
            [](const Anchor& x, const Anchor& y) { return x.x[0] < y.x[0]; });
  return SampleStretch(a, b, ends.front(), ends.back(), b.lo, b.hi);
}

// FindSurfaceStretch checks whether curve part a lies along the surface
// piece of part b from end to end (projected onto the whole piece, from b's
// middle: a curve part seldom lies within one part's box).
bool PairSearch::FindSurfaceStretch(const Part& a, const Part& b) {
  const int dim = first_.dimension;
  const double lo[2] = {0.0, 0.0};
  const double hi[2] = {1.0, 1.0};
  Anchor ends[2];
  for (int side = 0; side < 2; ++side) {
    Anchor& at = ends[side];
    at = Anchor{.first_piece = a.piece, .second_piece = b.piece};
    at.x[0] = side == 0 ? a.lo[0] : a.hi[0];
    at.x[1] = 0.5 * (b.lo[0] + b.hi[0]);
    at.x[2] = 0.5 * (b.lo[1] + b.hi[1]);
    const double* point =
        a.points.data() +
        (side == 0 ? 0 : a.points.size() - static_cast<size_t>(dim));
    if (ProjectOnSecond(point, lo, hi, at) > options_.tolerance) {
      return false;
    }
  }
  return SampleStretch(a, b, ends[0], ends[1], lo, hi);
}

// Examine returns true when the pair needs no halving: it is pruned, its
// single point was found, it is a leaf, or it is a stretch along which the
// inputs stay within tolerance.
bool PairSearch::Examine(const PartPtr& a, const PartPtr& b) {
  if (Pruned(*a, *b, prune_tolerance_)) return true;
  const bool small = a->diameter <= leaf_ && b->diameter <= leaf_;
  const bool curves = b->curve();
  const bool single = curves && ConesApart(a->cone, b->cone, first_.dimension);
  if (small || single) {
    const auto [at, distance] = Solve(*a, *b);
    if (distance <= options_.tolerance) {
      AddPoint(at, distance);
      return true;
    }
    if (small) return true;
    if (single) return false;
  }
  if (!a->cone.valid || !(a->cone.angle < kNarrowCone)) return false;
  if (curves) {
    return b->cone.valid && b->cone.angle < kNarrowCone &&
           FindCurveStretch(*a, *b);
  }
  return b->hull && !Steep(*a, *b) && FindSurfaceStretch(*a, *b);
}

absl::Status PairSearch::Run() {
  RETURN_IF_ERROR(CheckCancelled(cancel_));
  const double zero[2] = {0.0, 0.0};
  const double one[2] = {1.0, 1.0};
  std::vector<PartPtr> second_parts;
  for (size_t j = 0; j < second_.nets.size(); ++j) {
    second_parts.push_back(MakePart(j, zero, one, second_.nets[j]));
    budget_.Add(SplitCost(*second_parts.back()));
  }
  // Piece i of the first input is searched against the pieces of the second
  // whose boxes it meets, to the end, before piece i + 1: the stack holds
  // one piece's pairs and their halves, never all pairs of pieces.
  std::vector<std::pair<PartPtr, PartPtr>> stack;
  for (size_t i = 0; i < first_.nets.size(); ++i) {
    const PartPtr a = MakePart(i, zero, one, first_.nets[i]);
    budget_.Add(SplitCost(*a) +
                second_parts.size() * static_cast<uint64_t>(first_.dimension));
    for (const PartPtr& b : second_parts) {
      if (!BoxesApart(*a, *b, prune_tolerance_)) stack.emplace_back(a, b);
    }
    while (!stack.empty()) {
      RETURN_IF_ERROR(budget_.Check());
      auto [a_part, b_part] = std::move(stack.back());
      stack.pop_back();
      budget_.Add(ExamineCost(*a_part, *b_part));
      if (Examine(a_part, b_part)) {
        RETURN_IF_ERROR(Compact());
        continue;
      }
      const bool first_larger = a_part->diameter >= b_part->diameter;
      budget_.Add(SplitCost(first_larger ? *a_part : *b_part));
      if (first_larger) {
        auto [low, high] = Split(*a_part);
        stack.emplace_back(std::move(low), b_part);
        stack.emplace_back(std::move(high), b_part);
      } else {
        auto [low, high] = Split(*b_part);
        stack.emplace_back(a_part, std::move(low));
        stack.emplace_back(a_part, std::move(high));
      }
    }
  }
  RETURN_IF_ERROR(Merge());
  if (candidates_.size() > RunLimit(options_.max_results)) {
    return ExhaustedFieldError("max_results",
                               absl::StrCat("more than ", options_.max_results,
                                            " separate intersections"));
  }
  RETURN_IF_ERROR(Finish());
  return budget_.Check();
}

// Compact merges the candidates once they reach CompactionSize, so that
// their memory stays bounded; more runs than RunLimit are
// RESOURCE_EXHAUSTED naming "max_results".
absl::Status PairSearch::Compact() {
  const size_t limit = RunLimit(options_.max_results);
  if (candidates_.size() < CompactionSize(options_.max_results)) {
    return absl::OkStatus();
  }
  RETURN_IF_ERROR(Merge());
  if (candidates_.size() <= limit) return budget_.Check();
  return ExhaustedFieldError(
      "max_results",
      absl::StrCat("more than ", limit, " separate intersections, more than ",
                   options_.max_results));
}

const double* PairSearch::SecondPointOf(const Anchor& at) {
  const Net& net = second_.nets[at.second_piece];
  budget_.Add(EvaluationCost(net));
  evaluator_.Evaluate(net, at.x[1], at.x[2], scratch_b_.data());
  return scratch_b_.data();
}

const double* PairSearch::PointOf(const Anchor& at) {
  budget_.Add(EvaluationCost(first_.nets[at.first_piece]));
  evaluator_.Evaluate(first_.nets[at.first_piece], at.x[0], 0.0,
                      scratch_a_.data());
  return scratch_a_.data();
}

// Merge sorts the candidates by the first parameter and joins each into a
// run before it when Joined: one of the newest kMaxActiveRuns runs it
// starts within, or one of the kRecentRuns that ended last. The runs take
// the candidates' place (there are never more of them).
absl::Status PairSearch::Merge() {
  std::vector<Candidate>& candidates = candidates_;
  constexpr size_t kMaxActiveRuns = 16;
  constexpr size_t kRecentRuns = 1;
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& x, const Candidate& y) {
              return x.from < y.from || (x.from == y.from && x.to > y.to);
            });
  size_t runs = 0;  // candidates[0, runs) are the runs
  std::vector<size_t> active;
  std::vector<size_t> recent;
  auto retire = [&](size_t k) {
    recent.push_back(active[k]);
    if (recent.size() > kRecentRuns) recent.erase(recent.begin());
    active.erase(active.begin() + static_cast<std::ptrdiff_t>(k));
  };
  for (size_t n = 0; n < candidates.size(); ++n) {
    RETURN_IF_ERROR(budget_.Check());
    Candidate& next = candidates[n];
    for (size_t k = 0; k < active.size();) {
      if (candidates[active[k]].to + slack_s_ < next.from ||
          active.size() > kMaxActiveRuns) {
        retire(k);
      } else {
        ++k;
      }
    }
    bool joined = false;
    for (std::vector<size_t>* runs_of : {&active, &recent}) {
      for (size_t k = runs_of->size(); k-- > 0 && !joined;) {
        const size_t index = (*runs_of)[k];
        if (!Joined(candidates[index], next)) continue;
        Absorb(candidates[index], next);
        joined = true;
        if (runs_of == &recent) {
          recent.erase(recent.begin() + static_cast<std::ptrdiff_t>(k));
          active.push_back(index);
        }
      }
    }
    if (joined) continue;
    if (runs != n) candidates[runs] = std::move(next);
    active.push_back(runs++);
  }
  candidates.resize(runs);
  return absl::OkStatus();
}

// Absorb joins candidate `next` into `run`.
void Absorb(Candidate& run, const Candidate& next) {
  if (next.to > run.to) {
    run.to = next.to;
    run.end = next.end;
  }
  for (int c = 0; c < 2; ++c) {
    run.low[c] = std::min(run.low[c], next.low[c]);
    run.high[c] = std::max(run.high[c], next.high[c]);
  }
  run.stretch = run.stretch || next.stretch;
  run.parallel = run.parallel || next.parallel;
  if (next.has_point && next.distance < run.distance) {
    run.has_point = true;
    run.point = next.point;
    run.distance = next.distance;
  }
}

// Finish drops the point runs that lie inside an overlap (in the first's
// parameter and the second's, as points at a curve's seam do) and merges
// those within max(separation, tolerance) of each other, keeping the
// nearest point.
absl::Status PairSearch::Finish() {
  const size_t dim = static_cast<size_t>(first_.dimension);
  std::vector<size_t> overlaps;  // indices of the overlap runs
  std::vector<size_t> points;    // and of the point runs
  std::vector<double> coordinates(candidates_.size() * dim);
  for (size_t k = 0; k < candidates_.size(); ++k) {
    Candidate& run = candidates_[k];
    if (!run.parallel) continue;
    RETURN_IF_ERROR(budget_.Check());
    Extend(run.start, -1.0);
    Extend(run.end, 1.0);
    run.from = Global(run.start);
    run.to = Global(run.end);
    overlaps.push_back(k);
  }
  // The overlaps in the order of their start, and the farthest end of those
  // up to each (Inside).
  std::sort(overlaps.begin(), overlaps.end(), [&](size_t a, size_t b) {
    return candidates_[a].from < candidates_[b].from;
  });
  std::vector<double> reach(overlaps.size());
  for (size_t i = 0; i < overlaps.size(); ++i) {
    reach[i] = std::max(i > 0 ? reach[i - 1] : -kInfinity,
                        candidates_[overlaps[i]].to);
  }
  for (size_t k = 0; k < candidates_.size(); ++k) {
    const Candidate& run = candidates_[k];
    if (run.parallel || !run.has_point || Inside(run, overlaps, reach)) {
      continue;
    }
    RETURN_IF_ERROR(budget_.Check());
    std::copy_n(PointOf(run.point), dim, coordinates.begin() + k * dim);
    points.push_back(k);
  }
  auto at = [&](size_t k) { return coordinates.data() + k * dim; };
  std::sort(points.begin(), points.end(),
            [&](size_t a, size_t b) { return at(a)[0] < at(b)[0]; });
  // A point joins the last kept point within `near` among those whose first
  // coordinate is within `near` of its own.
  const double near = std::max(options_.separation, options_.tolerance);
  std::vector<bool> keep(candidates_.size(), false);
  for (size_t k = 0; k < candidates_.size(); ++k) {
    keep[k] = candidates_[k].parallel;
  }
  std::vector<size_t> kept;
  for (const size_t k : points) {
    size_t into = SIZE_MAX;
    for (size_t m = kept.size(); m-- > 0;) {
      if (at(kept[m])[0] < at(k)[0] - near) break;
      if (PointDistance(at(kept[m]), at(k), dim) <= near) {
        into = kept[m];
        break;
      }
    }
    if (into == SIZE_MAX) {
      kept.push_back(k);
      keep[k] = true;
    } else if (candidates_[k].distance < candidates_[into].distance) {
      candidates_[into].point = candidates_[k].point;
      candidates_[into].distance = candidates_[k].distance;
    }
  }
  size_t runs = 0;
  for (size_t k = 0; k < candidates_.size(); ++k) {
    if (!keep[k]) continue;
    if (runs != k) candidates_[runs] = std::move(candidates_[k]);
    ++runs;
  }
  candidates_.resize(runs);
  return absl::OkStatus();
}

// Extend moves the end `anchor` of an overlap (direction -1: its start, 1:
// its end, within its piece of the first) to where the first input leaves
// the tolerance of the second, or passes the end of the second's piece
// (OnOverlap): outwards while it is on the overlap, else inwards.
void PairSearch::Extend(Anchor& anchor, double direction) {
  Anchor at = anchor;
  if (OnOverlap(at)) {
    anchor = Walk(at, direction, true);
  } else {
    anchor = Walk(anchor, -direction, false);
  }
}

// OnOverlap projects the first's point at `at` onto the second (Near) and
// returns true when it is within tolerance there, and not beyond the end
// of the second's piece: nearest to a point of its boundary, off it by
// more than rounding (a fringe where the first runs on past the second's
// end).
bool PairSearch::OnOverlap(Anchor& at) {
  const double distance = DistanceToSecond(at);
  if (distance > options_.tolerance) return false;
  for (int c = 1; c <= SecondCount(second_); ++c) {
    const bool end = at.x[c] == 0.0 || at.x[c] == 1.0;
    if (end && distance > rounding_) return false;
  }
  return true;
}

// Walk returns the last point from `from` along the first's parameter in
// `direction` (within its piece) where OnOverlap is `on`, as it is at
// `from`: steps doubling from 2^-40 of the piece, then bisection, each point
// projected onto the second from the last one where it held.
Anchor PairSearch::Walk(Anchor from, double direction, bool on) {
  Anchor last = from;
  Anchor beyond;
  bool found = false;
  for (double step = 0x1p-40; !found && !budget_.exhausted(); step *= 2) {
    Anchor probe = last;
    probe.x[0] = std::clamp(last.x[0] + direction * step, 0.0, 1.0);
    if (probe.x[0] == last.x[0]) break;  // the piece's end
    found = OnOverlap(probe) != on;
    (found ? beyond : last) = probe;
  }
  for (int k = 0; found && k < 64 && !budget_.exhausted(); ++k) {
    Anchor middle = last;
    middle.x[0] = 0.5 * (last.x[0] + beyond.x[0]);
    if (middle.x[0] == last.x[0] || middle.x[0] == beyond.x[0]) break;
    (OnOverlap(middle) == on ? last : beyond) = middle;
  }
  return last;
}

// Inside returns true when the point of `run` lies inside one of the
// overlaps (the first's parameter in its interval, the second's in its box).
bool PairSearch::Inside(const Candidate& run,
                        const std::vector<size_t>& overlaps,
                        const std::vector<double>& reach) const {
  double x[2];
  SecondGlobal(run.point.second_piece, run.point.x[1], run.point.x[2], x);
  const double s = Global(run.point);
  // The overlaps starting before s, latest first, while one of them reaches
  // it.
  size_t i = static_cast<size_t>(
      std::upper_bound(
          overlaps.begin(), overlaps.end(), s + slack_s_,
          [&](double value, size_t k) { return value < candidates_[k].from; }) -
      overlaps.begin());
  while (i-- > 0 && reach[i] + slack_s_ >= s) {
    const Candidate& overlap = candidates_[overlaps[i]];
    bool inside = s <= overlap.to + slack_s_;
    for (int c = 0; c < SecondCount(second_); ++c) {
      inside = inside && x[c] >= overlap.low[c] - slack_second_[c] &&
               x[c] <= overlap.high[c] + slack_second_[c];
    }
    if (inside) return true;
  }
  return false;
}

// Joined returns true when `next` (starting at or after `run` starts) is
// part of `run`: it starts inside a stretch of it where the second's
// parameters meet too, or its point is within the separation of the run's
// end, or the inputs stay within tolerance between the two.
bool PairSearch::Joined(const Candidate& run, const Candidate& next) {
  if ((run.stretch || next.stretch) && next.from <= run.to + slack_s_) {
    bool meet = true;
    for (int c = 0; c < SecondCount(second_); ++c) {
      meet = meet && next.low[c] <= run.high[c] + slack_second_[c] &&
             run.low[c] <= next.high[c] + slack_second_[c];
    }
    if (meet) return true;
  }
  const int dim = first_.dimension;
  const double* end = PointOf(run.end);
  point_.assign(end, end + dim);
  if (PointDistance(point_.data(), PointOf(next.start), dim) <=
      std::max(options_.separation, options_.tolerance)) {
    return true;
  }
  return Connected(run.end, next.start);
}

// Connected returns true when the inputs stay within tolerance of each
// other between two anchors, along one sheet of the second: the first
// input is sampled between them (on one piece, or two neighbouring ones),
// each sample projected onto the second from the projection of the
// sample before, from `left` onwards and from `right` backwards; the two
// tracks must meet in the middle, at the same parameters of the second.
bool PairSearch::Connected(const Anchor& first, const Anchor& second) {
  const bool ordered = Global(first) <= Global(second);
  const Anchor& left = ordered ? first : second;
  const Anchor& right = ordered ? second : first;
  const bool same = left.first_piece == right.first_piece;
  if (!same && right.first_piece != left.first_piece + 1) return false;
  constexpr int kSteps = 4;  // samples per side, the middle included
  Anchor tracks[2] = {left, right};
  for (int side = 0; side < 2; ++side) {
    Anchor& at = tracks[side];
    const Anchor& from = side == 0 ? left : right;
    // The first's parameter runs from the anchor to the middle of the two,
    // or to the end of its piece that meets the other's.
    const double middle =
        same ? 0.5 * (left.x[0] + right.x[0]) : (side == 0 ? 1.0 : 0.0);
    for (int k = 1; k <= kSteps; ++k) {
      at.x[0] = from.x[0] + (middle - from.x[0]) * k / kSteps;
      if (!Near(at)) return false;
    }
  }
  double meet[2][2];
  for (int side = 0; side < 2; ++side) {
    SecondGlobal(tracks[side].second_piece, tracks[side].x[1],
                 tracks[side].x[2], meet[side]);
  }
  for (int c = 0; c < SecondCount(second_); ++c) {
    if (std::abs(meet[0][c] - meet[1][c]) > slack_second_[c]) return false;
  }
  return true;
}

// DistanceToSecond projects the first input's point at `at` onto the
// second's piece at.second_piece from at.x[1..] (updating them) and returns
// the distance.
double PairSearch::DistanceToSecond(Anchor& at) {
  const int dim = first_.dimension;
  const double lo[2] = {0.0, 0.0};
  const double hi[2] = {1.0, 1.0};
  const double* sample = PointOf(at);
  point_.assign(sample, sample + dim);
  return ProjectOnSecond(point_.data(), lo, hi, at);
}

// Near returns true when the first input at `at` is within tolerance of
// the second's piece (DistanceToSecond).
bool PairSearch::Near(Anchor& at) {
  return DistanceToSecond(at) <= options_.tolerance;
}

absl::Status CheckOptions(const IntersectionOptions& options) {
  return internal::CheckTolerances(options.tolerance, options.separation);
}

absl::Status CheckResults(size_t results, const IntersectionOptions& options) {
  if (results <= options.max_results) return absl::OkStatus();
  return ExhaustedFieldError(
      "max_results",
      absl::StrCat(results, " intersections, more than ", options.max_results));
}

double Width(const ParameterDomain& domain) {
  return domain.end - domain.start;
}

// A finished search: the pieces, in units of 2^exponent, and the runs.
struct Found {
  const Pieces& first;
  const Pieces& second;
  int exponent;
  PairSearch& search;

  // AppendPoint appends the first input's point at `at`, in the inputs'
  // units.
  void AppendPoint(const Anchor& at, std::vector<double>& points) const {
    const double* point = search.PointOf(at);
    for (int x = 0; x < first.dimension; ++x) {
      points.push_back(std::ldexp(point[x], exponent));
    }
  }
};

// Intersect checks the inputs, runs the pair search of `first` against
// `second` (a curve or a surface; `field` names its dimension, `names` the
// two inputs) and returns finish(the finished search). The pieces are
// divided by a power of two (exact) to coordinates of about 1, so that no
// squared distance overflows or underflows, and the tolerance is checked
// against what double precision resolves on them (CheckResolvableAt).
template <typename Second, typename Finish>
auto Intersect(const Curve& first, const Second& second,
               absl::string_view field, const IntersectionOptions& options,
               double slack_s, const double* slack_second,
               const CancellationToken* cancel, Finish finish)
    -> decltype(finish(std::declval<const Found&>())) {
  RETURN_IF_ERROR(CheckOptions(options));
  if (DimensionOf(second) != DimensionOf(first)) {
    return InvalidFieldError(
        field, absl::StrCat("must be the first input's dimension ",
                            DimensionOf(first), ", got ", DimensionOf(second)));
  }
  absl::StatusOr<Pieces> a = internal::LiftPieces(first, cancel);
  if (!a.ok()) return a.status();
  absl::StatusOr<Pieces> b = internal::LiftPieces(second, cancel);
  if (!b.ok()) return b.status();
  Pieces* const both[] = {&*a, &*b};
  const absl::StatusOr<internal::QueryScale> scale =
      internal::ScaleForQuery(options.tolerance, both);
  if (!scale.ok()) return scale.status();
  const int exponent = scale->exponent;
  IntersectionOptions scaled = options;
  scaled.tolerance = std::ldexp(options.tolerance, -exponent);
  scaled.separation = std::ldexp(options.separation, -exponent);
  const double prune_tolerance =
      scaled.tolerance + kPruneSlack * scale->largest;
  PairSearch search(*a, *b, scaled, slack_s, slack_second, prune_tolerance,
                    cancel);
  RETURN_IF_ERROR(search.Run());
  return finish(Found{*a, *b, exponent, search});
}

// CheckResolved checks that the inputs at the rounded parameters of an
// answer found at `at` still meet within the tolerance: the first's at `s`,
// the second's at `second` (t, or (u, v)), each mapped back onto the piece
// that found it (Pieces::locals). Where a knot span is only a few ulps of
// its position (spans of 0.125 at 1e15) or extreme weights move the
// geometry far between neighbouring doubles, the nearest double parameter
// lies elsewhere, and the answer would name a parameter whose point is not
// the intersection (UnresolvedError, naming the input that moved: `first`
// or `second`, `curve` or `surface`). The search works in units of
// 2^exponent; `rounding` is what its evaluations may differ by.
absl::Status CheckResolved(const Found& found, const Anchor& at, double s,
                           const double* second, double tolerance,
                           double rounding) {
  Anchor rounded = at;
  double local[2];
  found.first.locals(at.first_piece, &s, local);
  rounded.x[0] = local[0];
  found.second.locals(at.second_piece, second, local);
  rounded.x[1] = local[0];
  rounded.x[2] = local[1];
  const int dim = found.first.dimension;
  const double* exact = found.search.PointOf(at);
  const std::vector<double> point(exact, exact + dim);
  const double* first_at = found.search.PointOf(rounded);
  const std::vector<double> first(first_at, first_at + dim);
  const double* second_point = found.search.SecondPointOf(rounded);
  // The answer's point is the first input's at s, and the inputs meet
  // there within the tolerance.
  const double first_moved =
      internal::ScaledDistanceOf(first.data(), point.data(), dim);
  const double gap =
      internal::ScaledDistanceOf(second_point, first.data(), dim);
  const double allowed = tolerance + rounding;
  if (first_moved <= allowed && gap <= allowed) return absl::OkStatus();
  const bool curves = found.second.parameter_count == 1;
  if (first_moved > allowed) {
    return internal::UnresolvedError(curves ? "first" : "curve", {s},
                                     std::ldexp(first_moved, found.exponent));
  }
  return internal::UnresolvedError(
      curves ? "second" : "surface",
      absl::MakeConstSpan(second,
                          static_cast<size_t>(SecondCount(found.second))),
      std::ldexp(gap, found.exponent));
}

// CurveAnswer returns the points and overlaps of two curves.
absl::StatusOr<CurveIntersections> CurveAnswer(
    const IntersectionOptions& options, const Found& found) {
  const std::vector<Candidate>& runs = found.search.runs();
  RETURN_IF_ERROR(CheckResults(runs.size(), options));
  CurveIntersections result{.dimension = found.first.dimension};
  for (const Candidate& run : runs) {
    auto second_at = [&](const Anchor& at) {
      double t = 0.0;
      found.second.parameters(at.second_piece, at.x[1], 0.0, &t);
      return t;
    };
    const double tolerance = std::ldexp(options.tolerance, -found.exponent);
    if (run.parallel) {
      const double second_from = second_at(run.start);
      const double second_to = second_at(run.end);
      RETURN_IF_ERROR(CheckResolved(found, run.start, run.from, &second_from,
                                    tolerance, found.search.rounding()));
      RETURN_IF_ERROR(CheckResolved(found, run.end, run.to, &second_to,
                                    tolerance, found.search.rounding()));
      result.first_intervals.insert(result.first_intervals.end(),
                                    {run.from, run.to});
      result.second_intervals.insert(result.second_intervals.end(),
                                     {second_from, second_to});
      continue;
    }
    double s = 0.0;
    found.first.parameters(run.point.first_piece, run.point.x[0], 0.0, &s);
    const double t = second_at(run.point);
    RETURN_IF_ERROR(CheckResolved(found, run.point, s, &t, tolerance,
                                  found.search.rounding()));
    result.first_parameters.push_back(s);
    result.second_parameters.push_back(t);
    found.AppendPoint(run.point, result.points);
  }
  return result;
}

// SurfaceAnswer returns the points and overlaps of a curve and a surface
// in the order of the curve's parameter.
absl::StatusOr<CurveSurfaceIntersections> SurfaceAnswer(
    const IntersectionOptions& options, const Found& found) {
  const std::vector<Candidate>& runs = found.search.runs();
  RETURN_IF_ERROR(CheckResults(runs.size(), options));
  CurveSurfaceIntersections result{.dimension = found.first.dimension};
  const double tolerance = std::ldexp(options.tolerance, -found.exponent);
  auto surface_at = [&](const Anchor& at, double* uv) {
    found.second.parameters(at.second_piece, at.x[1], at.x[2], uv);
  };
  for (const Candidate& run : runs) {
    double uv[2];
    if (run.parallel) {
      for (const auto& [end, t] :
           {std::pair{&run.start, run.from}, std::pair{&run.end, run.to}}) {
        surface_at(*end, uv);
        RETURN_IF_ERROR(CheckResolved(found, *end, t, uv, tolerance,
                                      found.search.rounding()));
      }
      result.curve_intervals.insert(result.curve_intervals.end(),
                                    {run.from, run.to});
      continue;
    }
    double t = 0.0;
    found.first.parameters(run.point.first_piece, run.point.x[0], 0.0, &t);
    surface_at(run.point, uv);
    RETURN_IF_ERROR(CheckResolved(found, run.point, t, uv, tolerance,
                                  found.search.rounding()));
    result.curve_parameters.push_back(t);
    result.surface_parameters.insert(result.surface_parameters.end(),
                                     {uv[0], uv[1]});
    found.AppendPoint(run.point, result.points);
  }
  return result;
}

}  // namespace

uint64_t IntersectionCandidateBytes(size_t max_results, int dimension) {
  // The candidates' capacity (AddCandidate), and Finish's points'
  // coordinates, indices of the overlaps, of the points and of those kept,
  // and a flag per run.
  const uint64_t runs = RunLimit(max_results);
  return (CompactionSize(max_results) + 2) * sizeof(Candidate) +
         runs * (8 * static_cast<uint64_t>(dimension) + 3 * sizeof(size_t) + 1);
}

absl::StatusOr<CurveIntersections> IntersectCurves(
    const Curve& first, const Curve& second, const IntersectionOptions& options,
    const CancellationToken* cancel) {
  const double slack_second[2] = {kParameterSlack * Width(DomainOf(second)),
                                  0.0};
  return Intersect(
      first, second, "second.dimension", options,
      kParameterSlack * Width(DomainOf(first)), slack_second, cancel,
      [&](const Found& found) { return CurveAnswer(options, found); });
}

absl::StatusOr<CurveSurfaceIntersections> IntersectCurveSurface(
    const Curve& curve, const Surface& surface,
    const IntersectionOptions& options, const CancellationToken* cancel) {
  const SurfaceDomain domain = DomainOf(surface);
  const double slack_second[2] = {
      kParameterSlack * (domain.u_end - domain.u_start),
      kParameterSlack * (domain.v_end - domain.v_start)};
  return Intersect(
      curve, surface, "surface.dimension", options,
      kParameterSlack * Width(DomainOf(curve)), slack_second, cancel,
      [&](const Found& found) { return SurfaceAnswer(options, found); });
}

}  // namespace freeform
