#!/usr/bin/python3
"""Wall-clock time of igacontact with --threads 1, --threads 2 and the default, on three decks.

Usage:  scripts/bench_threads.py [--exe build/bin/igacontact] [--repeats 5] [--out DIR]

Decks: a small finite-strain deck (inputs/block_stretch_finite_2d.yaml), the Hertz
deck (inputs/hertz.yaml, small kinematics) and a large finite-strain deck (the Lame
cylinder with analysis.kinematics=finite, 64 x 64 spans, 8.7k DOFs). Each
configuration runs --repeats times, interleaved (1, 2, default, 1, 2, default, ...)
so that a change in the machine's load hits all three alike; the table gives the
median wall clock of the whole process (start to exit, results file included) and
the ratios to one thread. The load average before and after is printed: on a shared
machine, repeat when it is high. The default's thread count is the run's own
`--summary json` "threads".
"""

import argparse
import json
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]

DECKS = [
    ("small finite (block stretch)", "inputs/block_stretch_finite_2d.yaml", []),
    ("Hertz (small kinematics)", "inputs/hertz.yaml", []),
    ("large finite (Lame 64x64)", "inputs/lame_cylinder_2d.yaml",
     ["--set", "analysis.kinematics=finite", "--set", "bodies.tube.refine.spans=[64,64]"]),
]
CONFIGS = [("1 thread", ["--threads", "1"]), ("2 threads", ["--threads", "2"]), ("default", [])]


def run_once(exe, deck, extra, out):
    command = [str(exe), str(ROOT / deck), "-o", str(out), "-q", "--summary", "json"] + extra
    start = time.perf_counter()
    done = subprocess.run(command, capture_output=True, text=True)
    wall = time.perf_counter() - start
    if done.returncode != 0:
        sys.exit(f"error: {' '.join(command)} exited {done.returncode}:\n{done.stderr}")
    return wall, json.loads(done.stdout.strip().splitlines()[-1])


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--exe", type=pathlib.Path, default=ROOT / "build/bin/igacontact")
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--out", type=pathlib.Path, help="folder for the results files (default: a temporary one)")
    args = parser.parse_args(argv)
    out_dir = args.out or pathlib.Path(tempfile.mkdtemp(prefix="bench_threads_"))
    out_dir.mkdir(parents=True, exist_ok=True)

    load_before = os.getloadavg()
    rows = []
    for label, deck, extra in DECKS:
        times = {name: [] for name, _ in CONFIGS}
        summary = {}
        for repeat in range(args.repeats):
            for name, flags in CONFIGS:
                wall, s = run_once(args.exe, deck, extra + flags, out_dir / "bench.h5")
                times[name].append(wall)
                summary[name] = s
        median = {name: statistics.median(t) for name, t in times.items()}
        rows.append((label, int(summary["default"].get("dofs", 0)), int(summary["default"].get("threads", 0)),
                     median, times))
    load_after = os.getloadavg()

    print(f"cores: {os.cpu_count()}, repeats: {args.repeats}, load average (1 min) before {load_before[0]:.2f}, "
          f"after {load_after[0]:.2f}")
    print()
    print("| deck | DOFs | default threads | 1 thread [s] | 2 threads [s] | default [s] | 2 / 1 | default / 1 |")
    print("|---|---|---|---|---|---|---|---|")
    for label, dofs, threads, median, _ in rows:
        one = median["1 thread"]
        print(f"| {label} | {dofs} | {threads} | {one:.3f} | {median['2 threads']:.3f} | {median['default']:.3f} "
              f"| {median['2 threads'] / one:.2f} | {median['default'] / one:.2f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
