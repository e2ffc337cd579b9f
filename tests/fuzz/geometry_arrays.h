// The arrays of geometry that the structure-aware mutator
// (geometry_mutations.h) changes together: point sequences and nets
// resampled to another size (with their weights, by the same choice of
// rows and columns), knot vectors made for a degree and a count, weights
// made extreme, points made equal, collinear or huge. Each function keeps
// the sizes consistent: points * dimension coordinates, one weight per
// point, count + degree + 1 knots. Deterministic given the FuzzRandom.
#ifndef FREEFORM_TESTS_FUZZ_GEOMETRY_ARRAYS_H_
#define FREEFORM_TESTS_FUZZ_GEOMETRY_ARRAYS_H_

#include <cstddef>
#include <vector>

#include "absl/types/span.h"
#include "fuzz_random.h"
#include "google/protobuf/repeated_field.h"

namespace freeform::fuzz {

using DoubleField = google::protobuf::RepeatedField<double>;

// NewCount returns a new number of points for an array of `count`, at
// least `min_count` and at most `max_count`: count +- 1, doubled, halved,
// the minimum or a random count.
size_t NewCount(size_t count, size_t min_count, size_t max_count,
                FuzzRandom& random);

// SamplePositions returns `new_count` positions in [0, count - 1] (count
// >= 1) of the points of a resampled array, non-decreasing: whole numbers
// (points duplicated or dropped), evenly spaced (new points between old
// ones), or a prefix that repeats the last point.
std::vector<double> SamplePositions(size_t count, size_t new_count,
                                    FuzzRandom& random);

// Resample returns the points of `values` (points of `dimension` values)
// at `positions`, each linearly interpolated between its neighbours.
std::vector<double> Resample(absl::Span<const double> values, int dimension,
                             absl::Span<const double> positions);

// ResampleNet returns a net of count_u x count_v points of `dimension`
// values (row-major, P[i][j] at i * count_v + j) resampled to
// positions_u.size() x positions_v.size() points.
std::vector<double> ResampleNet(absl::Span<const double> values, int dimension,
                                size_t count_u, size_t count_v,
                                absl::Span<const double> positions_u,
                                absl::Span<const double> positions_v);

// MakeKnots returns count + degree + 1 knots for a B-spline of `degree`
// with `count` control points (count >= degree + 1): clamped uniform,
// uniform (unclamped), clamped with random or clustered interior knots,
// with an interior knot of multiplicity degree or degree + 1, `old`
// resized, or any of these scaled to 1e+-170 or shifted to 1e10 where
// the spans lose precision. The domain is the old one when it is usable.
std::vector<double> MakeKnots(size_t count, int degree,
                              absl::Span<const double> old, FuzzRandom& random);

// MutateWeights rewrites the weights of `count` points: all 1, one weight
// or every other one extreme (1e+-10 .. 1e+-300, 5e-324, 0), a ramp over
// 1e+-50, all scaled alike, random in [0.1, 10], one zero or negative, or
// none (polynomial).
void MutateWeights(DoubleField& weights, size_t count, FuzzRandom& random);

// MutatePointValues changes the coordinates of the points in place, the
// count kept: all equal, two neighbours equal, all on a line, one
// coordinate constant (a plane), scaled by 10^k, moved to 1e10, or one
// point far away.
void MutatePointValues(DoubleField& coordinates, int dimension,
                       FuzzRandom& random);

// Repack returns points of `dimension` values as points of
// `new_dimension` values: coordinates dropped, or added as zeros or
// copies of the first.
std::vector<double> Repack(absl::Span<const double> values, int dimension,
                           int new_dimension, FuzzRandom& random);

// Assign replaces the values of a repeated field.
void Assign(DoubleField& field, absl::Span<const double> values);

// Span returns a view of a repeated field.
inline absl::Span<const double> SpanOf(const DoubleField& field) {
  return absl::MakeConstSpan(field.data(), static_cast<size_t>(field.size()));
}

}  // namespace freeform::fuzz

#endif  // FREEFORM_TESTS_FUZZ_GEOMETRY_ARRAYS_H_
