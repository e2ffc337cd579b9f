"""freeform: a Python client of freeformd, numpy arrays in and out.

    import freeform

    with freeform.Client("127.0.0.1:50051") as client:
        cubic = freeform.bezier([[0, 0], [1, 2], [3, 2], [4, 0]])
        samples = client.curves.evaluate(cubic, [0, 0.5, 1],
                                         derivative_order=1)
        samples.points          # (3, 2): (0, 0), (2, 1.5), (4, 0)
        samples.derivatives[1]  # (3, 2): (3, 6), (4.5, 0), (3, -6)

``client.curves`` and ``client.surfaces`` have a method per RPC of
CurveService and SurfaceService; ``client.call`` / ``client.stream`` run
any RPC with its request message (``freeform.v1.*_pb2``, generated from the
repository's proto/ when the package is built). Failures raise
FreeformError, whose ``field`` names the offending request field.
docs/clients.md of the repository describes the package.
"""

from freeform._client import Client, tls_credentials
from freeform._errors import FieldViolation, FreeformError
from freeform._geometry import (Grid, Range, bernstein_basis, bezier,
                                bezier_surface, bicubic_hermite_patch,
                                bicubic_interpolating_patch, bspline,
                                bspline_basis, bspline_surface, hermite,
                                hermite_basis, lagrange, lagrange_basis, power,
                                to_array, to_control_net, to_points,
                                triangular_bezier_patch)
from freeform._results import (ArcSamples, BoundingBox, ClosestPoints,
                               CurveCurvature, CurveFit, CurveIntersections,
                               CurveKnotRemoval, CurveSamples,
                               CurveSurfaceIntersections, Decomposition,
                               DegreeReduction, Frames, Mesh, Polyline,
                               ScatteredFit, SectionPolyline, Subdivision,
                               SurfaceCurvature, SurfaceFit,
                               SurfaceKnotRemoval, SurfaceSamples)
from freeform._curves import Curves
from freeform._stream import Stream
from freeform._surfaces import Surfaces

__version__ = "0.1.0"

__all__ = [
    "ArcSamples", "BoundingBox", "Client", "ClosestPoints", "CurveCurvature",
    "CurveFit", "CurveIntersections", "CurveKnotRemoval", "CurveSamples",
    "CurveSurfaceIntersections", "Curves", "Decomposition", "DegreeReduction",
    "FieldViolation", "Frames", "FreeformError", "Grid", "Mesh", "Polyline",
    "Range", "ScatteredFit", "SectionPolyline", "Stream", "Subdivision",
    "SurfaceCurvature", "SurfaceFit", "SurfaceKnotRemoval", "SurfaceSamples",
    "Surfaces", "bernstein_basis", "bezier", "bezier_surface",
    "bicubic_hermite_patch", "bicubic_interpolating_patch", "bspline",
    "bspline_basis", "bspline_surface", "hermite", "hermite_basis",
    "lagrange", "lagrange_basis", "power", "tls_credentials", "to_array",
    "to_control_net", "to_points", "triangular_bezier_patch",
]
