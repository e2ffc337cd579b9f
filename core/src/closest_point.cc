#include "freeform/core/closest_point.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "absl/strings/str_cat.h"
#include "bezier_net.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/status.h"

namespace freeform {
namespace {

using internal::Distance;
using internal::LocalModel;
using internal::Net;
using internal::NetEvaluator;
using internal::Pieces;

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Newton steps per examined piece, and for the final candidates.
constexpr int kBranchNewtonSteps = 8;
constexpr int kPolishNewtonSteps = 60;

absl::Status CheckOptions(const ClosestPointOptions& options) {
  if (absl::Status status =
          internal::CheckTolerances(options.tolerance, options.separation);
      !status.ok()) {
    return status;
  }
  if (options.max_minima < 1 || options.max_minima > kMaxMinimaPerQuery) {
    return InvalidFieldError(
        "max_minima", absl::StrCat("must lie in [1, ", kMaxMinimaPerQuery,
                                   "], got ", options.max_minima));
  }
  if (options.max_pieces < 1) {
    return InvalidFieldError("max_pieces", "must be at least 1");
  }
  return absl::OkStatus();
}

absl::Status CheckQueries(const PointsView& queries, int dimension) {
  if (absl::Status status = ValidatePoints(queries, "queries"); !status.ok()) {
    return status;
  }
  if (queries.dimension != dimension) {
    return InvalidFieldError(
        "queries.dimension",
        absl::StrCat("must be the geometry's dimension ", dimension, ", got ",
                     queries.dimension));
  }
  return absl::OkStatus();
}

// A point found on piece `piece` at (x[0], x[1]) of its [0, 1]^2.
struct Candidate {
  size_t piece = 0;
  double x[2] = {0.0, 0.0};
  double distance = kInfinity;
};

// A part of a piece: its net over the box [lo, hi] of the piece's
// parameters, and what the search knows about it.
struct Node {
  size_t piece = 0;
  double lo[2] = {0.0, 0.0};
  double hi[2] = {1.0, 1.0};
  const Net* shared = nullptr;  // a whole piece's net, else `owned`
  Net owned;
  double bound = 0.0;
  double diameter = kInfinity;   // of its control points' box
  Candidate corner;              // its best corner (a point of the geometry)
  double guess[2] = {0.0, 0.0};  // where its control point nearest q sits
};

const Net& NetOf(const Node& node) {
  return node.shared != nullptr ? *node.shared : node.owned;
}

bool LaterBound(const Node& a, const Node& b) { return a.bound > b.bound; }

// The search for one query; one per thread, reused across queries.
class Search {
 public:
  Search(const Pieces& pieces, const ClosestPointOptions& options)
      : pieces_(pieces), options_(options) {
    evaluators_.reserve(pieces.nets.size());
    for (const Net& net : pieces.nets) evaluators_.emplace_back(net);
    partials_.resize(6 * static_cast<size_t>(pieces.dimension));
    corner_point_.resize(static_cast<size_t>(pieces.dimension));
    // The pieces' projected control points, shared by every query.
    projected_pieces_.resize(pieces.nets.size());
    hull_pieces_.resize(pieces.nets.size());
    for (size_t k = 0; k < pieces.nets.size(); ++k) {
      hull_pieces_[k] = internal::Project(pieces.nets[k], projected_pieces_[k]);
    }
    double start[2], end[2];
    pieces.parameters(0, 0.0, 0.0, start);
    pieces.parameters(pieces.nets.size() - 1, 1.0, 1.0, end);
    parameter_slack_ = 1e-9 * std::abs(end[0] - start[0]);
  }

  // Run answers query r into `answer`; returns the token's status when it
  // stopped the search.
  absl::Status Run(const double* query, size_t r, CancellationPoll& poll,
                   ClosestPoints& answer);

 private:
  Node MakeNode(size_t piece, const double* lo, const double* hi,
                const Net* shared, Net owned);
  Candidate Newton(const Candidate& start, const double* lo, const double* hi,
                   int iterations);
  void Model(size_t piece, const double* x, LocalModel& model);
  bool Branch(CancellationPoll& poll, absl::Status& status);
  void Report(size_t r, ClosestPoints& answer);
  double* PointOf(const Candidate& candidate);

  const Pieces& pieces_;
  const ClosestPointOptions& options_;
  std::vector<NetEvaluator> evaluators_;
  std::vector<double> partials_;
  std::vector<double> projected_;
  std::vector<std::vector<double>> projected_pieces_;
  std::vector<bool> hull_pieces_;
  std::vector<double> corner_point_;
  const double* query_ = nullptr;
  std::vector<Node> heap_;
  std::vector<Candidate> candidates_;
  double best_ = kInfinity;
  double lower_ = kInfinity;
  double parameter_slack_ = 0.0;  // curves: parameters this close are one
};

void Search::Model(size_t piece, const double* x, LocalModel& model) {
  internal::DistanceModel(evaluators_[piece], pieces_.parameter_count, query_,
                          x, partials_.data(), model);
}

Candidate Search::Newton(const Candidate& start, const double* lo,
                         const double* hi, int iterations) {
  Candidate result = start;
  const int count = pieces_.parameter_count;
  const double value = internal::MinimizeInBox(
      count, lo, hi, result.x,
      [&](const double* x, LocalModel& model) { Model(start.piece, x, model); },
      iterations);
  result.distance = std::sqrt(2.0 * value);
  return result.distance <= start.distance ? result : start;
}

double* Search::PointOf(const Candidate& candidate) {
  evaluators_[candidate.piece].Evaluate(candidate.x[0], candidate.x[1],
                                        partials_.data());
  return partials_.data();
}

Node Search::MakeNode(size_t piece, const double* lo, const double* hi,
                      const Net* shared, Net owned) {
  const int dim = pieces_.dimension;
  Node node{.piece = piece,
            .lo = {lo[0], lo[1]},
            .hi = {hi[0], hi[1]},
            .shared = shared,
            .owned = std::move(owned)};
  const Net& net = NetOf(node);
  const bool hull = shared != nullptr ? hull_pieces_[piece]
                                      : internal::Project(net, projected_);
  const std::vector<double>& projected =
      shared != nullptr ? projected_pieces_[piece] : projected_;
  const int nu = net.count_u;
  const int nv = net.count_v;
  double* point = corner_point_.data();
  node.corner.piece = piece;
  for (int i : {0, nu - 1}) {
    for (int j : {0, nv - 1}) {
      if (!internal::Point(net, i, j, point)) continue;
      const double d = Distance(point, query_, dim);
      if (d < node.corner.distance) {
        node.corner.distance = d;
        node.corner.x[0] = i == 0 ? lo[0] : hi[0];
        node.corner.x[1] = j == 0 ? lo[1] : hi[1];
      }
    }
  }
  double nearest = kInfinity;
  const double* nearest_point = nullptr;
  for (int i = 0; hull && i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const double d =
          Distance(projected.data() + (static_cast<size_t>(i) * nv + j) * dim,
                   query_, dim);
      if (d >= nearest) continue;
      nearest = d;
      nearest_point =
          projected.data() + (static_cast<size_t>(i) * nv + j) * dim;
      node.guess[0] = lo[0] + (nu > 1 ? i / (nu - 1.0) : 0.0) * (hi[0] - lo[0]);
      node.guess[1] = lo[1] + (nv > 1 ? j / (nv - 1.0) : 0.0) * (hi[1] - lo[1]);
    }
  }
  if (!hull) {
    node.guess[0] = 0.5 * (lo[0] + hi[0]);
    node.guess[1] = 0.5 * (lo[1] + hi[1]);
  } else {
    node.diameter = internal::BoxDiameter(projected, dim);
    node.bound = std::max(
        internal::BoxDistance(projected, dim, query_),
        internal::DirectionalBound(projected, dim, query_, nearest_point));
  }
  if (node.corner.distance < best_) {
    best_ = node.corner.distance;
    candidates_.push_back(node.corner);
  }
  return node;
}

// Branch takes the node of smallest bound: drops it (and stops) when the
// bound exceeds best + tolerance, else runs Newton in it and resolves or
// halves it. Returns false when the search is over.
bool Search::Branch(CancellationPoll& poll, absl::Status& status) {
  std::pop_heap(heap_.begin(), heap_.end(), LaterBound);
  Node node = std::move(heap_.back());
  heap_.pop_back();
  if (node.bound > best_ + options_.tolerance) return false;
  const Net& net = NetOf(node);
  status = poll.Done(net.values.size() * 16);
  if (!status.ok()) return false;
  Candidate start = node.corner;
  start.x[0] = node.guess[0];
  start.x[1] = node.guess[1];
  start.distance = kInfinity;
  // A few steps give the upper bound; the answer is polished in Report.
  Candidate found = Newton(start, node.lo, node.hi, kBranchNewtonSteps);
  if (node.corner.distance < found.distance) found = node.corner;
  candidates_.push_back(found);
  best_ = std::min(best_, found.distance);
  // Resolved: its distance is certified, and it is small enough to hold
  // one minimum of those within tolerance of the best (see the header).
  const double leaf = 16.0 * std::max({options_.separation, options_.tolerance,
                                       std::sqrt(options_.tolerance * best_)});
  if (found.distance - node.bound <= options_.tolerance &&
      node.diameter <= leaf) {
    lower_ = std::min(lower_, node.bound);
    return true;
  }
  internal::Project(net, projected_);
  double along_u = 1.0;
  double along_v = 0.0;
  if (net.count_v > 1) {
    internal::PolygonLengths(projected_, pieces_.dimension, net.count_u,
                             net.count_v, along_u, along_v);
  }
  const bool in_u = net.count_v == 1 || along_u >= along_v;
  Net low, high;
  internal::Halve(net, in_u, low, high);
  const int axis = in_u ? 0 : 1;
  const double middle = 0.5 * (node.lo[axis] + node.hi[axis]);
  double lo_high[2] = {node.lo[0], node.lo[1]};
  double hi_low[2] = {node.hi[0], node.hi[1]};
  lo_high[axis] = middle;
  hi_low[axis] = middle;
  for (Node child :
       {MakeNode(node.piece, node.lo, hi_low, nullptr, std::move(low)),
        MakeNode(node.piece, lo_high, node.hi, nullptr, std::move(high))}) {
    if (child.bound > best_ + options_.tolerance) continue;
    heap_.push_back(std::move(child));
    std::push_heap(heap_.begin(), heap_.end(), LaterBound);
  }
  return true;
}

absl::Status Search::Run(const double* query, size_t r, CancellationPoll& poll,
                         ClosestPoints& answer) {
  query_ = query;
  heap_.clear();
  candidates_.clear();
  best_ = kInfinity;
  lower_ = kInfinity;
  const double zero[2] = {0.0, 0.0};
  const double one[2] = {1.0, 1.0};
  for (size_t k = 0; k < pieces_.nets.size(); ++k) {
    heap_.push_back(MakeNode(k, zero, one, &pieces_.nets[k], Net{}));
  }
  std::make_heap(heap_.begin(), heap_.end(), LaterBound);
  size_t examined = 0;
  bool complete = true;
  absl::Status status;
  while (!heap_.empty()) {
    if (++examined > options_.max_pieces) {
      complete = false;
      lower_ = std::min(lower_, heap_.front().bound);
      break;
    }
    if (!Branch(poll, status)) break;
  }
  if (!status.ok()) return status;
  answer.complete[r] = complete ? 1 : 0;
  Report(r, answer);
  return absl::OkStatus();
}

// Report polishes the candidates within tolerance of the best on their
// whole piece and writes the distinct ones, closest first.
void Search::Report(size_t r, ClosestPoints& answer) {
  const double zero[2] = {0.0, 0.0};
  const double one[2] = {1.0, 1.0};
  const double limit = best_ + options_.tolerance;
  std::vector<Candidate> polished;
  for (const Candidate& candidate : candidates_) {
    if (candidate.distance <= limit) {
      polished.push_back(Newton(candidate, zero, one, kPolishNewtonSteps));
    }
  }
  std::sort(polished.begin(), polished.end(),
            [](const Candidate& a, const Candidate& b) {
              return a.distance < b.distance;
            });
  const int dim = pieces_.dimension;
  const int pc = pieces_.parameter_count;
  const size_t slots = static_cast<size_t>(answer.max_minima);
  const double smallest = polished.front().distance;
  int kept = 0;
  for (const Candidate& candidate : polished) {
    if (candidate.distance > smallest + options_.tolerance) break;
    const double* point = PointOf(candidate);
    double* points = answer.points.data() + r * slots * dim;
    double* parameters = answer.parameters.data() + r * slots * pc;
    double t = 0.0;
    pieces_.parameters(candidate.piece, candidate.x[0], candidate.x[1], &t);
    bool seen = false;
    for (int k = 0; k < kept && !seen; ++k) {
      // On a curve a point reached at two parameters (a self-intersection,
      // the seam of a closed curve) is two minima; on a surface one (a
      // collapsed edge such as a pole has many parameters).
      seen = Distance(point, points + static_cast<size_t>(k) * dim, dim) <=
                 options_.separation &&
             (pc == 2 || std::abs(t - parameters[k]) <= parameter_slack_);
    }
    if (seen) continue;
    if (kept == answer.max_minima) {
      answer.complete[r] = 0;
      break;
    }
    std::copy_n(point, dim, points + static_cast<size_t>(kept) * dim);
    pieces_.parameters(candidate.piece, candidate.x[0], candidate.x[1],
                       parameters + static_cast<size_t>(kept) * pc);
    ++kept;
  }
  answer.counts[r] = kept;
  answer.distances[r] = smallest;
  answer.lower_bounds[r] = std::min(lower_, smallest);
}

absl::StatusOr<ClosestPoints> Solve(const Pieces& pieces,
                                    const PointsView& queries,
                                    const ClosestPointOptions& options,
                                    const ExecutionContext& context) {
  const size_t count = queries.size();
  const size_t slots = count * static_cast<size_t>(options.max_minima);
  ClosestPoints answer{
      .dimension = pieces.dimension,
      .parameter_count = pieces.parameter_count,
      .max_minima = options.max_minima,
      .distances = std::vector<double>(count),
      .lower_bounds = std::vector<double>(count),
      .counts = std::vector<int>(count),
      .complete = std::vector<uint8_t>(count),
      .parameters = std::vector<double>(slots * pieces.parameter_count),
      .points = std::vector<double>(slots * pieces.dimension)};
  ExecutionContext chunks = context;
  chunks.grain = std::clamp<size_t>(context.grain, 1, 16);
  std::atomic<bool> stopped{false};
  absl::Status status = ParallelFor(count, chunks, [&](size_t b, size_t e) {
    Search search(pieces, options);
    CancellationPoll poll(context.cancellation);
    for (size_t r = b; r < e && !stopped.load(std::memory_order_relaxed); ++r) {
      if (!search.Run(queries.point(r), r, poll, answer).ok()) {
        stopped.store(true, std::memory_order_relaxed);
      }
    }
  });
  if (!status.ok()) return status;
  if (stopped.load()) return CheckCancelled(context.cancellation);
  return answer;
}

// ClosestPointsOn checks the options and queries and answers them on a
// curve or a surface.
template <typename Geometry>
absl::StatusOr<ClosestPoints> ClosestPointsOn(
    const Geometry& geometry, const PointsView& queries,
    const ClosestPointOptions& options, const ExecutionContext& context) {
  if (absl::Status status = CheckOptions(options); !status.ok()) return status;
  if (absl::Status status = CheckQueries(queries, DimensionOf(geometry));
      !status.ok()) {
    return status;
  }
  absl::StatusOr<Pieces> pieces =
      internal::LiftPieces(geometry, context.cancellation);
  if (!pieces.ok()) return pieces.status();
  return Solve(*pieces, queries, options, context);
}

}  // namespace

size_t ClosestPointsValues(size_t queries, int dimension, int parameter_count,
                           int max_minima) {
  const size_t per_minimum =
      static_cast<size_t>(dimension) + static_cast<size_t>(parameter_count);
  return queries * (2 + static_cast<size_t>(max_minima) * per_minimum);
}

absl::StatusOr<ClosestPoints> CurveClosestPoints(
    const Curve& curve, const PointsView& queries,
    const ClosestPointOptions& options, const ExecutionContext& context) {
  return ClosestPointsOn(curve, queries, options, context);
}

absl::StatusOr<ClosestPoints> SurfaceClosestPoints(
    const Surface& surface, const PointsView& queries,
    const ClosestPointOptions& options, const ExecutionContext& context) {
  return ClosestPointsOn(surface, queries, options, context);
}

}  // namespace freeform
