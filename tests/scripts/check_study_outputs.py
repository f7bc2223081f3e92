#!/usr/bin/python3
"""Checks of the outputs of the study scripts (run by CTest after their --quick modes).

Usage:  check_study_outputs.py accuracy DIR N_ROWS   (scripts/accuracy_vs_time.py --out DIR)
        check_study_outputs.py sweep DIR N_ROWS      (scripts/sweep_penalty.sh --out DIR; a row per run and side)
Every comparison is written so that NaN fails it. Exits 1 with the list of failures.
"""
import csv
import math
import os
import sys

# The script's own L2 integration (uniform grid, linear interpolation of the sampled
# post-processed curve) against the library's: they differ by the interpolation of
# ~100 samples per a, far below 1 % of the value.
L2_RECOMPUTE_REL = 0.01
# Penalty pressure p = eps g: a 100x stiffer penalty must cut the penetration by about
# 100x (the pressure itself changes by a few per cent); allow a factor 2 either way.
PENETRATION_RATIO_SLACK = 2.0
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"

failures = []


def check(ok, what):
    if not ok:
        failures.append(what)


def number(row, key):
    try:
        return float(row[key])
    except (KeyError, ValueError):
        return float("nan")


def check_png(path):
    check(os.path.isfile(path) and os.path.getsize(path) > 1000, f"{path}: missing or tiny")
    if os.path.isfile(path):
        with open(path, "rb") as f:
            check(f.read(8) == PNG_SIGNATURE, f"{path}: not a PNG")


def read_csv(path, columns, n_rows):
    check(os.path.isfile(path), f"{path}: missing")
    if not os.path.isfile(path):
        return []
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        missing = [c for c in columns if c not in (reader.fieldnames or [])]
        check(not missing, f"{path}: columns missing: {missing}")
        rows = list(reader)
    check(len(rows) == n_rows, f"{path}: {len(rows)} rows, expected {n_rows}")
    return rows


def check_accuracy(directory, n_rows):
    columns = ["degree", "h_edge", "penalty", "status", "dofs", "contact_gauss_points", "newton_iterations",
               "wall_s", "t_assembly", "t_linear_solve", "l2", "peak", "half_width", "gauss_l2", "gauss_peak",
               "gauss_half_width", "osc_rms", "osc_tv", "l2_ref", "l2_recomputed", "is_reference"]
    rows = read_csv(os.path.join(directory, "accuracy.csv"), columns, n_rows)
    for i, r in enumerate(rows):
        tag = f"accuracy.csv row {i + 1}"
        check(r["status"] == "completed", f"{tag}: status {r['status']}")
        check(number(r, "degree") >= 2, f"{tag}: degree {r['degree']} < 2")
        check(number(r, "dofs") > 0 and number(r, "contact_gauss_points") > 0, f"{tag}: no DOFs or Gauss points")
        check(number(r, "newton_iterations") >= 1, f"{tag}: no Newton iteration")
        wall = number(r, "wall_s")
        check(wall > 0 and number(r, "t_linear_solve") <= wall and number(r, "t_assembly") <= wall,
              f"{tag}: wall time {wall} not positive or smaller than its parts")
        l2 = number(r, "l2")
        check(0 < l2 < 1, f"{tag}: l2 = {l2} outside (0, 1)")
        check(abs(number(r, "l2_recomputed") - l2) <= L2_RECOMPUTE_REL * l2,
              f"{tag}: l2_recomputed {r['l2_recomputed']} != l2 {l2}")
        check(0 < number(r, "gauss_l2") < 1, f"{tag}: gauss_l2 outside (0, 1)")
        check(abs(number(r, "peak")) < 1 and abs(number(r, "half_width")) < 1, f"{tag}: peak/half-width error >= 100 %")
        check(number(r, "osc_rms") >= 0 and math.isfinite(number(r, "osc_tv")), f"{tag}: oscillation not finite")
        if r["is_reference"] == "1":
            check(number(r, "l2_ref") == 0, f"{tag}: the reference run is not at distance 0 from itself")
        else:
            check(number(r, "l2_ref") > 0, f"{tag}: l2_ref = {r['l2_ref']} not positive")
    check(sum(r["is_reference"] == "1" for r in rows) == 1, "accuracy.csv: not exactly one reference run")
    md = os.path.join(directory, "accuracy.md")
    check(os.path.isfile(md) and "## Headline" in open(md).read(), f"{md}: missing or without a headline")
    for png in ("l2_vs_time.png", "l2_vs_dofs.png", "error_vs_penalty.png", "oscillation.png"):
        check_png(os.path.join(directory, png))


def check_sweep(directory, n_rows):
    rows = read_csv(os.path.join(directory, "sweep.csv"),
                    ["penalty", "side", "status", "l2", "max_penetration", "normal_force", "newton_iterations",
                     "wall_s"], n_rows)
    for i, r in enumerate(rows):
        tag = f"sweep.csv row {i + 1}"
        check(r["status"] == "completed", f"{tag}: status {r['status']}")
        check(number(r, "penalty") > 0, f"{tag}: penalty {r['penalty']} (given {r.get('given')}) not positive")
        check(number(r, "max_penetration") > 0 and 0 < number(r, "l2") < 1, f"{tag}: penetration or l2 not sane")
        check(number(r, "normal_force") > 0, f"{tag}: normal force {r['normal_force']} not positive")
        check(os.path.isfile(os.path.join(directory, r["results"])), f"{tag}: results file missing")
    sides = list(dict.fromkeys(r["side"] for r in rows))
    # Every run has a row for every side (a two-body pair: both sides, not only the first).
    check(len(rows) == len(sides) * len({r["results"] for r in rows}), f"sweep.csv: sides {sides} not in every run")
    for side in sides:
        mine = [r for r in rows if r["side"] == side]
        for lo, hi in zip(mine, mine[1:]):
            ratio = number(lo, "max_penetration") / number(hi, "max_penetration")
            expected = number(hi, "penalty") / number(lo, "penalty")
            check(expected / PENETRATION_RATIO_SLACK <= ratio <= expected * PENETRATION_RATIO_SLACK,
                  f"sweep.csv, {side}: penetration ratio {ratio} for a penalty ratio {expected}")
    check_png(os.path.join(directory, "sweep.png"))


def main(argv):
    if len(argv) != 3 or argv[0] not in ("accuracy", "sweep"):
        sys.exit(__doc__)
    (check_accuracy if argv[0] == "accuracy" else check_sweep)(argv[1], int(argv[2]))
    for f in failures:
        print("FAIL:", f)
    print(f"{argv[0]} outputs in {argv[1]}: {'ok' if not failures else f'{len(failures)} failure(s)'}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
