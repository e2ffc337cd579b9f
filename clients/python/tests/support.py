"""The freeformd the tests call, and the curves and surfaces they share.

The server is FREEFORM_ADDRESS (HOST:PORT of a running freeformd) or, when
that is unset, the freeformd at FREEFORMD started on a free loopback port
for the whole test run (stopped at exit). FREEFORM_SOURCE_DIR is the
repository (default: three folders up), FREEFORM_CLI the freeform CLI (the
tests that compare with it are skipped without it).
"""

import atexit
import math
import os
import shutil
import signal
import subprocess
import tempfile
import time
import unittest

import freeform

SOURCE_DIR = os.environ.get("FREEFORM_SOURCE_DIR") or os.path.normpath(
    os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir,
                 os.pardir, os.pardir))
TIME_SCALE = float(os.environ.get("FREEFORM_TEST_TIME_SCALE", "1"))
TIMEOUT = 30 * TIME_SCALE

# The cubic Bezier curve of examples/cubic_bezier.json.
CUBIC_POINTS = [[0, 0], [1, 2], [3, 2], [4, 0]]
# The NURBS unit circle of examples/nurbs_circle_polyline.json: four
# rational quadratic quarters with weights 1, sqrt(1/2), 1.
CIRCLE_POINTS = [[1, 0], [1, 1], [0, 1], [-1, 1], [-1, 0], [-1, -1],
                 [0, -1], [1, -1], [1, 0]]
CIRCLE_KNOTS = [0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1]
CIRCLE_WEIGHTS = [1, math.sqrt(0.5)] * 4 + [1]


def cubic():
    return freeform.bezier(CUBIC_POINTS)


def unit_circle():
    return freeform.bspline(2, CIRCLE_POINTS, CIRCLE_KNOTS, CIRCLE_WEIGHTS)


def cubic_point(t):
    """The cubic at t in power form: (3t + 3t^2 - 2t^3, 6t(1 - t))."""
    return [3 * t + 3 * t * t - 2 * t ** 3, 6 * t * (1 - t)]


def cubic_derivative(t):
    return [3 + 6 * t - 6 * t * t, 6 - 12 * t]


class Server:
    """A freeformd on a free loopback port; stop() ends it."""

    def __init__(self, *flags):
        freeformd = os.environ.get("FREEFORMD")
        if not freeformd:
            raise RuntimeError("set FREEFORMD to the freeformd binary or "
                               "FREEFORM_ADDRESS to a running server")
        self._folder = tempfile.mkdtemp(prefix="freeform_python_")
        out_path = os.path.join(self._folder, "freeformd.out")
        with open(out_path, "w") as out, open(
                os.path.join(self._folder, "freeformd.log"), "w") as log:
            self._process = subprocess.Popen(
                [freeformd, "--listen=127.0.0.1:0"] + list(flags),
                stdout=out, stderr=log)
        deadline = time.monotonic() + TIMEOUT
        while time.monotonic() < deadline and self._process.poll() is None:
            with open(out_path) as out:
                for line in out:
                    if line.startswith("freeformd listening on "):
                        self.address = line.split()[-1]
                        return
            time.sleep(0.05)
        self.stop()
        raise RuntimeError("freeformd did not report its address")

    @property
    def port(self) -> str:
        return self.address.rpartition(":")[2]

    def stop(self) -> None:
        if self._process.poll() is None:
            self._process.send_signal(signal.SIGTERM)
            try:
                self._process.wait(timeout=TIMEOUT)
            except subprocess.TimeoutExpired:
                self._process.kill()
                self._process.wait()
        shutil.rmtree(self._folder, ignore_errors=True)


_shared_address = None


def address() -> str:
    """The address of the server the tests share."""
    global _shared_address
    if _shared_address is None:
        _shared_address = os.environ.get("FREEFORM_ADDRESS")
        if not _shared_address:
            server = Server()
            atexit.register(server.stop)
            _shared_address = server.address
    return _shared_address


def client(**options) -> freeform.Client:
    """A Client of the shared server."""
    options.setdefault("timeout", TIMEOUT)
    return freeform.Client(address(), **options)


class ClientTestCase(unittest.TestCase):
    """Tests that share one Client of the shared server, ``self.client``."""

    client: freeform.Client

    @classmethod
    def setUpClass(cls):
        cls.client = client()

    @classmethod
    def tearDownClass(cls):
        cls.client.close()
