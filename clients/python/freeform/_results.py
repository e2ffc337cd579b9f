"""The answers of the Client's methods: numpy arrays and freeform.v1 messages.

Every array is a fresh, aligned, writable numpy array (float64 for
coordinates and parameters, int64 for indices and counts). Points are
``(n, d)``; curve derivatives ``(k + 1, n, d)`` with ``[0]`` the points.
Curves and surfaces are ``geometry_pb2.Curve`` / ``Surface`` messages
(``freeform.to_array`` gives their control points).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Dict, Iterable, List, Optional, Tuple

import numpy as np

from freeform.v1 import geometry_pb2 as _geometry


def _nonempty(chunks: Iterable) -> list:
    chunks = list(chunks)
    if not chunks:
        raise ValueError("no chunks to join")
    return chunks


def _concatenate(chunks: list, field: str, axis: int = 0) -> np.ndarray:
    return np.concatenate([getattr(chunk, field) for chunk in chunks], axis)


@dataclass(frozen=True)
class CurveSamples:
    """Points and derivatives of a curve at n parameters.

    Attributes:
      derivatives: ``(k + 1, n, d)``: derivatives[j][r] is the j-th
        derivative at parameter r; derivatives[0] are the points.
      first_index: where these samples start among the parameters (0 for
        Evaluate; a stream chunk's position).
    """

    derivatives: np.ndarray
    first_index: int = 0

    @property
    def points(self) -> np.ndarray:
        """The ``(n, d)`` points (derivatives[0])."""
        return self.derivatives[0]

    @staticmethod
    def join(chunks: Iterable["CurveSamples"]) -> "CurveSamples":
        """One CurveSamples of a stream's chunks (in order)."""
        chunks = _nonempty(chunks)
        return CurveSamples(_concatenate(chunks, "derivatives", axis=1),
                            chunks[0].first_index)


@dataclass(frozen=True)
class SurfaceSamples:
    """Points, partial derivatives and normals of a surface at n points.

    Attributes:
      partials: ``{(k, l): (n, d) array}``, the partial d^(k+l)S/du^k dv^l,
        in the server's order (0,0), (1,0), (0,1), (2,0), (1,1), (0,2), ...
      normals: ``(n, 3)`` unit normals when asked for, else None.
      first_index: where these points start (a stream chunk's position).
    """

    partials: Dict[Tuple[int, int], np.ndarray]
    normals: Optional[np.ndarray] = None
    first_index: int = 0

    @property
    def points(self) -> np.ndarray:
        """The ``(n, d)`` points (partial (0, 0))."""
        return self.partials[(0, 0)]

    @staticmethod
    def join(chunks: Iterable["SurfaceSamples"]) -> "SurfaceSamples":
        """One SurfaceSamples of a stream's chunks (in order)."""
        chunks = _nonempty(chunks)
        return SurfaceSamples(
            {order: np.concatenate([chunk.partials[order]
                                    for chunk in chunks])
             for order in chunks[0].partials},
            (_concatenate(chunks, "normals")
             if chunks[0].normals is not None else None),
            chunks[0].first_index)


@dataclass(frozen=True)
class Polyline:
    """A curve's polyline: ``(n, d)`` points and their ``(n,)`` curve
    parameters."""

    points: np.ndarray
    parameters: np.ndarray


@dataclass(frozen=True)
class Mesh:
    """A triangle mesh.

    Attributes:
      vertices: ``(V, 3)`` vertex positions.
      triangles: ``(T, 3)`` int64 vertex indices, counter-clockwise seen
        against the normal S_u x S_v. In a TessellateStream chunk they index
        all the vertices of the stream so far.
      normals: ``(V, 3)`` unit normals when asked for, else None.
      surface_index: ``(V,)`` the surface each vertex lies on.
      uv: ``(V, 2)`` each vertex's parameters on that surface.
    """

    vertices: np.ndarray
    triangles: np.ndarray
    normals: Optional[np.ndarray]
    surface_index: np.ndarray
    uv: np.ndarray

    @staticmethod
    def join(chunks: Iterable["Mesh"]) -> "Mesh":
        """The whole mesh of a TessellateStream's chunks (in order)."""
        chunks = _nonempty(chunks)
        return Mesh(_concatenate(chunks, "vertices"),
                    _concatenate(chunks, "triangles"),
                    (_concatenate(chunks, "normals")
                     if chunks[0].normals is not None else None),
                    _concatenate(chunks, "surface_index"),
                    _concatenate(chunks, "uv"))


@dataclass(frozen=True)
class Decomposition:
    """A curve as Bezier segments: segment k covers [breakpoints[k],
    breakpoints[k + 1]] of the curve's parameter."""

    segments: List[_geometry.Curve]
    breakpoints: np.ndarray


@dataclass(frozen=True)
class Subdivision:
    """A subdivided polygon ``(n, d)`` and, when asked for, the polygon
    after each level."""

    polygon: np.ndarray
    levels: List[np.ndarray]


@dataclass(frozen=True)
class DegreeReduction:
    """A Bezier curve of lower degree and a bound of its distance to the
    original over [0, 1]."""

    curve: _geometry.Curve
    error_bound: float


@dataclass(frozen=True)
class CurveFit:
    """An interpolated, approximated or fitted B-spline curve.

    Attributes:
      curve: the B-spline curve.
      parameters: ``(n,)`` the parameter of each data point.
      max_residual, rms_residual: the largest and root-mean-square distance
        of a data point to the curve at its parameter.
      refinement_rounds: Fit only: how many times knots were inserted.
    """

    curve: _geometry.Curve
    parameters: np.ndarray
    max_residual: float
    rms_residual: float
    refinement_rounds: int = 0


@dataclass(frozen=True)
class CurveKnotRemoval:
    """The curve on fewer knots, how many copies went, and the certified
    bound of its distance to the input."""

    curve: _geometry.Curve
    removals: int
    error_bound: float


@dataclass(frozen=True)
class ClosestPoints:
    """The certified closest points of m queries.

    Attributes:
      distances: ``(m,)`` the smallest distance per query.
      lower_bounds: ``(m,)`` certified: no point is closer.
      minima_counts: ``(m,)`` how many minima each query has (>= 1).
      complete: ``(m,)`` whether those are all of them.
      parameters: ``(K, p)`` every minimum's parameters (p = 1 for a curve,
        2 for a surface), closest first within each query.
      points: ``(K, d)`` every minimum's point.
    """

    distances: np.ndarray
    lower_bounds: np.ndarray
    minima_counts: np.ndarray
    complete: np.ndarray
    parameters: np.ndarray
    points: np.ndarray

    def _firsts(self) -> np.ndarray:
        return np.cumsum(self.minima_counts) - self.minima_counts

    @property
    def closest_parameters(self) -> np.ndarray:
        """``(m, p)``: each query's closest minimum's parameters."""
        return self.parameters[self._firsts()]

    @property
    def closest_points(self) -> np.ndarray:
        """``(m, d)``: each query's closest point."""
        return self.points[self._firsts()]


@dataclass(frozen=True)
class CurveIntersections:
    """Where two curves meet: first(first_parameters[k]) is within the
    tolerance of second(second_parameters[k]), at points[k] ``(k, d)``;
    overlap j runs over first_intervals[j] ``(j, 2)`` of the first curve and
    second_intervals[j] of the second."""

    first_parameters: np.ndarray
    second_parameters: np.ndarray
    points: np.ndarray
    first_intervals: np.ndarray
    second_intervals: np.ndarray


@dataclass(frozen=True)
class CurveSurfaceIntersections:
    """Where a curve meets a surface: curve(curve_parameters[k]) is within
    the tolerance of surface(surface_parameters[k]) ``(k, 2)``, at
    points[k]."""

    curve_parameters: np.ndarray
    surface_parameters: np.ndarray
    points: np.ndarray


@dataclass(frozen=True)
class ArcSamples:
    """Curve parameters ``(n,)`` and the curve's points there ``(n, d)``."""

    parameters: np.ndarray
    points: np.ndarray


@dataclass(frozen=True)
class CurveCurvature:
    """The Frenet frame, curvature and torsion at n parameters.

    Attributes:
      tangents, normals: ``(n, d)`` unit vectors (zeros where undefined).
      binormals: ``(n, 3)`` for 3D curves, else None.
      curvatures: ``(n,)`` unsigned.
      torsions: ``(n,)`` for 3D curves, else None.
      statuses: ``(n,)`` CurvePointStatus values: 0 regular, 1 straight, 2
        singular.
    """

    tangents: np.ndarray
    normals: np.ndarray
    binormals: Optional[np.ndarray]
    curvatures: np.ndarray
    torsions: Optional[np.ndarray]
    statuses: np.ndarray


@dataclass(frozen=True)
class Frames:
    """Rotation-minimizing frames at n parameters: the unit tangents and
    reference vectors ``(n, d)``, and in 3D the third vectors t x r (else
    None)."""

    tangents: np.ndarray
    references: np.ndarray
    third: Optional[np.ndarray]


@dataclass(frozen=True)
class BoundingBox:
    """lower[j] <= x_j <= upper[j] for every point x of the geometry."""

    lower: np.ndarray
    upper: np.ndarray


@dataclass(frozen=True)
class SurfaceFit:
    """An interpolated or fitted B-spline surface and the grid's parameters
    (and, for Fit, the residuals and refinement rounds)."""

    surface: _geometry.Surface
    parameters_u: np.ndarray
    parameters_v: np.ndarray
    max_residual: float = 0.0
    rms_residual: float = 0.0
    refinement_rounds: int = 0


@dataclass(frozen=True)
class ScatteredFit:
    """A B-spline surface fitted to scattered points: the ``(n, 2)`` (u, v)
    of each point and its ``(n,)`` residual."""

    surface: _geometry.Surface
    parameters: np.ndarray
    residuals: np.ndarray
    max_residual: float
    rms_residual: float


@dataclass(frozen=True)
class SurfaceKnotRemoval:
    """The surface on fewer knots, the copies removed in u and v, and the
    certified bound of its distance to the input."""

    surface: _geometry.Surface
    removals_u: int
    removals_v: int
    error_bound: float


@dataclass(frozen=True)
class SectionPolyline:
    """One piece of a plane section: ``(n, d)`` points on the section, their
    ``(n, 2)`` surface parameters, whether it closes (its last point is
    then its first), and the fitted curve when asked for (else None)."""

    points: np.ndarray
    parameters: np.ndarray
    closed: bool
    curve: Optional[_geometry.Curve]


@dataclass(frozen=True)
class SurfaceCurvature:
    """Curvatures of a 3D surface at n points.

    Attributes:
      normals: ``(n, 3)`` unit normals.
      gaussian, mean: ``(n,)``.
      principal_curvatures: ``(n, 2)``: k1 >= k2.
      principal_directions: ``(n, 2, 3)``: the unit directions of k1, k2.
      statuses: ``(n,)`` SurfacePointStatus values: 0 regular, 1 umbilic, 2
        singular.
    """

    normals: np.ndarray
    gaussian: np.ndarray
    mean: np.ndarray
    principal_curvatures: np.ndarray
    principal_directions: np.ndarray
    statuses: np.ndarray
