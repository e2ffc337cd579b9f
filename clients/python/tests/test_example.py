"""examples/worked_cubic.py prints what the C++ CLI prints, and the right
numbers."""

import os
import subprocess
import sys
import unittest

import support

EXAMPLE = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir,
                       "examples", "worked_cubic.py")


def run(command):
    return subprocess.run(command, capture_output=True, text=True,
                          timeout=support.TIMEOUT, check=True).stdout


class WorkedCubicTest(unittest.TestCase):
    def setUp(self):
        self.output = run([sys.executable, EXAMPLE, "--address",
                           support.address()])

    def test_the_numbers(self):
        lines = self.output.splitlines()
        self.assertEqual(lines[0], "index,x0,x1,d1x0,d1x1")
        rows = [[float(value) for value in line.split(",")]
                for line in lines[1:]]
        # The points (0,0), (2,1.5), (4,0) and C'(t) = 3 sum_i B(2,i,t)
        # (P_{i+1} - P_i): (3,6), (4.5,0), (3,-6).
        self.assertEqual(rows, [[0, 0, 0, 3, 6], [1, 2, 1.5, 4.5, 0],
                                [2, 4, 0, 3, -6]])

    @unittest.skipUnless(os.environ.get("FREEFORM_CLI"), "needs FREEFORM_CLI")
    def test_the_cli_prints_the_same(self):
        cli = run([os.environ["FREEFORM_CLI"], "eval", "--address",
                   support.address(), "--file",
                   os.path.join(support.SOURCE_DIR, "examples",
                                "cubic_bezier.json"), "--format", "csv"])
        self.assertEqual(self.output, cli)


if __name__ == "__main__":
    unittest.main()
