#!/usr/bin/python3
"""Hard-case suite: difficult but valid decks must end cleanly.

Usage: run_hard.py IGACONTACT [WORK_DIR]          (CTest: verification.hard)

Every case in cases.txt (`case | completed|failed | checks`) is run as
`igacontact CASE.yaml -q -o WORK/CASE.h5 --summary json`. A case passes when
  - the exit code is 0 (completed) or 1 (failed), as expected: never 2, 3 or a
    signal, and it ends within the time limit;
  - the results file opens with h5py and its `status` attribute is the expected one;
  - no dataset or attribute anywhere in the file holds NaN or inf;
  - a failed run has a non-empty `message` (the summary's and the file's) naming
    the cause;
  - the optional checks hold (on the last stored increment):
      force=V        the sum of normal_force over the pair's sides of the first pair
                     that carries Gauss points equals V (relative tolerance 1e-6:
                     the load balance holds to the Newton tolerance, far below it)
      no_contact     every Gauss-point pressure of the last increment is 0
      max_pressure=P every Gauss-point |pressure| of every increment is <= P
                     (grazing: gaps are 0 up to round-off, so pressures are
                     round-off times the penalty)
      contact_first  the first stored increment has a positive pressure somewhere
      all_steps      one /steps group per converged increment (every_step default)
      message~TEXT   the message contains TEXT
Prints one table row per case: outcome, increments, cutbacks, Newton iterations.
Exit code 0 when every case passes.
"""
import json
import math
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
TIME_LIMIT_S = 60  # each deck runs in well under 5 s; 60 s means it hangs
FORCE_RTOL = 1e-6  # resultant vs applied load: Newton tolerance 1e-10 leaves ~1e-10


def read_cases(path):
    cases = []
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0].strip()
            if not line:
                continue
            parts = [p.strip() for p in line.split("|")]
            while len(parts) < 3:
                parts.append("")
            cases.append((parts[0], parts[1], parts[2].split()))
    return cases


def non_finite(h5):
    """Names of every dataset and attribute holding NaN or inf (or unreadable)."""
    bad = []

    def check_value(name, value):
        try:
            a = np.asarray(value)
        except Exception as e:  # noqa: BLE001 - any read problem is a finding
            bad.append(f"{name}: unreadable ({e})")
            return
        if a.dtype.kind in "fc" and not np.all(np.isfinite(a)):
            bad.append(name)

    def visit(name, obj):
        for key, value in obj.attrs.items():
            check_value(f"{name}@{key}", value)
        if isinstance(obj, h5py.Dataset):
            check_value(name, obj[()])

    for key, value in h5.attrs.items():
        check_value(f"/@{key}", value)
    h5.visititems(visit)
    return bad


def text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


def pair_sides(step):
    """(pair, side group) of the step's contact results."""
    out = []
    if "contact" in step:
        for pair in step["contact"]:
            for side in step["contact"][pair]:
                out.append((pair, step["contact"][pair][side]))
    return out


def run_checks(h5, checks, summary, problems):
    steps = h5["steps"] if "steps" in h5 else None
    names = sorted(steps) if steps is not None else []
    for check in checks:
        if check.startswith("message~"):
            want = check.split("~", 1)[1]
            if want not in text(h5.attrs.get("message", "")):
                problems.append(f"message does not contain '{want}'")
            continue
        if check == "all_steps":
            if len(names) != summary.get("increments", -1):
                problems.append(f"{len(names)} /steps groups for {summary.get('increments')} increments")
            continue
        if not names:
            problems.append(f"{check}: no converged increment stored")
            continue
        last, first = steps[names[-1]], steps[names[0]]
        if check.startswith("force="):
            want = float(check.split("=", 1)[1])
            sides = pair_sides(last)
            if not sides:
                problems.append("force: no contact results")
                continue
            first_pair = sides[0][0]
            forces = [float(g.attrs["normal_force"]) for p, g in sides if p == first_pair]
            # two-half-pass: each side carries the whole resultant; check each one
            for got in forces:
                if not abs(got - want) <= FORCE_RTOL * abs(want):
                    problems.append(f"normal_force {got:.9g}, expected {want:g}")
        elif check == "no_contact":
            for pair, g in pair_sides(last):
                p = g["gauss_points/pressure"][()]
                if np.any(p != 0.0):
                    problems.append(f"{pair}: pressure {np.max(np.abs(p)):.3g} on the last increment")
        elif check.startswith("max_pressure="):
            bound = float(check.split("=", 1)[1])
            for k in names:
                for pair, g in pair_sides(steps[k]):
                    p = g["gauss_points/pressure"][()]
                    if p.size and not np.max(np.abs(p)) <= bound:
                        problems.append(f"step {k} {pair}: |pressure| {np.max(np.abs(p)):.3g} > {bound:g}")
        elif check == "contact_first":
            if not any(np.any(g["gauss_points/pressure"][()] > 0.0) for _, g in pair_sides(first)):
                problems.append("no pressure on the first increment")
        else:
            problems.append(f"unknown check '{check}'")


def run_case(exe, work, name, expected, checks):
    deck = os.path.join(HERE, name + ".yaml")
    out = os.path.join(work, name + ".h5")
    if os.path.exists(out):
        os.remove(out)
    problems = []
    summary = {}
    try:
        p = subprocess.run([exe, deck, "-q", "-o", out, "--summary", "json"], capture_output=True, text=True,
                           timeout=TIME_LIMIT_S)
    except subprocess.TimeoutExpired:
        return {"outcome": "timeout"}, [f"did not end within {TIME_LIMIT_S} s"]
    want_code = {"completed": 0, "failed": 1}[expected]
    if p.returncode != want_code:
        problems.append(f"exit code {p.returncode}, expected {want_code}: {p.stderr.strip()[:300]}")
    try:
        summary = json.loads(p.stdout.strip().splitlines()[-1])
    except (ValueError, IndexError):
        problems.append(f"no JSON summary on stdout: {p.stdout[:200]!r}")
    if p.returncode not in (0, 1):
        return summary, problems
    try:
        with h5py.File(out, "r") as h5:
            status = text(h5.attrs.get("status", ""))
            message = text(h5.attrs.get("message", ""))
            summary["file_status"] = status
            if status != expected:
                problems.append(f"file status '{status}', expected '{expected}' ({message})")
            if expected == "failed" and not message.strip():
                problems.append("failed without a message")
            bad = non_finite(h5)
            if bad:
                problems.append("NaN/inf in " + ", ".join(bad[:5]) + (" ..." if len(bad) > 5 else ""))
            run_checks(h5, checks, summary, problems)
    except OSError as e:
        problems.append(f"results file not readable: {e}")
    if summary.get("status") != expected:
        problems.append(f"summary status '{summary.get('status')}'")
    if expected == "failed" and not str(summary.get("message", "")).strip():
        problems.append("summary: failed without a message")
    return summary, problems


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        return 2
    exe = os.path.abspath(sys.argv[1])
    work = sys.argv[2] if len(sys.argv) > 2 else tempfile.mkdtemp(prefix="iga_hard_")
    os.makedirs(work, exist_ok=True)
    cases = read_cases(os.path.join(HERE, "cases.txt"))
    print(f"{'case':26} {'expect':9} {'outcome':9} {'incr':>4} {'cuts':>4} {'newton':>6}  result")
    n_fail = 0
    for name, expected, checks in cases:
        summary, problems = run_case(exe, work, name, expected, checks)
        print(f"{name:26} {expected:9} {str(summary.get('status', summary.get('outcome', '?'))):9} "
              f"{summary.get('increments', '-'):>4} {summary.get('cutbacks', '-'):>4} "
              f"{summary.get('newton_iterations', '-'):>6}  {'ok' if not problems else 'FAIL'}")
        if summary.get("status") == "failed":
            print(f"    message: {summary.get('message', '')}")
        for problem in problems:
            print(f"    FAIL: {problem}")
        n_fail += bool(problems)
    print(f"{len(cases) - n_fail} of {len(cases)} hard cases pass")
    return 1 if n_fail else 0


if __name__ == "__main__":
    sys.exit(main())
