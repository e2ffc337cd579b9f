"""10^6 points through the package cost one copy, not a Python float each.

Evaluating the cubic at 10^6 parameters with its first derivative answers
32 MB of doubles. The package copies them once from the received bytes
into aligned numpy arrays. So the memory Python allocates during the call
(tracemalloc) peaks no higher than gRPC's own receiving of those bytes
(measured with a bytes-only call) or the bytes plus the arrays, whichever
is more, and once the call returns only the arrays remain. Reading them
through protobuf's message instead makes a Python float per value. The
times are printed, not asserted (clients/python/bench/conversion_bench.py
measures them).
"""

import gc
import time
import tracemalloc
import unittest
from unittest import mock

import grpc
import numpy as np

import freeform
import support
from freeform.v1 import curve_service_pb2
from support import cubic, cubic_derivative, cubic_point

COUNT = 10 ** 6
MB = 1e6
# What Python may allocate beyond the received bytes and the arrays: the
# message objects, the result, the request (a few kB), and gRPC's transient
# receive buffers, whose size varies from call to call (one run of about
# twenty, 2026-12-02, peaked 3.7 MB above the 64 MB of bytes and arrays).
# A second copy of the answer would add 32 MB, a float per value 64 MB more.
SLACK_BYTES = 6 << 20


def traced(call):
    """call()'s result, seconds, and Python's peak and retained bytes."""
    gc.collect()
    tracemalloc.start()
    start = time.perf_counter()
    result = call()
    seconds = time.perf_counter() - start
    retained, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    return result, seconds, peak, retained


class MillionPointsTest(unittest.TestCase):
    def test_evaluate_costs_one_copy(self):
        request = curve_service_pb2.EvaluateCurveRequest(
            curve=cubic(), derivative_order=1)
        request.parameters.range.count = COUNT
        with grpc.insecure_channel(support.address(), [
                ("grpc.max_receive_message_length", 64 << 20)]) as channel:
            receive_bytes = channel.unary_unary(
                "/freeform.v1.CurveService/Evaluate",
                request_serializer=lambda message: message.SerializeToString(),
                response_deserializer=None)
            receive_bytes(request, timeout=support.TIMEOUT)
            answer, raw_seconds, raw_peak, _ = traced(
                lambda: receive_bytes(request, timeout=support.TIMEOUT))
        wire_bytes = len(answer)
        del answer
        # The package's only value-by-value path (its fallback, should the
        # bytes disagree with the parsed message) must not run.
        with support.client() as client, mock.patch.object(
                np, "fromiter", side_effect=AssertionError("value by value")):
            client.curves.evaluate(cubic(), freeform.Range(1000), 1)
            samples, seconds, peak, retained = traced(
                lambda: client.curves.evaluate(cubic(), freeform.Range(COUNT),
                                               derivative_order=1))
        derivatives = samples.derivatives
        self.assertEqual(derivatives.shape, (2, COUNT, 2))
        array_bytes = derivatives.nbytes
        print("\n10^6 parameters, first derivative: %.1f MB answer; bytes "
              "only: %.3f s, Python peak %.1f MB; freeform: %.3f s, peak "
              "%.1f MB, retained %.1f MB" % (
                  wire_bytes / MB, raw_seconds, raw_peak / MB, seconds,
                  peak / MB, retained / MB))
        self.assertLess(wire_bytes, array_bytes + 100)
        self.assertLessEqual(peak, max(raw_peak, wire_bytes + array_bytes) +
                             SLACK_BYTES)
        self.assertLessEqual(retained, array_bytes + SLACK_BYTES)
        self.assertTrue(derivatives.flags.c_contiguous and
                        derivatives.flags.aligned and
                        derivatives.flags.writeable)
        # The values: C(t) and C'(t) at t = k / (COUNT - 1).
        for k in (0, 1, 123457, COUNT // 2, COUNT - 1):
            t = k / (COUNT - 1)
            np.testing.assert_allclose(derivatives[0, k], cubic_point(t),
                                       rtol=0, atol=1e-12)
            np.testing.assert_allclose(derivatives[1, k],
                                       cubic_derivative(t), rtol=0,
                                       atol=1e-12)
        exact = np.linspace(0, 1, COUNT)
        np.testing.assert_allclose(
            derivatives[0, :, 1], 6 * exact * (1 - exact), rtol=0,
            atol=1e-12)

    def test_sending_a_million_points_costs_one_copy(self):
        points = np.random.default_rng(11).normal(size=(COUNT, 3))
        message, seconds, peak, retained = traced(
            lambda: freeform.to_points(points))
        print("\n10^6 3D points into a Points message: %.1f MB in %.3f s; "
              "Python peak %.1f MB" % (points.nbytes / MB, seconds,
                                       peak / MB))
        # The bytes handed to protobuf's parser, then released.
        self.assertLessEqual(peak, points.nbytes + SLACK_BYTES)
        self.assertLessEqual(retained, SLACK_BYTES)
        self.assertEqual(len(message.coordinates), points.size)
        self.assertEqual(message.coordinates[4], points[1, 1])


if __name__ == "__main__":
    unittest.main()
