#!/usr/bin/python3
"""scripts/plot_pressure.py on a 3D result without a reference, at the size of
inputs/hertz_sphere_plane_3d.yaml's contact face (29 x 29 spans: 13456 Gauss points,
465 x 465 = 216225 post-processed samples, as its results file has): it draws the pressure map and the radial profile
(CTest gives it a TIMEOUT; the O(n_g n_s) arc-length abscissa it replaces ran 12
minutes on the real file and had not finished after 60 s on this one), and the geometry it draws is right: the projection
plane is normal to the contact resultant, the grid triangles are the grid's cells,
the radial distance is the distance from the peak.

Synthetic file (h5py, the documented layout): the lower octant of a sphere (R = 1,
centre (0, 0, 1)) touching the plane z = 0 at the origin, with the Hertz pressure
p0 sqrt(1 - r^2/a^2) over the radius a = 0.1 around the lowest point.
Usage: plot_pressure_3d_test.py SCRIPTS_DIR WORK_DIR"""

import importlib.util
import pathlib
import sys
import unittest

import h5py
import numpy as np

SCRIPTS = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else pathlib.Path(__file__).parents[2] / "scripts"
WORK = pathlib.Path(sys.argv[2]) if len(sys.argv) > 2 else pathlib.Path("/tmp/plot_pressure_3d_test")
EXACT = 1e-12  # coordinates of order 1 through a few products: round-off
RADIUS, A, P0 = 1.0, 0.1, 70.0
SPANS, GAUSS_PER_SPAN, SAMPLES_PER_SPAN = 29, 4, 16


def load(name):
    spec = importlib.util.spec_from_file_location(name, SCRIPTS / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


plot_pressure = load("plot_pressure")


def octant(t_meridian, t_circle):
    """Points of the lower sphere octant: meridian angle (pi/2) t^2 from the lowest point
    (graded towards it, as the deck's knots are), circle angle (pi/2) s; u fastest."""
    theta = 0.5 * np.pi * np.asarray(t_meridian) ** 2
    phi = 0.5 * np.pi * np.asarray(t_circle)
    th, ph = np.meshgrid(theta, phi, indexing="ij")
    points = np.column_stack([RADIUS * np.sin(th).ravel() * np.cos(ph).ravel(),
                              RADIUS * np.sin(th).ravel() * np.sin(ph).ravel(),
                              RADIUS * (1.0 - np.cos(th).ravel())])
    return points


def hertz(points):
    r2 = points[:, 0] ** 2 + points[:, 1] ** 2
    return P0 * np.sqrt(np.clip(1.0 - r2 / A ** 2, 0.0, None))


def pressed_flat(points):
    """Current coordinates (Hertz): the cap moved down by a^2 / R, flat on z = 0 where pressed."""
    current = points - [0.0, 0.0, A ** 2 / RADIUS]
    current[:, 2] = np.where(hertz(points) > 0, 0.0, np.maximum(current[:, 2], 0.0))
    return current


def write_result(path, obstacle_force=None):
    n_s = SPANS * SAMPLES_PER_SPAN + 1
    samples = octant(np.linspace(0, 1, n_s), np.linspace(0, 1, n_s))
    n_g = SPANS * GAUSS_PER_SPAN
    gauss = octant((np.arange(n_g) + 0.5) / n_g, (np.arange(n_g) + 0.5) / n_g)
    with h5py.File(path, "w") as h5:
        h5["deck"] = "format: 1\ncontact:\n  - {name: ball_floor, between: [ball.v0, floor]}\n"
        pair = h5.create_group("results/contact/ball_floor")
        if obstacle_force is not None:
            pair.attrs["obstacle_force"] = np.asarray(obstacle_force, dtype=float)
        side = pair.create_group("ball.v0")
        side["gauss_points/reference_coordinates"] = gauss
        side["gauss_points/coordinates"] = pressed_flat(gauss)
        side["gauss_points/pressure"] = hertz(gauss)
        side["gauss_points/weight"] = np.full(len(gauss), 1.0 / len(gauss))
        side["gauss_points/gap"] = np.zeros(len(gauss))
        side["gauss_points/parameter"] = np.zeros((len(gauss), 2))
        post = side.create_group("postprocessed")
        post["reference_coordinates"] = samples
        post["coordinates"] = pressed_flat(samples)
        post["pressure"] = hertz(samples)
        post.attrs["grid_shape"] = np.array([n_s, n_s], dtype=float)
    return samples, gauss


def is_png(path):
    return path.exists() and path.stat().st_size > 1000 and path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


class PlotPressure3d(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        WORK.mkdir(parents=True, exist_ok=True)
        cls.path = WORK / "sphere_octant.h5"
        cls.samples, cls.gauss = write_result(cls.path)

    def test_map_and_radial_profile_of_a_realistic_face(self):
        for extra, name in (([], "map.png"), (["--radial"], "radial.png")):
            out = WORK / name
            self.assertEqual(plot_pressure.main([str(self.path), "-o", str(out)] + extra), 0)
            self.assertTrue(is_png(out), name)

    def test_the_plane_is_normal_to_the_contact_resultant(self):
        with h5py.File(self.path, "r") as h5:
            gauss = h5["results/contact/ball_floor/ball.v0/gauss_points"]
            # No obstacle_force: the pressed points lie flat on z = 0 in the current
            # configuration, so the plane through them is normal to z (to round-off).
            projection = plot_pressure.FaceProjection(h5["results/contact/ball_floor"], gauss)
            self.assertLess(np.linalg.norm(np.cross(projection.normal, [0.0, 0.0, 1.0])), EXACT)
            x, y = projection(self.samples)
            # In-plane distance from the lowest point = R sin(theta): the cap's own radius.
            np.testing.assert_allclose(np.hypot(x, y), np.hypot(self.samples[:, 0], self.samples[:, 1]),
                                       rtol=0, atol=EXACT)
        # A stored obstacle force is taken as it is.
        tilted = WORK / "tilted.h5"
        write_result(tilted, obstacle_force=[0.0, 3.0, -4.0])
        with h5py.File(tilted, "r") as h5:
            projection = plot_pressure.FaceProjection(h5["results/contact/ball_floor"],
                                                      h5["results/contact/ball_floor/ball.v0/gauss_points"])
        np.testing.assert_allclose(projection.normal, [0.0, 0.6, -0.8], rtol=0, atol=EXACT)
        for e in (projection.e1, projection.e2):
            self.assertAlmostEqual(float(e @ projection.normal), 0.0, delta=EXACT)
            self.assertAlmostEqual(float(np.linalg.norm(e)), 1.0, delta=EXACT)

    def test_grid_triangles_are_the_cells_of_the_grid(self):
        with h5py.File(self.path, "r") as h5:
            post = h5["results/contact/ball_floor/ball.v0/postprocessed"]
            triangles = plot_pressure.grid_triangles(post, len(self.samples))
        n = SPANS * SAMPLES_PER_SPAN + 1
        self.assertEqual(triangles.shape, (2 * (n - 1) ** 2, 3))
        # Each triangle joins grid neighbours: index steps of 1 (u) and n (v) only.
        steps = {int(abs(a - b)) for t in triangles[:: 97] for a, b in ((t[0], t[1]), (t[1], t[2]), (t[0], t[2]))}
        self.assertTrue(steps <= {1, n, n + 1}, steps)


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0]], verbosity=2)
