#!/usr/bin/python3
"""Tests of scripts/plot_history.py and scripts/plot_pressure.py on synthetic results files
made with h5py (the documented layout only). Usage: plot_scripts_test.py SCRIPTS_DIR WORK_DIR"""

import contextlib
import importlib.util
import io
import pathlib
import sys
import unittest

import h5py
import numpy as np

SCRIPTS = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else pathlib.Path(__file__).parents[2] / "scripts"
WORK = pathlib.Path(sys.argv[2]) if len(sys.argv) > 2 else pathlib.Path("/tmp/plot_scripts_test")
EXACT = 1e-12  # the scripts only scale stored values: round-off


def load(name):
    spec = importlib.util.spec_from_file_location(name, SCRIPTS / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


plot_history = load("plot_history")
plot_pressure = load("plot_pressure")


def is_png(path):
    return path.exists() and path.stat().st_size > 1000 and path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


DISPLACEMENT_DECK = """format: 1
constraints:
  - {body: block, side: v0, fix: [x, y]}
  - {body: block, side: v1, displacement: [null, -0.002]}
contact:
  - {name: touch, between: [block.v1, punch]}
"""


def write_history(path, deck):
    load_factor = np.array([0.25, 0.5, 0.75, 1.0])
    with h5py.File(path, "w") as h5:
        h5["deck"] = deck
        h5["history/load_factor"] = load_factor
        h5["history/reactions/block.v0"] = np.column_stack([np.zeros(4), 10.0 * load_factor])
        h5["history/contact/touch/block.v1/normal_force"] = 9.0 * load_factor ** 1.5
        h5["history/contact/touch/block.v1/max_penetration"] = 1e-5 * load_factor
    return load_factor


class PlotHistory(unittest.TestCase):
    def test_prescribed_displacement_is_the_abscissa(self):
        path = WORK / "displacement.h5"
        load_factor = write_history(path, DISPLACEMENT_DECK)
        with h5py.File(path, "r") as h5:
            x, label, curves = plot_history.history_series(h5)
        np.testing.assert_allclose(x, -0.002 * load_factor, rtol=0, atol=EXACT)
        self.assertIn("block.v1 u_y", label)
        names = [name for name, _ in curves]
        # the x component of the reaction is zero throughout: not drawn
        self.assertEqual(names, ["reaction block.v0 (y)", "contact touch block.v1: normal force"])
        np.testing.assert_allclose(curves[0][1], 10.0 * load_factor, rtol=0, atol=EXACT)
        self.assertEqual(plot_history.main([str(path), "-o", str(WORK / "displacement.png")]), 0)
        self.assertTrue(is_png(WORK / "displacement.png"))

    def test_load_factor_without_a_prescribed_displacement(self):
        path = WORK / "load.h5"
        load_factor = write_history(path, "format: 1\nconstraints:\n  - {body: block, side: v0, fix: [x, y]}\n")
        with h5py.File(path, "r") as h5:
            x, label, _ = plot_history.history_series(h5)
        np.testing.assert_array_equal(x, load_factor)
        self.assertIn("load factor", label)
        self.assertEqual(plot_history.main([str(path)]), 0)
        self.assertTrue(is_png(WORK / "load_history.png"))


class PlotHistoryLoadPath(unittest.TestCase):
    def test_amplitude_scales_the_abscissa_and_friction_is_drawn(self):
        path = WORK / "path.h5"
        deck = ("format: 1\nconstraints:\n  - {body: block, side: v1, displacement: [~, -0.01]}\n"
                "  - {body: block, side: v1, displacement: [0.2, ~], amplitude: [[0, 0], [1, 0], [2, 1]]}\n")
        t = np.array([0.5, 1.0, 1.5, 2.0])
        with h5py.File(path, "w") as h5:
            h5["deck"] = deck
            h5["history/load_factor"] = t
            h5["history/contact/touch/block.v0/normal_force"] = np.full(4, 5.0)
            h5["history/contact/touch/block.v0/friction_force"] = np.column_stack([-np.array([0, 0, 1, 1.5]),
                                                                                   np.zeros(4)])
        with h5py.File(path, "r") as h5:
            x, label, curves = plot_history.history_series(h5, 1)
        # the slide's amplitude: 0 until t = 1, then linear to 1 at t = 2
        np.testing.assert_allclose(x, [0.0, 0.0, 0.1, 0.2], rtol=0, atol=EXACT)
        self.assertIn("u_x", label)
        names = [name for name, _ in curves]
        self.assertEqual(names, ["contact touch block.v0: normal force", "contact touch block.v0: friction force (x)"])
        with h5py.File(path, "r") as h5:
            x, _, _ = plot_history.history_series(h5)  # the first constraint: the default ramp, held after t = 1
        np.testing.assert_allclose(x, [-0.005, -0.01, -0.01, -0.01], rtol=0, atol=EXACT)


def write_side(group, coordinates, pressure):
    group["gauss_points/reference_coordinates"] = coordinates[::3]
    group["gauss_points/coordinates"] = coordinates[::3]
    group["gauss_points/pressure"] = pressure[::3]
    group["gauss_points/gap"] = np.zeros(len(pressure[::3]))
    group["gauss_points/parameter"] = np.linspace(0, 1, len(pressure[::3]))
    group["postprocessed/reference_coordinates"] = coordinates
    group["postprocessed/coordinates"] = coordinates
    group["postprocessed/pressure"] = pressure


class PlotPressure(unittest.TestCase):
    def test_pairs_in_deck_order_and_arc_length_on_a_curved_side(self):
        # Three quarters of a circle (x goes 0 -> 1 -> -1: not monotonic) pressed by two
        # punches: pairs "zeta" then "alpha" in the deck, both on the side drum.v0.
        angle = np.linspace(-0.5 * np.pi, np.pi, 61)
        arc = np.column_stack([np.cos(angle), np.sin(angle)])
        path = WORK / "two_punches.h5"
        with h5py.File(path, "w") as h5:
            h5["deck"] = "format: 1\ncontact:\n  - {name: zeta, between: [drum.v0, p1]}\n" \
                         "  - {name: alpha, between: [drum.v0, p2]}\n"
            write_side(h5.create_group("results/contact/zeta/drum.v0"), arc, np.maximum(0, np.cos(4 * angle)))
            write_side(h5.create_group("results/contact/alpha/drum.v0"), arc, np.maximum(0, -np.cos(4 * angle)))
        with h5py.File(path, "r") as h5:
            self.assertEqual(plot_pressure.choose_pairs(h5, h5["results"], None), ["zeta", "alpha"])
        axis = plot_pressure.SideAbscissa(arc)
        self.assertFalse(axis.use_x)
        s = axis(arc)
        # polyline (chord) length of 61 samples vs the arc: 1 - sin(h/2)/(h/2) ~ h^2/24 = 2.7e-4 relative
        np.testing.assert_allclose(s, angle + 0.5 * np.pi, rtol=0, atol=2e-3)
        self.assertTrue(np.all(np.diff(axis(arc[::-1])) < 0))  # points map back onto the side's order
        self.assertEqual(plot_pressure.main([str(path), "-o", str(WORK / "two_punches.png")]), 0)
        self.assertTrue(is_png(WORK / "two_punches.png"))

    def test_x_is_kept_where_it_is_monotonic(self):
        x = np.linspace(-1, 1, 11)
        self.assertTrue(plot_pressure.SideAbscissa(np.column_stack([x, 0.1 * x ** 2])).use_x)
        self.assertFalse(plot_pressure.SideAbscissa(np.column_stack([np.cos(x * 3), x])).use_x)


def write_press_release(path, every_step=True):
    """A press-and-release load path as inputs/rubber_press_release_2d.yaml writes it: four
    increments at t = 0.5, 1, 1.5, 2, the pressure scaled by f(t) = [0.5, 1, 0.5, 0]: the
    last step has no contact. /results is a second name of the last step; with
    every_step=False only that step is stored, /history keeps every increment."""
    x = np.linspace(0, 1, 31)
    coordinates = np.column_stack([x, np.zeros_like(x)])
    t, scale = [0.5, 1.0, 1.5, 2.0], [0.5, 1.0, 0.5, 0.0]
    with h5py.File(path, "w") as h5:
        h5["deck"] = "format: 1\ncontact:\n  - {name: touch, between: [rubber.v0, floor]}\n"
        h5["history/load_factor"] = t
        h5["history/contact/touch/rubber.v0/normal_force"] = [3.0 * f for f in scale]
        for k in range(4) if every_step else [3]:
            step = h5.create_group(f"steps/{k + 1:04d}")
            step.attrs["load_factor"] = t[k]
            side = step.create_group("contact/touch/rubber.v0")
            write_side(side, coordinates, scale[k] * np.maximum(0.0, 1.0 - (x / 0.6) ** 2))
            side.attrs["normal_force"] = 3.0 * scale[k]
        h5["results"] = h5["steps/0004"]  # the hard link the writer makes


class PlotPressureStep(unittest.TestCase):
    def test_a_released_last_step_gives_way_to_the_largest_force(self):
        path = WORK / "press_release.h5"
        write_press_release(path)
        with h5py.File(path, "r") as h5:
            group, name, why = plot_pressure.results_group(h5, None)
            self.assertEqual(name, "steps/0002")
            self.assertEqual(group.attrs["load_factor"], 1.0)
            self.assertIn("load factor 1", why)
            self.assertIn("largest total contact force", why)
            self.assertIn("/steps/0004 (load factor 2), has no contact", why)
            # an explicit step is drawn as asked, all zero or not
            group, name, why = plot_pressure.results_group(h5, "4")
            self.assertEqual(name, "steps/0004")
            self.assertIn("--step", why)
            _, name, _ = plot_pressure.results_group(h5, "0003")
            self.assertEqual(name, "steps/0003")
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            self.assertEqual(plot_pressure.main([str(path), "-o", str(WORK / "press_release.png")]), 0)
        self.assertIn("drawn: /steps/0002 (load factor 1): the step of largest total contact force", out.getvalue())
        self.assertTrue(is_png(WORK / "press_release.png"))

    def test_the_last_step_when_it_has_contact(self):
        path = WORK / "pressed.h5"
        write_press_release(path)
        with h5py.File(path, "a") as h5:  # end pressed: the last step keeps its contact
            h5["steps/0004/contact/touch/rubber.v0/gauss_points/pressure"][0] = 1.0
        with h5py.File(path, "r") as h5:
            _, name, why = plot_pressure.results_group(h5, None)
        self.assertEqual(name, "steps/0004")  # named by its step, not as /results
        self.assertEqual(why, "/steps/0004 (load factor 2): the last step")

    def test_only_the_last_step_stored(self):
        path = WORK / "press_release_last.h5"
        write_press_release(path, every_step=False)
        with h5py.File(path, "r") as h5:
            _, name, why = plot_pressure.results_group(h5, None)
        self.assertEqual(name, "steps/0004")
        self.assertIn("no contact pressure", why)
        self.assertIn("largest contact force (3) was at load factor 1, not stored", why)


if __name__ == "__main__":
    WORK.mkdir(parents=True, exist_ok=True)
    unittest.main(argv=[sys.argv[0]], verbosity=2)
