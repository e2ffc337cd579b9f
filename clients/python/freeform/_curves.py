"""Curves: the methods of CurveService, numpy arrays in and out."""

from __future__ import annotations

from typing import (TYPE_CHECKING, Any, Callable, List, Optional, Sequence,
                    Tuple, TypeVar, Union, overload)

import numpy as np
from numpy.typing import ArrayLike

from freeform import _answers, _results
from freeform._answers import enum_value
from freeform._geometry import CurveParameters, float_array
from freeform._geometry import parameters as parameters_message
from freeform._geometry import points_of, set_doubles, to_points
from freeform._requests import (check_type, closest_point_options,
                                intersection_options, set_optional)
from freeform._stream import Stream
from freeform._wire import View, WireError
from freeform.v1 import curve_service_pb2 as _curves
from freeform.v1 import geometry_pb2 as _geometry

if TYPE_CHECKING:
    from freeform._client import Client

T = TypeVar("T")
Interval = Tuple[Optional[float], Optional[float]]


def parameter_interval(interval: Optional[Interval],
                       message: _curves.ParameterInterval) -> None:
    if interval is not None:
        start, end = interval
        set_optional(message, start=start, end=end)


def _curve_fit(view: View) -> _results.CurveFit:
    message = view.message
    return _results.CurveFit(message.curve, view.doubles("parameters"),
                             message.max_residual, message.rms_residual,
                             getattr(message, "refinement_rounds", 0))


def _arc_samples(view: View) -> _results.ArcSamples:
    return _results.ArcSamples(view.doubles("parameters"),
                               points_of(view.submessage("points")))


class Curves:
    """CurveService: evaluation, refinement, interpolation, fitting,
    tessellation and queries of curves (``client.curves``).

    Curves are ``geometry_pb2.Curve`` messages (freeform.bezier,
    freeform.bspline, ...); points are ``(n, d)`` arrays; parameters a
    sequence of values, a freeform.Range or a Parameters message. Every
    method takes ``timeout=`` (seconds) and raises FreeformError.
    """

    def __init__(self, client: "Client"):
        self._client = client

    def _call(self, method: str, request: Any,
              convert: Callable[[View], T], timeout: Optional[float]) -> T:
        return self._client._rpc("CurveService." + method, request, convert,
                                 timeout)

    # ------------------------------------------------------ evaluation

    @staticmethod
    def _evaluate_request(curve: _geometry.Curve, at: CurveParameters,
                          derivative_order: int, algorithm: Any,
                          chunk_size: int = 0) -> _curves.EvaluateCurveRequest:
        return _curves.EvaluateCurveRequest(
            curve=check_type(curve, _geometry.Curve, "curve"),
            parameters=parameters_message(at),
            derivative_order=derivative_order,
            bezier_algorithm=enum_value(_curves.BezierAlgorithm, algorithm,
                                        "algorithm"),
            chunk_size=chunk_size)

    def evaluate(self, curve: _geometry.Curve, at: CurveParameters,
                 derivative_order: int = 0, *, algorithm: Any = None,
                 timeout: Optional[float] = None) -> _results.CurveSamples:
        """The points of ``curve`` at the parameters ``at`` and its
        derivatives up to ``derivative_order``: ``.points`` ``(n, d)``,
        ``.derivatives`` ``(derivative_order + 1, n, d)``. ``algorithm``
        picks the Bezier scheme ("de_casteljau", "horner", "ladder";
        default auto)."""
        return self._call("Evaluate", self._evaluate_request(
            curve, at, derivative_order, algorithm),
            _answers.curve_samples, timeout)

    def evaluate_stream(self, curve: _geometry.Curve, at: CurveParameters,
                        derivative_order: int = 0, *, chunk_size: int = 0,
                        algorithm: Any = None,
                        timeout: Optional[float] = None
                        ) -> Stream[_results.CurveSamples]:
        """evaluate for answers of any size: yields CurveSamples chunks of
        up to ``chunk_size`` parameters (0: the server's, 32768), each with
        its ``first_index``; CurveSamples.join(stream) joins them."""
        return self._client._rpc_stream(
            "CurveService.EvaluateStream",
            self._evaluate_request(curve, at, derivative_order, algorithm,
                                   chunk_size),
            _answers.curve_samples, timeout)

    def evaluate_basis(self, basis: _curves.Basis, at: CurveParameters,
                       derivative_order: int = 0, *,
                       timeout: Optional[float] = None) -> np.ndarray:
        """The blending functions of ``basis`` (freeform.bernstein_basis,
        bspline_basis, lagrange_basis, hermite_basis) at ``at``: a
        ``(derivative_order + 1, n, f)`` array, [k, r, i] the k-th
        derivative of function i at parameter r."""
        request = _curves.EvaluateBasisRequest(
            basis=check_type(basis, _curves.Basis, "basis"),
            parameters=parameters_message(at),
            derivative_order=derivative_order)

        def convert(view: View) -> np.ndarray:
            message = view.message
            derivatives = view.submessages("derivatives")
            out = np.empty((len(derivatives), message.count,
                            message.function_count))
            for k, derivative in enumerate(derivatives):
                derivative.doubles("values", out[k].reshape(-1))
            return out

        return self._call("EvaluateBasis", request, convert, timeout)

    # ----------------------------------------------------- refinement

    def split(self, curve: _geometry.Curve, at: ArrayLike, *,
              timeout: Optional[float] = None) -> List[_geometry.Curve]:
        """The pieces of a Bezier curve split at the increasing parameters
        ``at`` in (0, 1), each on [0, 1]."""
        request = _curves.SplitCurveRequest(
            curve=check_type(curve, _geometry.Curve, "curve"))
        set_doubles(request, "parameters", np.atleast_1d(at), "at")
        return self._call("Split", request,
                          lambda view: list(view.message.pieces), timeout)

    def insert_knots(self, curve: _geometry.Curve, knots: ArrayLike, *,
                     timeout: Optional[float] = None) -> _geometry.Curve:
        """The same B-spline curve with ``knots`` inserted (Boehm)."""
        request = _curves.InsertKnotsRequest(
            curve=check_type(curve, _geometry.Curve, "curve"))
        set_doubles(request, "knots", np.atleast_1d(knots), "knots")
        return self._call("InsertKnots", request,
                          lambda view: view.message.curve, timeout)

    def decompose(self, curve: _geometry.Curve, *,
                  timeout: Optional[float] = None) -> _results.Decomposition:
        """``curve`` as Bezier segments and their breakpoints."""
        request = _curves.DecomposeCurveRequest(
            curve=check_type(curve, _geometry.Curve, "curve"))
        return self._call("Decompose", request, lambda view: (
            _results.Decomposition(list(view.message.segments),
                                   view.doubles("breakpoints"))), timeout)

    def subdivide(self, polygon: ArrayLike, levels: int = 1, *,
                  scheme: Any = "chaikin", degree: int = 0,
                  closed: bool = False, keep_levels: bool = False,
                  timeout: Optional[float] = None) -> _results.Subdivision:
        """The ``(n, d)`` polygon after ``levels`` steps of Chaikin corner
        cutting (``scheme="chaikin"``) or of uniform B-spline subdivision of
        ``degree`` (``scheme="uniform_bspline"``); with ``keep_levels`` also
        the polygon after each step."""
        request = _curves.SubdivideRequest(
            polygon=to_points(polygon, "polygon"), closed=closed,
            scheme=enum_value(_curves.SubdivisionScheme, scheme, "scheme"),
            degree=degree, levels=levels, keep_levels=keep_levels)
        return self._call("Subdivide", request, lambda view: (
            _results.Subdivision(
                points_of(view.submessage("polygon")),
                [points_of(level) for level in view.submessages("levels")])),
            timeout)

    def tessellate(self, curve: _geometry.Curve, tolerance: float, *,
                   max_points: int = 0,
                   timeout: Optional[float] = None) -> _results.Polyline:
        """A polyline within ``tolerance`` of ``curve``: its points on the
        curve and their parameters (at most ``max_points``; 0: the server's
        limit)."""
        request = _curves.TessellateCurveRequest(
            curve=check_type(curve, _geometry.Curve, "curve"),
            tolerance=tolerance, max_points=max_points)
        return self._call("Tessellate", request, lambda view: (
            _results.Polyline(points_of(view.submessage("points")),
                              view.doubles("parameters"))), timeout)

    def elevate_degree(self, curve: _geometry.Curve, by: int = 1, *,
                       timeout: Optional[float] = None) -> _geometry.Curve:
        """The same Bezier or B-spline curve with its degree raised by
        ``by``."""
        request = _curves.ElevateCurveDegreeRequest(
            curve=check_type(curve, _geometry.Curve, "curve"), by=by)
        return self._call("ElevateDegree", request,
                          lambda view: view.message.curve, timeout)

    def reduce_degree(self, curve: _geometry.Curve, by: int = 1, *,
                      timeout: Optional[float] = None
                      ) -> _results.DegreeReduction:
        """A Bezier curve of degree lower by ``by`` and its error bound."""
        request = _curves.ReduceCurveDegreeRequest(
            curve=check_type(curve, _geometry.Curve, "curve"), by=by)
        return self._call("ReduceDegree", request, lambda view: (
            _results.DegreeReduction(view.message.curve,
                                     view.message.error_bound)), timeout)

    # -------------------------------------------------- interpolation

    def interpolate(self, points: ArrayLike, degree: int = 3, *,
                    parameterization: Any = None,
                    parameters: Optional[ArrayLike] = None,
                    knot_rule: Any = None,
                    start_derivative: Optional[ArrayLike] = None,
                    end_derivative: Optional[ArrayLike] = None,
                    closed: bool = False,
                    scale_end_derivatives: bool = False,
                    timeout: Optional[float] = None) -> _results.CurveFit:
        """The B-spline curve of ``degree`` through the ``(n, d)`` points.

        ``parameterization``: "uniform", "chord_length" (default),
        "centripetal" or "universal", or explicit ``parameters``;
        ``knot_rule``: "averaging" (default), "uniform" or "at_parameters"
        (OpenCASCADE's rule); optional end derivatives ``(d,)``; ``closed``
        for a periodic curve.
        """
        request = _curves.InterpolateCurveRequest(
            points=to_points(points))
        method = request.bspline
        method.degree = degree
        method.parameterization = enum_value(
            _curves.Parameterization, parameterization, "parameterization")
        method.knot_rule = enum_value(_curves.KnotRule, knot_rule,
                                      "knot_rule")
        method.closed = closed
        method.scale_end_derivatives = scale_end_derivatives
        _set_data_parameters(method, parameters)
        _set_end_derivatives(method, start_derivative, end_derivative)
        return self._call("Interpolate", request, _curve_fit, timeout)

    def cubic_spline(self, points: ArrayLike, parameters: ArrayLike, *,
                     end_condition: Any = None,
                     start_derivative: Optional[ArrayLike] = None,
                     end_derivative: Optional[ArrayLike] = None,
                     timeout: Optional[float] = None) -> _results.CurveFit:
        """The cubic spline through the ``(n, d)`` values at the increasing
        abscissas ``parameters``; ``end_condition``: "not_a_knot"
        (default), "natural", "clamped" (with the end derivatives) or
        "periodic"."""
        request = _curves.InterpolateCurveRequest(points=to_points(points))
        method = request.cubic_spline
        set_doubles(method, "parameters", parameters, "parameters")
        method.end_condition = enum_value(
            _curves.SplineEndCondition, end_condition, "end_condition")
        _set_end_derivatives(method, start_derivative, end_derivative)
        method.SetInParent()
        return self._call("Interpolate", request, _curve_fit, timeout)

    def approximate(self, points: ArrayLike, degree: int,
                    control_point_count: int, *,
                    parameterization: Any = None,
                    parameters: Optional[ArrayLike] = None,
                    timeout: Optional[float] = None) -> _results.CurveFit:
        """The least-squares B-spline curve of ``degree`` with
        ``control_point_count`` control points to the ``(n, d)`` points,
        with its residuals."""
        request = _curves.InterpolateCurveRequest(points=to_points(points))
        method = request.least_squares
        method.degree = degree
        method.control_point_count = control_point_count
        method.parameterization = enum_value(
            _curves.Parameterization, parameterization, "parameterization")
        _set_data_parameters(method, parameters)
        return self._call("Interpolate", request, _curve_fit, timeout)

    def fit(self, points: ArrayLike, degree: int, tolerance: float, *,
            parameterization: Any = None,
            parameters: Optional[ArrayLike] = None,
            max_control_points: int = 0, parameter_corrections: int = 0,
            timeout: Optional[float] = None) -> _results.CurveFit:
        """A B-spline curve of ``degree`` within ``tolerance`` of every one
        of the ``(n, d)`` points (least squares, knots inserted where the
        error is too large), with ``refinement_rounds``."""
        request = _curves.FitCurveRequest(
            points=to_points(points), degree=degree, tolerance=tolerance,
            parameterization=enum_value(_curves.Parameterization,
                                        parameterization, "parameterization"),
            max_control_points=max_control_points,
            parameter_corrections=parameter_corrections)
        _set_data_parameters(request, parameters)
        return self._call("Fit", request, _curve_fit, timeout)

    def remove_knots(self, curve: _geometry.Curve, tolerance: float, *,
                     knot: Optional[float] = None, times: int = 0,
                     timeout: Optional[float] = None
                     ) -> _results.CurveKnotRemoval:
        """``curve`` with every knot that can go within ``tolerance``
        removed, or with up to ``times`` copies (0: all) of ``knot``."""
        request = _curves.RemoveCurveKnotsRequest(
            curve=check_type(curve, _geometry.Curve, "curve"),
            tolerance=tolerance, times=times)
        set_optional(request, knot=knot)
        return self._call("RemoveKnots", request, lambda view: (
            _results.CurveKnotRemoval(view.message.curve,
                                      view.message.removals,
                                      view.message.error_bound)), timeout)

    # -------------------------------------------------------- queries

    def closest_point(self, curve: _geometry.Curve, queries: ArrayLike, *,
                      tolerance: Optional[float] = None,
                      separation: Optional[float] = None,
                      max_minima: int = 0,
                      timeout: Optional[float] = None
                      ) -> _results.ClosestPoints:
        """The certified closest points of ``curve`` to the ``(m, d)``
        queries (``.closest_points``, ``.closest_parameters``, every minimum
        and the certified lower bounds)."""
        request = _curves.CurveClosestPointRequest(
            curve=check_type(curve, _geometry.Curve, "curve"),
            queries=to_points(queries, "queries"),
            options=closest_point_options(tolerance, separation, max_minima))
        return self._call("ClosestPoint", request, _answers.closest_points,
                          timeout)

    def intersect(self, first: _geometry.Curve, second: _geometry.Curve, *,
                  tolerance: Optional[float] = None,
                  separation: Optional[float] = None, max_results: int = 0,
                  timeout: Optional[float] = None
                  ) -> _results.CurveIntersections:
        """The points where two curves meet and the stretches where they
        overlap."""
        request = _curves.IntersectCurvesRequest(
            first=check_type(first, _geometry.Curve, "first"),
            second=check_type(second, _geometry.Curve, "second"),
            options=intersection_options(tolerance, separation, max_results))
        return self._call("Intersect", request, lambda view: (
            _results.CurveIntersections(
                view.doubles("first_parameters"),
                view.doubles("second_parameters"),
                points_of(view.submessage("points"),
                          empty_dimension=view.message.dimension),
                _answers.pairs(view, "first_intervals"),
                _answers.pairs(view, "second_intervals"))), timeout)

    @overload
    def arc_length(self, curve: _geometry.Curve, intervals: None = None, *,
                   tolerance: Optional[float] = None,
                   timeout: Optional[float] = None) -> float: ...

    @overload
    def arc_length(self, curve: _geometry.Curve,
                   intervals: Sequence[Interval], *,
                   tolerance: Optional[float] = None,
                   timeout: Optional[float] = None) -> np.ndarray: ...

    def arc_length(self, curve, intervals=None, *, tolerance=None,
                   timeout=None):
        """The length of ``curve`` over its domain (a float), or over each
        (start, end) of ``intervals`` (an array; None for an end of the
        domain)."""
        request = _curves.ArcLengthRequest(
            curve=check_type(curve, _geometry.Curve, "curve"))
        set_optional(request, tolerance=tolerance)
        for interval in intervals if intervals is not None else ():
            parameter_interval(interval, request.intervals.add())

        def convert(view: View) -> Union[float, np.ndarray]:
            lengths = view.doubles("lengths")
            if intervals is not None:
                return lengths
            if lengths.size != 1:
                raise WireError("%d lengths for the whole domain" %
                                lengths.size)
            return float(lengths[0])

        return self._call("ArcLength", request, convert, timeout)

    def parameters_at_arc_length(self, curve: _geometry.Curve,
                                 lengths: ArrayLike, *,
                                 start: Optional[float] = None,
                                 tolerance: Optional[float] = None,
                                 timeout: Optional[float] = None
                                 ) -> _results.ArcSamples:
        """The parameters (and points) at the arc ``lengths`` from
        ``start`` (default: the domain's start)."""
        request = _curves.ParametersAtArcLengthRequest(
            curve=check_type(curve, _geometry.Curve, "curve"))
        set_doubles(request, "lengths", np.atleast_1d(lengths), "lengths")
        set_optional(request, start=start, tolerance=tolerance)
        return self._call("ParametersAtArcLength", request, _arc_samples,
                          timeout)

    def sample_by_arc_length(self, curve: _geometry.Curve, count: int, *,
                             interval: Optional[Interval] = None,
                             tolerance: Optional[float] = None,
                             timeout: Optional[float] = None
                             ) -> _results.ArcSamples:
        """``count`` samples equally far apart along ``curve`` (over the
        (start, end) ``interval``, default the domain), both ends
        included."""
        request = _curves.SampleByArcLengthRequest(
            curve=check_type(curve, _geometry.Curve, "curve"), count=count)
        parameter_interval(interval, request.interval)
        set_optional(request, tolerance=tolerance)
        return self._call("SampleByArcLength", request, _arc_samples,
                          timeout)

    def curvature(self, curve: _geometry.Curve, at: CurveParameters, *,
                  timeout: Optional[float] = None
                  ) -> _results.CurveCurvature:
        """The Frenet frame, curvature and (3D) torsion at ``at``."""
        request = _curves.CurveCurvatureRequest(
            curve=check_type(curve, _geometry.Curve, "curve"),
            parameters=parameters_message(at))

        def convert(view: View) -> _results.CurveCurvature:
            torsions = view.doubles("torsions")
            return _results.CurveCurvature(
                points_of(view.submessage("tangents"),
                          empty_dimension=view.message.dimension),
                points_of(view.submessage("normals"),
                          empty_dimension=view.message.dimension),
                _answers.optional_points(view, "binormals"),
                view.doubles("curvatures"),
                torsions if view.message.dimension == 3 else None,
                view.varints("statuses", np.int64))

        return self._call("Curvature", request, convert, timeout)

    def frames(self, curve: _geometry.Curve, at: CurveParameters, *,
               initial_reference: Optional[ArrayLike] = None,
               timeout: Optional[float] = None) -> _results.Frames:
        """Rotation-minimizing frames carried through ``at`` in order (the
        double reflection method), from ``initial_reference`` (default: the
        principal normal there)."""
        request = _curves.RotationMinimizingFramesRequest(
            curve=check_type(curve, _geometry.Curve, "curve"),
            parameters=parameters_message(at))
        if initial_reference is not None:
            set_doubles(request, "initial_reference", initial_reference,
                        "initial_reference")
        return self._call("RotationMinimizingFrames", request, lambda view: (
            _results.Frames(
                points_of(view.submessage("tangents"),
                          empty_dimension=view.message.dimension),
                points_of(view.submessage("references"),
                          empty_dimension=view.message.dimension),
                _answers.optional_points(view, "third"))), timeout)

    def bounding_box(self, curve: _geometry.Curve, *,
                     tolerance: Optional[float] = None,
                     timeout: Optional[float] = None) -> _results.BoundingBox:
        """The tight axis-aligned box of the curve itself (not of its
        control points), within ``tolerance``."""
        request = set_optional(_curves.CurveBoundingBoxRequest(
            curve=check_type(curve, _geometry.Curve, "curve")),
            tolerance=tolerance)
        return self._call("BoundingBox", request, _answers.bounding_box,
                          timeout)


def _set_data_parameters(method: Any, values: Optional[ArrayLike]) -> None:
    if values is not None:
        set_doubles(method, "parameters", values, "parameters")


def _set_end_derivatives(method: Any, start: Optional[ArrayLike],
                         end: Optional[ArrayLike]) -> None:
    for field, value in (("start_derivative", start),
                         ("end_derivative", end)):
        if value is not None:
            getattr(method, field).CopyFrom(to_points(
                float_array(value, field, 1).reshape(1, -1), field))
