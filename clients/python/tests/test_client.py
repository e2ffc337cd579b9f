"""The Client itself: streams, the generic calls, TLS."""

import os
import shutil
import subprocess
import tempfile
import unittest

import grpc
import numpy as np

import freeform
import support
from freeform.v1 import curve_service_pb2, geometry_pb2
from support import cubic, cubic_point


class StreamTest(support.ClientTestCase):
    def test_chunks_follow_one_another(self):
        chunks = list(self.client.curves.evaluate_stream(
            cubic(), freeform.Range(9), 1, chunk_size=4))
        self.assertEqual([chunk.first_index for chunk in chunks], [0, 4, 8])
        self.assertEqual([len(chunk.points) for chunk in chunks], [4, 4, 1])
        joined = freeform.CurveSamples.join(chunks)
        self.assertEqual(joined.derivatives.shape, (2, 9, 2))
        np.testing.assert_allclose(
            joined.points, [cubic_point(k / 8) for k in range(9)], rtol=0,
            atol=1e-12)

    def test_cancel_stops_the_stream(self):
        with self.client.curves.evaluate_stream(
                cubic(), freeform.Range(10 ** 6), chunk_size=1000) as stream:
            first = next(stream)
        self.assertEqual(first.points.shape, (1000, 2))
        with self.assertRaises(freeform.FreeformError) as caught:
            for _ in stream:
                pass
        self.assertEqual(caught.exception.code, grpc.StatusCode.CANCELLED)

    def test_generic_stream(self):
        request = curve_service_pb2.EvaluateCurveRequest(
            curve=cubic(), chunk_size=2,
            parameters=geometry_pb2.Parameters(
                range=geometry_pb2.UniformRange(count=5)))
        chunks = list(self.client.stream("freeform.v1.CurveService/"
                                         "EvaluateStream", request))
        self.assertEqual([chunk.first_index for chunk in chunks], [0, 2, 4])
        self.assertIsInstance(chunks[0],
                              curve_service_pb2.EvaluateCurveResponse)
        self.assertEqual(list(chunks[2].derivatives[0].coordinates), [4, 0])


class GenericCallTest(unittest.TestCase):
    def test_call_with_a_message(self):
        with support.client() as client:
            client.wait_until_ready()
            request = curve_service_pb2.ElevateCurveDegreeRequest(
                curve=cubic(), by=1)
            response = client.call("/freeform.v1.CurveService/ElevateDegree",
                                   request)
        self.assertIsInstance(response,
                              curve_service_pb2.ElevateCurveDegreeResponse)
        np.testing.assert_allclose(
            freeform.to_array(response.curve),
            [[0, 0], [0.75, 1.5], [2, 2], [3.25, 1.5], [4, 0]], rtol=0,
            atol=1e-12)

    def test_an_existing_channel(self):
        channel = grpc.insecure_channel(support.address())
        with freeform.Client(channel=channel,
                             timeout=support.TIMEOUT) as client:
            samples = client.curves.evaluate(cubic(), [0.5])
        np.testing.assert_allclose(samples.points, [[2, 1.5]])


def make_certificates(folder):
    """A CA, a server certificate for 127.0.0.1 and a client certificate."""
    script = """set -e
openssl req -x509 -newkey rsa:2048 -nodes -days 2 -subj /CN=test-ca \
  -keyout ca.key -out ca.pem
printf 'subjectAltName=IP:127.0.0.1,DNS:localhost' > san.ext
openssl req -newkey rsa:2048 -nodes -subj /CN=localhost \
  -keyout server.key -out server.csr
openssl x509 -req -in server.csr -CA ca.pem -CAkey ca.key -CAcreateserial \
  -days 2 -extfile san.ext -out server.pem
openssl req -newkey rsa:2048 -nodes -subj /CN=client \
  -keyout client.key -out client.csr
openssl x509 -req -in client.csr -CA ca.pem -CAkey ca.key -CAcreateserial \
  -days 2 -out client.pem
"""
    subprocess.run(["sh", "-c", script], cwd=folder, check=True,
                   capture_output=True)


@unittest.skipUnless(os.environ.get("FREEFORMD") and shutil.which("openssl"),
                     "needs FREEFORMD and openssl")
class TlsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.mkdtemp(prefix="freeform_tls_")
        make_certificates(cls.folder)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.folder, ignore_errors=True)

    def path(self, name):
        return os.path.join(self.folder, name)

    def evaluate(self, address, tls):
        with freeform.Client(address, tls=tls, timeout=5,
                             retry_unavailable=False) as client:
            return client.curves.evaluate(cubic(), [0.5]).points

    def test_tls(self):
        server = support.Server("--tls_cert=" + self.path("server.pem"),
                                "--tls_key=" + self.path("server.key"))
        try:
            tls = freeform.tls_credentials(root_ca=self.path("ca.pem"))
            np.testing.assert_allclose(self.evaluate(server.address, tls),
                                       [[2, 1.5]])
            with self.assertRaises(freeform.FreeformError) as caught:
                self.evaluate(server.address, False)
            self.assertEqual(caught.exception.code,
                             grpc.StatusCode.UNAVAILABLE)
        finally:
            server.stop()

    def test_mutual_tls(self):
        server = support.Server("--tls_cert=" + self.path("server.pem"),
                                "--tls_key=" + self.path("server.key"),
                                "--tls_client_ca=" + self.path("ca.pem"))
        try:
            anonymous = freeform.tls_credentials(root_ca=self.path("ca.pem"))
            with self.assertRaises(freeform.FreeformError) as caught:
                self.evaluate(server.address, anonymous)
            self.assertEqual(caught.exception.code,
                             grpc.StatusCode.UNAVAILABLE)
            identified = freeform.tls_credentials(
                root_ca=self.path("ca.pem"), cert=self.path("client.pem"),
                key=self.path("client.key"))
            np.testing.assert_allclose(
                self.evaluate(server.address, identified), [[2, 1.5]])
        finally:
            server.stop()

    def test_half_a_client_identity_is_refused(self):
        with self.assertRaisesRegex(ValueError, "both cert and key"):
            freeform.tls_credentials(cert=self.path("client.pem"))


if __name__ == "__main__":
    unittest.main()
