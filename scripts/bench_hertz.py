#!/usr/bin/python3
"""Whole-run timing of the canonical Hertz deck (a benchmark, not a test).

Runs inputs/hertz.yaml at several refinements, degrees and penalties, each
`--repeat` times (median wall time), and prints a Markdown table: DOFs, Newton
iterations, median wall time, the /timings split of the median run, and the
errors against Hertz (post-processed L2, peak, half-width). Single-threaded
(OMP_NUM_THREADS=1) so that the figure is one core's, like the comparison codes'.
"""
import argparse, json, os, statistics, subprocess, sys, tempfile

import h5py

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hertz_mesh  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run_once(exe, deck, sets, out):
    cmd = [exe, deck, "-o", out, "-q", "--summary", "json"]
    for s in sets:
        cmd += ["--set", s]
    env = dict(os.environ, OMP_NUM_THREADS="1")
    p = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({p.returncode}): {p.stderr[-400:]}")
    summary = json.loads(p.stdout.strip().splitlines()[-1])
    with h5py.File(out, "r") as f:
        timings = {k: float(v) for k, v in f["timings"].attrs.items()}
    return summary, timings


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "bin", "igacontact"))
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--quick", action="store_true", help="two settings only")
    args = ap.parse_args()
    deck = os.path.join(ROOT, "inputs", "hertz.yaml")

    # (label, degree, h_in, h_edge, penalty)
    cases = [
        ("coarse", 2, 0.008, 0.002, 1e6), ("canonical", 2, 0.004, 0.001, 1e6),
        ("coarse", 2, 0.008, 0.002, 1e8), ("canonical", 2, 0.004, 0.001, 1e8),
        ("fine", 2, 0.003, 0.0007, 1e8),
        ("coarse", 3, 0.008, 0.002, 1e8), ("canonical", 3, 0.004, 0.001, 1e8),
    ]
    if args.quick:
        cases = [cases[1], cases[3]]
    print("| mesh | degree | penalty | DOFs | Newton it. | wall s (median) | assembly | contact | linear_solve "
          "| output | L2 % | peak % | half-width % |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for label, degree, h_in, h_edge, penalty in cases:
            sets = [hertz_mesh.insert_override(h_in, h_edge), f"contact.cyl_floor.penalty={penalty:g}",
                    f"bodies.cylinder.refine.elevate=[{degree - 2},{degree - 1}]"]
            runs = [run_once(args.exe, deck, sets, os.path.join(tmp, "r.h5")) for _ in range(args.repeat)]
            runs.sort(key=lambda r: r[0]["wall_s"])
            summary, t = runs[len(runs) // 2]
            e = summary["errors"]
            print(f"| {label} | {degree} | {penalty:g} | {summary['dofs']} | {summary['newton_iterations']} "
                  f"| {statistics.median(r[0]['wall_s'] for r in runs):.3f} | {t['assembly']:.3f} "
                  f"| {t['contact']:.3f} | {t['linear_solve']:.3f} | {t['output']:.3f} "
                  f"| {100 * e['l2']:.2f} | {100 * e['peak']:+.2f} | {100 * e['half_width']:+.2f} |", flush=True)


if __name__ == "__main__":
    main()
