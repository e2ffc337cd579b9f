#include "queries/speed.h"

#include <algorithm>
#include <array>

#include "absl/types/span.h"
#include "base/scaled.h"
#include "freeform/core/arc_length.h"

namespace freeform::internal {
namespace {

struct Rule {
  std::array<double, kSpeedRulePoints> nodes;
  std::array<double, kSpeedRulePoints> weights;
};

const Rule& SixteenPointRule() {
  static const Rule rule = [] {
    Rule r;
    GaussLegendreRule(kSpeedRulePoints, absl::MakeSpan(r.nodes),
                      absl::MakeSpan(r.weights));
    return r;
  }();
  return rule;
}

}  // namespace

const double* Reduce(double* points, int count, size_t stride, double s) {
  for (int level = count - 1; level > 0; --level) {
    for (int i = 0; i < level; ++i) {
      double* p = points + static_cast<size_t>(i) * stride;
      for (size_t x = 0; x < stride; ++x) {
        p[x] = (1.0 - s) * p[x] + s * p[x + stride];
      }
    }
  }
  return points;
}

double SpeedIntegrator::Integrate(const Net& net, double a, double b) {
  const Rule& rule = SixteenPointRule();
  const double mid = 0.5 * (a + b);
  const double half = 0.5 * (b - a);
  Nodes s;
  for (int i = 0; i < kSpeedRulePoints; ++i) {
    s[i] = std::clamp(mid + half * rule.nodes[i], a, b);
  }
  Nodes speeds;
  Speeds(net, s, speeds);
  double sum = 0.0;
  for (int i = 0; i < kSpeedRulePoints; ++i) sum += rule.weights[i] * speeds[i];
  return half * sum;
}

void SpeedIntegrator::Speeds(const Net& net, const Nodes& s, Nodes& speeds) {
  const int n = net.count_u - 1;
  if (n <= 0) {
    speeds.fill(0.0);
    return;
  }
  const size_t stride = static_cast<size_t>(net.stride());
  const size_t dim = static_cast<size_t>(net.dimension);
  constexpr size_t kNodes = kSpeedRulePoints;
  // Every value once per node, the nodes innermost: one de Casteljau step
  // runs over the nodes at once.
  auto spread = [&](std::vector<double>& batch, size_t count, auto value) {
    batch.resize(count * kNodes);
    for (size_t k = 0; k < count; ++k) {
      std::fill_n(batch.data() + k * kNodes, kNodes, value(k));
    }
  };
  spread(differences_, static_cast<size_t>(n) * stride,
         [&](size_t k) { return net.values[k + stride] - net.values[k]; });
  ReduceNodes(differences_.data(), n, stride, s);
  gather_.resize(dim);
  const double* d = differences_.data();
  if (!net.rational) {
    for (size_t node = 0; node < kNodes; ++node) {
      for (size_t x = 0; x < dim; ++x) gather_[x] = d[x * kNodes + node];
      speeds[node] = n * ScaledNorm(gather_.data(), net.dimension);
    }
    return;
  }
  spread(values_, static_cast<size_t>(n + 1) * stride,
         [&](size_t k) { return net.values[k]; });
  ReduceNodes(values_.data(), n + 1, stride, s);
  const double* a = values_.data();
  for (size_t node = 0; node < kNodes; ++node) {
    const double w = a[dim * kNodes + node];
    const double dw = d[dim * kNodes + node];
    for (size_t x = 0; x < dim; ++x) {
      gather_[x] = d[x * kNodes + node] * w - a[x * kNodes + node] * dw;
    }
    speeds[node] = n * ScaledNorm(gather_.data(), net.dimension) / (w * w);
  }
}

void SpeedIntegrator::ReduceNodes(double* batch, int count, size_t stride,
                                  const Nodes& s) {
  constexpr size_t kNodes = kSpeedRulePoints;
  Nodes complement;
  for (size_t node = 0; node < kNodes; ++node) complement[node] = 1.0 - s[node];
  const size_t point = stride * kNodes;
  for (int level = count - 1; level > 0; --level) {
    for (int i = 0; i < level; ++i) {
      double* p = batch + static_cast<size_t>(i) * point;
      const double* q = p + point;
      for (size_t x = 0; x < stride; ++x) {
        for (size_t node = 0; node < kNodes; ++node) {
          const size_t k = x * kNodes + node;
          p[k] = complement[node] * p[k] + s[node] * q[k];
        }
      }
    }
  }
}

double SpeedIntegrator::Speed(const Net& net, double s) {
  const int n = net.count_u - 1;
  if (n <= 0) return 0.0;
  const size_t stride = static_cast<size_t>(net.stride());
  const size_t dim = static_cast<size_t>(net.dimension);
  differences_.resize(static_cast<size_t>(n) * stride);
  for (size_t k = 0; k < differences_.size(); ++k) {
    differences_[k] = net.values[k + stride] - net.values[k];
  }
  const double* d = Reduce(differences_.data(), n, stride, s);
  if (!net.rational) return n * ScaledNorm(d, net.dimension);
  values_.assign(net.values.begin(), net.values.end());
  const double* a = Reduce(values_.data(), n + 1, stride, s);
  const double w = a[dim];
  gather_.resize(dim);
  for (size_t x = 0; x < dim; ++x) gather_[x] = d[x] * w - a[x] * d[dim];
  return n * ScaledNorm(gather_.data(), net.dimension) / (w * w);
}

}  // namespace freeform::internal
