#!/usr/bin/python3
"""Runs and grades the hard scenes of issue 31 (verification/scenes/README.md).

Usage: /usr/bin/python3 verification/scenes/run_scenes.py BINARY [WORK_DIR] [--only NAME ...] [--quick]
                                                          [--timeout-factor F]

Runs each scene's deck with BINARY, one at a time, writes its results file, log and
figures into WORK_DIR (default: a new folder under /tmp), reads the results with h5py and
prints one row per scene and a PASS/FAIL line per criterion. Exit status 1 when any
criterion of any scene that was run fails (a scene that fails to complete fails them all).

--only NAME ...  run only these scenes (names as in the table below: ironing_2d_press03, ...)
--quick          only the 2D scenes (a few minutes); the 3D ones take up to ~5 min each
--timeout-factor multiplies each scene's wall-time limit (default 1)

Criteria (issue 31, "Done when"), for every scene:
  increments  converged increments <= 2 x planned (steps.count, plus the increments that
              amplitude kinks inside a planned step add: none here)
  min_step    the smallest increment taken >= 1/8 of the planned one (T/steps.count). An
              increment that was shortened only to land on an amplitude kink or on the end
              of the path (no cutback, ending exactly there) is not counted; all others are,
              whether the step control or a cutback made them small
  newton      mean Newton iterations per converged increment <= 8, counting the iterations
              of failed (cut back) attempts too (/counters newton_iterations)
Scene-specific:
  ironing_2d_*  the die's horizontal force (the reaction of its driven top, die.v1) over
                the steady slide s in [1.5 R, 8 - 1 R] = [1.5, 7] (R = 1 the die radius): the
                largest deviation from its mean <= 3 % of the mean (the peak-to-peak range is
                printed too); F_x/F_y (force on the die's top) is printed against mu; a figure
                of both forces against the slide is written to WORK_DIR/<scene>_history.png
  two_spheres   the post-processed peak pressure and contact radius within 3 % of Hertz and
                the radial L2 error within 5 % (/reference/spheres, both sides); the run time
                against the one-sphere-on-a-plane deck of about the same size, run right
                after it with the same thread count: ratio <= 3
A scene that does not complete (status failed, a crash, or the wall-time limit, after which
it is stopped with SIGTERM and graded on what it wrote) fails every criterion; how far it
got is printed.
"""
import argparse
import math
import os
import signal
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))

# name, deck, dimension, wall-time limit (s) on the reference machine (2 cores, shared)
SCENES = [
    ("ironing_2d_press03", "ironing_2d_press03.yaml", 2, 600),
    ("ironing_2d_press10", "ironing_2d_press10.yaml", 2, 600),
    ("block_drag_2d", "block_drag_2d.yaml", 2, 600),
    ("ironing_3d", "ironing_3d.yaml", 3, 600),
    ("two_spheres_ssnv104", "two_spheres_ssnv104.yaml", 3, 600),
    ("hollow_sphere", "hollow_sphere.yaml", 3, 600),
    ("sphere_octant_on_slab", "sphere_octant_on_slab.yaml", 3, 600),
]
COMPANION = ("one_sphere_ssnv104", "one_sphere_ssnv104.yaml", 3, 600)

MAX_INCREMENT_RATIO = 2.0
MIN_STEP_RATIO = 1.0 / 8.0
MAX_MEAN_NEWTON = 8.0
IRONING_MAX_VARIATION = 0.03
IRONING_STEADY = (1.5, 7.0)  # slide window: 1.5 die radii after the press position .. 1 radius before the end of 8
IRONING_MU = 0.3
HERTZ_PEAK, HERTZ_RADIUS, HERTZ_L2 = 0.03, 0.03, 0.05
MAX_TIME_RATIO = 3.0
THREADS = "1"  # every run single-threaded, so that the time ratio compares like with like


def yaml_steps(deck_text):
    """steps.count, the amplitude kink times and the end T of the path, from the resolved
    deck (/deck). Every item without an amplitude ramps over [0, 1], so 1 counts as a kink."""
    import re
    try:
        import yaml
        d = yaml.safe_load(deck_text)
        count = int((d.get("steps") or {}).get("count", 1))
        amps = []
        for key in ("constraints", "loads"):
            amps += [it["amplitude"] for it in (d.get(key) or []) if isinstance(it, dict) and "amplitude" in it]
        amps += [b["rigid"]["amplitude"] for b in (d.get("bodies") or []) if "amplitude" in (b.get("rigid") or {})]
    except ImportError:  # the resolved deck is written in block style with flow-style items
        m = re.search(r"\nsteps:\s*\n\s*count:\s*(\d+)", deck_text)
        count = int(m.group(1)) if m else 1
        amps = [[[float(x) for x in p.split(",")] for p in re.findall(r"\[([-0-9.e+]+,\s*[-0-9.e+]+)\]", am.group(1))]
                for am in re.finditer(r"amplitude:\s*(\[\[.*?\]\])", deck_text)]
    kinks = {1.0}
    for pts in amps:
        kinks.update(float(p[0]) for p in pts)
    return count, sorted(kinks), max(kinks)


def run(binary, deck, out, log, limit):
    """Runs one deck; returns (exit code or 'timeout', process wall time)."""
    cmd = [binary, deck, "-o", out, "--threads", THREADS, "--summary", "json"]
    t0 = time.monotonic()
    with open(log, "w") as f:
        p = subprocess.Popen(cmd, stdout=f, stderr=subprocess.STDOUT)
        try:
            rc = p.wait(timeout=limit)
        except subprocess.TimeoutExpired:
            p.send_signal(signal.SIGTERM)  # igacontact stops cleanly and writes what converged
            try:
                p.wait(timeout=120)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()
            rc = "timeout"
    return rc, time.monotonic() - t0


def basic(path):
    """Step statistics of a results file."""
    with h5py.File(path, "r") as f:
        status, message = str(f.attrs["status"]), str(f.attrs["message"])
        deck = f["deck"].asstr()[()]
        count, kinks, end = yaml_steps(deck)
        c = dict(f["counters"].attrs) if "counters" in f else {}
        total = float(f["timings"].attrs["total"]) if "timings" in f else float("nan")
        t = f["history/load_factor"][:] if "history/load_factor" in f else np.zeros(0)
        conv = f["convergence"][:] if "convergence" in f else np.zeros((0, 4))
    planned = end / count
    increments = len(t)
    starts = np.concatenate([[0.0], t[:-1]])
    dt = t - starts
    # increments per step in /convergence: max iteration index of each increment
    per_inc = {}
    for row in conv:
        per_inc[int(row[0])] = max(per_inc.get(int(row[0]), 0), int(row[1]))
    # cutbacks per increment are not in /history; an increment ending on a kink or on T
    # counts as landing there when it is shorter than planned and no other increment had to be
    # cut: conservatively only when it ends exactly on the kink and starts after the previous kink
    graded = []
    for k, (a, b) in enumerate(zip(starts, t)):
        on_kink = any(abs(b - kt) < 1e-9 * max(1.0, end) for kt in kinks)
        if on_kink and dt[k] < planned * (1 - 1e-9):
            continue
        graded.append(dt[k])
    min_all = float(dt.min() / planned) if increments else float("nan")
    min_graded = float(min(graded) / planned) if graded else (min_all if increments else float("nan"))
    newton = int(c.get("newton_iterations", 0))
    return dict(status=status, message=message, count=count, end=end, planned=planned, t=t,
                increments=increments, cutbacks=int(c.get("cutbacks", 0)), newton=newton,
                newton_conv=sum(per_inc.values()), min_all=min_all, min_graded=min_graded,
                time_total=total, dofs=int(c.get("dofs", 0)), reached=float(t[-1]) if increments else 0.0)


def common_checks(b):
    done = b["status"] == "completed"
    mean = b["newton"] / b["increments"] if b["increments"] else float("inf")
    b["mean_newton"] = mean
    return [
        ("completes", done, b["status"] if done else "%s at t = %.4g of %g: %s" % (b["status"], b["reached"], b["end"], b["message"][:200])),
        ("increments <= 2x planned", done and b["increments"] <= MAX_INCREMENT_RATIO * b["count"],
         "%d / %d" % (b["increments"], b["count"])),
        ("min step >= planned/8", done and b["min_graded"] >= MIN_STEP_RATIO * (1 - 1e-9),
         "%.4g (all increments: %.4g)" % (b["min_graded"], b["min_all"])),
        ("mean Newton <= 8", done and mean <= MAX_MEAN_NEWTON,
         "%.2f (converged attempts only: %.2f; cutbacks %d)" % (mean, b["newton_conv"] / max(b["increments"], 1), b["cutbacks"])),
    ]


def ironing_checks(path, b, work, name):
    with h5py.File(path, "r") as f:
        t = f["history/load_factor"][:]
        reac = f["history/reactions/die.v1"][:]
        fr = f["history/contact/iron/die.v0/friction_force"][:] if "history/contact/iron/die.v0/friction_force" in f else None
    slide = np.clip(t - 1.0, 0.0, None)  # the slide of 8 goes over pseudo-time [1, 9]
    fx, fy = reac[:, 0], reac[:, 1]  # the force the driven top exerts on the die
    lo, hi = IRONING_STEADY
    sel = (slide >= lo - 1e-9) & (slide <= hi + 1e-9)
    out = []
    if sel.sum() >= 3:
        mean = fx[sel].mean()
        dev = np.abs(fx[sel] - mean).max() / abs(mean)
        p2p = (fx[sel].max() - fx[sel].min()) / abs(mean)
        ratio = np.abs(fx[sel]).mean() / np.abs(fy[sel]).mean()
        ok = b["status"] == "completed" and dev <= IRONING_MAX_VARIATION
        out.append(("F_x steady variation <= 3 %", ok,
                    "max |F_x - mean| = %.1f %% of mean %.4g (peak-to-peak %.1f %%) over %d increments, slide %.1f..%.1f"
                    % (100 * dev, mean, 100 * p2p, sel.sum(), lo, hi)))
        out.append(("F_x/F_y against mu (reported)", None, "%.4f (mu = %.2f; mean F_y %.4g)" % (ratio, IRONING_MU, fy[sel].mean())))
    else:
        out.append(("F_x steady variation <= 3 %", False,
                    "no steady sliding reached (slide %.3g of 8)" % (slide[-1] if len(slide) else 0)))
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(7, 4))
        ax.plot(slide, fx, ".-", ms=3, label="F_x (horizontal, on the die's top)")
        ax.plot(slide, -fy, ".-", ms=3, label="-F_y (vertical)")
        ax.plot(slide, IRONING_MU * -fy, ":", label="mu (-F_y)")
        if fr is not None:
            ax.plot(slide, -fr[:, 0], "--", lw=1, label="friction force on the die (-x)")
        ax.axvspan(lo, hi, color="0.9", label="steady window")
        ax.set_xlabel("slide of the die's top (= pseudo-time - 1)")
        ax.set_ylabel("force per unit thickness")
        ax.set_title("%s: %s" % (name, b["status"]))
        ax.legend(fontsize=8)
        fig.tight_layout()
        png = os.path.join(work, name + "_history.png")
        fig.savefig(png, dpi=110)
        plt.close(fig)
        out.append(("figure", None, png))
    except Exception as e:  # the figure is a by-product; its absence is not a criterion
        out.append(("figure", None, "not written: %s" % e))
    return out


def hertz_checks(path, b):
    out = []
    with h5py.File(path, "r") as f:
        if "reference/spheres" not in f:
            return [("Hertz (peak, radius, L2)", False, "no /reference/spheres (nothing converged)")]
        at = dict(f["reference/spheres"].attrs)
    prefixes = [""] + sorted({k.rsplit(".", 1)[0] + "." for k in at if k.endswith(".peak") and k != "peak"})
    for pre in prefixes:
        side = pre.rstrip(".") or "first side"
        peak, rad, l2 = (float(at.get(pre + k, float("nan"))) for k in ("peak", "contact_radius", "l2"))
        ok = b["status"] == "completed"
        out.append(("peak within 3 %% (%s)" % side, ok and abs(peak) <= HERTZ_PEAK, "%+.2f %%" % (100 * peak)))
        out.append(("contact radius within 3 %% (%s)" % side, ok and abs(rad) <= HERTZ_RADIUS, "%+.2f %%" % (100 * rad)))
        out.append(("radial L2 within 5 %% (%s)" % side, ok and abs(l2) <= HERTZ_L2, "%.2f %%" % (100 * l2)))
    return out



def failures(checks):
    """Names of the failed criteria. `ok` may be a numpy bool (`is False` misses it);
    None marks a figure that is only reported."""
    return [c for c, ok, _ in checks if ok is not None and not ok]

def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("binary")
    ap.add_argument("work", nargs="?")
    ap.add_argument("--only", nargs="+", default=None)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--timeout-factor", type=float, default=1.0)
    args = ap.parse_args()
    binary = os.path.abspath(args.binary)
    work = os.path.abspath(args.work) if args.work else tempfile.mkdtemp(prefix="scenes_")
    os.makedirs(work, exist_ok=True)
    names = [s[0] for s in SCENES]
    if args.only:
        bad = [n for n in args.only if n not in names]
        if bad:
            sys.exit("unknown scene(s) %s; scenes: %s" % (", ".join(bad), ", ".join(names)))
    scenes = [s for s in SCENES if (not args.only or s[0] in args.only) and (not args.quick or s[2] == 2)]
    print("work folder:", work)
    rows, failed = [], False
    for name, deck, dim, limit in scenes:
        out, log = os.path.join(work, name + ".h5"), os.path.join(work, name + ".log")
        print("running %s ..." % name, flush=True)
        rc, wall = run(binary, os.path.join(HERE, deck), out, log, limit * args.timeout_factor)
        if not os.path.exists(out):
            checks = [("completes", False, "exit %s after %.0f s, no results file (see %s)" % (rc, wall, log))]
            rows.append((name, dict(status="no file", increments=0, count=0, min_graded=float("nan"), mean_newton=float("nan")), wall, checks))
            failed = True
            continue
        b = basic(out)
        if rc == "timeout":
            b["status"] = "timeout"
            b["message"] = "stopped after the wall-time limit of %.0f s" % (limit * args.timeout_factor)
        checks = common_checks(b)
        if name.startswith("ironing_2d"):
            checks += ironing_checks(out, b, work, name)
        if name == "two_spheres_ssnv104":
            checks += hertz_checks(out, b)
            cname, cdeck, _, climit = COMPANION
            cout, clog = os.path.join(work, cname + ".h5"), os.path.join(work, cname + ".log")
            print("running %s (companion, for the time ratio) ..." % cname, flush=True)
            crc, cwall = run(binary, os.path.join(HERE, cdeck), cout, clog, climit * args.timeout_factor)
            if os.path.exists(cout):
                cb = basic(cout)
                ratio = wall / cwall
                checks.append(("time ratio to one sphere <= 3", b["status"] == "completed" and cb["status"] == "completed" and ratio <= MAX_TIME_RATIO,
                               "%.2f (two spheres %.1f s, %d dofs, %d Newton; one sphere %.1f s, %d dofs, %d Newton, %s)"
                               % (ratio, wall, b["dofs"], b["newton"], cwall, cb["dofs"], cb["newton"], cb["status"])))
            else:
                checks.append(("time ratio to one sphere <= 3", False, "the companion wrote no results (exit %s)" % crc))
        rows.append((name, b, wall, checks))
        failed |= bool(failures(checks))
        print_scene(name, b, wall, checks)
    print()
    print("| scene | status | increments / planned | min step / planned | mean Newton | wall s | verdict |")
    print("|---|---|---|---|---|---|---|")
    for name, b, wall, checks in rows:
        verdict = "FAIL (%s)" % ", ".join(failures(checks)) if failures(checks) else "PASS"
        print("| %s | %s | %d / %d | %.3g | %.2f | %.0f | %s |" % (
            name, b["status"], b["increments"], b["count"], b["min_graded"], b.get("mean_newton", float("nan")), wall, verdict))
    sys.exit(1 if failed else 0)


def print_scene(name, b, wall, checks):
    print("%s: %s, %d increments (planned %d), %d cutbacks, %.0f s, %d dofs" % (
        name, b["status"], b["increments"], b["count"], b["cutbacks"], wall, b["dofs"]))
    for crit, ok, text in checks:
        mark = "    " if ok is None else ("PASS" if ok else "FAIL")
        print("  %s  %-36s %s" % (mark, crit, text))
    sys.stdout.flush()


if __name__ == "__main__":
    main()
