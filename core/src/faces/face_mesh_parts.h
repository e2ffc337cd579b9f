// The steps of TessellateFace (face_mesh.h): the boundary's samples and
// the interior grid in (u, v). Internal to the core.
#ifndef FREEFORM_CORE_SRC_FACES_FACE_MESH_PARTS_H_
#define FREEFORM_CORE_SRC_FACES_FACE_MESH_PARTS_H_

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "faces/face_metric.h"
#include "freeform/core/cancellation.h"
#include "freeform/core/constrained_delaunay.h"
#include "freeform/core/trimmed_surface.h"

namespace freeform::internal {

// The boundary of a face as closed chains of (u, v) points.
struct SampledBoundary {
  std::vector<freeform::Point2> points;
  std::vector<std::array<int32_t, 2>> segments;
};

// SampleFaceBoundary samples every loop (the parameter rectangle's sides
// without an outer loop): SampleTrimCurve at tolerance / 2, then chords
// halved at their curve parameter's midpoint until metric.SegmentBound is
// at most tolerance / 2. Points are clamped into the surface's domain.
// Fails as SampleTrimCurve does, and with RESOURCE_EXHAUSTED naming
// "max_vertices" beyond max_vertices points.
absl::StatusOr<SampledBoundary> SampleFaceBoundary(
    const TrimmedSurface& face, const FaceMetric& metric, double tolerance,
    size_t max_vertices, const CancellationToken* cancel);

// InteriorGrid returns the nodes of each span rectangle's uniform grid
// (cells meeting the planner's bound, NeededCells of A du^2 and B dv^2)
// that ClassifyPoints puts inside the face with a boundary tolerance of
// 0.3 grid spacings. Fails with RESOURCE_EXHAUSTED naming "max_vertices"
// when the grids, with `boundary_points`, exceed max_vertices (counted
// before any node is made), and with the token's status.
absl::StatusOr<std::vector<freeform::Point2>> InteriorGrid(
    const TrimmedSurface& face, const FaceMetric& metric, double tolerance,
    size_t boundary_points, size_t max_vertices,
    const CancellationToken* cancel);

// TooManyVertices is the RESOURCE_EXHAUSTED naming "max_vertices".
absl::Status TooManyVertices(size_t max_vertices);

}  // namespace freeform::internal

#endif  // FREEFORM_CORE_SRC_FACES_FACE_MESH_PARTS_H_
