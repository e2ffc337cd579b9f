"""Surfaces: the methods of SurfaceService, numpy arrays in and out."""

from __future__ import annotations

from typing import (TYPE_CHECKING, Any, Callable, List, Optional, Sequence,
                    Tuple, TypeVar, Union)

import numpy as np
from numpy.typing import ArrayLike

from freeform import _answers, _results
from freeform._answers import enum_value
from freeform._geometry import SurfaceParameters, float_array
from freeform._geometry import points_of, set_doubles, surface_parameters
from freeform._geometry import to_control_net, to_points
from freeform._requests import (check_type, closest_point_options,
                                intersection_options, set_optional)
from freeform._stream import Stream
from freeform._wire import View, WireError
from freeform.v1 import curve_service_pb2 as _curves
from freeform.v1 import geometry_pb2 as _geometry
from freeform.v1 import surface_service_pb2 as _surfaces

if TYPE_CHECKING:
    from freeform._client import Client

T = TypeVar("T")
# A tensor basis is a pair of curve bases (u, v); an int is the degree of
# the triangular Bernstein polynomials.
SurfaceBasis = Union[Tuple[_curves.Basis, _curves.Basis], int]


def _direction(value: Any) -> Any:
    return enum_value(_surfaces.SurfaceDirection, value, "direction")


def _surface_list(surfaces: Union[_geometry.Surface,
                                  Sequence[_geometry.Surface]]
                  ) -> List[_geometry.Surface]:
    if isinstance(surfaces, _geometry.Surface):
        return [surfaces]
    return [check_type(surface, _geometry.Surface, "surfaces[%d]" % index)
            for index, surface in enumerate(surfaces)]


def _surface_fit(view: View) -> _results.SurfaceFit:
    message = view.message
    return _results.SurfaceFit(
        message.surface, view.doubles("parameters_u"),
        view.doubles("parameters_v"),
        getattr(message, "max_residual", 0.0),
        getattr(message, "rms_residual", 0.0),
        getattr(message, "refinement_rounds", 0))


def _section_polyline(view: View) -> _results.SectionPolyline:
    message = view.message
    return _results.SectionPolyline(
        points_of(view.submessage("points")), _answers.pairs(view,
                                                             "parameters"),
        message.closed,
        message.curve if message.HasField("curve") else None)


class Surfaces:
    """SurfaceService: evaluation, refinement, meshing, interpolation,
    fitting and queries of surfaces (``client.surfaces``).

    Surfaces are ``geometry_pb2.Surface`` messages
    (freeform.bspline_surface, ...); nets are ``(m, n, d)`` arrays; surface
    parameters an ``(n, 2)`` array of (u, v), a freeform.Grid or a
    SurfaceParameters message. Every method takes ``timeout=`` (seconds)
    and raises FreeformError.
    """

    def __init__(self, client: "Client"):
        self._client = client

    def _call(self, method: str, request: Any,
              convert: Callable[[View], T], timeout: Optional[float]) -> T:
        return self._client._rpc("SurfaceService." + method, request,
                                 convert, timeout)

    # ------------------------------------------------------ evaluation

    @staticmethod
    def _evaluate_request(surface: _geometry.Surface, at: SurfaceParameters,
                          derivative_order: int, normals: bool,
                          chunk_size: int = 0
                          ) -> _surfaces.EvaluateSurfaceRequest:
        return _surfaces.EvaluateSurfaceRequest(
            surface=check_type(surface, _geometry.Surface, "surface"),
            parameters=surface_parameters(at),
            derivative_order=derivative_order, normals=normals,
            chunk_size=chunk_size)

    def evaluate(self, surface: _geometry.Surface, at: SurfaceParameters,
                 derivative_order: int = 0, *, normals: bool = False,
                 timeout: Optional[float] = None) -> _results.SurfaceSamples:
        """The points of ``surface`` at ``at`` (``(n, 2)`` (u, v) pairs or
        a freeform.Grid, u-major), every partial of total order up to
        ``derivative_order`` (``.partials[(k, l)]``) and, with ``normals``,
        the unit normals."""
        return self._call(
            "Evaluate",
            self._evaluate_request(surface, at, derivative_order, normals),
            lambda view: _answers.surface_samples(view, normals), timeout)

    def evaluate_stream(self, surface: _geometry.Surface,
                        at: SurfaceParameters, derivative_order: int = 0, *,
                        normals: bool = False, chunk_size: int = 0,
                        timeout: Optional[float] = None
                        ) -> Stream[_results.SurfaceSamples]:
        """evaluate for answers of any size, in SurfaceSamples chunks of up
        to ``chunk_size`` points (0: the server's) with their
        ``first_index``; SurfaceSamples.join(stream) joins them."""
        return self._client._rpc_stream(
            "SurfaceService.EvaluateStream",
            self._evaluate_request(surface, at, derivative_order, normals,
                                   chunk_size),
            lambda view: _answers.surface_samples(view, normals), timeout)

    def evaluate_basis(self, basis: SurfaceBasis, at: SurfaceParameters, *,
                       timeout: Optional[float] = None) -> np.ndarray:
        """The surface blending functions at ``at``: an ``(n, f)`` array.
        ``basis`` is a pair (u, v) of curve bases (their tensor product,
        functions ordered like the net) or the degree of the triangular
        Bernstein polynomials."""
        request = _surfaces.EvaluateSurfaceBasisRequest(
            parameters=surface_parameters(at))
        if isinstance(basis, (int, np.integer)):
            request.triangular_degree = int(basis)
        else:
            u, v = basis
            request.tensor.u.CopyFrom(check_type(u, _curves.Basis, "basis[0]"))
            request.tensor.v.CopyFrom(check_type(v, _curves.Basis, "basis[1]"))

        def convert(view: View) -> np.ndarray:
            message = view.message
            values = view.doubles("values")
            if values.size != message.count * message.function_count:
                raise WireError("%d basis values, not %d x %d" % (
                    values.size, message.count, message.function_count))
            return values.reshape(message.count, message.function_count)

        return self._call("EvaluateBasis", request, convert, timeout)

    # ----------------------------------------------------- refinement

    def split(self, surface: _geometry.Surface,
              at: Union[float, Tuple[float, float]], *,
              direction: Any = None,
              timeout: Optional[float] = None) -> List[_geometry.Surface]:
        """A tensor Bezier patch split at the parameter ``at`` in
        ``direction`` ("u" or "v") into two pieces, or a triangular patch
        split at the barycentric point ``at`` = (u, v) into three."""
        request = _surfaces.SplitSurfaceRequest(
            surface=check_type(surface, _geometry.Surface, "surface"),
            direction=_direction(direction))
        if direction is None:
            if np.shape(at) != (2,):
                raise ValueError("a triangular patch splits at a point (u, "
                                 "v); a tensor patch at a parameter with "
                                 "direction='u' or 'v'")
            request.u, request.v = at  # type: ignore[misc]
        else:
            request.parameter = at  # type: ignore[assignment]
        return self._call("Split", request,
                          lambda view: list(view.message.pieces), timeout)

    def insert_knots(self, surface: _geometry.Surface, knots: ArrayLike,
                     direction: Any, *,
                     timeout: Optional[float] = None) -> _geometry.Surface:
        """The same B-spline surface with ``knots`` inserted in
        ``direction`` ("u" or "v")."""
        request = _surfaces.InsertSurfaceKnotsRequest(
            surface=check_type(surface, _geometry.Surface, "surface"),
            direction=_direction(direction))
        set_doubles(request, "knots", np.atleast_1d(knots), "knots")
        return self._call("InsertKnots", request,
                          lambda view: view.message.surface, timeout)

    def elevate_degree(self, surface: _geometry.Surface, by_u: int = 0,
                       by_v: int = 0, *, by: int = 0,
                       timeout: Optional[float] = None) -> _geometry.Surface:
        """The same tensor surface with its degrees raised by ``by_u`` and
        ``by_v``, or a triangular patch's by ``by``."""
        request = _surfaces.ElevateSurfaceDegreeRequest(
            surface=check_type(surface, _geometry.Surface, "surface"),
            by_u=by_u, by_v=by_v, by=by)
        return self._call("ElevateDegree", request,
                          lambda view: view.message.surface, timeout)

    # ------------------------------------------------------- meshing

    @staticmethod
    def _tessellate_request(surfaces: Any, tolerance: float, normals: bool,
                            max_vertices: int,
                            max_edge_length: Optional[float],
                            max_normal_angle: Optional[float],
                            chunk_size: int = 0
                            ) -> _surfaces.TessellateSurfaceRequest:
        request = _surfaces.TessellateSurfaceRequest(
            surfaces=_surface_list(surfaces), tolerance=tolerance,
            normals=normals, max_vertices=max_vertices,
            chunk_size=chunk_size)
        return set_optional(request, max_edge_length=max_edge_length,
                            max_normal_angle=max_normal_angle)

    def tessellate(self, surfaces: Union[_geometry.Surface,
                                         Sequence[_geometry.Surface]],
                   tolerance: float, *, normals: bool = False,
                   max_vertices: int = 0,
                   max_edge_length: Optional[float] = None,
                   max_normal_angle: Optional[float] = None,
                   timeout: Optional[float] = None) -> _results.Mesh:
        """A welded triangle mesh within ``tolerance`` of one surface or of
        several meshed together without cracks: ``(V, 3)`` vertices,
        ``(T, 3)`` triangles and, with ``normals``, unit normals per
        vertex."""
        return self._call("Tessellate", self._tessellate_request(
            surfaces, tolerance, normals, max_vertices, max_edge_length,
            max_normal_angle), lambda view: _answers.mesh(view, normals),
            timeout)

    def tessellate_stream(self, surfaces: Union[_geometry.Surface,
                                                Sequence[_geometry.Surface]],
                          tolerance: float, *, normals: bool = False,
                          max_vertices: int = 0,
                          max_edge_length: Optional[float] = None,
                          max_normal_angle: Optional[float] = None,
                          chunk_size: int = 0,
                          timeout: Optional[float] = None
                          ) -> Stream[_results.Mesh]:
        """tessellate for meshes of any size, in chunks of up to
        ``chunk_size`` triangles whose indices refer to all the vertices
        sent so far; Mesh.join(stream) gives the whole mesh."""
        return self._client._rpc_stream(
            "SurfaceService.TessellateStream", self._tessellate_request(
                surfaces, tolerance, normals, max_vertices, max_edge_length,
                max_normal_angle, chunk_size),
            lambda view: _answers.mesh(view, normals), timeout)

    # ---------------------------------------- interpolation and fitting

    def interpolate(self, net: ArrayLike, degree_u: int = 3,
                    degree_v: int = 3, *, parameterization: Any = None,
                    knot_rule: Any = None,
                    timeout: Optional[float] = None) -> _results.SurfaceFit:
        """The B-spline surface through the ``(m, n, d)`` grid of points."""
        request = _surfaces.InterpolateSurfaceRequest(
            points=to_control_net(net, "net"), degree_u=degree_u,
            degree_v=degree_v,
            parameterization=enum_value(_curves.Parameterization,
                                        parameterization, "parameterization"),
            knot_rule=enum_value(_curves.KnotRule, knot_rule, "knot_rule"))
        return self._call("Interpolate", request, _surface_fit, timeout)

    def fit(self, net: ArrayLike, degree_u: int, degree_v: int,
            tolerance: float, *, parameterization: Any = None,
            max_control_points_u: int = 0, max_control_points_v: int = 0,
            timeout: Optional[float] = None) -> _results.SurfaceFit:
        """A B-spline surface within ``tolerance`` of every point of the
        ``(m, n, d)`` grid, with its residuals."""
        request = _surfaces.FitSurfaceRequest(
            points=to_control_net(net, "net"), degree_u=degree_u,
            degree_v=degree_v, tolerance=tolerance,
            parameterization=enum_value(_curves.Parameterization,
                                        parameterization, "parameterization"),
            max_control_points_u=max_control_points_u,
            max_control_points_v=max_control_points_v)
        return self._call("Fit", request, _surface_fit, timeout)

    def fit_scattered(self, points: ArrayLike, degree_u: int, degree_v: int,
                      control_count_u: int, control_count_v: int, *,
                      parameters: Optional[ArrayLike] = None,
                      smoothing: Optional[float] = None,
                      timeout: Optional[float] = None
                      ) -> _results.ScatteredFit:
        """A B-spline surface with the given control counts fitted to the
        ``(n, d)`` scattered points (``parameters``: their ``(n, 2)`` (u,
        v), default from the best-fit plane), with thin-plate
        ``smoothing``."""
        request = _surfaces.FitScatteredSurfaceRequest(
            points=to_points(points), degree_u=degree_u, degree_v=degree_v,
            control_count_u=control_count_u, control_count_v=control_count_v)
        if parameters is not None:
            set_doubles(request, "parameters",
                        float_array(parameters, "parameters", 2).reshape(-1),
                        "parameters")
        set_optional(request, smoothing=smoothing)
        return self._call("FitScattered", request, lambda view: (
            _results.ScatteredFit(
                view.message.surface, _answers.pairs(view, "parameters"),
                view.doubles("residuals"), view.message.max_residual,
                view.message.rms_residual)), timeout)

    def remove_knots(self, surface: _geometry.Surface, tolerance: float, *,
                     direction: Any = "both", knot: Optional[float] = None,
                     times: int = 0, timeout: Optional[float] = None
                     ) -> _results.SurfaceKnotRemoval:
        """``surface`` with every knot of ``direction`` ("u", "v" or
        "both") that can go within ``tolerance`` removed, or up to
        ``times`` copies of ``knot`` in direction "u" or "v"."""
        request = _surfaces.RemoveSurfaceKnotsRequest(
            surface=check_type(surface, _geometry.Surface, "surface"),
            direction=_direction(direction), tolerance=tolerance,
            times=times)
        set_optional(request, knot=knot)
        return self._call("RemoveKnots", request, lambda view: (
            _results.SurfaceKnotRemoval(
                view.message.surface, view.message.removals_u,
                view.message.removals_v, view.message.error_bound)), timeout)

    # -------------------------------------------------------- queries

    def closest_point(self, surface: _geometry.Surface, queries: ArrayLike,
                      *, tolerance: Optional[float] = None,
                      separation: Optional[float] = None,
                      max_minima: int = 0,
                      timeout: Optional[float] = None
                      ) -> _results.ClosestPoints:
        """The certified closest points of ``surface`` to the ``(m, d)``
        queries; parameters are (u, v) pairs."""
        request = _surfaces.SurfaceClosestPointRequest(
            surface=check_type(surface, _geometry.Surface, "surface"),
            queries=to_points(queries, "queries"),
            options=closest_point_options(tolerance, separation, max_minima))
        return self._call("ClosestPoint", request, _answers.closest_points,
                          timeout)

    def intersect_curve(self, curve: _geometry.Curve,
                        surface: _geometry.Surface, *,
                        tolerance: Optional[float] = None,
                        separation: Optional[float] = None,
                        max_results: int = 0,
                        timeout: Optional[float] = None
                        ) -> _results.CurveSurfaceIntersections:
        """The points where ``curve`` meets ``surface``, as t and (u, v)."""
        request = _surfaces.IntersectCurveSurfaceRequest(
            curve=check_type(curve, _geometry.Curve, "curve"),
            surface=check_type(surface, _geometry.Surface, "surface"),
            options=intersection_options(tolerance, separation, max_results))
        return self._call("IntersectCurve", request, lambda view: (
            _results.CurveSurfaceIntersections(
                view.doubles("curve_parameters"),
                _answers.pairs(view, "surface_parameters"),
                points_of(view.submessage("points"),
                          empty_dimension=view.message.dimension))), timeout)

    def section(self, surface: _geometry.Surface, plane_point: ArrayLike,
                plane_normal: ArrayLike, *,
                tolerance: Optional[float] = None, max_points: int = 0,
                fit_tolerance: Optional[float] = None,
                timeout: Optional[float] = None
                ) -> List[_results.SectionPolyline]:
        """The section of ``surface`` by the plane through ``plane_point``
        with ``plane_normal``: polylines within ``tolerance`` (and, with
        ``fit_tolerance``, a B-spline curve fitted to each)."""
        request = _surfaces.SectionSurfaceRequest(
            surface=check_type(surface, _geometry.Surface, "surface"),
            max_points=max_points)
        set_doubles(request, "plane_point", plane_point, "plane_point")
        set_doubles(request, "plane_normal", plane_normal, "plane_normal")
        set_optional(request, tolerance=tolerance,
                     fit_tolerance=fit_tolerance)
        return self._call("Section", request, lambda view: [
            _section_polyline(polyline)
            for polyline in view.submessages("polylines")], timeout)

    def curvature(self, surface: _geometry.Surface, at: SurfaceParameters,
                  *, timeout: Optional[float] = None
                  ) -> _results.SurfaceCurvature:
        """Unit normal, Gaussian, mean and principal curvatures and
        directions of a 3D surface at ``at``."""
        request = _surfaces.SurfaceCurvatureRequest(
            surface=check_type(surface, _geometry.Surface, "surface"),
            parameters=surface_parameters(at))

        def convert(view: View) -> _results.SurfaceCurvature:
            normals = points_of(view.submessage("normals"), empty_dimension=3)
            directions = view.doubles("principal_directions")
            if directions.size != normals.shape[0] * 6:
                raise WireError("%d principal direction values for %d "
                                "points" % (directions.size,
                                            normals.shape[0]))
            return _results.SurfaceCurvature(
                normals, view.doubles("gaussian"), view.doubles("mean"),
                _answers.pairs(view, "principal_curvatures"),
                directions.reshape(-1, 2, 3),
                view.varints("statuses", np.int64))

        return self._call("Curvature", request, convert, timeout)

    def bounding_box(self, surface: _geometry.Surface, *,
                     tolerance: Optional[float] = None,
                     timeout: Optional[float] = None) -> _results.BoundingBox:
        """The tight axis-aligned box of the surface itself, within
        ``tolerance``."""
        request = set_optional(_surfaces.SurfaceBoundingBoxRequest(
            surface=check_type(surface, _geometry.Surface, "surface")),
            tolerance=tolerance)
        return self._call("BoundingBox", request, _answers.bounding_box,
                          timeout)
