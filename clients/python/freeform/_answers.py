"""Answers of both services, from the Views of the received messages."""

from __future__ import annotations

import re
from typing import Any, Optional

import numpy as np

from freeform import _results
from freeform._geometry import points_of
from freeform._wire import View, WireError


def enum_value(enum: Any, value: Any, name: str) -> Any:
    """The number of an enum value given by its number, its full name
    ("KNOT_RULE_UNIFORM") or its short name in any case ("uniform"); None is
    0 (the proto's default). (Any: the generated type hints give each enum
    a type of its own.)"""
    if value is None:
        return 0
    if isinstance(value, str):
        prefix = re.sub(r"(?<!^)(?=[A-Z])", "_",
                        enum.DESCRIPTOR.name).upper() + "_"
        full = value.upper()
        if not full.startswith(prefix):
            full = prefix + full
        if full in enum.keys():
            return enum.Value(full)
        raise ValueError("%s must be one of %s, not %r" % (
            name, ", ".join(key[len(prefix):].lower()
                            for key in enum.keys()), value))
    return int(value)


def pairs(view: View, field: str) -> np.ndarray:
    """The repeated double ``field`` as ``(n, 2)`` pairs."""
    values = view.doubles(field)
    if values.size % 2:
        raise WireError("%s has %d values, not pairs" % (field, values.size))
    return values.reshape(-1, 2)


def optional_points(view: View, field: str) -> Optional[np.ndarray]:
    """The Points ``field``, or None when the answer left it empty."""
    points = view.submessage(field)
    if not points.message.coordinates and not points.message.dimension:
        return None
    return points_of(points)


def curve_samples(view: View) -> _results.CurveSamples:
    """An EvaluateCurveResponse (unary or a stream's chunk)."""
    message = view.message
    derivatives = view.submessages("derivatives")
    out = np.empty((len(derivatives), message.count, message.dimension))
    for k, derivative in enumerate(derivatives):
        if derivative.message.dimension != message.dimension:
            raise WireError("derivative %d has dimension %d, not %d" % (
                k, derivative.message.dimension, message.dimension))
        derivative.doubles("coordinates", out[k].reshape(-1))
    return _results.CurveSamples(out, message.first_index)


def surface_samples(view: View, normals: bool) -> _results.SurfaceSamples:
    """An EvaluateSurfaceResponse (unary or a stream's chunk)."""
    message = view.message
    partials = {}
    for partial in view.submessages("partials"):
        values = points_of(partial.submessage("values"),
                           empty_dimension=message.dimension)
        if values.shape[0] != message.count:
            raise WireError("partial (%d, %d) has %d points, not %d" % (
                partial.message.order_u, partial.message.order_v,
                values.shape[0], message.count))
        partials[(partial.message.order_u, partial.message.order_v)] = values
    return _results.SurfaceSamples(
        partials,
        points_of(view.submessage("normals"), empty_dimension=3)
        if normals else None,
        message.first_index)


def mesh(view: View, normals: bool) -> _results.Mesh:
    """A TessellateSurfaceResponse (unary or a stream's chunk)."""
    triangles = view.varints("triangles", np.int64)
    if triangles.size % 3:
        raise WireError("%d triangle indices" % triangles.size)
    return _results.Mesh(
        points_of(view.submessage("vertices"), empty_dimension=3),
        triangles.reshape(-1, 3),
        points_of(view.submessage("normals"), empty_dimension=3)
        if normals else None,
        view.varints("surface_index", np.int64),
        pairs(view, "uv"))


def closest_points(view: View) -> _results.ClosestPoints:
    """A ClosestPointResponse of either service."""
    parameter_count = view.message.parameter_count
    parameters = view.doubles("parameters")
    if parameter_count == 0 or parameters.size % parameter_count:
        raise WireError("%d parameters, %d per minimum" %
                        (parameters.size, parameter_count))
    return _results.ClosestPoints(
        view.doubles("distances"), view.doubles("lower_bounds"),
        view.varints("minima_counts", np.int64),
        view.varints("complete", np.bool_),
        parameters.reshape(-1, parameter_count),
        points_of(view.submessage("points")))


def bounding_box(view: View) -> _results.BoundingBox:
    """A BoundingBoxResponse of either service."""
    return _results.BoundingBox(view.doubles("lower"), view.doubles("upper"))
