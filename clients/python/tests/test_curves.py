"""client.curves against the real freeformd: answers derived by hand."""

import math
import unittest

import numpy as np

import freeform
import support
from support import cubic, cubic_derivative, cubic_point, unit_circle

TOLERANCE = 1e-12


def close(actual, expected, tolerance=TOLERANCE):
    np.testing.assert_allclose(actual, expected, rtol=0, atol=tolerance)


def line(start, end):
    return freeform.bezier([start, end])


class EvaluateTest(support.ClientTestCase):
    def test_worked_cubic(self):
        samples = self.client.curves.evaluate(cubic(), [0, 0.5, 1],
                                              derivative_order=1)
        self.assertEqual(samples.derivatives.shape, (2, 3, 2))
        # C(t) and C'(t) = 3 sum_i B(2,i,t) (P_{i+1} - P_i).
        close(samples.points, [[0, 0], [2, 1.5], [4, 0]])
        close(samples.derivatives[1], [[3, 6], [4.5, 0], [3, -6]])
        self.assertEqual(samples.first_index, 0)

    def test_higher_derivatives(self):
        samples = self.client.curves.evaluate(cubic(), [0, 0.5, 1], 3)
        # C'' = 6 sum_i B(1,i,t) D2P_i with D2P_0 = (1, -2), D2P_1 = (-1,
        # -2); C''' = 6 (D2P_1 - D2P_0) = (-12, 0).
        close(samples.derivatives[2], [[6, -12], [0, -12], [-6, -12]])
        close(samples.derivatives[3], [[-12, 0]] * 3)

    def test_range_is_linspace(self):
        samples = self.client.curves.evaluate(cubic(), freeform.Range(9),
                                              derivative_order=1)
        t = np.linspace(0, 1, 9)
        close(samples.points, [cubic_point(value) for value in t])
        close(samples.derivatives[1], [cubic_derivative(value)
                                       for value in t])
        part = self.client.curves.evaluate(cubic(), freeform.Range(3, 0.25,
                                                                   0.75))
        close(part.points, [cubic_point(t) for t in (0.25, 0.5, 0.75)])

    def test_one_parameter_and_algorithms(self):
        for algorithm in ("de_casteljau", "horner", "ladder", None):
            samples = self.client.curves.evaluate(cubic(), 0.25,
                                                  algorithm=algorithm)
            close(samples.points, [cubic_point(0.25)])

    def test_nurbs_circle(self):
        t = np.linspace(0, 1, 101)
        points = self.client.curves.evaluate(unit_circle(), t).points
        close(np.hypot(points[:, 0], points[:, 1]), np.ones(101), 1e-15)
        # The quarter points at t = q / 4.
        close(points[::25], [[1, 0], [0, 1], [-1, 0], [0, -1], [1, 0]])

    def test_other_kinds(self):
        # The Lagrange polynomial through (0, 0), (1, 1), (2, 4) at nodes
        # 0, 1, 2 is x = t, y = t^2.
        parabola = freeform.lagrange([[0, 0], [1, 1], [2, 4]], [0, 1, 2])
        close(self.client.curves.evaluate(parabola, [1.5]).points,
              [[1.5, 2.25]])
        # The power form of the cubic is 3t + 3t^2 - 2t^3, 6t - 6t^2.
        power = freeform.power([[0, 0], [3, 6], [3, -6], [-2, 0]])
        close(self.client.curves.evaluate(power, [0.3]).points,
              [cubic_point(0.3)])
        # The Hermite segment with the cubic's ends and end tangents is the
        # cubic.
        hermite = freeform.hermite([[0, 0], [4, 0]], [[3, 6], [3, -6]])
        close(self.client.curves.evaluate(hermite, [0.3]).points,
              [cubic_point(0.3)])

    def test_basis(self):
        t = np.array([0, 0.25, 0.5, 1])
        values = self.client.curves.evaluate_basis(
            freeform.bernstein_basis(3), t, derivative_order=1)
        self.assertEqual(values.shape, (2, 4, 4))
        expected = [[math.comb(3, i) * (1 - x) ** (3 - i) * x ** i
                     for i in range(4)] for x in t]
        close(values[0], expected)
        close(values[0].sum(axis=1), np.ones(4))
        # d/dt B(3,0,t) = -3 (1 - t)^2.
        close(values[1][:, 0], -3 * (1 - t) ** 2)
        hermite = self.client.curves.evaluate_basis(
            freeform.hermite_basis(), [0.5])
        # H0..H3 at 1/2: 1/2, 1/2, 1/8, -1/8.
        close(hermite[0], [[0.5, 0.5, 0.125, -0.125]])


class RefinementTest(support.ClientTestCase):
    def test_split_is_de_casteljau(self):
        left, right = self.client.curves.split(cubic(), 0.5)
        # The de Casteljau triangle at 1/2: P01 = (0.5, 1), P12 = (2, 2),
        # P23 = (3.5, 1), P012 = (1.25, 1.5), P123 = (2.75, 1.5), C = (2,
        # 1.5).
        close(freeform.to_array(left),
              [[0, 0], [0.5, 1], [1.25, 1.5], [2, 1.5]])
        close(freeform.to_array(right),
              [[2, 1.5], [2.75, 1.5], [3.5, 1], [4, 0]])

    def test_elevate_degree(self):
        quartic = self.client.curves.elevate_degree(cubic())
        # Q_i = i/4 P_{i-1} + (1 - i/4) P_i.
        close(freeform.to_array(quartic),
              [[0, 0], [0.75, 1.5], [2, 2], [3.25, 1.5], [4, 0]])

    def test_insert_knots_keeps_the_curve(self):
        bspline = freeform.bspline(3, support.CUBIC_POINTS,
                                   [0, 0, 0, 0, 1, 1, 1, 1])
        refined = self.client.curves.insert_knots(bspline, [0.5, 0.5])
        self.assertEqual(list(refined.bspline.knots),
                         [0, 0, 0, 0, 0.5, 0.5, 1, 1, 1, 1])
        t = np.linspace(0, 1, 17)
        close(self.client.curves.evaluate(refined, t).points,
              [cubic_point(value) for value in t])
        # The new middle control point is the de Casteljau point (2, 1.5)
        # with multiplicity 3 - 1 = 2 once the knot's multiplicity is 2:
        # the control points are P0, P01, P012, P123, P23, P3.
        close(freeform.to_array(refined),
              [[0, 0], [0.5, 1], [1.25, 1.5], [2.75, 1.5], [3.5, 1],
               [4, 0]])

    def test_decompose(self):
        bspline = freeform.bspline(3, support.CUBIC_POINTS,
                                   [0, 0, 0, 0, 1, 1, 1, 1])
        refined = self.client.curves.insert_knots(bspline, [0.5] * 3)
        decomposition = self.client.curves.decompose(refined)
        close(decomposition.breakpoints, [0, 0.5, 1])
        self.assertEqual(len(decomposition.segments), 2)
        left, right = self.client.curves.split(cubic(), 0.5)
        close(freeform.to_array(decomposition.segments[0]),
              freeform.to_array(left))
        close(freeform.to_array(decomposition.segments[1]),
              freeform.to_array(right))

    def test_chaikin(self):
        square = [[0, 0], [4, 0], [4, 4], [0, 4]]
        result = self.client.curves.subdivide(square, 2, closed=True,
                                              keep_levels=True)
        # One step: the points at 1/4 and 3/4 of every edge.
        close(result.levels[0], [[1, 0], [3, 0], [4, 1], [4, 3], [3, 4],
                                 [1, 4], [0, 3], [0, 1]])
        self.assertEqual(result.polygon.shape, (16, 2))
        close(result.polygon, result.levels[1])
        close(result.polygon[:2], [[1.5, 0], [2.5, 0]])

    def test_reduce_degree_of_an_elevated_curve(self):
        quartic = self.client.curves.elevate_degree(cubic())
        reduction = self.client.curves.reduce_degree(quartic)
        close(freeform.to_array(reduction.curve), support.CUBIC_POINTS,
              1e-12)
        self.assertLess(reduction.error_bound, 1e-12)


class InterpolationTest(support.ClientTestCase):
    def test_interpolate_passes_through_the_points(self):
        angles = np.linspace(0, math.pi, 7)
        points = np.stack([np.cos(angles), np.sin(angles)], axis=1)
        fit = self.client.curves.interpolate(points, 3)
        self.assertEqual(fit.parameters.shape, (7,))
        close(fit.parameters[[0, -1]], [0, 1])
        close(self.client.curves.evaluate(fit.curve, fit.parameters).points,
              points)
        self.assertLess(fit.max_residual, 1e-12)
        # Equal chords: chord-length parameters are uniform.
        close(fit.parameters, np.linspace(0, 1, 7))

    def test_centripetal_and_at_parameters(self):
        points = [[0, 0], [1, 0], [1, 4], [2, 4]]
        centripetal = self.client.curves.interpolate(
            points, 2, parameterization="centripetal")
        # Chords 1, 4, 1: square roots 1, 2, 1 over 4.
        close(centripetal.parameters, [0, 0.25, 0.75, 1])
        at_parameters = self.client.curves.interpolate(
            points, 3, knot_rule="at_parameters")
        close(self.client.curves.evaluate(
            at_parameters.curve, at_parameters.parameters).points, points)

    def test_not_a_knot_spline_reproduces_a_cubic(self):
        x = np.arange(5.0)
        spline = self.client.curves.cubic_spline((x ** 3).reshape(-1, 1), x)
        close(self.client.curves.evaluate(spline.curve, [2.5]).points,
              [[15.625]], 1e-12)

    def test_natural_spline_ends_straight(self):
        x = np.arange(5.0)
        spline = self.client.curves.cubic_spline(
            (x ** 2).reshape(-1, 1), x, end_condition="natural")
        second = self.client.curves.evaluate(spline.curve, [0, 4], 2)
        close(second.derivatives[2], [[0], [0]], 1e-12)

    def test_least_squares_of_a_line_is_the_line(self):
        x = np.linspace(0, 1, 20)
        points = np.stack([x, 2 * x + 1], axis=1)
        fit = self.client.curves.approximate(points, 3, 5)
        self.assertLess(fit.max_residual, 1e-12)
        close(fit.parameters, x)

    def test_fit_within_tolerance(self):
        x = np.linspace(-1, 1, 200)
        points = np.stack([x, np.sin(3 * x)], axis=1)
        fit = self.client.curves.fit(points, 3, 1e-4)
        self.assertLessEqual(fit.max_residual, 1e-4)
        on_curve = self.client.curves.evaluate(fit.curve, fit.parameters)
        distances = np.linalg.norm(on_curve.points - points, axis=1)
        self.assertLessEqual(distances.max(), 1e-4)
        close(distances.max(), fit.max_residual, 1e-12)

    def test_remove_an_inserted_knot(self):
        bspline = freeform.bspline(3, support.CUBIC_POINTS,
                                   [0, 0, 0, 0, 1, 1, 1, 1])
        refined = self.client.curves.insert_knots(bspline, [0.3])
        removal = self.client.curves.remove_knots(refined, 1e-9, knot=0.3)
        self.assertEqual(removal.removals, 1)
        self.assertLess(removal.error_bound, 1e-9)
        close(freeform.to_array(removal.curve), support.CUBIC_POINTS, 1e-12)
        simplified = self.client.curves.remove_knots(refined, 1e-9)
        self.assertEqual(list(simplified.curve.bspline.knots),
                         [0, 0, 0, 0, 1, 1, 1, 1])


class QueryTest(support.ClientTestCase):
    def test_closest_points_of_the_circle(self):
        answer = self.client.curves.closest_point(
            unit_circle(), [[2, 0], [0, 3], [-3, -4]])
        close(answer.distances, [1, 2, 4], 1e-9)
        close(answer.closest_points, [[1, 0], [0, 1], [-0.6, -0.8]], 1e-9)
        self.assertTrue(np.all(answer.lower_bounds <= answer.distances))
        self.assertEqual(answer.minima_counts.dtype, np.int64)
        # (2, 0) is closest at t = 0 and at t = 1 (the seam).
        self.assertEqual(list(answer.minima_counts), [2, 1, 1])
        close(answer.closest_parameters[1], [0.25], 1e-9)

    def test_crossing_lines(self):
        answer = self.client.curves.intersect(line([0, 0], [2, 2]),
                                              line([0, 2], [2, 0]))
        close(answer.first_parameters, [0.5], 1e-9)
        close(answer.second_parameters, [0.5], 1e-9)
        close(answer.points, [[1, 1]], 1e-9)
        self.assertEqual(answer.first_intervals.shape, (0, 2))

    def test_overlapping_lines(self):
        answer = self.client.curves.intersect(line([0, 0], [4, 0]),
                                              line([3, 0], [1, 0]))
        # The second runs from x = 3 to x = 1: first on [1/4, 3/4], second
        # from 1 to 0.
        close(answer.first_intervals, [[0.25, 0.75]], 1e-9)
        close(answer.second_intervals, [[1, 0]], 1e-9)

    def test_arc_length(self):
        segment = line([0, 0], [3, 4])
        self.assertAlmostEqual(self.client.curves.arc_length(segment), 5,
                               places=12)
        close(self.client.curves.arc_length(segment, [(0, 0.5), (0.5, None),
                                                      (None, None)]),
              [2.5, 2.5, 5])
        self.assertAlmostEqual(self.client.curves.arc_length(unit_circle()),
                               2 * math.pi, places=9)
        at = self.client.curves.parameters_at_arc_length(segment, [1, 2.5])
        close(at.parameters, [0.2, 0.5], 1e-9)
        close(at.points, [[0.6, 0.8], [1.5, 2]], 1e-9)

    def test_samples_by_arc_length(self):
        samples = self.client.curves.sample_by_arc_length(unit_circle(), 5)
        close(samples.points, [[1, 0], [0, 1], [-1, 0], [0, -1], [1, 0]],
              1e-9)
        half = self.client.curves.sample_by_arc_length(
            unit_circle(), 3, interval=(0, 0.5))
        close(half.points, [[1, 0], [0, 1], [-1, 0]], 1e-9)

    def test_curvature(self):
        circle = self.client.curves.curvature(unit_circle(),
                                              [0, 0.125, 0.5])
        close(circle.curvatures, [1, 1, 1], 1e-12)
        # The principal normal points to the centre: minus the point.
        s = math.sqrt(0.5)
        close(circle.normals, [[-1, 0], [-s, -s], [1, 0]], 1e-12)
        self.assertIsNone(circle.binormals)
        self.assertIsNone(circle.torsions)
        straight = self.client.curves.curvature(line([0, 0], [1, 1]), [0.5])
        self.assertEqual(list(straight.statuses), [1])  # STRAIGHT
        close(straight.curvatures, [0])
        # The unit circle lifted to z = 1: torsion 0, binormal (0, 0, 1)
        # (counter-clockwise seen from above).
        circle3 = freeform.bspline(
            2, [[x, y, 1] for x, y in support.CIRCLE_POINTS],
            support.CIRCLE_KNOTS, support.CIRCLE_WEIGHTS)
        frenet = self.client.curves.curvature(circle3, [0.1])
        close(frenet.binormals, [[0, 0, 1]], 1e-12)
        close(frenet.torsions, [0], 1e-12)

    def test_rotation_minimizing_frames_of_a_line(self):
        frames = self.client.curves.frames(line([0, 0, 0], [0, 0, 2]),
                                           [0, 0.5, 1],
                                           initial_reference=[1, 0, 0])
        close(frames.tangents, [[0, 0, 1]] * 3)
        close(frames.references, [[1, 0, 0]] * 3)
        close(frames.third, [[0, 1, 0]] * 3)  # t x r

    def test_bounding_box_of_the_curve_not_its_polygon(self):
        box = self.client.curves.bounding_box(cubic(), tolerance=1e-12)
        # y = 6 t (1 - t) peaks at 1.5; the control points reach 2.
        close(box.lower, [0, 0], 1e-12)
        close(box.upper, [4, 1.5], 1e-12)

    def test_tessellate_the_circle(self):
        polyline = self.client.curves.tessellate(unit_circle(), 1e-3)
        points = polyline.points
        close(np.hypot(points[:, 0], points[:, 1]),
              np.ones(len(points)), 1e-12)
        self.assertEqual(polyline.parameters[0], 0)
        self.assertEqual(polyline.parameters[-1], 1)
        self.assertTrue(np.all(np.diff(polyline.parameters) > 0))
        middles = (points[1:] + points[:-1]) / 2
        sagittas = 1 - np.hypot(middles[:, 0], middles[:, 1])
        self.assertLessEqual(sagittas.max(), 1e-3)


if __name__ == "__main__":
    unittest.main()
