#!/usr/bin/env python3
"""The workloads W1-W5 of docs/benchmarks.md with scipy.interpolate.

Run by scripts/performance.sh (Debian's python3-scipy; needs numpy and
scipy, so /usr/bin/python3 where another python3 comes first on PATH):

  /usr/bin/python3 bench/peers/scipy_workloads.py [runs]

The data is bench/workloads.h's, drawn from the same LCG (bit-identical
doubles). Each workload runs `runs` times (default 3); the best wall time
counts. Output, as bench/peers/peer_result.h prints it:

  RESULT <workload> <implementation> <value> <unit> checksum=<x>

W1: BSpline.__call__ on 10^6 parameters (vectorized). W2: the same and
BSpline(x, nu=1). W3: FITPACK's bisplev on the 1000 x 1000 grid, once per
coordinate, and the product of design matrices B_u P B_v^T. W4: the Bezier
as a BSpline on the knots 0,0,0,0,1,1,1,1 at 10^7 parameters. W5:
make_interp_spline of the 10^5 points at chord-length parameters, with
averaging knots (freeform's rule: the checksum, the sum of the
coefficients, matches freeform's) and with scipy's default (not-a-knot).
scipy has no degree elevation (W6).
"""
import math
import sys
import time

import numpy as np
from scipy.interpolate import BSpline, bisplev, make_interp_spline

MASK = (1 << 64) - 1


def lcg_values(seed, count):
    """count values of rnd() in [-1, 1) from the workloads' LCG."""
    state = seed
    values = np.empty(count)
    for k in range(count):
        state = (state * 6364136223846793005 + 1442695040888963407) & MASK
        values[k] = 2.0 * ((state >> 11) * 2.0**-53) - 1.0
    return values


def random_points(seed, count):
    return lcg_values(seed, 3 * count).reshape(count, 3)


def clamped_uniform_knots(count, degree):
    inner = [i / (count - degree) for i in range(1, count - degree)]
    return np.array([0.0] * (degree + 1) + inner + [1.0] * (degree + 1))


def uniform_parameters(count):
    return np.arange(count) / (count - 1)


def w5_points(count):
    r = random_points(4, count)
    t = 0.01 * np.arange(count)
    # The same operations as workloads.h's W5Points, element by element.
    cos = np.array([math.cos(x) for x in t])
    sin = np.array([math.sin(x) for x in t])
    return np.stack([10 * cos + 0.1 * r[:, 0], 10 * sin + 0.1 * r[:, 1],
                     t + 0.1 * r[:, 2]], axis=1)


def best(runs, work):
    """The shortest wall time of `runs` calls of work() and its last result."""
    seconds = math.inf
    result = None
    for _ in range(runs):
        start = time.perf_counter()
        result = work()
        seconds = min(seconds, time.perf_counter() - start)
    return seconds, result


def print_rate(workload, implementation, points, seconds, checksum):
    print("RESULT %s %s %.6e points_per_s checksum=%.12g" %
          (workload, implementation, points / seconds, checksum), flush=True)


def print_seconds(workload, implementation, seconds, checksum):
    print("RESULT %s %s %.6e seconds checksum=%.12g" %
          (workload, implementation, seconds, checksum), flush=True)


def rate(runs, workload, implementation, points, work):
    """Times work(), which returns arrays, and prints the rate and their sum."""
    seconds, arrays = best(runs, work)
    print_rate(workload, implementation, points, seconds,
               sum(float(a.sum()) for a in arrays))


def run_curves(runs):
    curve = BSpline(clamped_uniform_knots(100, 3), random_points(1, 100), 3)
    x = uniform_parameters(10**6)
    rate(runs, "W1", "scipy:BSpline.__call__", x.size, lambda: [curve(x)])
    rate(runs, "W2", "scipy:BSpline.__call__(nu=0,1)", x.size,
         lambda: [curve(x), curve(x, nu=1)])


def run_surface(runs):
    knots = clamped_uniform_knots(20, 3)
    net = random_points(2, 400).reshape(20, 20, 3)
    grid = uniform_parameters(1000)
    rate(runs, "W3", "scipy:bisplev", grid.size**2, lambda: [
        bisplev(grid, grid, (knots, knots, net[:, :, c].ravel(), 3, 3))
        for c in range(3)])

    def design_matrices():
        basis = BSpline.design_matrix(grid, knots, 3).toarray()
        return [np.einsum("ui,ijc,vj->uvc", basis, net, basis, optimize=True)]
    rate(runs, "W3", "scipy:design_matrix_product", grid.size**2,
         design_matrices)


def run_bezier(runs):
    bezier = BSpline(np.array([0, 0, 0, 0, 1, 1, 1, 1.0]),
                     random_points(3, 4), 3)
    x = uniform_parameters(10**7)
    rate(runs, "W4", "scipy:BSpline.__call__", x.size, lambda: [bezier(x)])


def chord_parameters(points):
    lengths = np.concatenate([[0.0], np.cumsum(
        np.linalg.norm(np.diff(points, axis=0), axis=1))])
    return lengths / lengths[-1]


def averaging_knots(u, degree):
    """The NURBS Book (9.8): each inner knot the mean of `degree` parameters."""
    sums = np.concatenate([[0.0], np.cumsum(u)])
    inner = (sums[1 + degree:u.size] - sums[1:u.size - degree]) / degree
    return np.concatenate([[u[0]] * (degree + 1), inner,
                           [u[-1]] * (degree + 1)])


def run_interpolation(runs):
    points = w5_points(10**5)

    def averaging():
        u = chord_parameters(points)
        return make_interp_spline(u, points, k=3, t=averaging_knots(u, 3))

    def not_a_knot():
        return make_interp_spline(chord_parameters(points), points, k=3)
    for name, work in (("averaging", averaging), ("not-a-knot", not_a_knot)):
        seconds, spline = best(runs, work)
        print_seconds("W5", "scipy:make_interp_spline(%s)" % name, seconds,
                      float(spline.c.sum()))


def main():
    runs = max(1, int(sys.argv[1])) if len(sys.argv) > 1 else 3
    run_curves(runs)
    run_surface(runs)
    run_bezier(runs)
    run_interpolation(runs)


if __name__ == "__main__":
    main()
