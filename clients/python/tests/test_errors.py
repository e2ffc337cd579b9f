"""FreeformError: the server's google.rpc.BadRequest, naming the field.

The expected paths follow from the requests: the field the test broke,
spelled as server/errors.cc's BadRequest field violations spell request
paths (docs/clients.md).
"""

import math
import pickle
import socket
import unittest

import grpc
import numpy as np

import freeform
import support
from freeform.v1 import curve_service_pb2
from support import cubic, unit_circle


class FieldViolationTest(support.ClientTestCase):
    def assert_names_field(self, call, code, field):
        with self.assertRaises(freeform.FreeformError) as caught:
            call()
        error = caught.exception
        self.assertEqual(error.code, code)
        self.assertEqual(error.field, field)
        self.assertEqual(len(error.violations), 1)
        self.assertEqual(error.violations[0].field, field)
        self.assertTrue(error.description)
        # The message starts with the path, and str() gives the code.
        self.assertTrue(error.message.startswith(field + ": "), error.message)
        self.assertEqual(str(error), "%s: %s" % (code.name, error.message))
        self.assertIsInstance(error.rpc_error, grpc.RpcError)
        return error

    def test_coordinates_not_a_multiple_of_the_dimension(self):
        # The examples' bad request: three coordinates in dimension 2, sent
        # as a dict through the generic call.
        request = {"curve": {"bezier": {"control_points": {
            "dimension": 2, "coordinates": [0, 0, 1]}}},
            "parameters": {"list": {"values": [0.5]}}}
        self.assert_names_field(
            lambda: self.client.call("CurveService.Evaluate", request),
            grpc.StatusCode.INVALID_ARGUMENT,
            "curve.bezier.control_points.coordinates")

    def test_a_nan_knot_names_its_index(self):
        knots = [0, 0, 0, 1, 1, 1]
        knots[2] = math.nan
        curve = freeform.bspline(2, [[0, 0], [1, 1], [2, 0]], knots)
        self.assert_names_field(
            lambda: self.client.curves.evaluate(curve, [0.5]),
            grpc.StatusCode.INVALID_ARGUMENT, "curve.bspline.knots[2]")

    def test_a_parameter_outside_the_domain(self):
        self.assert_names_field(
            lambda: self.client.curves.evaluate(cubic(), [0.5, 3]),
            grpc.StatusCode.INVALID_ARGUMENT, "parameters.list.values[1]")

    def test_surface_field_paths(self):
        # knots_v[3] = 0.5 comes after 1.
        net = np.zeros((2, 2, 3))
        surface = freeform.bspline_surface(1, 1, net, [0, 0, 1, 1],
                                           [0, 0, 1, 0.5])
        self.assert_names_field(
            lambda: self.client.surfaces.evaluate(surface, [0.5, 0.5]),
            grpc.StatusCode.INVALID_ARGUMENT, "surface.bspline.knots_v[3]")
        self.assert_names_field(
            lambda: self.client.surfaces.tessellate(
                [freeform.bezier_surface(net), surface], 0.01),
            grpc.StatusCode.INVALID_ARGUMENT, "surfaces[1].bspline.knots_v[3]")

    def test_a_limit_names_the_field_too(self):
        # More than 5 points at 1e-6 on the circle: RESOURCE_EXHAUSTED.
        error = self.assert_names_field(
            lambda: self.client.curves.tessellate(unit_circle(), 1e-6,
                                                  max_points=5),
            grpc.StatusCode.RESOURCE_EXHAUSTED, "tolerance")
        self.assertIn("5", error.description)

    def test_an_error_pickles_with_its_fields(self):
        with self.assertRaises(freeform.FreeformError) as caught:
            self.client.curves.evaluate(cubic(), [2])
        error = caught.exception
        copy = pickle.loads(pickle.dumps(error))
        self.assertEqual((copy.code, copy.message, copy.violations),
                         (error.code, error.message, error.violations))
        self.assertEqual(copy.field, "parameters.list.values[0]")
        self.assertEqual(str(copy), str(error))

    def test_a_stream_raises_when_iterated(self):
        stream = self.client.curves.evaluate_stream(cubic(), [0.5, -1])
        with self.assertRaises(freeform.FreeformError) as caught:
            next(stream)
        self.assertEqual(caught.exception.field, "parameters.list.values[1]")


class CallFailureTest(unittest.TestCase):
    def test_deadline(self):
        with support.client() as client:
            with self.assertRaises(freeform.FreeformError) as caught:
                client.curves.evaluate(unit_circle(), freeform.Range(10 ** 6),
                                       timeout=1e-4)
        self.assertEqual(caught.exception.code,
                         grpc.StatusCode.DEADLINE_EXCEEDED)
        self.assertIsNone(caught.exception.field)

    def test_nobody_listening(self):
        with socket.socket() as probe:
            probe.bind(("127.0.0.1", 0))
            port = probe.getsockname()[1]
        # The port is closed again: connecting is refused.
        with freeform.Client("127.0.0.1:%d" % port, timeout=2) as client:
            with self.assertRaises(freeform.FreeformError) as caught:
                client.curves.evaluate(cubic(), [0.5])
        self.assertEqual(caught.exception.code, grpc.StatusCode.UNAVAILABLE)

    def test_an_answer_over_the_receive_limit(self):
        with support.client(max_receive_message_bytes=10000) as client:
            with self.assertRaises(freeform.FreeformError) as caught:
                client.curves.evaluate(cubic(), freeform.Range(10000))
            self.assertEqual(caught.exception.code,
                             grpc.StatusCode.RESOURCE_EXHAUSTED)
            # The stream's chunks each fit.
            chunks = list(client.curves.evaluate_stream(
                cubic(), freeform.Range(10000), chunk_size=500))
        self.assertEqual(sum(len(chunk.points) for chunk in chunks), 10000)


class LocalErrorTest(unittest.TestCase):
    """Requests the client refuses before sending, naming the argument."""

    def test_shapes(self):
        with self.assertRaisesRegex(ValueError, "control_points must have 2"):
            freeform.bezier([0, 0, 1, 2])
        with self.assertRaisesRegex(ValueError, "net must have 3"):
            freeform.bezier_surface([[0, 0, 0]])
        with self.assertRaisesRegex(ValueError, r"weights of shape \(2, 3\)"):
            freeform.bezier_surface(np.zeros((3, 2, 3)),
                                    weights=np.ones((2, 3)))
        with self.assertRaisesRegex(ValueError,
                                    r"parameters must be \(u, v\)"):
            with support.client() as client:
                client.surfaces.evaluate(freeform.bezier_surface(
                    np.zeros((2, 2, 3))), [0.1, 0.2, 0.3])
        with self.assertRaisesRegex(TypeError, "must hold real numbers"):
            freeform.bezier([[1j, 0]])
        with self.assertRaisesRegex(TypeError, "to_array takes"):
            freeform.to_array(freeform.bernstein_basis(2))

    def test_types_and_names(self):
        with support.client() as client:
            with self.assertRaisesRegex(TypeError, "curve must be a freeform"):
                client.curves.evaluate([[0, 0], [1, 1]], [0.5])
            with self.assertRaisesRegex(ValueError, "direction='u' or 'v'"):
                client.surfaces.split(freeform.bezier_surface(
                    np.zeros((2, 2, 3))), 0.5)
            with self.assertRaisesRegex(ValueError, "algorithm must be one"):
                client.curves.evaluate(cubic(), [0.5], algorithm="magic")
            with self.assertRaisesRegex(ValueError, "unknown method"):
                client.call("CurveService.Evalu", {})
            with self.assertRaisesRegex(TypeError, "takes a "
                                        "TessellateCurveRequest"):
                client.call("CurveService.Tessellate",
                            curve_service_pb2.EvaluateCurveRequest())
            with self.assertRaisesRegex(ValueError, "use stream"):
                client.call("CurveService.EvaluateStream", {})
            with self.assertRaisesRegex(ValueError, "use call"):
                client.stream("CurveService.Evaluate", {})


if __name__ == "__main__":
    unittest.main()
