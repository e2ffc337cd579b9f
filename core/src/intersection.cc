#include "freeform/core/intersection.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"
#include "bezier_net.h"
#include "freeform/core/points.h"
#include "freeform/core/status.h"

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
// when overlaps are merged and points matched against them.
constexpr double kParameterSlack = 1e-6;

double Dot(const double* a, const double* b, int dimension) {
  double sum = 0.0;
  for (int x = 0; x < dimension; ++x) sum += a[x] * b[x];
  return sum;
}

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

// NormalSlabApart is the slab test of a 3D surface part across the cross
// product of its corner diagonals.
bool NormalSlabApart(const Part& surface, const Part& other, double tolerance) {
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
  double normal[3] = {d1[1] * d2[2] - d1[2] * d2[1],
                      d1[2] * d2[0] - d1[0] * d2[2],
                      d1[0] * d2[1] - d1[1] * d2[0]};
  const double length = std::sqrt(Dot(normal, normal, 3));
  if (!(length > 0.0)) return false;
  for (double& n : normal) n /= length;
  return SlabApart(normal, surface, other, tolerance);
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

// A point where the inputs meet: x holds the parameters in the pieces
// (s on the first; t, or u and v, on the second).
struct Hit {
  size_t first_piece = 0;
  size_t second_piece = 0;
  double x[3] = {0.0, 0.0, 0.0};
  double distance = kInfinity;
};

// The pair search shared by curve-curve and curve-surface: parts of the
// first input (a curve) against parts of the second.
class PairSearch {
 public:
  PairSearch(const Pieces& first, const Pieces& second,
             const IntersectionOptions& options,
             const CancellationToken* cancel)
      : first_(first),
        second_(second),
        options_(options),
        cancel_(cancel),
        leaf_(std::max(options.tolerance, 1e-7 * Extent(first, second))),
        scratch_a_(6 * static_cast<size_t>(first.dimension)),
        scratch_b_(6 * static_cast<size_t>(first.dimension)) {}

  // Run examines every pair of pieces.
  absl::Status Run();

  // Overlaps found, in the first's and second's parameters: s0, s1, t0, t1.
  const std::vector<std::array<double, 4>>& overlaps() const {
    return overlaps_;
  }
  // Hits, matched and merged.
  std::vector<Hit> DistinctHits();
  // PointOf returns the first input's point of a hit.
  const double* PointOf(const Hit& hit);

 private:
  bool Examine(const PartPtr& a, const PartPtr& b);
  Hit Solve(const Part& a, const Part& b);
  void Model(size_t first_piece, size_t second_piece, const double* x,
             LocalModel& model);
  bool FindOverlap(const Part& a, const Part& b);
  // Project returns the parameter of the point of curve piece `piece`
  // (of `pieces`) nearest `point` within [lo, hi], and the distance.
  std::pair<double, double> Project(bool on_first, size_t piece,
                                    const double* point, double lo, double hi,
                                    double guess);
  double SinAngle(const Part& a, double s, const Part& b, double t);
  bool SameHit(const Hit& a, const Hit& b);

  const Pieces& first_;
  const Pieces& second_;
  const IntersectionOptions& options_;
  const CancellationToken* cancel_;
  const double leaf_;
  NetEvaluator evaluator_;
  std::vector<double> scratch_a_;
  std::vector<double> scratch_b_;
  std::vector<double> residual_;
  std::vector<double> point_;
  std::vector<Hit> hits_;
  std::vector<std::array<double, 4>> overlaps_;
};

void PairSearch::Model(size_t first_piece, size_t second_piece, const double* x,
                       LocalModel& model) {
  const int dim = first_.dimension;
  const bool curves = second_.parameter_count == 1;
  evaluator_.Evaluate(first_.nets[first_piece], x[0], 0.0, scratch_a_.data());
  evaluator_.Evaluate(second_.nets[second_piece], x[1], curves ? 0.0 : x[2],
                      scratch_b_.data());
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

Hit PairSearch::Solve(const Part& a, const Part& b) {
  Hit hit{.first_piece = a.piece, .second_piece = b.piece};
  const int count = b.curve() ? 2 : 3;
  const double lower[3] = {a.lo[0], b.lo[0], b.lo[1]};
  const double upper[3] = {a.hi[0], b.hi[0], b.hi[1]};
  for (int i = 0; i < count; ++i) hit.x[i] = 0.5 * (lower[i] + upper[i]);
  const double value = internal::MinimizeInBox(
      count, lower, upper, hit.x, [&](const double* x, LocalModel& model) {
        Model(a.piece, b.piece, x, model);
      });
  hit.distance = std::sqrt(2.0 * value);
  return hit;
}

std::pair<double, double> PairSearch::Project(bool on_first, size_t piece,
                                              const double* point, double lo,
                                              double hi, double guess) {
  const Net& net = on_first ? first_.nets[piece] : second_.nets[piece];
  const std::vector<double> query(point, point + first_.dimension);
  std::vector<double> partials(6 * static_cast<size_t>(first_.dimension));
  double x = std::clamp(guess, lo, hi);
  const double value = internal::MinimizeInBox(
      1, &lo, &hi, &x, [&](const double* at, LocalModel& model) {
        internal::DistanceModel(evaluator_, net, 1, query.data(), at,
                                partials.data(), model);
      });
  return {x, std::sqrt(2.0 * value)};
}

double PairSearch::SinAngle(const Part& a, double s, const Part& b, double t) {
  const int dim = first_.dimension;
  evaluator_.Evaluate(first_.nets[a.piece], s, 0.0, scratch_a_.data());
  evaluator_.Evaluate(second_.nets[b.piece], t, 0.0, scratch_b_.data());
  const double* da = scratch_a_.data() + dim;
  const double* db = scratch_b_.data() + dim;
  const double la = std::sqrt(Dot(da, da, dim));
  const double lb = std::sqrt(Dot(db, db, dim));
  if (!(la > 0.0) || !(lb > 0.0)) return 0.0;
  double same = 0.0;
  double opposite = 0.0;
  for (int x = 0; x < dim; ++x) {
    same += (da[x] / la - db[x] / lb) * (da[x] / la - db[x] / lb);
    opposite += (da[x] / la + db[x] / lb) * (da[x] / la + db[x] / lb);
  }
  return std::sqrt(std::min(same, opposite));
}

// FindOverlap checks whether parts a and b of two curves run along each
// other between the end points of either that lie on the other, and
// records the stretch.
bool PairSearch::FindOverlap(const Part& a, const Part& b) {
  const int dim = first_.dimension;
  const double tolerance = options_.tolerance;
  struct End {
    double s;
    double t;
  };
  std::vector<End> ends;
  const size_t last_a = a.points.size() - static_cast<size_t>(dim);
  const size_t last_b = b.points.size() - static_cast<size_t>(dim);
  for (int side = 0; side < 2; ++side) {
    const double* point = a.points.data() + (side == 0 ? 0 : last_a);
    const auto [t, d] = Project(false, b.piece, point, b.lo[0], b.hi[0],
                                0.5 * (b.lo[0] + b.hi[0]));
    if (d <= tolerance) ends.push_back({side == 0 ? a.lo[0] : a.hi[0], t});
  }
  for (int side = 0; side < 2; ++side) {
    const double* point = b.points.data() + (side == 0 ? 0 : last_b);
    const auto [s, d] = Project(true, a.piece, point, a.lo[0], a.hi[0],
                                0.5 * (a.lo[0] + a.hi[0]));
    if (d <= tolerance) ends.push_back({s, side == 0 ? b.lo[0] : b.hi[0]});
  }
  if (ends.size() < 2) return false;
  std::sort(ends.begin(), ends.end(),
            [](const End& x, const End& y) { return x.s < y.s; });
  const End start = ends.front();
  const End end = ends.back();
  std::vector<double> from(static_cast<size_t>(dim));
  evaluator_.Evaluate(first_.nets[a.piece], start.s, 0.0, scratch_a_.data());
  std::copy_n(scratch_a_.data(), dim, from.data());
  evaluator_.Evaluate(first_.nets[a.piece], end.s, 0.0, scratch_a_.data());
  if (PointDistance(from.data(), scratch_a_.data(), dim) <=
      std::max(options_.separation, 10.0 * tolerance)) {
    return false;
  }
  const int samples = 2 * (a.net.count_u + b.net.count_u) + 1;
  for (int k = 0; k <= samples + 1; ++k) {
    const double f = static_cast<double>(k) / (samples + 1);
    const double s = start.s + f * (end.s - start.s);
    evaluator_.Evaluate(first_.nets[a.piece], s, 0.0, scratch_a_.data());
    std::copy_n(scratch_a_.data(), dim, from.data());
    const auto [t, d] = Project(false, b.piece, from.data(), b.lo[0], b.hi[0],
                                start.t + f * (end.t - start.t));
    if (d > tolerance || SinAngle(a, s, b, t) > kOverlapAngle) return false;
  }
  std::array<double, 4> overlap;
  first_.parameters(a.piece, start.s, 0.0, &overlap[0]);
  first_.parameters(a.piece, end.s, 0.0, &overlap[1]);
  second_.parameters(b.piece, start.t, 0.0, &overlap[2]);
  second_.parameters(b.piece, end.t, 0.0, &overlap[3]);
  overlaps_.push_back(overlap);
  return true;
}

// Examine returns true when the pair needs no halving: it is pruned, its
// single point was found, it is a leaf, or it is an overlap.
bool PairSearch::Examine(const PartPtr& a, const PartPtr& b) {
  const double tolerance = options_.tolerance;
  if (Pruned(*a, *b, tolerance)) return true;
  const bool small = a->diameter <= leaf_ && b->diameter <= leaf_;
  const bool curves = b->curve();
  const bool single = curves && ConesApart(a->cone, b->cone, first_.dimension);
  if (small || single) {
    const Hit hit = Solve(*a, *b);
    if (hit.distance <= tolerance) {
      hits_.push_back(hit);
      return true;
    }
    if (small) return true;
  }
  return curves && !single && a->cone.valid && b->cone.valid &&
         a->cone.angle < kNarrowCone && b->cone.angle < kNarrowCone &&
         FindOverlap(*a, *b);
}

absl::Status PairSearch::Run() {
  if (absl::Status status = CheckCancelled(cancel_); !status.ok()) {
    return status;
  }
  const double zero[2] = {0.0, 0.0};
  const double one[2] = {1.0, 1.0};
  std::vector<PartPtr> second_parts;
  for (size_t j = 0; j < second_.nets.size(); ++j) {
    second_parts.push_back(MakePart(j, zero, one, second_.nets[j]));
  }
  // Piece i of the first input is searched against the pieces of the second
  // whose boxes it meets, to the end, before piece i + 1: the stack holds
  // one piece's pairs and their halves, never all pairs of pieces.
  CancellationPoll poll(cancel_);
  std::vector<std::pair<PartPtr, PartPtr>> stack;
  size_t pairs = 0;
  for (size_t i = 0; i < first_.nets.size(); ++i) {
    const PartPtr a = MakePart(i, zero, one, first_.nets[i]);
    for (const PartPtr& b : second_parts) {
      if (!BoxesApart(*a, *b, options_.tolerance)) stack.emplace_back(a, b);
    }
    if (absl::Status status = poll.Done(second_parts.size()); !status.ok()) {
      return status;
    }
    while (!stack.empty()) {
      auto [a_part, b_part] = std::move(stack.back());
      stack.pop_back();
      if (++pairs > options_.max_pairs) {
        return ExhaustedFieldError(
            "max_pairs",
            absl::StrCat("more than ", options_.max_pairs,
                         " pairs of parts lie within tolerance of each other"));
      }
      if (absl::Status status = poll.Done(
              8 * (a_part->net.values.size() + b_part->net.values.size()));
          !status.ok()) {
        return status;
      }
      if (Examine(a_part, b_part)) continue;
      if (a_part->diameter >= b_part->diameter) {
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
  return absl::OkStatus();
}

const double* PairSearch::PointOf(const Hit& hit) {
  evaluator_.Evaluate(first_.nets[hit.first_piece], hit.x[0], 0.0,
                      scratch_a_.data());
  return scratch_a_.data();
}

// SameHit returns true when two hits are closer than the separation, or
// lie on the same pieces with the inputs within tolerance half-way between
// them (a tangential point found from neighbouring pairs).
bool PairSearch::SameHit(const Hit& a, const Hit& b) {
  const int dim = first_.dimension;
  point_.assign(PointOf(a), PointOf(a) + dim);
  if (PointDistance(point_.data(), PointOf(b), dim) <=
      std::max(options_.separation, options_.tolerance)) {
    return true;
  }
  if (a.first_piece != b.first_piece || a.second_piece != b.second_piece) {
    return false;
  }
  double middle[3];
  for (int i = 0; i < 3; ++i) {
    if (std::abs(a.x[i] - b.x[i]) > 1e-3) return false;
    middle[i] = 0.5 * (a.x[i] + b.x[i]);
  }
  LocalModel model;
  Model(a.first_piece, a.second_piece, middle, model);
  return std::sqrt(2.0 * model.value) <= options_.tolerance;
}

std::vector<Hit> PairSearch::DistinctHits() {
  std::sort(hits_.begin(), hits_.end(),
            [](const Hit& a, const Hit& b) { return a.distance < b.distance; });
  // A hit is compared with the kept hits whose first coordinate is within
  // the separation of its own (SameHit's first test) and with those of the
  // same pair of pieces (its second), not with every kept hit.
  const double near = std::max(options_.separation, options_.tolerance);
  std::multimap<double, size_t> by_coordinate;
  std::map<std::pair<size_t, size_t>, std::vector<size_t>> by_pieces;
  std::vector<Hit> kept;
  for (const Hit& hit : hits_) {
    const double x = PointOf(hit)[0];
    bool seen = false;
    for (auto it = by_coordinate.lower_bound(x - near);
         it != by_coordinate.end() && it->first <= x + near && !seen; ++it) {
      seen = SameHit(hit, kept[it->second]);
    }
    const std::pair<size_t, size_t> pieces = {hit.first_piece,
                                              hit.second_piece};
    auto same = by_pieces.find(pieces);
    if (same != by_pieces.end()) {
      for (size_t k : same->second) {
        if (seen) break;
        seen = SameHit(hit, kept[k]);
      }
    }
    if (seen) continue;
    by_coordinate.emplace(x, kept.size());
    by_pieces[pieces].push_back(kept.size());
    kept.push_back(hit);
  }
  return kept;
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

// MergeOverlaps joins overlaps whose intervals meet on both curves.
std::vector<std::array<double, 4>> MergeOverlaps(
    std::vector<std::array<double, 4>> overlaps, double slack_s,
    double slack_t) {
  std::sort(overlaps.begin(), overlaps.end());
  std::vector<std::array<double, 4>> merged;
  for (const std::array<double, 4>& o : overlaps) {
    if (!merged.empty()) {
      std::array<double, 4>& m = merged.back();
      const bool meet_s = o[0] <= m[1] + slack_s;
      const bool meet_t =
          std::min(o[2], o[3]) <= std::max(m[2], m[3]) + slack_t &&
          std::min(m[2], m[3]) <= std::max(o[2], o[3]) + slack_t;
      if (meet_s && meet_t) {
        if (o[1] > m[1]) {
          m[1] = o[1];
          m[3] = o[3];
        }
        continue;
      }
    }
    merged.push_back(o);
  }
  return merged;
}

bool InsideOverlap(double s, double t,
                   const std::vector<std::array<double, 4>>& overlaps,
                   double slack_s, double slack_t) {
  for (const std::array<double, 4>& o : overlaps) {
    if (s >= o[0] - slack_s && s <= o[1] + slack_s &&
        t >= std::min(o[2], o[3]) - slack_t &&
        t <= std::max(o[2], o[3]) + slack_t) {
      return true;
    }
  }
  return false;
}

// Intersect checks the inputs, runs the pair search of `first` against
// `second` (a curve or a surface; `field` names its dimension) and returns
// finish(first's pieces, second's pieces, the search).
template <typename Second, typename Finish>
auto Intersect(const Curve& first, const Second& second,
               absl::string_view field, const IntersectionOptions& options,
               const CancellationToken* cancel, Finish finish)
    -> decltype(finish(std::declval<const Pieces&>(),
                       std::declval<const Pieces&>(),
                       std::declval<PairSearch&>())) {
  if (absl::Status status = CheckOptions(options); !status.ok()) return status;
  if (DimensionOf(second) != DimensionOf(first)) {
    return InvalidFieldError(
        field, absl::StrCat("must be the first input's dimension ",
                            DimensionOf(first), ", got ", DimensionOf(second)));
  }
  absl::StatusOr<Pieces> a = internal::LiftPieces(first, cancel);
  if (!a.ok()) return a.status();
  absl::StatusOr<Pieces> b = internal::LiftPieces(second, cancel);
  if (!b.ok()) return b.status();
  PairSearch search(*a, *b, options, cancel);
  if (absl::Status status = search.Run(); !status.ok()) return status;
  return finish(*a, *b, search);
}

// CurveAnswer returns the distinct points and merged overlaps of two curves.
absl::StatusOr<CurveIntersections> CurveAnswer(
    const Curve& first, const Curve& second, const IntersectionOptions& options,
    const Pieces& a, const Pieces& b, PairSearch& search) {
  const double slack_s = kParameterSlack * Width(DomainOf(first));
  const double slack_t = kParameterSlack * Width(DomainOf(second));
  CurveIntersections result{.dimension = a.dimension};
  std::vector<std::array<double, 4>> overlaps =
      MergeOverlaps(search.overlaps(), slack_s, slack_t);
  std::vector<std::pair<double, std::vector<double>>> points;
  for (const Hit& hit : search.DistinctHits()) {
    double s = 0.0;
    double t = 0.0;
    a.parameters(hit.first_piece, hit.x[0], 0.0, &s);
    b.parameters(hit.second_piece, hit.x[1], 0.0, &t);
    if (InsideOverlap(s, t, overlaps, slack_s, slack_t)) continue;
    const double* point = search.PointOf(hit);
    std::vector<double> entry = {s, t};
    entry.insert(entry.end(), point, point + a.dimension);
    points.emplace_back(s, std::move(entry));
  }
  if (absl::Status status =
          CheckResults(points.size() + overlaps.size(), options);
      !status.ok()) {
    return status;
  }
  std::sort(points.begin(), points.end(),
            [](const auto& x, const auto& y) { return x.first < y.first; });
  for (const auto& [s, entry] : points) {
    result.first_parameters.push_back(entry[0]);
    result.second_parameters.push_back(entry[1]);
    result.points.insert(result.points.end(), entry.begin() + 2, entry.end());
  }
  for (const std::array<double, 4>& o : overlaps) {
    result.first_intervals.insert(result.first_intervals.end(), {o[0], o[1]});
    result.second_intervals.insert(result.second_intervals.end(), {o[2], o[3]});
  }
  return result;
}

// SurfaceAnswer returns the distinct points of a curve and a surface in the
// order of the curve's parameter.
absl::StatusOr<CurveSurfaceIntersections> SurfaceAnswer(
    const IntersectionOptions& options, const Pieces& a, const Pieces& b,
    PairSearch& search) {
  const std::vector<Hit> hits = search.DistinctHits();
  if (absl::Status status = CheckResults(hits.size(), options); !status.ok()) {
    return status;
  }
  std::vector<std::array<double, 3>> order;
  for (size_t k = 0; k < hits.size(); ++k) {
    double t = 0.0;
    a.parameters(hits[k].first_piece, hits[k].x[0], 0.0, &t);
    order.push_back({t, static_cast<double>(k), 0.0});
  }
  std::sort(order.begin(), order.end());
  CurveSurfaceIntersections result{.dimension = a.dimension};
  for (const std::array<double, 3>& entry : order) {
    const Hit& hit = hits[static_cast<size_t>(entry[1])];
    double uv[2];
    b.parameters(hit.second_piece, hit.x[1], hit.x[2], uv);
    result.curve_parameters.push_back(entry[0]);
    result.surface_parameters.insert(result.surface_parameters.end(),
                                     {uv[0], uv[1]});
    const double* point = search.PointOf(hit);
    result.points.insert(result.points.end(), point, point + a.dimension);
  }
  return result;
}

}  // namespace

absl::StatusOr<CurveIntersections> IntersectCurves(
    const Curve& first, const Curve& second, const IntersectionOptions& options,
    const CancellationToken* cancel) {
  return Intersect(first, second, "second.dimension", options, cancel,
                   [&](const Pieces& a, const Pieces& b, PairSearch& search) {
                     return CurveAnswer(first, second, options, a, b, search);
                   });
}

absl::StatusOr<CurveSurfaceIntersections> IntersectCurveSurface(
    const Curve& curve, const Surface& surface,
    const IntersectionOptions& options, const CancellationToken* cancel) {
  return Intersect(curve, surface, "surface.dimension", options, cancel,
                   [&](const Pieces& a, const Pieces& b, PairSearch& search) {
                     return SurfaceAnswer(options, a, b, search);
                   });
}

}  // namespace freeform
