#!/usr/bin/python3
"""Peak memory of igacontact runs: a markdown table of deck, dofs, wall time, peak RSS.

Each deck runs once under /usr/bin/time -v (peak RSS = its "Maximum resident set
size", the high-water mark of the whole process); dofs are read from the results
file's /counters (docs/results.md). docs/performance.md "Memory in 3D".

Usage: /usr/bin/python3 scripts/bench_memory.py DECK.yaml [DECK.yaml ...]
           [--binary build/bin/igacontact] [--out-dir /tmp] [-- extra igacontact args]
"""

import argparse
import os
import re
import subprocess
import sys
import time

import h5py


def run(binary, deck, out_dir, extra):
    out = os.path.join(out_dir, os.path.splitext(os.path.basename(deck))[0] + ".memory.h5")
    cmd = ["/usr/bin/time", "-v", binary, deck, "-o", out] + extra
    start = time.monotonic()
    proc = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wall = time.monotonic() - start
    peak_kb = re.search(r"Maximum resident set size \(kbytes\): (\d+)", proc.stderr)
    if proc.returncode != 0 or peak_kb is None:
        sys.stderr.write(proc.stderr[-2000:])
        raise SystemExit(f"{deck}: igacontact failed (exit {proc.returncode})")
    with h5py.File(out, "r") as f:
        dofs = int(f["counters"].attrs["dofs"]) if "dofs" in f["counters"].attrs else int(f["counters/dofs"][()])
    return dofs, wall, int(peak_kb.group(1)) / 1024.0


def main():
    argv = sys.argv[1:]
    extra = []
    if "--" in argv:
        extra = argv[argv.index("--") + 1:]
        argv = argv[:argv.index("--")]
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("decks", nargs="+")
    parser.add_argument("--binary", default="build/bin/igacontact")
    parser.add_argument("--out-dir", default="/tmp")
    args = parser.parse_args(argv)

    print("| deck | dofs | wall s | peak RSS MB |")
    print("|---|---:|---:|---:|")
    for deck in args.decks:
        dofs, wall, peak = run(args.binary, deck, args.out_dir, extra)
        print(f"| {os.path.basename(deck)} | {dofs} | {wall:.1f} | {peak:.0f} |", flush=True)


if __name__ == "__main__":
    main()
