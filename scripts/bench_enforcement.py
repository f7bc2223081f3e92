#!/usr/bin/python3
"""Penalty against augmented Lagrangian on the canonical Hertz deck (a benchmark, not a test).

Runs inputs/hertz.yaml (quarter cylinder, degree 2, graded knots, 3080 DOFs) with
`--set` for each enforcement and penalty, `--repeat` times each (median wall time),
and prints a Markdown table read from the results files (docs/results.md):
post-processed L2, peak and half-width errors against Hertz (/reference/cyl_floor),
Newton iterations and Uzawa updates of the increment (/steps/0001 attributes), the
penalty in effect at the end (raised by the augmented Lagrangian's safeguard) and the
median wall time. Single-threaded (OMP_NUM_THREADS=1), like bench_hertz.py.

--auto-sweep instead measures the penalty against c = eps h / E' (the conditioning
term of `penalty: auto`): it reads E' and h of the auto rule from one run (pair
attributes penalty_modulus, penalty_element_size) and runs the penalty at c = 1 ... 1e4,
reporting the errors, the Newton iterations and eps h / E' (= c, the conditioning
added to the tangent).
Usage: scripts/bench_enforcement.py [--exe build/bin/igacontact] [--repeat 3] [--auto-sweep]
"""
import argparse, os, statistics, subprocess, sys, tempfile

import h5py

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PAIR = "cyl_floor"


def run(exe, sets, out):
    cmd = [exe, os.path.join(ROOT, "inputs", "hertz.yaml"), "-o", out, "-q"]
    for s in sets:
        cmd += ["--set", s]
    p = subprocess.run(cmd, capture_output=True, text=True, env=dict(os.environ, OMP_NUM_THREADS="1"))
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({p.returncode}): {p.stderr[-400:]}")
    with h5py.File(out, "r") as f:
        ref = f["reference/" + PAIR].attrs
        step = f["steps/0001"].attrs
        pair = f["steps/0001/contact/" + PAIR].attrs
        return {
            "l2": float(ref["l2"]), "peak": float(ref["peak"]), "half_width": float(ref["half_width"]),
            "newton": int(step["newton_iterations"]), "uzawa": int(step.get("uzawa_updates", 0)),
            "penalty": float(pair["penalty"]), "wall": float(f["timings"].attrs["total"]),
            "dofs": int(f["counters"].attrs["dofs"]),
        }


def median_run(exe, sets, out, repeat):
    runs = [run(exe, sets, out) for _ in range(repeat)]
    result = dict(runs[0])
    result["wall"] = statistics.median(r["wall"] for r in runs)
    return result


def enforcement_table(args, tmp):
    cases = [("penalty", 1e4), ("penalty", 1e6), ("penalty", 1e8),
             ("augmented_lagrangian", 1e4), ("augmented_lagrangian", 1e6)]
    print("| enforcement | ε (deck) | ε at the end | L2 % | peak % | half-width % | Newton it. | Uzawa updates "
          "| wall s (median) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for enforcement, penalty in cases:
        sets = [f"contact.{PAIR}.enforcement={enforcement}", f"contact.{PAIR}.penalty={penalty:g}"]
        r = median_run(args.exe, sets, os.path.join(tmp, "r.h5"), args.repeat)
        print(f"| {enforcement} | {penalty:g} | {r['penalty']:g} | {100 * r['l2']:.2f} | {100 * r['peak']:+.2f} "
              f"| {100 * r['half_width']:+.2f} | {r['newton']} | {r['uzawa']} | {r['wall']:.3f} |", flush=True)


def auto_sweep(args, tmp):
    auto_file = os.path.join(tmp, "auto.h5")
    auto = run(args.exe, [f"contact.{PAIR}.penalty=auto"], auto_file)
    with h5py.File(auto_file, "r") as f:
        pair = f["results/contact/" + PAIR].attrs
        unit = float(pair["penalty_modulus"]) / float(pair["penalty_element_size"])  # E'/h
    print(f"E'/h = {unit:.4g} (penalty auto = {auto['penalty']:.4g}, c = {auto['penalty'] / unit:.3g})")
    print("| c = ε h / E' | ε | L2 % | peak % | half-width % | Newton it. | wall s (median) |")
    print("|---|---|---|---|---|---|---|")
    for c in (1, 10, 100, 1000, 10000):
        r = median_run(args.exe, [f"contact.{PAIR}.penalty={c * unit:.6g}"], os.path.join(tmp, "r.h5"), args.repeat)
        print(f"| {c:g} | {c * unit:.3g} | {100 * r['l2']:.2f} | {100 * r['peak']:+.2f} | {100 * r['half_width']:+.2f} "
              f"| {r['newton']} | {r['wall']:.3f} |", flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "bin", "igacontact"))
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--auto-sweep", action="store_true", help="measure the constant of penalty: auto instead")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        (auto_sweep if args.auto_sweep else enforcement_table)(args, tmp)


if __name__ == "__main__":
    sys.exit(main())
