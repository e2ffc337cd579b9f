"""Pieces of requests that both services' methods build."""

from __future__ import annotations

from typing import Any, Optional

from freeform.v1 import query_pb2 as _query


def check_type(value: Any, kind: type, name: str) -> Any:
    """``value`` when it is a ``kind`` message; TypeError naming ``name``
    otherwise."""
    if not isinstance(value, kind):
        raise TypeError("%s must be a freeform.v1 %s (see freeform.bezier, "
                        "freeform.bspline_surface, ...), not %s" %
                        (name, kind.__name__, type(value).__name__))
    return value


def set_optional(message: Any, **fields: Any) -> Any:
    """Sets the given fields of ``message`` that are not None (so that
    proto3 ``optional`` fields left as None stay absent)."""
    for name, value in fields.items():
        if value is not None:
            setattr(message, name, value)
    return message


def closest_point_options(tolerance: Optional[float],
                          separation: Optional[float],
                          max_minima: int) -> _query.ClosestPointOptions:
    return set_optional(_query.ClosestPointOptions(max_minima=max_minima),
                        tolerance=tolerance, separation=separation)


def intersection_options(tolerance: Optional[float],
                         separation: Optional[float],
                         max_results: int) -> _query.IntersectionOptions:
    return set_optional(_query.IntersectionOptions(max_results=max_results),
                        tolerance=tolerance, separation=separation)
