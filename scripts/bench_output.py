#!/usr/bin/python3
"""Cost of writing the results file per increment (a benchmark, not a test).

Generates a tiny linear deck (small kinematics, one rectangle of 2 x 2 quadratic
spans held on its left side, a traction on its right side, no contact) and runs it
with `steps: {count: N, adaptive: false}` and `output.every_step: true` for each N.
Reads the /timings attribute `output` (seconds spent writing the results file,
including the per-increment step data) and prints a Markdown table: N, total
output seconds, output milliseconds per increment, results file size, total wall
time of the run and wall milliseconds per increment.

Flat means the per-increment output cost at the largest N is within about 2x of the
one at the smallest N. Uses Debian's /usr/bin/python3 (h5py).

    /usr/bin/python3 scripts/bench_output.py --exe build/bin/igacontact [--counts 100 1000 10000]
"""
import argparse, json, os, subprocess, sys, tempfile, time

import h5py

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

DECK = """\
format: 1
title: output benchmark (linear block, {count} increments)
analysis: {{dimension: 2, plane: strain, kinematics: small}}
materials:
  - {{name: soft, model: linear_elastic, E: 1000.0, nu: 0.3}}
bodies:
  - name: block
    material: soft
    shape: {{type: rectangle, corner: [0.0, 0.0], size: [1.0, 1.0]}}
    refine: {{elevate: [1, 1], spans: [2, 2]}}
constraints:
  - {{body: block, side: u0, fix: [x, y]}}
loads:
  - {{body: block, side: u1, traction: [1.0, 0.0]}}
steps: {{count: {count}, adaptive: false}}
output: {{every_step: true}}
"""


def run(exe, folder, count):
    deck = os.path.join(folder, f"bench_{count}.yaml")
    out = os.path.join(folder, f"bench_{count}.h5")
    with open(deck, "w") as f:
        f.write(DECK.format(count=count))
    cmd = [exe, deck, "-o", out, "-q", "--summary", "json"]
    env = dict(os.environ, OMP_NUM_THREADS="1")
    start = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True, env=env)
    wall = time.perf_counter() - start
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({p.returncode}): {p.stderr[-400:]}")
    summary = json.loads(p.stdout.strip().splitlines()[-1])
    with h5py.File(out, "r") as f:
        output_s = float(f["timings"].attrs["output"])
        n_steps = len(f["steps"])
    size = os.path.getsize(out)
    os.remove(out)
    return summary, output_s, n_steps, size, wall


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "bin", "igacontact"))
    ap.add_argument("--counts", type=int, nargs="+", default=[100, 1000, 10000])
    args = ap.parse_args()
    print("| N increments | output s | output ms / increment | file MB | total wall s | wall ms / increment |")
    print("|---|---|---|---|---|---|")
    per_increment = []
    with tempfile.TemporaryDirectory() as tmp:
        for n in args.counts:
            summary, output_s, n_steps, size, wall = run(args.exe, tmp, n)
            if n_steps != n or summary["increments"] != n:
                raise RuntimeError(f"N = {n}: {n_steps} steps stored, {summary['increments']} increments run")
            per_increment.append(1e3 * output_s / n)
            print(f"| {n} | {output_s:.3f} | {1e3 * output_s / n:.3f} | {size / 1e6:.1f} | {wall:.2f} "
                  f"| {1e3 * wall / n:.3f} |", flush=True)
    ratio = per_increment[-1] / per_increment[0]
    print(f"\noutput cost per increment at N = {args.counts[-1]} / at N = {args.counts[0]}: {ratio:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
