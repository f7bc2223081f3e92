#!/usr/bin/python3
"""Accuracy on demand against the hand-graded decks and against uniform refinement.

For each case: the `accuracy:` run from an ungraded coarse start (all its levels), the
hand-graded deck of inputs/ once, and the coarse start refined uniformly
(--refine-levels k, every knot span halved k times) until its error against Hertz is at
most the adaptive run's. Prints one table (markdown) of dofs, the error against Hertz,
the final estimate and the wall time (for the levels: all of them together) and checks
the estimates: each level's within a factor of two of its error against Hertz.
First, the stick zone of the Cattaneo-Mindlin cylinders from an ungraded start, level by
level against theory (its own table), and the 2D Hertz contact half-width against Hertz's
a (its own table: the target met for real, never claimed early).

"Against Hertz" is the error in the estimate's own norm: the L2 norm of the recovered
pressure's difference from Hertz's over the whole contact side, relative to Hertz's
(/accuracy/levels column reference_error). The graded and uniform runs get it from an
accuracy: block that stops after level 0 (a dofs budget of 1). The results' own
/reference/<pair> l2 (over |x| <= 1.2a, and in 3D on the ring-averaged radial curve) is
printed beside it.

Usage: /usr/bin/python3 verification/accuracy/run_accuracy.py build/bin/igacontact [WORK_DIR] [--quick]
  --quick: the 2D cases only (seconds); the 3D case takes a few minutes.
Exit 1 when an estimate misses by more than a factor of two or a run fails unexpectedly.
"""

import math
import os
import subprocess
import sys
import tempfile
import time

import h5py

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# (name, coarse deck, --set for the coarse start, hand-graded deck, uniform levels at most)
CASES = [
    ("2D Hertz, cylinder on a plane", "inputs/hertz_accuracy_2d.yaml", [], "inputs/hertz.yaml", 6),
    ("2D Hertz, two cylinders", "inputs/hertz_two_cylinders_2d.yaml",
     ["bodies.0.refine={elevate: [0, 1], spans: [8, 4]}", "bodies.1.refine={elevate: [0, 1], spans: [8, 4]}",
      "accuracy={target: {pair: mate, error: 0.01}, budget: {levels: 9}}"],
     "inputs/hertz_two_cylinders_2d.yaml", 5),
    ("2D Hertz, half cylinder of two patches (contact on a named surface)", "inputs/hertz_two_patches.yaml",
     ["bodies.0.patches.0.refine=null", "bodies.0.patches.1.refine=null",
      "bodies.0.refine={elevate: [0, 1], spans: [8, 2]}", "contact.0.penalty=auto",
      "accuracy={target: {pair: cyl_floor, error: 0.01}, budget: {levels: 10}}"],
     "inputs/hertz_two_patches.yaml", 5),
    ("3D Hertz, sphere on a plane", "inputs/hertz_sphere_plane_3d.yaml",
     ["bodies.0.refine={elevate: [0, 1, 0], spans: [4, 4, 4]}",
      "accuracy={target: {pair: ball_floor, error: 0.03}, budget: {levels: 9, seconds: 1200}}"],
     "inputs/hertz_sphere_plane_3d.yaml", 3),
]


def run(app, deck, sets, out, extra=()):
    args = [app, os.path.join(ROOT, deck), "-o", out, "-q", "--threads", "1"] + list(extra)
    for s in sets:
        args += ["--set", s]
    start = time.perf_counter()
    done = subprocess.run(args, capture_output=True, text=True)
    return done.returncode, time.perf_counter() - start, done.stderr


def l2_error(path):
    """The error of the last level in the estimate's own norm (see above)."""
    with h5py.File(path, "r") as f:
        return abs(float(f["accuracy/levels"][-1][5]))


def stored_l2(path):
    with h5py.File(path, "r") as f:
        for pair in f["reference"]:
            return abs(float(f["reference"][pair].attrs["l2"]))
    return math.nan


def level0_only(pair):
    """An accuracy: block that runs level 0 only: its error in the estimate's norm."""
    return f"accuracy={{target: {{pair: {pair}, error: 1e-9}}, budget: {{levels: 2, dofs: 1}}}}"


def dofs(path):
    with h5py.File(path, "r") as f:
        return int(f["counters"].attrs["dofs"])


# The stick zone (quantity: stick_zone) of the Cattaneo-Mindlin cylinders from an ungraded
# start: two identical elastic cylinders decouple the normal and the tangential problem
# (Johnson, Contact Mechanics, 7.1), so the stick zone is central, of length 2c,
# c/a = sqrt(1 - Q/(mu P)), a Hertz's half-width of two cylinders at the measured P.
STICK_CASE = ("2D Cattaneo-Mindlin, stick zone", "inputs/cattaneo_mindlin_accuracy_2d.yaml")
STICK_TOLERANCE = 0.02  # issue 33: the stick zone within 2 % of theory


def stick_zone_theory(path, E=1000.0, nu=0.3, R=1.0, mu=0.3):
    """2c of Cattaneo-Mindlin at the last increment of one level's results, from its first
    contact side's measured P and Q."""
    with h5py.File(path, "r") as f:
        steps = f["steps"]
        pair = steps[sorted(steps.keys())[-1]]["contact"]
        pair = pair[next(iter(pair))]
        side = pair[next(k for k in pair if isinstance(pair[k], h5py.Group))]
        P = float(side.attrs["normal_force"])
        Q = abs(float(side.attrs["friction_force"][0]))
    e_star, r_star = E / (2.0 * (1.0 - nu * nu)), R / 2.0
    a = math.sqrt(4.0 * P * r_star / (math.pi * e_star))
    return 2.0 * a * math.sqrt(1.0 - Q / (mu * P))


def levels_run(app, work, name, deck, sets, stem, columns, failures):
    """Runs an accuracy case into WORK/<stem>.h5 and prints its title and the head of its
    per-level table (`columns`: the measured value and the exact one). Returns the
    /accuracy/levels rows, whether the target was reached and the levels' folder; None
    (with a failure) when the run exited otherwise than 0 or 1."""
    out = os.path.join(work, stem + ".h5")
    code, wall, err = run(app, deck, sets, out)
    if code not in (0, 1):
        failures.append(f"{name}: the accuracy run exited {code}: {err.strip()[-200:]}")
        return None
    with h5py.File(out, "r") as f:
        levels = f["accuracy/levels"][()]
        reached = int(f["accuracy"].attrs["reached"])
    print(f"{name} ({'reached' if reached else 'not reached'}, {wall:.3g} s for all levels)")
    print(f"| level | dofs | {columns} | error | estimated | estimate / error |")
    print("|---|---|---|---|---|---|---|")
    return levels, reached, os.path.join(work, stem + "_levels")


def stick_zone_case(app, work, failures):
    """Runs the stick-zone case; prints a per-level table; the last level within
    STICK_TOLERANCE of theory and every estimate within a factor of two of the error."""
    name, deck = STICK_CASE
    ran = levels_run(app, work, name, deck, [], "stick_zone", "2c measured | 2c theory", failures)
    if ran is None:
        return
    levels, reached, folder = ran
    for row in levels:
        k = int(row[0])
        theory = stick_zone_theory(os.path.join(folder, f"level{k}.h5"))
        error = abs(row[2] / theory - 1.0)
        ratio = row[3] / error if k > 0 else math.nan
        est = "—" if k == 0 else f"{100 * row[3]:.3g} %"
        print(f"| {k} | {int(row[1])} | {row[2]:.5f} | {theory:.5f} | {100 * error:.3g} % | {est} | {ratio:.3g} |")
        if k > 0 and not (0.5 <= ratio <= 2.0):
            failures.append(f"{name}: level {k} estimate {row[3]:.3g} against the error {error:.3g}")
    if not reached:
        failures.append(f"{name}: the target was not reached")
    if error > STICK_TOLERANCE:
        failures.append(f"{name}: the last level's stick zone is {100 * error:.3g} % from theory")
    print()


# The contact zone's half-width (quantity: contact_radius) of the 2D Hertz start against
# Hertz's a. The zone is a sum of pressed Gauss points' weights, so its error jumps by an
# edge point's weight from level to level (0.42 %, then 0.05 %, then 0.25 % on this start)
# and no estimate can follow it within a factor of two: the ratios are printed, and what is
# graded is that the target is met for real, never claimed early (before the zone's
# resolution floored its difference, level 1 claimed 0.07 % at 16 % from a).
RADIUS_CASE = ("2D Hertz, contact half-width", "inputs/hertz_accuracy_2d.yaml",
               ["accuracy.target.quantity=contact_radius", "accuracy.target.error=0.02",
                "accuracy.budget.levels=12"], 0.02)


def contact_radius_case(app, work, failures):
    """Runs the half-width case; prints a per-level table; the level that meets the
    target within it of Hertz's a (from the level's /reference)."""
    name, deck, sets, target = RADIUS_CASE
    ran = levels_run(app, work, name, deck, sets, "contact_radius", "half-width | Hertz a", failures)
    if ran is None:
        return
    levels, reached, folder = ran
    error = math.nan
    for row in levels:
        k = int(row[0])
        with h5py.File(os.path.join(folder, f"level{k}.h5"), "r") as f:
            a = float(next(iter(f["reference"].values())).attrs["a"])
        error = abs(row[2] / a - 1.0)
        est = "—" if k == 0 else f"{100 * row[3]:.3g} %"
        ratio = "—" if k == 0 else f"{row[3] / error:.3g}"
        print(f"| {k} | {int(row[1])} | {row[2]:.5f} | {a:.5f} | {100 * error:.3g} % | {est} | {ratio} |")
    if not reached:
        failures.append(f"{name}: the target was not reached")
    elif error > target:
        failures.append(f"{name}: a false success: the target {target:g} met at {100 * error:.3g} % from Hertz's a")
    print()


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    quick = "--quick" in sys.argv
    if not args:
        print(__doc__)
        return 2
    app = os.path.abspath(args[0])
    work = args[1] if len(args) > 1 else tempfile.mkdtemp(prefix="accuracy_")
    os.makedirs(work, exist_ok=True)
    rows, failures = [], []
    stick_zone_case(app, work, failures)
    contact_radius_case(app, work, failures)
    for name, deck, sets, graded, uniform_levels in CASES:
        if quick and name.startswith("3D"):
            continue
        tag = "".join(c if c.isalnum() else "_" for c in name)
        out = os.path.join(work, tag + ".h5")
        code, wall, err = run(app, deck, sets, out)
        if code not in (0, 1):  # 1: the target not reached, which the table says
            failures.append(f"{name}: the accuracy run exited {code}: {err.strip()[-200:]}")
            continue
        with h5py.File(out, "r") as f:
            levels = f["accuracy/levels"][()]
            reached = int(f["accuracy"].attrs["reached"])
            pair = f["accuracy"].attrs["pair"]
            pair = pair.decode() if isinstance(pair, bytes) else str(pair)
        for row in levels[1:]:
            ratio = row[3] / row[5]
            if not (0.5 <= ratio <= 2.0):
                failures.append(f"{name}: level {int(row[0])} estimate {row[3]:.3g} against {row[5]:.3g}")
        last = levels[-1]
        rows.append((name, f"accuracy, {len(levels)} levels ({'reached' if reached else 'not reached'})",
                     int(last[1]), last[5], stored_l2(out), last[4], wall))
        graded_out = os.path.join(work, tag + "_graded.h5")
        code_g, wall_g, _ = run(app, graded, [level0_only(pair)], graded_out)
        if code_g != 1:  # 1: the dofs budget stops it after level 0
            failures.append(f"{name}: the hand-graded deck exited {code_g}")
        else:
            rows.append((name, "hand-graded deck", dofs(graded_out), l2_error(graded_out), stored_l2(graded_out),
                         math.nan, wall_g))
        # Uniform: the coarse start solved once per level (accuracy=null), every span halved
        # k times, until its error is no larger than the adaptive run's.
        plain = [s for s in sets if not s.startswith("accuracy=")] + [level0_only(pair)]
        total = 0.0
        for k in range(uniform_levels + 1):
            u_out = os.path.join(work, f"{tag}_uniform{k}.h5")
            code_u, wall_u, err_u = run(app, deck, plain, u_out, ["--refine-levels", str(k)])
            total += wall_u
            if code_u != 1:
                failures.append(f"{name}: uniform level {k} exited {code_u}: {err_u.strip()[-200:]}")
                break
            if l2_error(u_out) <= last[5] or k == uniform_levels:
                rows.append((name, f"uniform, {k + 1} levels", dofs(u_out), l2_error(u_out), stored_l2(u_out),
                             math.nan, total))
                break
    print("| case | run | dofs | L2 against Hertz | results' l2 | estimated | wall s |")
    print("|---|---|---|---|---|---|---|")
    for name, how, n, error, stored, estimate, wall in rows:
        est = "—" if math.isnan(estimate) else f"{100 * estimate:.3g} %"
        print(f"| {name} | {how} | {n} | {100 * error:.3g} % | {100 * stored:.3g} % | {est} | {wall:.3g} |")
    for line in failures:
        print("FAIL:", line)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
