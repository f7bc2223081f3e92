#!/usr/bin/python3
"""Tests of scripts/sweep_penalty.py on synthetic sweep folders made with h5py (the
documented layout only, docs/results.md; no binary needed).
Usage: sweep_penalty_test.py SCRIPTS_DIR WORK_DIR"""

import contextlib
import csv
import importlib.util
import io
import json
import pathlib
import shutil
import sys
import unittest

import h5py

SCRIPTS = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else pathlib.Path(__file__).parents[2] / "scripts"
WORK = pathlib.Path(sys.argv[2]) if len(sys.argv) > 2 else pathlib.Path("/tmp/sweep_penalty_test")
EXACT = 1e-12  # the script only copies and scales stored values: round-off


def load(name):
    spec = importlib.util.spec_from_file_location(name, SCRIPTS / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


sweep_penalty = load("sweep_penalty")

# A two-body pair as inputs/hertz_two_cylinders_2d.yaml writes it: `between` lists upper.v0
# first, HDF5 lists lower.v1 first (alphabetical); the first side's errors are unprefixed.
TWO_BODY_DECK = "format: 1\ncontact:\n  - {name: mate, between: [upper.v0, lower.v1], formulation: two_half_pass}\n"
SIDES = {"upper.v0": dict(l2=0.011, peak=-0.0038, half_width=0.0155, gauss_l2=0.0099,
                          max_penetration=6.0e-5, normal_force=5.0),
         "lower.v1": dict(l2=0.0077, peak=-0.0004, half_width=0.0126, gauss_l2=0.0036,
                          max_penetration=5.9e-5, normal_force=4.98)}
AUTO_PENALTY = 3.5e6  # what the run "chose": the pair's `penalty` attribute


def write_run(directory, value, penalty, scale):
    """penalty_<value>.json and .h5 of one completed two-body run; errors and penetrations x scale."""
    (directory / f"penalty_{value}.json").write_text(json.dumps(
        {"status": "completed", "newton_iterations": 11, "cutbacks": 0, "wall_s": 1.5}) + "\n")
    with h5py.File(directory / f"penalty_{value}.h5", "w") as h5:
        h5["deck"] = TWO_BODY_DECK
        pair = h5.create_group("results/contact/mate")
        pair.attrs.update(penalty=penalty, penalty_rule="auto" if value == "auto" else "value",
                          max_penetration=scale * SIDES["upper.v0"]["max_penetration"])
        reference = h5.create_group("reference/mate")
        reference.attrs.update(a=0.1076, p0=59.14, type="hertz_two_cylinders")
        for k, (side, values) in enumerate(SIDES.items()):
            group = pair.create_group(side)
            group["gauss_points/pressure"] = [0.0, 1.0]
            group.attrs.update(max_penetration=scale * values["max_penetration"], normal_force=values["normal_force"])
            prefix = "" if k == 0 else f"{side}."
            for key in ("l2", "peak", "half_width", "gauss_l2"):
                reference.attrs[prefix + key] = scale * values[key]


class SweepPenalty(unittest.TestCase):
    def setUp(self):
        self.directory = WORK / "two_body"
        shutil.rmtree(self.directory, ignore_errors=True)
        self.directory.mkdir(parents=True)
        write_run(self.directory, "1e5", 1e5, scale=10.0)
        write_run(self.directory, "auto", AUTO_PENALTY, scale=1.0)

    def run_main(self, *values):
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            status = sweep_penalty.main([str(self.directory), "mate", *values])
        return status, out.getvalue()

    def test_every_side_of_a_two_body_pair_has_its_row(self):
        status, text = self.run_main("auto", "1e5")
        self.assertEqual(status, 0, text)
        with open(self.directory / "sweep.csv", newline="") as f:
            rows = list(csv.DictReader(f))
        # by penalty, then the sides in deck order (upper.v0 first, as `between` has it)
        self.assertEqual([(r["given"], r["side"]) for r in rows],
                         [("1e5", "upper.v0"), ("1e5", "lower.v1"), ("auto", "upper.v0"), ("auto", "lower.v1")])
        for r in rows:
            scale = 10.0 if r["given"] == "1e5" else 1.0
            expected = SIDES[r["side"]]
            for key in ("l2", "peak", "half_width", "gauss_l2", "max_penetration"):
                self.assertAlmostEqual(float(r[key]), scale * expected[key], delta=EXACT * abs(expected[key]) + 1e-300,
                                       msg=f"{r['given']} {r['side']} {key}")
            self.assertAlmostEqual(float(r["normal_force"]), expected["normal_force"], delta=EXACT)
        table = [line for line in text.splitlines() if line.startswith("| ") and "completed" in line]
        self.assertEqual(len(table), 4, text)
        self.assertIn("lower.v1", text)

    def test_auto_is_labelled_with_the_penalty_used(self):
        status, text = self.run_main("1e5", "auto")
        self.assertEqual(status, 0, text)
        auto_lines = [line for line in text.splitlines() if "(auto)" in line]
        self.assertEqual(len(auto_lines), 2, text)  # one per side
        self.assertTrue(all(line.startswith(f"| {AUTO_PENALTY:.2e} (auto) |") for line in auto_lines), text)
        with open(self.directory / "sweep.csv", newline="") as f:
            penalties = {float(r["penalty"]) for r in csv.DictReader(f) if r["given"] == "auto"}
        self.assertEqual(penalties, {AUTO_PENALTY})

    def test_a_missing_run_is_a_row_and_fails_the_sweep(self):
        status, text = self.run_main("1e5", "auto", "1e9")
        self.assertEqual(status, 1)
        self.assertIn("| missing |", text)


if __name__ == "__main__":
    WORK.mkdir(parents=True, exist_ok=True)
    unittest.main(argv=[sys.argv[0]], verbosity=2)
