"""client.surfaces against the real freeformd: answers derived by hand.

Most cases use the bilinear saddle S(u, v) = (u, v, uv): S_u = (1, 0, v),
S_v = (0, 1, u), S_uv = (0, 0, 1), unit normal (-v, -u, 1) / sqrt(1 + u^2 +
v^2), Gaussian curvature -1 / (1 + u^2 + v^2)^2.
"""

import json
import math
import os
import unittest

import numpy as np

import freeform
import support

TOLERANCE = 1e-12
SADDLE_NET = [[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 1]]]


def close(actual, expected, tolerance=TOLERANCE):
    np.testing.assert_allclose(actual, expected, rtol=0, atol=tolerance)


def saddle():
    return freeform.bezier_surface(SADDLE_NET)


def saddle_bspline():
    return freeform.bspline_surface(1, 1, SADDLE_NET, [0, 0, 1, 1],
                                    [0, 0, 1, 1])


def saddle_point(uv):
    uv = np.asarray(uv, dtype=float).reshape(-1, 2)
    return np.stack([uv[:, 0], uv[:, 1], uv[:, 0] * uv[:, 1]], axis=1)


def saddle_normal(uv):
    u, v = np.asarray(uv, dtype=float).reshape(-1, 2).T
    normal = np.stack([-v, -u, np.ones_like(u)], axis=1)
    return normal / np.linalg.norm(normal, axis=1, keepdims=True)


def projected_area(mesh):
    """The signed area of the mesh projected onto the xy plane."""
    a, b, c = (mesh.vertices[mesh.triangles[:, k]] for k in range(3))
    return 0.5 * np.sum((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) -
                        (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]))


class EvaluateTest(support.ClientTestCase):
    def test_partials_and_normals(self):
        uv = [[0.25, 0.5], [1, 0]]
        samples = self.client.surfaces.evaluate(saddle(), uv, 2,
                                                normals=True)
        self.assertEqual(list(samples.partials),
                         [(0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2)])
        close(samples.points, saddle_point(uv))
        close(samples.partials[(1, 0)], [[1, 0, 0.5], [1, 0, 0]])
        close(samples.partials[(0, 1)], [[0, 1, 0.25], [0, 1, 1]])
        close(samples.partials[(1, 1)], [[0, 0, 1]] * 2)
        close(samples.partials[(2, 0)], [[0, 0, 0]] * 2)
        close(samples.normals, saddle_normal(uv))

    def test_grid_is_u_major(self):
        samples = self.client.surfaces.evaluate(
            saddle(), freeform.Grid([0, 0.5, 1], freeform.Range(2)))
        close(samples.points, saddle_point(
            [[0, 0], [0, 1], [0.5, 0], [0.5, 1], [1, 0], [1, 1]]))
        self.assertIsNone(samples.normals)

    def test_bspline_and_triangular(self):
        close(self.client.surfaces.evaluate(saddle_bspline(),
                                            [0.3, 0.7]).points,
              saddle_point([0.3, 0.7]))
        # The linear triangle with corners (1,0,0), (0,1,0), (0,0,1) maps
        # barycentric (u, v, w) to (u, v, w).
        triangle = freeform.triangular_bezier_patch(
            1, [[1, 0, 0], [0, 1, 0], [0, 0, 1]])
        close(self.client.surfaces.evaluate(triangle, [0.2, 0.3]).points,
              [[0.2, 0.3, 0.5]])

    def test_basis(self):
        tensor = self.client.surfaces.evaluate_basis(
            (freeform.bernstein_basis(1), freeform.bernstein_basis(1)),
            [0.25, 0.5])
        # (1-u)(1-v), (1-u) v, u (1-v), u v: ordered like the net.
        close(tensor, [[0.375, 0.375, 0.125, 0.125]])
        triangular = self.client.surfaces.evaluate_basis(1, [0.2, 0.3])
        close(triangular, [[0.2, 0.3, 0.5]])

    def test_stream_joins_to_the_unary_answer(self):
        grid = freeform.Grid(freeform.Range(7), freeform.Range(5))
        chunks = list(self.client.surfaces.evaluate_stream(
            saddle(), grid, 1, normals=True, chunk_size=10))
        self.assertEqual([chunk.first_index for chunk in chunks],
                         [0, 10, 20, 30])
        joined = freeform.SurfaceSamples.join(chunks)
        unary = self.client.surfaces.evaluate(saddle(), grid, 1,
                                              normals=True)
        for order, values in unary.partials.items():
            close(joined.partials[order], values, 0)
        close(joined.normals, unary.normals, 0)


class MeshTest(support.ClientTestCase):
    def check_saddle_mesh(self, mesh):
        self.assertEqual(mesh.vertices.shape[1], 3)
        self.assertEqual(mesh.triangles.shape[1], 3)
        self.assertEqual(mesh.triangles.dtype, np.int64)
        self.assertGreaterEqual(mesh.triangles.min(), 0)
        self.assertLess(mesh.triangles.max(), len(mesh.vertices))
        # Every vertex lies on the surface at its (u, v).
        close(mesh.vertices, saddle_point(mesh.uv))
        close(mesh.surface_index, np.zeros(len(mesh.vertices)))
        # The mesh covers the unit square once, counter-clockwise seen
        # from above (the side of S_u x S_v).
        self.assertAlmostEqual(projected_area(mesh), 1, places=12)

    def test_tessellate(self):
        mesh = self.client.surfaces.tessellate(saddle(), 1e-3, normals=True)
        self.check_saddle_mesh(mesh)
        close(mesh.normals, saddle_normal(mesh.uv))
        plain = self.client.surfaces.tessellate([saddle()], 1e-3)
        self.assertIsNone(plain.normals)
        close(plain.vertices, mesh.vertices, 0)

    def test_tessellate_stream(self):
        chunks = list(self.client.surfaces.tessellate_stream(
            saddle(), 1e-4, normals=True, chunk_size=64))
        self.assertGreater(len(chunks), 1)
        vertices_so_far = 0
        for chunk in chunks:
            vertices_so_far += len(chunk.vertices)
            self.assertLessEqual(len(chunk.triangles), 64)
            if len(chunk.triangles):
                self.assertLess(chunk.triangles.max(), vertices_so_far)
        mesh = freeform.Mesh.join(chunks)
        self.check_saddle_mesh(mesh)
        close(mesh.normals, saddle_normal(mesh.uv))

    def test_torus_by_the_generic_call(self):
        # examples/torus_mesh.json as a dict, through client.call: the NURBS
        # torus of radii 3 and 1.
        with open(os.path.join(support.SOURCE_DIR, "examples",
                               "torus_mesh.json")) as file:
            request = json.load(file)
        response = self.client.call("SurfaceService.Tessellate", request)
        vertices = freeform.to_array(response.vertices)
        ring = np.hypot(vertices[:, 0], vertices[:, 1]) - 3
        close(ring ** 2 + vertices[:, 2] ** 2, np.ones(len(vertices)), 1e-12)
        # Closed: every edge is shared by two triangles.
        triangles = np.array(response.triangles).reshape(-1, 3)
        edges = np.sort(np.concatenate([triangles[:, [0, 1]],
                                        triangles[:, [1, 2]],
                                        triangles[:, [2, 0]]]), axis=1)
        _, counts = np.unique(edges, axis=0, return_counts=True)
        self.assertEqual(set(counts.tolist()), {2})
        # V - E + F = 0 on a torus.
        self.assertEqual(len(vertices) - len(counts) + len(triangles), 0)


class RefinementTest(support.ClientTestCase):
    def test_split_in_u(self):
        low, high = self.client.surfaces.split(saddle(), 0.5, direction="u")
        close(freeform.to_array(low),
              [[[0, 0, 0], [0, 1, 0]], [[0.5, 0, 0], [0.5, 1, 0.5]]])
        close(freeform.to_array(high),
              [[[0.5, 0, 0], [0.5, 1, 0.5]], [[1, 0, 0], [1, 1, 1]]])

    def test_split_a_triangle(self):
        triangle = freeform.triangular_bezier_patch(
            1, [[1, 0, 0], [0, 1, 0], [0, 0, 1]])
        pieces = self.client.surfaces.split(triangle, (1 / 3, 1 / 3))
        self.assertEqual(len(pieces), 3)
        # Each piece has the centroid as one of its corners.
        for piece in pieces:
            corners = freeform.to_array(piece)
            self.assertTrue(np.any(np.all(np.abs(corners - 1 / 3) < 1e-15,
                                          axis=1)))

    def test_insert_knots_and_remove_them(self):
        refined = self.client.surfaces.insert_knots(saddle_bspline(), [0.5],
                                                    "u")
        close(freeform.to_array(refined),
              [[[0, 0, 0], [0, 1, 0]], [[0.5, 0, 0], [0.5, 1, 0.5]],
               [[1, 0, 0], [1, 1, 1]]])
        close(self.client.surfaces.evaluate(refined, [0.3, 0.7]).points,
              saddle_point([0.3, 0.7]))
        removal = self.client.surfaces.remove_knots(refined, 1e-9,
                                                    direction="u", knot=0.5)
        self.assertEqual((removal.removals_u, removal.removals_v), (1, 0))
        close(freeform.to_array(removal.surface), SADDLE_NET)

    def test_elevate_degree(self):
        elevated = self.client.surfaces.elevate_degree(saddle(), by_u=1)
        close(freeform.to_array(elevated),
              [[[0, 0, 0], [0, 1, 0]], [[0.5, 0, 0], [0.5, 1, 0.5]],
               [[1, 0, 0], [1, 1, 1]]])


class FittingTest(support.ClientTestCase):
    def test_interpolate_a_grid(self):
        x = np.linspace(0, 1, 5)
        net = np.stack(np.meshgrid(x, x, indexing="ij") +
                       [np.outer(np.sin(x), np.cos(x))], axis=2)
        fit = self.client.surfaces.interpolate(net, 3, 3)
        self.assertEqual(fit.parameters_u.shape, (5,))
        samples = self.client.surfaces.evaluate(
            fit.surface, freeform.Grid(fit.parameters_u, fit.parameters_v))
        close(samples.points, net.reshape(-1, 3))

    def test_fit_a_grid(self):
        x = np.linspace(0, 2, 30)
        net = np.stack(np.meshgrid(x, x, indexing="ij") +
                       [np.outer(np.sin(x), np.cos(x))], axis=2)
        fit = self.client.surfaces.fit(net, 3, 3, 1e-3)
        samples = self.client.surfaces.evaluate(
            fit.surface, freeform.Grid(fit.parameters_u, fit.parameters_v))
        distances = np.linalg.norm(samples.points - net.reshape(-1, 3),
                                   axis=1)
        self.assertLessEqual(distances.max(), 1e-3)
        close(distances.max(), fit.max_residual, 1e-12)

    def test_fit_scattered_points_of_a_plane(self):
        random = np.random.default_rng(7)
        xy = random.uniform(0, 1, (200, 2))
        points = np.column_stack([xy, 2 * xy[:, 0] + 3 * xy[:, 1] + 1])
        fit = self.client.surfaces.fit_scattered(points, 3, 3, 4, 4,
                                                 parameters=xy)
        close(fit.parameters, xy, 0)
        self.assertLess(fit.max_residual, 1e-9)
        close(self.client.surfaces.evaluate(fit.surface, xy).points, points,
              1e-9)


class QueryTest(support.ClientTestCase):
    def test_closest_point_above_a_plane(self):
        plane = freeform.bezier_surface(
            [[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 0]]])
        answer = self.client.surfaces.closest_point(plane, [[0.3, 0.4, 2]])
        close(answer.distances, [2], 1e-9)
        close(answer.closest_parameters, [[0.3, 0.4]], 1e-9)
        close(answer.closest_points, [[0.3, 0.4, 0]], 1e-9)

    def test_a_line_through_the_saddle(self):
        through = freeform.bezier([[0.5, 0.25, -1], [0.5, 0.25, 1]])
        answer = self.client.surfaces.intersect_curve(through, saddle())
        # z = uv = 1/8 at (1/2, 1/4): -1 + 2t = 1/8.
        close(answer.curve_parameters, [0.5625], 1e-9)
        close(answer.surface_parameters, [[0.5, 0.25]], 1e-9)
        close(answer.points, [[0.5, 0.25, 0.125]], 1e-9)

    def test_section_by_a_plane(self):
        polylines = self.client.surfaces.section(saddle(), [0.5, 0, 0],
                                                 [1, 0, 0],
                                                 fit_tolerance=1e-6)
        self.assertEqual(len(polylines), 1)
        section = polylines[0]
        self.assertFalse(section.closed)
        # x = 1/2 cuts the straight line (1/2, v, v/2).
        close(section.points[:, 0], 0.5)
        close(section.points[:, 2], section.points[:, 1] / 2)
        close(sorted(section.points[[0, -1], 1]), [0, 1])
        close(section.parameters, section.points[:, :2])
        self.assertIsNotNone(section.curve)

    def test_curvature_of_the_saddle(self):
        answer = self.client.surfaces.curvature(saddle(),
                                                [[0, 0], [0.5, 0.5]])
        close(answer.normals, saddle_normal([[0, 0], [0.5, 0.5]]))
        close(answer.gaussian, [-1, -1 / 1.5 ** 2])
        close(answer.mean[0], 0)
        close(answer.principal_curvatures[0], [1, -1])
        # At the origin z = xy bends up along (1, 1) and down along (1, -1).
        d1, d2 = answer.principal_directions[0]
        close(abs(d1 @ [math.sqrt(0.5), math.sqrt(0.5), 0]), 1)
        close(abs(d2 @ [math.sqrt(0.5), -math.sqrt(0.5), 0]), 1)
        self.assertEqual(list(answer.statuses), [0, 0])

    def test_bounding_box(self):
        box = self.client.surfaces.bounding_box(saddle(), tolerance=1e-12)
        close(box.lower, [0, 0, 0])
        close(box.upper, [1, 1, 1])


if __name__ == "__main__":
    unittest.main()
