#include "geometry_arrays.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "field_mutations.h"

namespace freeform::fuzz {
namespace {

// Weights where rational arithmetic changes behaviour: products with
// coordinates overflow or underflow, sums lose the small terms.
constexpr double kExtremeWeights[] = {1e10,
                                      1e15,
                                      1e20,
                                      1e50,
                                      1e100,
                                      1e300,
                                      1e-10,
                                      1e-15,
                                      1e-50,
                                      1e-300,
                                      std::numeric_limits<double>::denorm_min(),
                                      0.0};

std::vector<double> ClampedUniform(size_t count, int degree, double lo,
                                   double hi) {
  const size_t p = static_cast<size_t>(degree);
  const size_t interior = count - p - 1;
  std::vector<double> knots(p + 1, lo);
  for (size_t i = 1; i <= interior; ++i) {
    knots.push_back(lo + (hi - lo) * static_cast<double>(i) /
                             static_cast<double>(interior + 1));
  }
  knots.insert(knots.end(), p + 1, hi);
  return knots;
}

std::vector<double> Uniform(size_t size, double lo, double hi) {
  std::vector<double> knots(size);
  for (size_t i = 0; i < size; ++i) {
    knots[i] =
        lo + (hi - lo) * static_cast<double>(i) / static_cast<double>(size - 1);
  }
  return knots;
}

// Resized keeps the old knots, sorted, and drops interior ones or adds
// knots in the middle of the widest spans until there are `size`.
std::vector<double> Resized(absl::Span<const double> old, size_t size,
                            FuzzRandom& random) {
  std::vector<double> knots(old.begin(), old.end());
  knots.erase(std::remove_if(knots.begin(), knots.end(),
                             [](double k) { return !std::isfinite(k); }),
              knots.end());
  std::sort(knots.begin(), knots.end());
  if (knots.size() < 2) knots = {0.0, 1.0};
  // size >= 2 (a count >= 1 and a degree >= 0): the ends stay.
  while (knots.size() > size) {
    knots.erase(knots.begin() +
                static_cast<ptrdiff_t>(1 + random.Below(knots.size() - 2)));
  }
  while (knots.size() < size) {
    size_t widest = 0;
    for (size_t i = 1; i + 1 < knots.size(); ++i) {
      if (knots[i + 1] - knots[i] > knots[widest + 1] - knots[widest]) {
        widest = i;
      }
    }
    // Now and then a copy of an existing knot instead (a multiple knot).
    const size_t at = widest + 1;
    const double value = random.OneIn(4)
                             ? knots[random.Below(knots.size())]
                             : 0.5 * (knots[widest] + knots[widest + 1]);
    knots.insert(knots.begin() + static_cast<ptrdiff_t>(at), value);
    std::sort(knots.begin(), knots.end());
  }
  return knots;
}

// The old domain [knots[degree], knots[size - degree - 1]] when it is
// finite and not empty, else [0, 1].
void DomainOf(absl::Span<const double> old, int degree, double& lo,
              double& hi) {
  lo = 0.0;
  hi = 1.0;
  const size_t p = static_cast<size_t>(std::max(degree, 0));
  if (old.size() < 2 * p + 2) {
    if (old.size() >= 2 && std::isfinite(old.front()) &&
        std::isfinite(old.back()) && old.front() < old.back()) {
      lo = old.front();
      hi = old.back();
    }
    return;
  }
  const double a = old[p], b = old[old.size() - p - 1];
  if (std::isfinite(a) && std::isfinite(b) && a < b) {
    lo = a;
    hi = b;
  }
}

// Distort moves knots to where their spans lose precision: scaled to
// 1e+-170 (squared lengths overflow), shifted to 1e10 (spans of a few
// ulps), or squeezed into 1e-12 around the middle (clustered).
void Distort(std::vector<double>& knots, FuzzRandom& random) {
  switch (random.Below(3)) {
    case 0: {
      const double scale = random.Pick(
          absl::MakeConstSpan({1e170, 1e-170, 1e300, 1e-300, 1e50, 1e-50}));
      for (double& k : knots) k *= scale;
      return;
    }
    case 1: {
      const double offset = random.Pick(absl::MakeConstSpan({1e10, 1e15}));
      for (double& k : knots) k += offset;
      return;
    }
    default: {
      const double middle = 0.5 * (knots.front() + knots.back());
      for (size_t i = 1; i + 1 < knots.size(); ++i) {
        knots[i] = middle + (knots[i] - middle) * 1e-12;
      }
      std::sort(knots.begin(), knots.end());
    }
  }
}

}  // namespace

size_t NewCount(size_t count, size_t min_count, size_t max_count,
                FuzzRandom& random) {
  size_t result = count;
  switch (random.Below(6)) {
    case 0:
      result = count + 1;
      break;
    case 1:
      result = count > 0 ? count - 1 : 0;
      break;
    case 2:
      result = 2 * count;
      break;
    case 3:
      result = count / 2;
      break;
    case 4:
      result = min_count + random.Below(2);
      break;
    default:
      result = min_count + random.Below(2 * count + 3);
  }
  return std::clamp(result, min_count, std::max(min_count, max_count));
}

std::vector<double> SamplePositions(size_t count, size_t new_count,
                                    FuzzRandom& random) {
  std::vector<double> positions(new_count);
  const double last = static_cast<double>(count - 1);
  switch (random.Below(3)) {
    case 0:  // whole numbers: points duplicated or dropped
      for (double& p : positions) {
        p = static_cast<double>(random.Below(count));
      }
      std::sort(positions.begin(), positions.end());
      break;
    case 1:  // evenly spaced: new points between the old ones
      for (size_t i = 0; i < new_count; ++i) {
        positions[i] = new_count == 1 ? 0.0
                                      : last * static_cast<double>(i) /
                                            static_cast<double>(new_count - 1);
      }
      break;
    default:  // the first points, then the last one repeated
      for (size_t i = 0; i < new_count; ++i) {
        positions[i] = std::min(static_cast<double>(i), last);
      }
  }
  return positions;
}

std::vector<double> Resample(absl::Span<const double> values, int dimension,
                             absl::Span<const double> positions) {
  const size_t dim = static_cast<size_t>(dimension);
  const size_t count = values.size() / dim;
  std::vector<double> out;
  out.reserve(positions.size() * dim);
  for (double position : positions) {
    const size_t i = std::min(static_cast<size_t>(position), count - 1);
    const size_t next = std::min(i + 1, count - 1);
    const double f = position - static_cast<double>(i);
    for (size_t j = 0; j < dim; ++j) {
      const double a = values[i * dim + j], b = values[next * dim + j];
      out.push_back(f == 0.0 ? a : a + f * (b - a));
    }
  }
  return out;
}

std::vector<double> ResampleNet(absl::Span<const double> values, int dimension,
                                size_t count_u, size_t count_v,
                                absl::Span<const double> positions_u,
                                absl::Span<const double> positions_v) {
  const size_t row = count_v * static_cast<size_t>(dimension);
  // Rows first (each row is one "point" of count_v * dimension values),
  // then the columns of every new row.
  const std::vector<double> rows = Resample(values.subspan(0, count_u * row),
                                            static_cast<int>(row), positions_u);
  std::vector<double> out;
  for (size_t i = 0; i < positions_u.size(); ++i) {
    const std::vector<double> columns =
        Resample(absl::MakeConstSpan(rows).subspan(i * row, row), dimension,
                 positions_v);
    out.insert(out.end(), columns.begin(), columns.end());
  }
  return out;
}

std::vector<double> MakeKnots(size_t count, int degree,
                              absl::Span<const double> old,
                              FuzzRandom& random) {
  const size_t size = count + static_cast<size_t>(degree) + 1;
  double lo = 0.0, hi = 1.0;
  DomainOf(old, degree, lo, hi);
  std::vector<double> knots;
  switch (random.Below(6)) {
    case 0:
    case 1:
      knots = ClampedUniform(count, degree, lo, hi);
      break;
    case 2:
      knots = Uniform(size, lo, hi);
      break;
    case 3: {  // clamped, random interior knots
      knots = ClampedUniform(count, degree, lo, hi);
      for (size_t i = static_cast<size_t>(degree) + 1; i < count; ++i) {
        knots[i] = lo + (hi - lo) * random.Unit();
      }
      std::sort(knots.begin(), knots.end());
      break;
    }
    case 4: {  // an interior knot of multiplicity degree or degree + 1
      knots = ClampedUniform(count, degree, lo, hi);
      const size_t first = static_cast<size_t>(degree) + 1;
      if (count > first) {
        const size_t at = first + random.Below(count - first);
        const size_t run =
            static_cast<size_t>(degree) + (random.OneIn(3) ? 1 : 0);
        for (size_t i = at; i < std::min(at + run, count); ++i) {
          knots[i] = knots[at];
        }
        std::sort(knots.begin(), knots.end());
      }
      break;
    }
    default:
      knots = Resized(old, size, random);
  }
  if (random.OneIn(6)) Distort(knots, random);
  return knots;
}

void MutateWeights(DoubleField& weights, size_t count, FuzzRandom& random) {
  std::vector<double> w(SpanOf(weights).begin(), SpanOf(weights).end());
  w.resize(count, 1.0);
  const auto extreme = [&] {
    return random.Pick(absl::MakeConstSpan(kExtremeWeights));
  };
  switch (random.Below(9)) {
    case 0:
      std::fill(w.begin(), w.end(), 1.0);
      break;
    case 1:
    case 2:
      if (count > 0) w[random.Below(count)] = extreme();
      break;
    case 3: {  // every other weight extreme
      const double value = extreme();
      for (size_t i = 1; i < count; i += 2) w[i] = value;
      break;
    }
    case 4: {  // a ramp over many orders of magnitude
      const double exponent = random.Pick(
          absl::MakeConstSpan({10.0, -10.0, 50.0, -50.0, 300.0, -300.0}));
      for (size_t i = 0; i < count; ++i) {
        w[i] = std::pow(
            10.0, exponent * static_cast<double>(i) /
                      static_cast<double>(std::max<size_t>(count - 1, 1)));
      }
      break;
    }
    case 5: {  // all scaled alike: the same geometry
      const double scale = ExtremePowerOfTen(random);
      for (double& value : w) value *= scale;
      break;
    }
    case 6:
      for (double& value : w) value = 0.1 + 9.9 * random.Unit();
      break;
    case 7:  // one zero or negative weight
      if (count > 0) w[random.Below(count)] = random.OneIn(2) ? 0.0 : -1.0;
      break;
    default:
      w.clear();
  }
  Assign(weights, w);
}

void MutatePointValues(DoubleField& coordinates, int dimension,
                       FuzzRandom& random) {
  const size_t dim = static_cast<size_t>(std::max(dimension, 1));
  const size_t count = static_cast<size_t>(coordinates.size()) / dim;
  if (count == 0) return;
  double* p = coordinates.mutable_data();
  const auto point = [&](size_t i) { return p + i * dim; };
  switch (random.Below(7)) {
    case 0: {  // all equal
      const size_t from = random.Below(count);
      for (size_t i = 0; i < count; ++i) {
        std::copy_n(point(from), dim, point(i));
      }
      return;
    }
    case 1: {  // two neighbours equal
      if (count < 2) return;
      const size_t i = random.Below(count - 1);
      std::copy_n(point(i), dim, point(i + 1));
      return;
    }
    case 2: {  // all on the line through the first two
      if (count < 3) return;
      for (size_t i = 2; i < count; ++i) {
        const double t = static_cast<double>(i);
        for (size_t j = 0; j < dim; ++j) {
          point(i)[j] = point(0)[j] + t * (point(1)[j] - point(0)[j]);
        }
      }
      return;
    }
    case 3: {  // one coordinate constant: a plane
      const size_t j = random.Below(dim);
      for (size_t i = 0; i < count; ++i) point(i)[j] = point(0)[j];
      return;
    }
    case 4: {
      const double scale = ExtremePowerOfTen(random);
      for (size_t k = 0; k < count * dim; ++k) p[k] *= scale;
      return;
    }
    case 5: {
      const double offset = random.Pick(absl::MakeConstSpan({1e10, 1e15}));
      for (size_t k = 0; k < count * dim; ++k) p[k] += offset;
      return;
    }
    default: {  // one point far away
      const double scale = ExtremePowerOfTen(random);
      double* q = point(random.Below(count));
      for (size_t j = 0; j < dim; ++j) q[j] *= scale;
    }
  }
}

std::vector<double> Repack(absl::Span<const double> values, int dimension,
                           int new_dimension, FuzzRandom& random) {
  const size_t dim = static_cast<size_t>(dimension);
  const size_t new_dim = static_cast<size_t>(new_dimension);
  const size_t count = values.size() / dim;
  const bool zeros = random.OneIn(2);
  std::vector<double> out;
  out.reserve(count * new_dim);
  for (size_t i = 0; i < count; ++i) {
    for (size_t j = 0; j < new_dim; ++j) {
      out.push_back(j < dim ? values[i * dim + j]
                            : (zeros ? 0.0 : values[i * dim]));
    }
  }
  return out;
}

void Assign(DoubleField& field, absl::Span<const double> values) {
  field.Clear();
  field.Add(values.begin(), values.end());
}

}  // namespace freeform::fuzz
