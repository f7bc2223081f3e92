#!/usr/bin/python3
"""What accuracy costs in time: the Hertz benchmark over degree, mesh and penalty.

Runs inputs/hertz.yaml (quarter cylinder on a rigid plane, docs/theory.md "The Hertz benchmark") over
  - degree p = 2, 3, 4 in both directions (elevate [p-2, p-1]: quarter_disc is
    degree (2, 1) as built, and its arc is an exact conic, which needs degree >= 2;
    degree 1 would be a faceted polygon, a different geometry, so it is not run),
  - five meshes: hertz_mesh.knots(h_in = 4 h_edge, h_edge) with
    h_edge = 0.004, 0.002, 0.001 (canonical), 0.0007, 0.0005,
  - penalty 1e6 and 1e8 on every (degree, mesh), plus 1e4, 1e5, 1e7 on the
    canonical mesh of every degree (the penalty sweep),
in parallel (--jobs, default 2; each run single-threaded, OMP_NUM_THREADS=1) and
`--repeat` times each (median wall time). Per run it records DOFs, contact Gauss
points, Newton iterations, wall time with its /timings split, the errors against
Hertz stored in /reference/<pair> (post-processed and Gauss-point: L2, peak,
half-width), two oscillation measures of the Gauss-point pressure and the L2
distance of the post-processed pressure to a converged reference run.

Definitions (x = (X - center) . tangent in reference coordinates, window |x| <= 1.2a,
p0 and a from /reference/<pair>):
  osc_rms  RMS over active Gauss points (p_g > 0, in the window) of
           (p_g - p_pp(x_g)) / p0, with p_pp the post-processed pressure
           interpolated (linearly in x) at the Gauss point;
  osc_tv   total variation of p_g (Gauss points sorted by x, in the window) minus
           that of the post-processed curve over the same window, divided by
           n_sides * p0 (n_sides = 1 for the quarter model, whose curve runs from
           the peak down to 0 once, 2 for a full model): 0 for a monotone curve,
           0.1 means the Gauss points go up and down by an extra 10 % of p0;
  l2_recomputed  this script's L2 of the post-processed pressure against the analytic
           Hertz curve: reproduces l2 (a check of the integration behind l2_ref);
  l2_ref   L2 of the post-processed pressure against the finest run's
           post-processed curve (largest DOFs at the largest penalty, then the
           highest degree), same norm as l2: sqrt(int (p_h - p_ref)^2 dx) /
           (p0 sqrt(a)) over |x| <= 1.2a, a half model counting its half twice.
           Against Hertz, no setting can show much less than ~0.6 % (the finite
           cylinder differs from the half-space theory, docs/theory.md "The Hertz benchmark");
           l2_ref measures the discretization alone.

Writes OUT/accuracy.csv, OUT/accuracy.md and OUT/*.png (default OUT = docs/accuracy).
Needs /usr/bin/python3 with numpy, h5py and matplotlib.
"""
import argparse
import concurrent.futures as futures
import csv
import json
import math
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hertz_mesh  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PAIR = "cyl_floor"
WINDOW = 1.2  # |x| <= 1.2 a: the window of igacontact's L2 error (docs/theory.md "The Hertz benchmark")
GRID = 4001  # samples of the window for the L2 integrals (curves are piecewise smooth)
ONE_SIDED_SLACK = 1e-8  # relative round-off allowed on the empty side of x = 0

DEGREES = (2, 3, 4)
H_EDGES = (0.004, 0.002, 0.001, 0.0007, 0.0005)
CANONICAL_H_EDGE = 0.001
MESH_PENALTIES = (1e6, 1e8)
SWEEP_PENALTIES = (1e4, 1e5, 1e6, 1e7, 1e8)

COLUMNS = ["degree", "h_in", "h_edge", "penalty", "status", "dofs", "contact_gauss_points",
           "newton_iterations", "increments", "cutbacks", "wall_s", "wall_s_min", "repeats",
           "t_assembly", "t_elements", "t_contact", "t_contact_search", "t_projection",
           "t_linear_solve", "t_output", "l2", "peak", "half_width", "gauss_l2", "gauss_peak",
           "gauss_half_width", "osc_rms", "osc_tv", "l2_ref", "l2_recomputed", "is_reference"]


def cases(quick):
    """(degree, h_in, h_edge, penalty), without duplicates, the expensive ones first."""
    if quick:  # three tiny runs: two degrees and two penalties on the coarsest mesh
        return [(2, 0.016, 0.004, 1e6), (3, 0.016, 0.004, 1e6), (2, 0.016, 0.004, 1e8)]
    out = [(p, 4 * h, h, eps) for p in DEGREES for h in H_EDGES for eps in MESH_PENALTIES]
    out += [(p, 4 * CANONICAL_H_EDGE, CANONICAL_H_EDGE, eps) for p in DEGREES for eps in SWEEP_PENALTIES]
    out = list(dict.fromkeys(out))
    # Longest first, so that two workers finish together.
    out.sort(key=lambda c: (-c[0] / c[2], -c[3]))
    return out


def reference_x(coords, attrs):
    return (np.asarray(coords) - np.asarray(attrs["center"])) @ np.asarray(attrs["tangent"])


def total_variation(values):
    return float(np.sum(np.abs(np.diff(values)))) if len(values) > 1 else 0.0


def read_results(path):
    """Timings, counters, reference attributes and the pressure curves of one results file."""
    with h5py.File(path, "r") as f:
        out = {"status": f.attrs["status"].decode() if isinstance(f.attrs["status"], bytes) else str(f.attrs["status"])}
        out["timings"] = {k: float(v) for k, v in f["timings"].attrs.items()}
        out["counters"] = {k: int(v) for k, v in f["counters"].attrs.items()} if "counters" in f else {}
        ref = f["reference"][PAIR].attrs
        out["ref"] = {k: ref[k] for k in ("a", "p0", "center", "tangent", "l2", "peak", "half_width",
                                          "gauss_l2", "gauss_peak", "gauss_half_width")}
        sides = f["results"]["contact"][PAIR]
        gx, gp, px, pp = [], [], [], []
        for name in sides:
            side = sides[name]
            if not isinstance(side, h5py.Group) or "gauss_points" not in side:
                continue
            gx.append(reference_x(side["gauss_points/reference_coordinates"][()], ref))
            gp.append(side["gauss_points/pressure"][()])
            px.append(reference_x(side["postprocessed/reference_coordinates"][()], ref))
            pp.append(side["postprocessed/pressure"][()])
    out["gauss"] = (np.concatenate(gx), np.concatenate(gp))
    out["post"] = (np.concatenate(px), np.concatenate(pp))
    return out


def sorted_curve(x, p):
    order = np.argsort(x, kind="stable")
    return x[order], p[order]


def one_sided(x, a):
    return bool(np.all(x >= -ONE_SIDED_SLACK * a)) or bool(np.all(x <= ONE_SIDED_SLACK * a))


def symmetric(curve, a):
    """A one-sided (quarter-model) curve mirrored to both sides of x = 0; others unchanged."""
    x, p = curve
    if one_sided(x, a):
        x, p = np.concatenate([-np.abs(x), np.abs(x)]), np.concatenate([p, p])
    return sorted_curve(x, p)


def l2_between(curve, ref_curve, a, p0):
    """sqrt(int (p - p_ref)^2 dx)/(p0 sqrt(a)) over |x| <= 1.2a; a one-sided curve is mirrored
    (a half model counts its half twice)."""
    x, p = symmetric(curve, a)
    xr, pr = symmetric(ref_curve, a)
    grid = np.linspace(-WINDOW * a, WINDOW * a, GRID)
    d = np.interp(grid, x, p, left=0.0, right=0.0) - np.interp(grid, xr, pr, left=0.0, right=0.0)
    return math.sqrt(np.trapz(d * d, grid)) / (p0 * math.sqrt(a))


def oscillation(data):
    a, p0 = float(data["ref"]["a"]), float(data["ref"]["p0"])
    gx, gp = sorted_curve(*data["gauss"])
    px, pp = sorted_curve(*data["post"])
    n_sides = 1 if one_sided(gx, a) else 2
    win_g = np.abs(gx) <= WINDOW * a
    win_p = np.abs(px) <= WINDOW * a
    active = win_g & (gp > 0.0)
    if not np.any(active):
        return float("nan"), float("nan")
    diff = (gp[active] - np.interp(gx[active], px, pp)) / p0
    osc_rms = float(np.sqrt(np.mean(diff * diff)))
    osc_tv = (total_variation(gp[win_g]) - total_variation(pp[win_p])) / (n_sides * p0)
    return osc_rms, osc_tv


def run_case(exe, deck, case, repeat, tmp):
    degree, h_in, h_edge, penalty = case
    sets = [hertz_mesh.insert_override(h_in, h_edge), f"contact.{PAIR}.penalty={penalty:g}",
            f"bodies.cylinder.refine.elevate=[{degree - 2},{degree - 1}]"]
    out = os.path.join(tmp, f"p{degree}_h{h_edge:g}_e{penalty:g}.h5")
    cmd = [exe, deck, "-o", out, "-q", "--summary", "json"]
    for s in sets:
        cmd += ["--set", s]
    env = dict(os.environ, OMP_NUM_THREADS="1")
    runs = []
    for _ in range(repeat):
        try:
            proc = subprocess.run(cmd, capture_output=True, text=True, env=env)
        except OSError as e:
            return {"case": case, "status": f"error: {e}"}
        lines = [ln for ln in proc.stdout.splitlines() if ln.startswith("{")]
        if not lines:
            return {"case": case, "status": f"error {proc.returncode}: {proc.stderr.strip()[-200:]}"}
        summary = json.loads(lines[-1])
        if summary.get("status") != "completed":
            return {"case": case, "status": summary.get("status", "failed"), "summary": summary}
        runs.append((summary["wall_s"], summary, read_results(out)))
    runs.sort(key=lambda r: r[0])
    wall, summary, data = runs[len(runs) // 2]
    os.remove(out)
    return {"case": case, "status": "completed", "summary": summary, "data": data,
            "wall_s": statistics.median(r[0] for r in runs), "wall_s_min": runs[0][0], "repeats": len(runs)}


def row_of(result):
    degree, h_in, h_edge, penalty = result["case"]
    row = {c: "" for c in COLUMNS}
    row.update(degree=degree, h_in=h_in, h_edge=h_edge, penalty=penalty, status=result["status"], is_reference=0)
    if result["status"] != "completed":
        return row
    s, d = result["summary"], result["data"]
    c = d["counters"]
    row.update(dofs=s["dofs"], contact_gauss_points=s["contact_gauss_points"], newton_iterations=s["newton_iterations"],
               increments=s["increments"], cutbacks=s["cutbacks"], wall_s=result["wall_s"],
               wall_s_min=result["wall_s_min"], repeats=result["repeats"])
    assert c.get("dofs", s["dofs"]) == s["dofs"], "summary and /counters disagree on DOFs"
    for k in ("assembly", "elements", "contact", "contact_search", "projection", "linear_solve", "output"):
        row["t_" + k] = d["timings"].get(k, float("nan"))
    for k in ("l2", "peak", "half_width", "gauss_l2", "gauss_peak", "gauss_half_width"):
        row[k] = float(d["ref"][k])
    row["osc_rms"], row["osc_tv"] = oscillation(d)
    # This script's own L2 against the analytic Hertz curve: it must reproduce the stored l2,
    # which checks the integration that l2_ref uses.
    a, p0 = float(d["ref"]["a"]), float(d["ref"]["p0"])
    x = np.linspace(-1.5 * a, 1.5 * a, 200001)
    row["l2_recomputed"] = l2_between(d["post"], (x, p0 * np.sqrt(np.clip(1.0 - (x / a) ** 2, 0.0, None))), a, p0)
    return row


def fmt(v, spec):
    return format(v, spec) if isinstance(v, (int, float)) and not (isinstance(v, float) and math.isnan(v)) else "-"


def ok(r):
    return r["status"] == "completed"


def plot_lines(rows, xkey, ykey, path, xlabel, title):
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8), sharex=True)
    colors = {2: "tab:blue", 3: "tab:orange", 4: "tab:green"}
    for ax, key, label in ((axes[0], ykey[0], "L2 vs Hertz [%]"), (axes[1], ykey[1], "L2 vs converged run [%]")):
        for degree in sorted({r["degree"] for r in rows}):
            for penalty, style in ((1e6, "-"), (1e8, "--")):
                sel = [r for r in rows if ok(r) and r["degree"] == degree and r["penalty"] == penalty
                       and r[key] != "" and r[key] > 0]
                if len(sel) < 1:
                    continue
                sel.sort(key=lambda r: r["h_edge"], reverse=True)
                ax.loglog([r[xkey] for r in sel], [100 * r[key] for r in sel], style, marker="o",
                          color=colors.get(degree), label=f"p = {degree}, eps = {penalty:.0e}")
        if key == "l2":
            for level in (2.0, 1.0):
                ax.axhline(level, color="grey", lw=0.8, ls=":")
            ax.axhline(0.6, color="tab:red", lw=1.0, ls="-.", label="half-space model error of the benchmark (~0.6 %)")
        ax.set_xlabel(xlabel)
        ax.set_ylabel(label)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_penalty(rows, path):
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    colors = {2: "tab:blue", 3: "tab:orange", 4: "tab:green"}
    for degree in sorted({r["degree"] for r in rows}):
        sel = sorted([r for r in rows if ok(r) and r["degree"] == degree and r["h_edge"] == CANONICAL_H_EDGE],
                     key=lambda r: r["penalty"])
        if not sel:
            continue
        eps = [r["penalty"] for r in sel]
        axes[0].loglog(eps, [100 * r["l2"] for r in sel], "-o", color=colors.get(degree), label=f"p = {degree}: L2 post-processed")
        axes[0].loglog(eps, [100 * r["gauss_l2"] for r in sel], ":x", color=colors.get(degree), label=f"p = {degree}: L2 Gauss points")
        axes[1].semilogx(eps, [100 * r["peak"] for r in sel], "-o", color=colors.get(degree), label=f"p = {degree}: peak")
        axes[1].semilogx(eps, [100 * r["half_width"] for r in sel], "--s", color=colors.get(degree), label=f"p = {degree}: half-width")
    axes[0].set_ylabel("L2 error vs Hertz [%]")
    axes[1].set_ylabel("error vs Hertz [%]")
    axes[1].axhline(0.0, color="grey", lw=0.8)
    for ax in axes:
        ax.set_xlabel("penalty eps_N")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle(f"Hertz: error vs penalty (canonical mesh, h_edge = {CANONICAL_H_EDGE})")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_oscillation(rows, path):
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    colors = {2: "tab:blue", 3: "tab:orange", 4: "tab:green"}
    for ax, key, label in ((axes[0], "osc_rms", "osc_rms: RMS (p_gauss - p_postprocessed)/p0 [%]"),
                           (axes[1], "osc_tv", "osc_tv: excess total variation of p_gauss / p0 [%]")):
        for degree in sorted({r["degree"] for r in rows}):
            for penalty, style in ((1e6, "-"), (1e8, "--")):
                sel = sorted([r for r in rows if ok(r) and r["degree"] == degree and r["penalty"] == penalty],
                             key=lambda r: r["h_edge"], reverse=True)
                if sel:
                    ax.semilogx([r["h_edge"] for r in sel], [100 * r[key] for r in sel], style, marker="o",
                                color=colors.get(degree), label=f"p = {degree}, eps = {penalty:.0e}")
        ax.invert_xaxis()
        ax.set_xlabel("h_edge (knot span at the contact edge)")
        ax.set_ylabel(label)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("Gauss-point pressure oscillation about the post-processed curve")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def cheapest(rows, key, level):
    sel = [r for r in rows if ok(r) and r[key] != "" and not r["is_reference"] and r[key] <= level]
    return min(sel, key=lambda r: r["wall_s"]) if sel else None


def describe(r):
    if r is None:
        return "none of the settings"
    return (f"p = {r['degree']}, h_edge = {r['h_edge']:g} (h_in = {r['h_in']:g}), eps = {r['penalty']:.0e}: "
            f"{r['dofs']} DOFs, {r['newton_iterations']} Newton iterations, {r['wall_s']:.3f} s "
            f"(L2 vs Hertz {100 * r['l2']:.2f} %, vs converged run {100 * r['l2_ref']:.2f} %)")


def write_markdown(rows, path, args, elapsed, load_before, load_after):
    ref = next((r for r in rows if r["is_reference"]), None)
    lines = ["# Accuracy vs time: the Hertz benchmark", "",
             "Generated by `scripts/accuracy_vs_time.sh" + (" --quick" if args.quick else "") + "` "
             f"({len(rows)} settings, {args.repeat} repeat(s) each, median wall time, {args.jobs} parallel jobs, "
             f"OMP_NUM_THREADS=1; study took {elapsed:.0f} s). Raw numbers: `accuracy.csv`.", "",
             f"Machine load average (1, 5, 15 min) before: {load_before}, after: {load_after}. The machine was "
             "shared with other work, so wall times are noisy (tens of per cent); compare orders of magnitude, "
             "not the last digit.", "",
             "Degrees: 2, 3 and 4 in both directions. Degree 1 is not run: the quarter_disc arc is an exact "
             "conic (rational degree 2), and degree 1 would replace it by a polygon, a different geometry "
             "whose kinks dominate the contact pressure.", ""]
    lines += ["## Headline", ""]
    for level in (0.02, 0.01):
        lines.append(f"- Cheapest setting with L2 vs Hertz <= {100 * level:g} %: {describe(cheapest(rows, 'l2', level))}.")
    for level in (0.01, 0.005, 0.0025):
        lines.append(f"- Cheapest setting with L2 vs the converged run <= {100 * level:g} %: "
                     f"{describe(cheapest(rows, 'l2_ref', level))}.")
    lines += ["", "Below about 0.6 % the L2 error against Hertz stops measuring the discretization: the finite "
              "cylinder (a/R ~ 0.1) itself differs from Hertz's half-space theory by about that much "
              "([theory.md, \"The Hertz benchmark\"](../theory.md#the-hertz-benchmark)), so the column `L2 ref` measures every run against the converged run "
              + (f"(p = {ref['degree']}, h_edge = {ref['h_edge']:g}, eps = {ref['penalty']:.0e}, {ref['dofs']} DOFs; "
                 "its own entry is 0 by construction and it still carries its own penalty error)"
                 if ref else "(none completed)") + ". Runs with a softer penalty than the converged run keep "
              "their penalty error in `L2 ref` (the contact zone widens as the penalty softens), so at 1e6 it "
              "levels off at the penalty error instead of going to 0.", ""]
    lines += ["## Gauss-point oscillation per degree", "",
              "osc_rms = RMS over active Gauss points in |x| <= 1.2a of (p_gauss - p_postprocessed(x_gauss))/p0; "
              "osc_tv = excess total variation of the Gauss-point pressure over the post-processed curve in the "
              "same window, / p0 (quarter model: the curve falls from p0 to 0 once). Mean over the meshes, "
              f"and the value on the canonical mesh (h_edge = {CANONICAL_H_EDGE:g}):", "",
              "| degree | penalty | osc_rms mean % | osc_rms canonical % | osc_tv mean % | osc_tv canonical % | "
              "L2 Gauss canonical % | L2 post-proc. canonical % |", "|---|---|---|---|---|---|---|---|"]
    for degree in sorted({r["degree"] for r in rows}):
        for penalty in sorted({r["penalty"] for r in rows}):
            sel = [r for r in rows if ok(r) and r["degree"] == degree and r["penalty"] == penalty]
            if not sel:
                continue
            can = next((r for r in sel if r["h_edge"] == CANONICAL_H_EDGE), None)
            lines.append(f"| {degree} | {penalty:.0e} | {100 * statistics.mean(r['osc_rms'] for r in sel):.2f} | "
                         f"{fmt(100 * can['osc_rms'] if can else float('nan'), '.2f')} | "
                         f"{100 * statistics.mean(r['osc_tv'] for r in sel):.2f} | "
                         f"{fmt(100 * can['osc_tv'] if can else float('nan'), '.2f')} | "
                         f"{fmt(100 * can['gauss_l2'] if can else float('nan'), '.2f')} | "
                         f"{fmt(100 * can['l2'] if can else float('nan'), '.2f')} |")
    meshes = sorted({r["h_edge"] for r in rows}, reverse=True)
    for penalty in MESH_PENALTIES:
        lines += ["", f"osc_rms % / osc_tv % per degree and mesh, penalty {penalty:.0e}:", "",
                  "| degree | " + " | ".join(f"h_edge {h:g}" for h in meshes) + " |",
                  "|---|" + "---|" * len(meshes)]
        for degree in sorted({r["degree"] for r in rows}):
            cells = []
            for h in meshes:
                r = next((r for r in rows if ok(r) and r["degree"] == degree and r["penalty"] == penalty
                          and r["h_edge"] == h), None)
                cells.append(f"{100 * r['osc_rms']:.2f} / {100 * r['osc_tv']:.1f}" if r else "-")
            lines.append(f"| {degree} | " + " | ".join(cells) + " |")
    lines += ["", "Reading the measures: where osc_tv is about 0 the Gauss-point pressure is monotone like the "
              "post-processed curve, and osc_rms then measures the post-processing's smoothing at the contact "
              "edge, not an oscillation. A slightly negative osc_tv (soft penalties) means the contact zone "
              "reaches past the 1.2a window, whose ends the Gauss points do not sample exactly.", ""]
    degrees = sorted({r["degree"] for r in rows})
    for penalty in MESH_PENALTIES:
        rising, compared, worst = 0, 0, []
        for h in meshes:
            tv = {r["degree"]: r["osc_tv"] for r in rows if ok(r) and r["penalty"] == penalty and r["h_edge"] == h}
            if len(tv) == len(degrees) and len(degrees) > 1:
                compared += 1
                rising += all(tv[p] < tv[q] for p, q in zip(degrees, degrees[1:]))
                worst.append(f"{h:g}: p = {max(tv, key=tv.get)}")
        if compared:
            lines.append(f"- Penalty {penalty:.0e}: osc_tv rises strictly with the degree on {rising} of {compared} "
                         f"meshes; the most oscillating degree per mesh (h_edge: degree) is " + ", ".join(worst) + ".")
    lines += ["", "## All runs", "",
              "Errors in per cent (peak and half-width signed, relative to Hertz); times in seconds "
              "(median wall time; assembly includes elements and contact).", "",
              "| p | h_edge | eps | status | DOFs | GPs | Newton | wall s | assembly | contact | lin. solve | "
              "L2 | peak | half-w. | L2 GP | L2 ref | osc_rms | osc_tv |",
              "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in sorted(rows, key=lambda r: (r["degree"], -r["h_edge"], r["penalty"])):
        pct = lambda k, spec=".2f": fmt(100 * r[k] if r[k] != "" else float("nan"), spec)  # noqa: E731
        lines.append(f"| {r['degree']} | {r['h_edge']:g} | {r['penalty']:.0e} | {r['status']} | {fmt(r['dofs'], 'd')} | "
                     f"{fmt(r['contact_gauss_points'], 'd')} | {fmt(r['newton_iterations'], 'd')} | "
                     f"{fmt(r['wall_s'], '.3f')} | {fmt(r['t_assembly'], '.3f')} | {fmt(r['t_contact'], '.3f')} | "
                     f"{fmt(r['t_linear_solve'], '.3f')} | {pct('l2')} | {pct('peak', '+.2f')} | "
                     f"{pct('half_width', '+.2f')} | {pct('gauss_l2')} | {pct('l2_ref')} | {pct('osc_rms')} | "
                     f"{pct('osc_tv')} |")
    lines += ["", "## Plots", "", "![L2 vs wall time](l2_vs_time.png)", "", "![L2 vs DOFs](l2_vs_dofs.png)", "",
              "![error vs penalty](error_vs_penalty.png)", "", "![oscillation](oscillation.png)", ""]
    with open(path, "w") as f:
        f.write("\n".join(lines))


def load_average():
    try:
        return ", ".join(f"{x:.2f}" for x in os.getloadavg())
    except OSError:
        return "unknown"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "bin", "igacontact"))
    ap.add_argument("--deck", default=os.path.join(ROOT, "inputs", "hertz.yaml"))
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "accuracy"))
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--repeat", type=int, default=None, help="runs per setting (default 3, --quick 1)")
    ap.add_argument("--quick", action="store_true", help="three tiny settings (a smoke test)")
    args = ap.parse_args()
    args.repeat = args.repeat or (1 if args.quick else 3)
    if not os.access(args.exe, os.X_OK):
        sys.exit(f"error: {args.exe} is not an executable (build it with scripts/build.sh igacontact)")
    os.makedirs(args.out, exist_ok=True)
    load_before, start = load_average(), time.monotonic()
    todo = cases(args.quick)
    global CANONICAL_H_EDGE  # the mesh of the penalty sweep: the one with the most penalties
    CANONICAL_H_EDGE = max({c[2] for c in todo}, key=lambda h: sum(c[2] == h for c in todo))
    results = []
    with tempfile.TemporaryDirectory() as tmp, futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        # A private copy of the binary: every run uses the same one even if the build tree is
        # relinked meanwhile.
        exe = shutil.copy2(args.exe, os.path.join(tmp, "igacontact"))
        jobs = {pool.submit(run_case, exe, args.deck, c, args.repeat, tmp): c for c in todo}
        for job in futures.as_completed(jobs):
            r = job.result()
            results.append(r)
            degree, _, h_edge, penalty = r["case"]
            extra = f"{r['wall_s']:.3f} s, L2 {100 * float(r['data']['ref']['l2']):.2f} %" if ok(r) else ""
            print(f"[{len(results)}/{len(todo)}] p={degree} h_edge={h_edge:g} eps={penalty:.0e}: {r['status']} {extra}",
                  flush=True)
    elapsed = time.monotonic() - start
    done = [r for r in results if ok(r)]
    reference = max(done, key=lambda r: (r["case"][3], r["summary"]["dofs"], r["case"][0])) if done else None
    rows = []
    for r in results:
        row = row_of(r)
        if ok(r):
            d = r["data"]
            row["l2_ref"] = l2_between(d["post"], reference["data"]["post"], float(d["ref"]["a"]), float(d["ref"]["p0"]))
            row["is_reference"] = int(r is reference)
        rows.append(row)
    rows.sort(key=lambda r: (r["degree"], -r["h_edge"], r["penalty"]))
    with open(os.path.join(args.out, "accuracy.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS)
        w.writeheader()
        w.writerows(rows)
    plot_lines(rows, "wall_s", ("l2", "l2_ref"), os.path.join(args.out, "l2_vs_time.png"), "wall time [s] (median, 1 core)",
               "Hertz: post-processed L2 error vs wall time")
    plot_lines(rows, "dofs", ("l2", "l2_ref"), os.path.join(args.out, "l2_vs_dofs.png"), "DOFs",
               "Hertz: post-processed L2 error vs DOFs")
    plot_penalty(rows, os.path.join(args.out, "error_vs_penalty.png"))
    plot_oscillation(rows, os.path.join(args.out, "oscillation.png"))
    write_markdown(rows, os.path.join(args.out, "accuracy.md"), args, elapsed, load_before, load_average())
    print(f"wrote {args.out}/accuracy.csv, accuracy.md and 4 PNGs ({elapsed:.0f} s of runs)")
    return 0 if len(done) == len(results) else 1


if __name__ == "__main__":
    sys.exit(main())
