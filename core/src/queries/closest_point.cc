#include "freeform/core/closest_point.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "base/scaled.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/points.h"
#include "freeform/core/status.h"
#include "freeform/core/status_macros.h"
#include "geometry/scaled_geometry.h"
#include "queries/bezier_net.h"

namespace freeform {
namespace {

using internal::LocalModel;
using internal::Net;
using internal::NetEvaluator;
using internal::Pieces;

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Newton steps per examined piece, and for the final candidates.
constexpr int kBranchNewtonSteps = 8;
constexpr int kPolishNewtonSteps = 60;

absl::Status CheckOptions(const ClosestPointOptions& options) {
  RETURN_IF_ERROR(
      internal::CheckTolerances(options.tolerance, options.separation));
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
  RETURN_IF_ERROR(ValidatePoints(queries, "queries"));
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
  // False for a point of a flat part, which Newton has nowhere to move
  // (it would only follow the rounding of a zero gradient).
  bool polish = true;
};

// What every query reads about the pieces, computed once per batch: their
// projected control points, whether the hull property holds (positive
// weights), and the box of the control points (its centre and half widths
// by coordinate, piece after piece, so that one pass over all pieces runs
// in SIMD lanes) with the radius of the ball about its centre.
struct Prepared {
  explicit Prepared(const Pieces& pieces);

  // Gaps writes, for every piece k < padded, box[k] = the squared distance
  // from `query` to its box (0 without the hull property) and centre[k] =
  // the squared distance to the box's centre.
  void Gaps(const double* query, double* box, double* centre) const;
  // Reachable returns false when piece k, whose gaps are box and centre, is
  // certainly farther than `limit`: its box or its ball is.
  bool Reachable(size_t k, double box, double centre, double limit) const {
    const double ball = limit + radius[k];
    return box <= limit * limit && centre <= ball * ball;
  }

  const Pieces& pieces;
  std::vector<std::vector<double>> projected;
  std::vector<uint8_t> hull;
  std::vector<size_t> hull_less;  // the pieces without the hull property
  size_t padded = 0;              // the number of pieces rounded up to 4
  std::vector<double> middle;     // [x * padded + k]: the box's centre
  std::vector<double> half;       // [x * padded + k]: its half width
  std::vector<double> radius;     // of the ball about the box's centre
  std::vector<double> diameter;
  double parameter_slack = 0.0;  // curves: parameters this close are one
};

Prepared::Prepared(const Pieces& pieces_in) : pieces(pieces_in) {
  const size_t count = pieces.nets.size();
  const size_t dim = static_cast<size_t>(pieces.dimension);
  projected.resize(count);
  hull.resize(count);
  padded = (count + 3) / 4 * 4;
  middle.assign(padded * dim, kInfinity);
  half.assign(padded * dim, 0.0);
  radius.assign(count, kInfinity);
  diameter.assign(count, kInfinity);
  std::vector<double> lo(dim), hi(dim);
  for (size_t k = 0; k < count; ++k) {
    hull[k] = internal::Project(pieces.nets[k], projected[k]) ? 1 : 0;
    if (!hull[k]) {
      hull_less.push_back(k);
      continue;
    }
    const std::vector<double>& points = projected[k];
    std::copy_n(points.data(), dim, lo.data());
    std::copy_n(points.data(), dim, hi.data());
    for (size_t i = 0; i < points.size(); ++i) {
      lo[i % dim] = std::min(lo[i % dim], points[i]);
      hi[i % dim] = std::max(hi[i % dim], points[i]);
    }
    for (size_t x = 0; x < dim; ++x) {
      middle[x * padded + k] = 0.5 * (lo[x] + hi[x]);
      half[x * padded + k] = 0.5 * (hi[x] - lo[x]);
    }
    diameter[k] = PointDistance(lo.data(), hi.data(), pieces.dimension);
    double widest = 0.0;
    for (size_t i = 0; i < points.size(); i += dim) {
      double sum = 0.0;
      for (size_t x = 0; x < dim; ++x) {
        const double d = points[i + x] - middle[x * padded + k];
        sum += d * d;
      }
      widest = std::max(widest, sum);
    }
    radius[k] = std::sqrt(widest);
  }
  double start[2], end[2];
  pieces.parameters(0, 0.0, 0.0, start);
  pieces.parameters(count - 1, 1.0, 1.0, end);
  parameter_slack = 1e-9 * std::abs(end[0] - start[0]);
}

// GapsOf is Prepared::Gaps for `Dimension` coordinates (0: any, `dim`),
// four pieces at a time (SIMD lanes); the padding pieces are infinitely
// far.
template <int Dimension>
void GapsOf(const Prepared& prepared, int dim, const double* query, double* box,
            double* centre) {
  const size_t padded = prepared.padded;
  const int d = Dimension > 0 ? Dimension : dim;
  for (size_t k = 0; k < padded; k += 4) {
    double outside[4] = {0.0, 0.0, 0.0, 0.0};
    double inside[4] = {0.0, 0.0, 0.0, 0.0};
    for (int x = 0; x < d; ++x) {
      const double* middle = prepared.middle.data() + x * padded + k;
      const double* half = prepared.half.data() + x * padded + k;
      for (int lane = 0; lane < 4; ++lane) {
        const double offset = query[x] - middle[lane];
        const double beyond = std::abs(offset) - half[lane];
        const double gap = 0.5 * (beyond + std::abs(beyond));  // max(., 0)
        outside[lane] += gap * gap;
        inside[lane] += offset * offset;
      }
    }
    for (int lane = 0; lane < 4; ++lane) {
      box[k + lane] = outside[lane];
      centre[k + lane] = inside[lane];
    }
  }
  for (const size_t k : prepared.hull_less) box[k] = 0.0;
}

void Prepared::Gaps(const double* query, double* box, double* centre) const {
  switch (pieces.dimension) {
    case 2:
      return GapsOf<2>(*this, 2, query, box, centre);
    case 3:
      return GapsOf<3>(*this, 3, query, box, centre);
    default:
      return GapsOf<0>(*this, pieces.dimension, query, box, centre);
  }
}

// What the Bernstein coefficients of phi(s) = |C(s) - q|^2 / 2 tell about a
// polynomial curve part in its own parameter s in [0, 1]: lower bounds of
// phi and of phi'' over the part (-infinity when unknown).
struct PhiHull {
  double lowest = -kInfinity;
  double curvature = -kInfinity;
};

// PhiHulls computes the PhiHull of polynomial curve parts: phi is the
// polynomial of degree m = 2n with the Bernstein coefficients
// c_k = sum_{i+j=k} binom(n,i) binom(n,j) / binom(m,k) (P_i - q).(P_j - q)
// / 2, so phi >= min_k c_k and
// phi'' = m (m - 1) sum_k (c_k - 2 c_{k+1} + c_{k+2}) B(m-2,k) >=
// m (m - 1) min_k of the second differences (docs/references.md, 'Closest
// points by branch and bound'). Each c_k is a convex combination of the
// products, so it is exact to a few rounding errors of max_i |P_i - q|^2,
// which both bounds give up. It keeps the weights of the last degree.
class PhiHulls {
 public:
  // Of returns the PhiHull of the part with `count` control points
  // `points` of `dimension` coordinates for the query q.
  PhiHull Of(const double* points, int count, int dimension, const double* q);

 private:
  int degree_ = -1;
  std::vector<double> weights_;  // [i * (n + 1) + j], j >= i
  std::vector<double> c_;
};

PhiHull PhiHulls::Of(const double* points, int count, int dimension,
                     const double* q) {
  const int n = count - 1;
  const int m = 2 * n;
  constexpr int kMaxDegree = 64;
  if (n < 0 || n > kMaxDegree) return {};
  const size_t row = static_cast<size_t>(count);
  if (n != degree_) {
    double binomial_n[kMaxDegree + 1];
    double binomial_m[2 * kMaxDegree + 1];
    binomial_n[0] = binomial_m[0] = 1.0;
    for (int i = 1; i <= n; ++i) {
      binomial_n[i] = binomial_n[i - 1] * (n - i + 1) / i;
    }
    for (int k = 1; k <= m; ++k) {
      binomial_m[k] = binomial_m[k - 1] * (m - k + 1) / k;
    }
    weights_.assign(row * row, 0.0);
    for (int i = 0; i <= n; ++i) {
      for (int j = i; j <= n; ++j) {
        weights_[i * row + j] = (i == j ? 0.5 : 1.0) * binomial_n[i] *
                                binomial_n[j] / binomial_m[i + j];
      }
    }
    degree_ = n;
  }
  c_.assign(static_cast<size_t>(m) + 1, 0.0);
  double reach = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double* a = points + static_cast<size_t>(i) * dimension;
    for (int j = i; j <= n; ++j) {
      const double* b = points + static_cast<size_t>(j) * dimension;
      double dot = 0.0;
      for (int x = 0; x < dimension; ++x) dot += (a[x] - q[x]) * (b[x] - q[x]);
      if (i == j) reach = std::max(reach, dot);
      c_[static_cast<size_t>(i + j)] += weights_[i * row + j] * dot;
    }
  }
  double lowest = kInfinity;
  for (const double value : c_) lowest = std::min(lowest, value);
  double second = kInfinity;
  for (size_t k = 0; k + 2 <= static_cast<size_t>(m); ++k) {
    second = std::min(second, c_[k] - 2.0 * c_[k + 1] + c_[k + 2]);
  }
  const double rounding = 4.0 * (dimension + m + 4) *
                          std::numeric_limits<double>::epsilon() * reach;
  // A part of degree 0 is a point: phi is its constant, no curvature.
  return {.lowest = lowest - rounding,
          .curvature = m < 2 ? -kInfinity
                             : static_cast<double>(m) * (m - 1) *
                                   (second - 4.0 * rounding)};
}

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
  PhiHull phi;                   // polynomial curves
};

const Net& NetOf(const Node& node) {
  return node.shared != nullptr ? *node.shared : node.owned;
}

bool LaterBound(const Node& a, const Node& b) { return a.bound > b.bound; }

// The search for one query; one per thread, reused across queries.
class Search {
 public:
  Search(const Prepared& prepared, const ClosestPointOptions& options)
      : prepared_(prepared),
        pieces_(prepared.pieces),
        options_(options),
        partials_(6 * static_cast<size_t>(prepared.pieces.dimension)),
        corner_point_(static_cast<size_t>(prepared.pieces.dimension)) {}

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
  double ConvexBound(const Node& node, const Candidate& found,
                     double curvature);
  bool Examine(Node node, CancellationPoll& poll, absl::Status& status);
  void MarkIfFlat(const Node& node, const Candidate& found);
  void Push(Node node);
  bool AlreadyPolished(const Candidate& candidate);
  void Report(size_t r, ClosestPoints& answer);
  double* PointOf(const Candidate& candidate);
  Net Spare();

  const Prepared& prepared_;
  const Pieces& pieces_;
  const ClosestPointOptions& options_;
  NetEvaluator evaluator_;
  std::vector<double> partials_;
  std::vector<double> projected_;
  std::vector<double> corner_point_;
  PhiHulls phi_;
  std::vector<double> box_gaps_;
  std::vector<double> centre_gaps_;
  const double* query_ = nullptr;
  // How much a distance to the query can change by rounding alone.
  double distance_rounding_ = 0.0;
  std::vector<Node> heap_;
  std::vector<Net> spare_;
  std::vector<Candidate> candidates_;
  std::vector<Candidate> polished_;
  // The points of polished_ (surfaces only), dimension values each.
  std::vector<double> polished_points_;
  double best_ = kInfinity;
  double lower_ = kInfinity;
  // A resolved part lies at one distance from the query to rounding: the
  // minimum is attained along a stretch or region (a constant piece).
  bool flat_ = false;
};

void Search::Model(size_t piece, const double* x, LocalModel& model) {
  internal::DistanceModel(evaluator_, pieces_.nets[piece],
                          pieces_.parameter_count, query_, x, partials_.data(),
                          model);
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
  // Near a minimum the distance is flat: a start off by 1e-8 in its
  // parameters can compute a distance an ulp below Newton's exact point.
  // Newton's point wins unless it is farther by more than the rounding of
  // a distance between points of the query's size.
  const double slack =
      distance_rounding_ +
      16.0 * std::numeric_limits<double>::epsilon() * start.distance;
  return result.distance <= start.distance + slack ? result : start;
}

double* Search::PointOf(const Candidate& candidate) {
  evaluator_.Evaluate(pieces_.nets[candidate.piece], candidate.x[0],
                      candidate.x[1], partials_.data());
  return partials_.data();
}

Net Search::Spare() {
  if (spare_.empty()) return Net{};
  Net net = std::move(spare_.back());
  spare_.pop_back();
  return net;
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
  // A polynomial curve part is bounded by the coefficients of phi, and
  // most parts are ruled out by that alone.
  const bool polynomial_curve = net.count_v == 1 && !net.rational;
  if (polynomial_curve) {
    node.phi = phi_.Of(net.values.data(), net.count_u, dim, query_);
    node.bound = std::sqrt(2.0 * std::max(node.phi.lowest, 0.0));
    if (node.bound > best_ + options_.tolerance) return node;
  }
  const bool hull = shared != nullptr ? prepared_.hull[piece] != 0
                                      : internal::Project(net, projected_);
  const std::vector<double>& projected =
      shared != nullptr ? prepared_.projected[piece] : projected_;
  const int nu = net.count_u;
  const int nv = net.count_v;
  double* point = corner_point_.data();
  node.corner.piece = piece;
  for (int i : {0, nu - 1}) {
    for (int j : {0, nv - 1}) {
      if (!internal::Point(net, i, j, point)) continue;
      const double d = PointDistance(point, query_, dim);
      if (d < node.corner.distance) {
        node.corner.distance = d;
        node.corner.x[0] = i == 0 ? lo[0] : hi[0];
        node.corner.x[1] = j == 0 ? lo[1] : hi[1];
      }
    }
  }
  double nearest = kInfinity;  // squared
  const double* nearest_point = nullptr;
  for (int i = 0; hull && i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const double* p =
          projected.data() + (static_cast<size_t>(i) * nv + j) * dim;
      double d = 0.0;
      for (int x = 0; x < dim; ++x)
        d += (p[x] - query_[x]) * (p[x] - query_[x]);
      if (d >= nearest) continue;
      nearest = d;
      nearest_point = p;
      node.guess[0] = lo[0] + (nu > 1 ? i / (nu - 1.0) : 0.0) * (hi[0] - lo[0]);
      node.guess[1] = lo[1] + (nv > 1 ? j / (nv - 1.0) : 0.0) * (hi[1] - lo[1]);
    }
  }
  if (!hull) {
    node.guess[0] = 0.5 * (lo[0] + hi[0]);
    node.guess[1] = 0.5 * (lo[1] + hi[1]);
  } else {
    node.diameter = shared != nullptr ? prepared_.diameter[piece]
                                      : internal::BoxDiameter(projected, dim);
    if (!polynomial_curve) {
      // No control point is nearest when every distance overflows.
      node.bound = std::max(internal::BoxDistance(projected, dim, query_),
                            nearest_point == nullptr
                                ? 0.0
                                : internal::DirectionalBound(
                                      projected, dim, query_, nearest_point));
    }
  }
  if (node.corner.distance < best_) {
    best_ = node.corner.distance;
    candidates_.push_back(node.corner);
  }
  return node;
}

// ConvexBound returns a lower bound of the distance to q over a part of a
// curve piece on which phi = |C - q|^2 / 2 is strictly convex, phi'' >=
// `curvature` > 0 on [lo, hi] (in the piece's parameter): phi(s) >=
// phi(x) + phi'(x) (s - x) + curvature (s - x)^2 / 2 about the point x that
// Newton found, whose minimum over [lo, hi] is exact to second order in
// phi'(x) (docs/references.md, 'Closest points by branch and bound').
double Search::ConvexBound(const Node& node, const Candidate& found,
                           double curvature) {
  LocalModel model;
  Model(node.piece, found.x, model);
  const double x = found.x[0];
  const double g = model.gradient[0];
  const double s = std::clamp(x - g / curvature, node.lo[0], node.hi[0]);
  const double lowest =
      model.value + g * (s - x) + 0.5 * curvature * (s - x) * (s - x);
  return std::sqrt(2.0 * std::max(lowest, 0.0));
}

// MarkIfFlat sets flat_ when a resolved part is a single point to rounding
// (the box of its control points, which holds it, is that small: a
// constant piece, all its control points equal). Every parameter of such a
// part is a minimum; on a curve max_minima of them, evenly spread, become
// candidates (on a surface its parameters count as one minimum, since they
// give one point).
void Search::MarkIfFlat(const Node& node, const Candidate& found) {
  if (!internal::Project(NetOf(node), projected_)) return;
  // The copy's coordinates are at most 1 (scaled_geometry.h).
  constexpr double kRounding = 32.0 * std::numeric_limits<double>::epsilon();
  if (!(internal::BoxDiameter(projected_, pieces_.dimension) <= kRounding)) {
    return;
  }
  flat_ = true;
  if (pieces_.parameter_count != 1) return;
  const int count = options_.max_minima;
  for (int k = 0; k < count; ++k) {
    Candidate spread = found;
    spread.polish = false;
    const double fraction = count > 1 ? k / (count - 1.0) : 0.5;
    spread.x[0] = node.lo[0] + fraction * (node.hi[0] - node.lo[0]);
    candidates_.push_back(spread);
  }
}

void Search::Push(Node node) {
  if (node.bound > best_ + options_.tolerance) {
    if (node.shared == nullptr) spare_.push_back(std::move(node.owned));
    return;
  }
  heap_.push_back(std::move(node));
  std::push_heap(heap_.begin(), heap_.end(), LaterBound);
}

// Examine runs Newton in a node whose bound is within tolerance of the best,
// then resolves it, drops it (a convex part whose minimum is too far) or
// halves it. Returns false when the token stopped the search.
bool Search::Examine(Node node, CancellationPoll& poll, absl::Status& status) {
  const Net& net = NetOf(node);
  status = poll.Done(net.values.size() * 16);
  if (!status.ok()) return false;
  if (node.bound > best_ + options_.tolerance) {
    if (node.shared == nullptr) spare_.push_back(std::move(node.owned));
    return true;
  }
  Candidate start = node.corner;
  start.x[0] = node.guess[0];
  start.x[1] = node.guess[1];
  start.distance = kInfinity;
  // A few steps give the upper bound; the answer is polished in Report.
  Candidate found = Newton(start, node.lo, node.hi, kBranchNewtonSteps);
  if (node.corner.distance < found.distance) found = node.corner;
  candidates_.push_back(found);
  best_ = std::min(best_, found.distance);
  // Resolved: its distance is certified, and it holds one minimum of those
  // within tolerance of the best: it is convex, or small (see the header).
  const double leaf = 16.0 * std::max({options_.separation, options_.tolerance,
                                       std::sqrt(options_.tolerance * best_)});
  const bool tight = found.distance - node.bound <= options_.tolerance;
  const double width = node.hi[0] - node.lo[0];
  const double curvature = node.phi.curvature / (width * width);
  if ((!tight || node.diameter > leaf) && curvature > 0.0 &&
      std::isfinite(curvature)) {
    node.bound = std::max(node.bound, ConvexBound(node, found, curvature));
    node.diameter = 0.0;  // one minimum: resolved once tight
  }
  if (node.bound > best_ + options_.tolerance) {
    if (node.shared == nullptr) spare_.push_back(std::move(node.owned));
    return true;
  }
  if (found.distance - node.bound <= options_.tolerance &&
      node.diameter <= leaf) {
    lower_ = std::min(lower_, node.bound);
    MarkIfFlat(node, found);
    if (node.shared == nullptr) spare_.push_back(std::move(node.owned));
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
  Net low = Spare();
  Net high = Spare();
  internal::Halve(net, in_u, low, high);
  if (node.shared == nullptr) spare_.push_back(std::move(node.owned));
  const int axis = in_u ? 0 : 1;
  const double middle = 0.5 * (node.lo[axis] + node.hi[axis]);
  double lo_high[2] = {node.lo[0], node.lo[1]};
  double hi_low[2] = {node.hi[0], node.hi[1]};
  lo_high[axis] = middle;
  hi_low[axis] = middle;
  // Newton in the half that holds the point found here starts from it.
  for (Node child :
       {MakeNode(node.piece, node.lo, hi_low, nullptr, std::move(low)),
        MakeNode(node.piece, lo_high, node.hi, nullptr, std::move(high))}) {
    if (found.piece == node.piece && found.x[axis] >= child.lo[axis] &&
        found.x[axis] <= child.hi[axis]) {
      child.guess[0] = found.x[0];
      child.guess[1] = found.x[1];
    }
    Push(std::move(child));
  }
  return true;
}

absl::Status Search::Run(const double* query, size_t r, CancellationPoll& poll,
                         ClosestPoints& answer) {
  query_ = query;
  double size = 0.0;
  for (int j = 0; j < pieces_.dimension; ++j) {
    size = std::max(size, std::abs(query[j]));
  }
  distance_rounding_ = 16.0 * std::numeric_limits<double>::epsilon() * size;
  heap_.clear();
  candidates_.clear();
  best_ = kInfinity;
  lower_ = kInfinity;
  flat_ = false;
  // The piece nearest by its box (then by its box's centre) is examined
  // first: the best distance it sets rules out most other pieces at once.
  const size_t count = pieces_.nets.size();
  box_gaps_.resize(prepared_.padded);
  centre_gaps_.resize(prepared_.padded);
  prepared_.Gaps(query, box_gaps_.data(), centre_gaps_.data());
  size_t seed = 0;
  for (size_t k = 1; k < count; ++k) {
    if (box_gaps_[k] < box_gaps_[seed] ||
        (box_gaps_[k] == box_gaps_[seed] &&
         centre_gaps_[k] < centre_gaps_[seed])) {
      seed = k;
    }
  }
  const double zero[2] = {0.0, 0.0};
  const double one[2] = {1.0, 1.0};
  size_t examined = 1;
  absl::Status status;
  bool running = Examine(MakeNode(seed, zero, one, &pieces_.nets[seed], Net{}),
                         poll, status);
  for (size_t k = 0; running && k < count; ++k) {
    if (k == seed || !prepared_.Reachable(k, box_gaps_[k], centre_gaps_[k],
                                          best_ + options_.tolerance)) {
      continue;
    }
    Push(MakeNode(k, zero, one, &pieces_.nets[k], Net{}));
  }
  bool complete = true;
  while (running && !heap_.empty() &&
         heap_.front().bound <= best_ + options_.tolerance) {
    if (++examined > options_.max_pieces) {
      complete = false;
      lower_ = std::min(lower_, heap_.front().bound);
      break;
    }
    std::pop_heap(heap_.begin(), heap_.end(), LaterBound);
    Node node = std::move(heap_.back());
    heap_.pop_back();
    running = Examine(std::move(node), poll, status);
  }
  for (Node& node : heap_) {
    if (node.shared == nullptr) spare_.push_back(std::move(node.owned));
  }
  if (!status.ok()) return status;
  answer.complete[r] = complete && !flat_ ? 1 : 0;
  Report(r, answer);
  return absl::OkStatus();
}

// AlreadyPolished says whether a surface candidate would only repeat a
// polished minimum: one at least as close, on the same piece, whose point
// is within the separation of the candidate's, so that the two would be
// reported as one minimum. Neighbouring parts of a search converge to the
// same minimum, and polishing each of them (kPolishNewtonSteps evaluations)
// cost half of a degree-9 triangle's search that found 1024 of them. On a
// curve two such points may still be two minima (their parameters differ:
// a self-intersection), so curves polish every candidate.
bool Search::AlreadyPolished(const Candidate& candidate) {
  if (pieces_.parameter_count != 2 || polished_.empty()) return false;
  const int dim = pieces_.dimension;
  const double* point = PointOf(candidate);
  for (size_t k = 0; k < polished_.size(); ++k) {
    if (polished_[k].piece != candidate.piece ||
        polished_[k].distance > candidate.distance) {
      continue;
    }
    if (PointDistance(point, &polished_points_[k * static_cast<size_t>(dim)],
                      dim) <= options_.separation) {
      return true;
    }
  }
  return false;
}

// Report polishes the candidates within tolerance of the best on their
// whole piece and writes the distinct ones, closest first.
void Search::Report(size_t r, ClosestPoints& answer) {
  const double zero[2] = {0.0, 0.0};
  const double one[2] = {1.0, 1.0};
  const double limit = best_ + options_.tolerance;
  polished_.clear();
  polished_points_.clear();
  const Candidate* last = nullptr;  // the last candidate polished
  for (const Candidate& candidate : candidates_) {
    if (!(candidate.distance <= limit)) continue;
    // The halves of a part start from its point and often end there too.
    if (last != nullptr && last->piece == candidate.piece &&
        last->x[0] == candidate.x[0] && last->x[1] == candidate.x[1]) {
      continue;
    }
    last = &candidate;
    if (candidate.polish && AlreadyPolished(candidate)) continue;
    const Candidate polished =
        candidate.polish ? Newton(candidate, zero, one, kPolishNewtonSteps)
                         : candidate;
    if (!std::isfinite(polished.distance)) continue;
    polished_.push_back(polished);
    if (pieces_.parameter_count == 2) {
      const double* point = PointOf(polished);
      polished_points_.insert(polished_points_.end(), point,
                              point + pieces_.dimension);
    }
  }
  // Stable: minima at one distance (a flat part's) keep their order.
  std::stable_sort(polished_.begin(), polished_.end(),
                   [](const Candidate& a, const Candidate& b) {
                     return a.distance < b.distance;
                   });
  const int dim = pieces_.dimension;
  const int pc = pieces_.parameter_count;
  const size_t slots = static_cast<size_t>(answer.max_minima);
  if (polished_.empty()) {  // every distance overflowed: no finite minimum
    answer.counts[r] = 0;
    answer.complete[r] = 0;
    answer.distances[r] = kInfinity;
    answer.lower_bounds[r] = kInfinity;
    return;
  }
  const double smallest = polished_.front().distance;
  int kept = 0;
  for (const Candidate& candidate : polished_) {
    if (candidate.distance > smallest + options_.tolerance) break;
    const double* point = PointOf(candidate);
    double* points = answer.points.data() + r * slots * dim;
    double* parameters = answer.parameters.data() + r * slots * pc;
    double t[2] = {0.0, 0.0};  // (u, v) on a surface
    pieces_.parameters(candidate.piece, candidate.x[0], candidate.x[1], t);
    bool seen = false;
    for (int k = 0; k < kept && !seen; ++k) {
      // On a curve a point reached at two parameters (a self-intersection,
      // the seam of a closed curve) is two minima; on a surface one (a
      // collapsed edge such as a pole has many parameters).
      seen = PointDistance(point, points + static_cast<size_t>(k) * dim, dim) <=
                 options_.separation &&
             (pc == 2 ||
              std::abs(t[0] - parameters[k]) <= prepared_.parameter_slack);
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

// The search runs on the geometry's copy rescaled by powers of two
// (scaled_geometry.h: coordinates and weights at most 1), each query divided
// by the same 2^e. A query farther than 2^kFarQueryExponent from the origin
// in those units (the geometry lies within sqrt(dimension) of it) is
// searched from kFarSearch along its direction instead: every point of the
// geometry is at the same distance from it to rounding (their distances
// differ by at most 2 sqrt(dimension), below 2^-450 of the distance), and
// the nearest point from there is the geometry's point farthest along that
// direction, as it is from the query itself to rounding.
constexpr int kFarQueryExponent = 500;
constexpr double kFarSearch = 0x1p20;
// Tolerances in the copy's units are kept below this, whose square is
// finite.
constexpr double kLargestScaledTolerance = 0x1p510;

// SearchPoint writes where query q (dim coordinates, original units) is
// searched from; returns true when it is a far query.
bool SearchPoint(const double* q, int dim, const internal::ScaledValues& scale,
                 double* out) {
  double largest = 0.0;
  for (int x = 0; x < dim; ++x) largest = std::max(largest, std::abs(q[x]));
  if (internal::ExponentAbove(largest) - scale.coordinate_exponent <=
      kFarQueryExponent) {
    for (int x = 0; x < dim; ++x) out[x] = scale.Unlength(q[x]);
    return false;
  }
  const double norm = internal::ScaledNorm(q, dim);
  for (int x = 0; x < dim; ++x) out[x] = kFarSearch * (q[x] / norm);
  return true;
}

ClosestPointOptions ScaledOptions(const ClosestPointOptions& options,
                                  const internal::ScaledValues& scale) {
  ClosestPointOptions scaled = options;
  scaled.tolerance =
      std::min(scale.Unlength(options.tolerance), kLargestScaledTolerance);
  scaled.separation =
      std::min(scale.Unlength(options.separation), kLargestScaledTolerance);
  return scaled;
}

// Search answers every query on the pieces of the scaled copy; far[r] says
// whether query r was a far one. Distances, points and parameters are the
// copy's.
absl::StatusOr<ClosestPoints> SearchAll(const Pieces& pieces,
                                        const PointsView& queries,
                                        const internal::ScaledValues& scale,
                                        const ClosestPointOptions& options,
                                        const ExecutionContext& context,
                                        std::vector<uint8_t>& far) {
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
  far.assign(count, 0);
  const Prepared prepared(pieces);
  ExecutionContext chunks = context;
  chunks.grain = std::clamp<size_t>(context.grain, 1, 64);
  std::atomic<bool> stopped{false};
  absl::Status status = ParallelFor(count, chunks, [&](size_t b, size_t e) {
    Search search(prepared, options);
    CancellationPoll poll(context.cancellation);
    std::vector<double> from(static_cast<size_t>(pieces.dimension));
    for (size_t r = b; r < e && !stopped.load(std::memory_order_relaxed); ++r) {
      far[r] =
          SearchPoint(queries.point(r), pieces.dimension, scale, from.data());
      if (!search.Run(from.data(), r, poll, answer).ok()) {
        stopped.store(true, std::memory_order_relaxed);
      }
    }
  });
  if (!status.ok()) return status;
  if (stopped.load()) return CheckCancelled(context.cancellation);
  return answer;
}

// Evaluates a geometry's points at `count` parameter tuples.
using PointEvaluator = absl::FunctionRef<absl::Status(absl::Span<const double>,
                                                      absl::Span<double>)>;

// Finisher turns the search's answer into the geometry's own: parameters
// and distances back in the original units, each returned point the
// geometry's point at its returned parameter (evaluated, not the search's
// approximation), the distance the distance to that point, and a check that
// the distance is still within the tolerance of the certified lower bound.
struct Finisher {
  const PointsView& queries;
  const internal::ScaledValues& scale;
  const ClosestPointOptions& options;  // in original units
  const std::vector<uint8_t>& far;
  bool rational;
  PointEvaluator evaluate;

  absl::Status Finish(size_t r, ClosestPoints& answer) const;
  absl::Status CertificationError(size_t r, double distance,
                                  double lower) const;
  absl::Status DistanceOverflow(size_t r, int dim) const;
  // KeepMinimaWithin drops the minima of query r farther than `distance`
  // plus the tolerance at their double parameters (weights so steep that
  // the search's point moved when its parameter was rounded), marking the
  // answer incomplete when it dropped one.
  void KeepMinimaWithin(size_t r, double distance, ClosestPoints& answer) const;
};

void Finisher::KeepMinimaWithin(size_t r, double distance,
                                ClosestPoints& answer) const {
  const size_t count = static_cast<size_t>(answer.counts[r]);
  const size_t dim = static_cast<size_t>(answer.dimension);
  const size_t pc = static_cast<size_t>(answer.parameter_count);
  const size_t slot = r * static_cast<size_t>(answer.max_minima);
  double* points = answer.points.data() + slot * dim;
  double* parameters = answer.parameters.data() + slot * pc;
  constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
  const double limit =
      distance + options.tolerance + 64.0 * kEpsilon * distance;
  size_t kept = 0;
  for (size_t k = 0; k < count; ++k) {
    if (!(internal::ScaledDistance(points + k * dim, queries.point(r),
                                   static_cast<int>(dim)) <= limit)) {
      continue;
    }
    if (kept != k) {
      std::copy_n(points + k * dim, dim, points + kept * dim);
      std::copy_n(parameters + k * pc, pc, parameters + kept * pc);
    }
    ++kept;
  }
  if (kept == count) return;
  answer.counts[r] = static_cast<int>(kept);
  answer.complete[r] = 0;
}

absl::Status Finisher::DistanceOverflow(size_t r, int dim) const {
  const double* q = queries.point(r);
  int largest = 0;
  for (int x = 1; x < dim; ++x) {
    if (std::abs(q[x]) > std::abs(q[largest])) largest = x;
  }
  return InvalidFieldError(
      IndexedField("queries.coordinates",
                   r * static_cast<size_t>(dim) + static_cast<size_t>(largest)),
      "the distance from this query point to the geometry exceeds the "
      "largest double");
}

absl::Status Finisher::CertificationError(size_t r, double distance,
                                          double lower) const {
  const std::string rule = absl::StrCat(
      "the closest point of queries[", r, "] cannot be certified within ",
      options.tolerance, ": the point at the nearest double parameter is ",
      distance, " away while no point of the geometry is nearer than ", lower,
      "; the geometry moves that far between adjacent parameters there");
  if (rational) {
    return InvalidFieldError(
        "weights", absl::StrCat(rule,
                                " (its weights vary that steeply: "
                                "docs/references.md, 'Closest points by branch "
                                "and bound')"));
  }
  return InvalidFieldError("tolerance", rule);
}

absl::Status Finisher::Finish(size_t r, ClosestPoints& answer) const {
  const size_t count = static_cast<size_t>(answer.counts[r]);
  if (count == 0) return absl::OkStatus();
  const int dim = answer.dimension;
  const size_t pc = static_cast<size_t>(answer.parameter_count);
  const size_t slot = r * static_cast<size_t>(answer.max_minima);
  double* parameters = answer.parameters.data() + slot * pc;
  for (size_t k = 0; k < count * pc; ++k) {
    parameters[k] = std::ldexp(
        parameters[k], k % pc == 0 ? scale.u_exponent : scale.v_exponent);
  }
  double* points = answer.points.data() + slot * static_cast<size_t>(dim);
  RETURN_IF_ERROR(
      evaluate(absl::MakeConstSpan(parameters, count * pc),
               absl::MakeSpan(points, count * static_cast<size_t>(dim))));
  const double* q = queries.point(r);
  double distance = kInfinity;
  for (size_t k = 0; k < count; ++k) {
    distance =
        std::min(distance, internal::ScaledDistance(
                               points + k * static_cast<size_t>(dim), q, dim));
  }
  if (!std::isfinite(distance)) return DistanceOverflow(r, dim);
  KeepMinimaWithin(r, distance, answer);
  constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
  const double lower =
      far[r] != 0 ? distance * (1.0 - 16.0 * kEpsilon)
                  : std::min(scale.Length(answer.lower_bounds[r]), distance);
  answer.distances[r] = distance;
  answer.lower_bounds[r] = lower;
  // From a far query every point is at the minimum distance to rounding.
  if (far[r] != 0) answer.complete[r] = 0;
  if (answer.complete[r] == 0) return absl::OkStatus();
  // The rounding of the hull bounds and of the evaluations: a few units in
  // the last place of the coordinates' scale.
  double size = scale.Length(1.0);
  for (int x = 0; x < dim; ++x) size = std::max(size, std::abs(q[x]));
  if (distance - lower <= options.tolerance + 64.0 * kEpsilon * size) {
    return absl::OkStatus();
  }
  return CertificationError(r, distance, lower);
}

// Finish runs the Finisher over every query in chunks; the failure of the
// first query that fails, if any, is returned.
absl::Status Finish(const Finisher& finisher, ClosestPoints& answer,
                    const ExecutionContext& context) {
  std::atomic<size_t> first_failure{std::numeric_limits<size_t>::max()};
  std::vector<absl::Status> failures(answer.counts.size());
  ExecutionContext chunks = context;
  chunks.grain = std::clamp<size_t>(context.grain, 1, 256);
  absl::Status status =
      ParallelFor(answer.counts.size(), chunks, [&](size_t b, size_t e) {
        for (size_t r = b; r < e; ++r) {
          absl::Status result = finisher.Finish(r, answer);
          if (result.ok()) continue;
          failures[r] = std::move(result);
          size_t seen = first_failure.load();
          while (r < seen && !first_failure.compare_exchange_weak(seen, r)) {
          }
          return;
        }
      });
  if (!status.ok()) return status;
  const size_t r = first_failure.load();
  return r < failures.size() ? failures[r] : absl::OkStatus();
}

bool IsRational(const Pieces& pieces) {
  for (const Net& net : pieces.nets) {
    if (net.rational) return true;
  }
  return false;
}

absl::StatusOr<Pieces> ScaledPieces(const internal::ScaledCurve& scaled,
                                    const CancellationToken* cancel) {
  return internal::LiftPieces(scaled.curve(), cancel);
}

absl::StatusOr<Pieces> ScaledPieces(const internal::ScaledSurface& scaled,
                                    const CancellationToken* cancel) {
  return internal::LiftPieces(scaled.surface(), cancel);
}

internal::ScaledCurve ScaledOf(const Curve& curve) {
  return internal::ScaledCurve::Of(curve);
}

internal::ScaledSurface ScaledOf(const Surface& surface) {
  return internal::ScaledSurface::Of(surface);
}

absl::Status EvaluatePoints(const Curve& curve,
                            absl::Span<const double> parameters,
                            absl::Span<double> points) {
  const absl::Span<double> output[] = {points};
  return EvaluateCurve(curve, parameters, output);
}

absl::Status EvaluatePoints(const Surface& surface,
                            absl::Span<const double> parameters,
                            absl::Span<double> points) {
  const absl::Span<double> output[] = {points};
  return EvaluateSurface(surface, SurfaceSamples::Pairs(parameters), output,
                         {});
}

// ClosestPointsOn checks the options and queries and answers them on a
// curve or a surface.
template <typename Geometry>
absl::StatusOr<ClosestPoints> ClosestPointsOn(
    const Geometry& geometry, const PointsView& queries,
    const ClosestPointOptions& options, const ExecutionContext& context) {
  RETURN_IF_ERROR(CheckOptions(options));
  RETURN_IF_ERROR(CheckQueries(queries, DimensionOf(geometry)));
  const auto scaled = ScaledOf(geometry);
  absl::StatusOr<Pieces> pieces = ScaledPieces(scaled, context.cancellation);
  if (!pieces.ok()) return pieces.status();
  for (Net& net : pieces->nets) internal::NormalizeWeights(net);
  std::vector<uint8_t> far;
  absl::StatusOr<ClosestPoints> answer =
      SearchAll(*pieces, queries, scaled.scale(),
                ScaledOptions(options, scaled.scale()), context, far);
  if (!answer.ok()) return answer.status();
  const auto evaluate = [&](absl::Span<const double> parameters,
                            absl::Span<double> points) {
    return EvaluatePoints(geometry, parameters, points);
  };
  const Finisher finisher{.queries = queries,
                          .scale = scaled.scale(),
                          .options = options,
                          .far = far,
                          .rational = IsRational(*pieces),
                          .evaluate = evaluate};
  RETURN_IF_ERROR(Finish(finisher, *answer, context));
  return answer;
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
