"""Curves, surfaces, bases and parameters from numpy arrays, and back.

The builders return the messages of ``freeform.v1`` (``geometry_pb2.Curve``,
``geometry_pb2.Surface``, ...), so that their results go straight into any
RPC, including ``Client.call``. Arrays travel as the proto's packed
``repeated double``: written in one move (the array's bytes behind the
field's tag), never one Python float at a time.

Shapes: points are ``(n, d)`` (n points of dimension d), control nets
``(m, n, d)`` (m rows in u of n points in v), weights one per point.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple, Optional, Sequence, Union

import numpy as np
from google.protobuf import message as _message
from numpy.typing import ArrayLike

from freeform._wire import SMALL_FIELD, View, WireError
from freeform.v1 import curve_service_pb2 as _curves
from freeform.v1 import geometry_pb2 as _geometry

_LITTLE_ENDIAN_DOUBLE = np.dtype("<f8")


def _varint(value: int) -> bytes:
    out = bytearray()
    while value > 0x7F:
        out.append((value & 0x7F) | 0x80)
        value >>= 7
    out.append(value)
    return bytes(out)


def float_array(values: ArrayLike, name: str, ndim: int) -> np.ndarray:
    """``values`` as a C-contiguous little-endian float64 array of ``ndim``
    dimensions; ValueError naming ``name`` otherwise."""
    array = np.asarray(values)
    if array.dtype.kind not in "biuf":
        raise TypeError("%s must hold real numbers, not %s" %
                        (name, array.dtype))
    if array.ndim != ndim:
        raise ValueError("%s must have %d dimension%s, got shape %s" %
                         (name, ndim, "s" if ndim > 1 else "", array.shape))
    return np.ascontiguousarray(array, dtype=_LITTLE_ENDIAN_DOUBLE)


def set_doubles(message: _message.Message, field: str,
                values: ArrayLike, name: str) -> None:
    """Sets the packed repeated double ``field`` of ``message`` to the 1-D
    ``values`` (``name`` in errors) in one parse of their bytes."""
    array = float_array(values, name, 1)
    message.ClearField(field)
    if array.size < SMALL_FIELD:
        # A few values: quicker one by one (tolist keeps every double).
        getattr(message, field).extend(array.tolist())
        return
    number = message.DESCRIPTOR.fields_by_name[field].number
    # Tag (length-delimited), byte count, then the doubles themselves.
    message.MergeFromString(b"".join((
        _varint(number << 3 | 2), _varint(array.nbytes),
        array.data.cast("B"))))


def _fill_points(message: _message.Message, points: ArrayLike,
                 name: str) -> None:
    array = float_array(points, name, 2)
    message.dimension = array.shape[1]
    set_doubles(message, "coordinates", array.reshape(-1), name)


def to_points(values: ArrayLike, name: str = "points") -> _geometry.Points:
    """A ``Points`` message of the ``(n, d)`` array ``values``."""
    message = _geometry.Points()
    _fill_points(message, values, name)
    return message


def _fill_net(message: _message.Message, net: ArrayLike,
              name: str) -> None:
    array = float_array(net, name, 3)
    message.count_u, message.count_v, message.dimension = array.shape
    set_doubles(message, "coordinates", array.reshape(-1), name)


def to_control_net(values: ArrayLike,
                   name: str = "net") -> _geometry.ControlNet:
    """A ``ControlNet`` of the ``(m, n, d)`` array ``values``: m rows in u of
    n points in v."""
    message = _geometry.ControlNet()
    _fill_net(message, values, name)
    return message


def _set_weights(message: _message.Message, weights: Optional[ArrayLike],
                 point_shape: Sequence[int]) -> None:
    """Weights: 1-D, or shaped like the points of a net ``(m, n)``."""
    if weights is None:
        return
    array = np.asarray(weights)
    if array.ndim == 2 and tuple(array.shape) != tuple(point_shape):
        raise ValueError("weights of shape %s do not match the net's %s" %
                         (array.shape, tuple(point_shape)))
    set_doubles(message, "weights", array.reshape(-1), "weights")


def _set_optional_doubles(message: _message.Message, field: str,
                          values: Optional[ArrayLike]) -> None:
    if values is not None:
        set_doubles(message, field, values, field)


# ----------------------------------------------------------------- curves --

def bezier(control_points: ArrayLike,
           weights: Optional[ArrayLike] = None) -> _geometry.Curve:
    """The Bezier curve of the ``(n + 1, d)`` control points on [0, 1]
    (rational with ``weights``, one per point)."""
    curve = _geometry.Curve()
    _fill_points(curve.bezier.control_points, control_points,
                 "control_points")
    _set_weights(curve.bezier, weights, ())
    return curve


def bspline(degree: int, control_points: ArrayLike, knots: ArrayLike,
            weights: Optional[ArrayLike] = None) -> _geometry.Curve:
    """The B-spline curve of ``degree`` (NURBS with ``weights``): ``(n + 1,
    d)`` control points and the full knot vector of n + degree + 2 values."""
    curve = _geometry.Curve()
    curve.bspline.degree = degree
    _fill_points(curve.bspline.control_points, control_points,
                 "control_points")
    set_doubles(curve.bspline, "knots", knots, "knots")
    _set_weights(curve.bspline, weights, ())
    return curve


def lagrange(points: ArrayLike,
             nodes: Optional[ArrayLike] = None) -> _geometry.Curve:
    """The polynomial through the ``(n + 1, d)`` points at ``nodes``
    (default: uniform on [0, 1])."""
    curve = _geometry.Curve()
    _fill_points(curve.lagrange.points, points, "points")
    _set_optional_doubles(curve.lagrange, "nodes", nodes)
    return curve


def hermite(points: ArrayLike, tangents: ArrayLike,
            nodes: Optional[ArrayLike] = None) -> _geometry.Curve:
    """The piecewise cubic Hermite curve through the ``(K, d)`` points with
    the ``(K, d)`` tangents at ``nodes`` (default 0, 1, ..., K - 1)."""
    curve = _geometry.Curve()
    _fill_points(curve.hermite.points, points, "points")
    _fill_points(curve.hermite.tangents, tangents, "tangents")
    _set_optional_doubles(curve.hermite, "nodes", nodes)
    return curve


def power(coefficients: ArrayLike) -> _geometry.Curve:
    """The polynomial A_0 + A_1 t + ... + A_n t^n on [0, 1] of the ``(n + 1,
    d)`` coefficient vectors."""
    curve = _geometry.Curve()
    _fill_points(curve.power.coefficients, coefficients, "coefficients")
    return curve


# --------------------------------------------------------------- surfaces --

def _net_shape(net: _geometry.ControlNet):
    return (net.count_u, net.count_v)


def bezier_surface(net: ArrayLike,
                   weights: Optional[ArrayLike] = None) -> _geometry.Surface:
    """The tensor-product Bezier surface of the ``(m + 1, n + 1, d)`` net on
    [0, 1]^2 (rational with ``weights`` of shape ``(m + 1, n + 1)``)."""
    surface = _geometry.Surface()
    _fill_net(surface.bezier.control_net, net, "net")
    _set_weights(surface.bezier, weights,
                 _net_shape(surface.bezier.control_net))
    return surface


def bspline_surface(degree_u: int, degree_v: int, net: ArrayLike,
                    knots_u: ArrayLike, knots_v: ArrayLike,
                    weights: Optional[ArrayLike] = None) -> _geometry.Surface:
    """The tensor-product B-spline (NURBS with ``weights`` of shape ``(m,
    n)``) surface of the ``(m, n, d)`` net and the full knot vectors: m +
    degree_u + 1 values in u, n + degree_v + 1 in v."""
    surface = _geometry.Surface()
    bspline_ = surface.bspline
    bspline_.degree_u, bspline_.degree_v = degree_u, degree_v
    _fill_net(bspline_.control_net, net, "net")
    set_doubles(bspline_, "knots_u", knots_u, "knots_u")
    set_doubles(bspline_, "knots_v", knots_v, "knots_v")
    _set_weights(bspline_, weights, _net_shape(bspline_.control_net))
    return surface


def bicubic_interpolating_patch(net: ArrayLike) -> _geometry.Surface:
    """The bicubic patch through the ``(4, 4, d)`` points at the parameters
    0, 1/3, 2/3, 1 in u and in v."""
    surface = _geometry.Surface()
    _fill_net(surface.bicubic_interpolating.points, net, "net")
    return surface


def bicubic_hermite_patch(positions: ArrayLike, derivatives_u: ArrayLike,
                          derivatives_v: ArrayLike,
                          twists: Optional[ArrayLike] = None
                          ) -> _geometry.Surface:
    """The bicubic Hermite (Ferguson) patch given at its corners by ``(2, 2,
    d)`` positions, u- and v-derivatives and twists (default zero)."""
    surface = _geometry.Surface()
    patch = surface.bicubic_hermite
    _fill_net(patch.positions, positions, "positions")
    _fill_net(patch.derivatives_u, derivatives_u, "derivatives_u")
    _fill_net(patch.derivatives_v, derivatives_v, "derivatives_v")
    if twists is not None:
        _fill_net(patch.twists, twists, "twists")
    return surface


def triangular_bezier_patch(degree: int, control_points: ArrayLike,
                            weights: Optional[ArrayLike] = None,
                            domain_triangle: Optional[ArrayLike] = None
                            ) -> _geometry.Surface:
    """The triangular Bezier patch of ``degree`` with its ``((n + 1)(n + 2)
    / 2, d)`` control points ordered P(n,0,0), P(n-1,1,0), P(n-1,0,1), ...
    (rational with ``weights``); with a ``(3, 2)`` ``domain_triangle`` its
    parameters are points (x, y) of that triangle."""
    surface = _geometry.Surface()
    patch = surface.triangular_bezier
    patch.degree = degree
    _fill_points(patch.control_points, control_points, "control_points")
    _set_weights(patch, weights, ())
    if domain_triangle is not None:
        _fill_points(patch.domain_triangle, domain_triangle,
                     "domain_triangle")
    return surface


# ------------------------------------------------------------------ bases --

def bernstein_basis(degree: int,
                    weights: Optional[ArrayLike] = None) -> _curves.Basis:
    """The degree + 1 Bernstein polynomials (rational with ``weights``)."""
    basis = _curves.Basis()
    basis.bernstein.degree = degree
    _set_weights(basis.bernstein, weights, ())
    return basis


def bspline_basis(degree: int, knots: ArrayLike,
                  weights: Optional[ArrayLike] = None) -> _curves.Basis:
    """The B-splines of ``degree`` on ``knots`` (rational with
    ``weights``)."""
    basis = _curves.Basis()
    basis.bspline.degree = degree
    set_doubles(basis.bspline, "knots", knots, "knots")
    _set_weights(basis.bspline, weights, ())
    return basis


def lagrange_basis(nodes: ArrayLike) -> _curves.Basis:
    """The Lagrange polynomials of the strictly increasing ``nodes``."""
    basis = _curves.Basis()
    set_doubles(basis.lagrange, "nodes", nodes, "nodes")
    return basis


def hermite_basis() -> _curves.Basis:
    """The four cubic Hermite functions H0..H3 on [0, 1]."""
    basis = _curves.Basis()
    basis.hermite.SetInParent()
    return basis


# ------------------------------------------------------------- parameters --

@dataclass(frozen=True)
class Range:
    """``count`` equally spaced parameters from ``start`` to ``end``
    (numpy.linspace's values), computed by the server; without start and
    end, the whole domain of the geometry."""

    count: int
    start: Optional[float] = None
    end: Optional[float] = None


CurveParameters = Union[Range, _geometry.Parameters, ArrayLike]


class Grid(NamedTuple):
    """Every u of ``u`` with every v of ``v`` (each a Range or values);
    results are u-major: point (i, j) is i * len(v) + j."""

    u: CurveParameters
    v: CurveParameters


SurfaceParameters = Union[Grid, _geometry.SurfaceParameters, ArrayLike]


def parameters(values: CurveParameters,
               name: str = "parameters") -> _geometry.Parameters:
    """A ``Parameters`` message: a Range, a list of values (a scalar is one
    value) or a ``Parameters`` message (copied)."""
    message = _geometry.Parameters()
    if isinstance(values, _geometry.Parameters):
        message.CopyFrom(values)
    elif isinstance(values, Range):
        message.range.count = values.count
        if values.start is not None:
            message.range.start = values.start
        if values.end is not None:
            message.range.end = values.end
    else:
        array = np.asarray(values)
        set_doubles(message.list, "values",
                    array.reshape(-1) if array.ndim == 0 else array, name)
        message.list.SetInParent()
    return message


def surface_parameters(values: SurfaceParameters,
                       name: str = "parameters"
                       ) -> _geometry.SurfaceParameters:
    """A ``SurfaceParameters`` message: a Grid, an ``(n, 2)`` array of (u, v)
    pairs (one ``(2,)`` pair is one point) or the message (copied)."""
    message = _geometry.SurfaceParameters()
    if isinstance(values, _geometry.SurfaceParameters):
        message.CopyFrom(values)
    elif isinstance(values, Grid):
        message.grid.u.CopyFrom(parameters(values.u, name + ".u"))
        message.grid.v.CopyFrom(parameters(values.v, name + ".v"))
    else:
        array = np.asarray(values)
        if array.ndim == 1 and array.shape[0] == 2:
            array = array.reshape(1, 2)
        if array.ndim != 2 or array.shape[1] != 2:
            raise ValueError("%s must be (u, v) pairs of shape (n, 2) or a "
                             "Grid, got shape %s" % (name, array.shape))
        set_doubles(message.points, "uv", array.reshape(-1), name)
        message.points.SetInParent()
    return message


# ------------------------------------------------------------ to numpy --

def _points_view(view: View, shape_fields: Sequence[str],
                 empty_dimension: int) -> np.ndarray:
    message = view.message
    shape = tuple(getattr(message, field) for field in shape_fields)
    values = view.doubles("coordinates")
    dimension = message.dimension
    count = int(np.prod(shape)) if shape else None
    if dimension == 0 and values.size == 0:
        dimension = empty_dimension
        if dimension == 0 and not count:
            return values.reshape((shape or (0,)) + (0,))
    if dimension == 0 or values.size % dimension or (
            count is not None and values.size != count * dimension):
        raise WireError("%d coordinates do not make %s of dimension %d" % (
            values.size, "a %d x %d net" % shape if shape else "points",
            dimension))
    return values.reshape((shape or (-1,)) + (dimension,))


def points_of(view: View, empty_dimension: int = 0) -> np.ndarray:
    """The ``(n, d)`` array of a ``Points`` View (``(0, empty_dimension)``
    when it is empty and has no dimension)."""
    return _points_view(view, (), empty_dimension)


def net_of(view: View) -> np.ndarray:
    """The ``(m, n, d)`` array of a ``ControlNet`` View."""
    return _points_view(view, ("count_u", "count_v"), 0)


# The field of each curve and surface kind that to_array returns.
_CURVE_POINTS = {"bezier": "control_points", "bspline": "control_points",
                 "lagrange": "points", "hermite": "points",
                 "power": "coefficients"}
_SURFACE_POINTS = {"bezier": "control_net", "bspline": "control_net",
                   "bicubic_interpolating": "points",
                   "bicubic_hermite": "positions",
                   "triangular_bezier": "control_points"}


def to_array(message: _message.Message) -> np.ndarray:
    """The points of a message as a numpy array, in one copy of their bytes.

    ``Points`` give ``(n, d)``; ``ControlNet`` ``(m, n, d)``; a ``Curve``
    its control points (Lagrange and Hermite: its points; power form: its
    coefficients); a ``Surface`` its control net (a bicubic Hermite patch:
    its positions; a triangular patch: its ``(n, d)`` control points).
    """
    if isinstance(message, _geometry.Curve):
        kind = message.WhichOneof("kind")
        if kind is None:
            raise ValueError("the curve has no kind set")
        return to_array(getattr(getattr(message, kind), _CURVE_POINTS[kind]))
    if isinstance(message, _geometry.Surface):
        kind = message.WhichOneof("kind")
        if kind is None:
            raise ValueError("the surface has no kind set")
        return to_array(getattr(getattr(message, kind),
                                _SURFACE_POINTS[kind]))
    if not isinstance(message, (_geometry.Points, _geometry.ControlNet)):
        raise TypeError("to_array takes Points, ControlNet, Curve or "
                        "Surface, not %s" % type(message).__name__)
    # Few values are read from the message itself (View.doubles).
    view = View(message.SerializeToString()
                if len(message.coordinates) >= SMALL_FIELD else b"", message)
    if isinstance(message, _geometry.Points):
        return points_of(view)
    return net_of(view)
