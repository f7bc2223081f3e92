#!/usr/bin/python3
"""Table and plot of a penalty sweep made by scripts/sweep_penalty.sh.

Usage:  scripts/sweep_penalty.py DIR PAIR V1 V2 ...   (a V may be `auto`: the penalty the run chose)

Reads DIR/penalty_<V>.json (the `--summary json` line) and DIR/penalty_<V>.h5 for each
value V, prints a Markdown table (penalty, status, errors against the analytic
reference of /reference/<PAIR> when there is one, max penetration from the
`max_penetration` attributes under /results/contact/<PAIR>, Newton iterations, wall
time), writes it also as DIR/sweep.csv, and plots DIR/sweep.png: the L2 errors
against penalty when a reference exists, otherwise the max penetration against
penalty (both log-log). A value whose run failed is listed with its status and left
out of the plot. Needs /usr/bin/python3 with numpy, h5py and matplotlib.
"""
import csv
import json
import math
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)

COLUMNS = ["penalty", "status", "l2", "peak", "half_width", "gauss_l2", "max_penetration",
           "newton_iterations", "cutbacks", "wall_s", "results", "given"]


def max_penetration(h5, pair):
    """Largest `max_penetration` attribute of the pair's group and its side groups (nan if none)."""
    if "results" not in h5 or "contact" not in h5["results"] or pair not in h5["results"]["contact"]:
        return float("nan")
    values = []
    group = h5["results"]["contact"][pair]
    for g in [group] + [group[k] for k in group if isinstance(group[k], h5py.Group)]:
        if "max_penetration" in g.attrs:
            values.append(float(g.attrs["max_penetration"]))
    return max(values) if values else float("nan")


def read_one(directory, pair, value):
    row = {c: float("nan") for c in COLUMNS}
    # `auto` (the deck's documented value) is the penalty the run chose: the pair's
    # `penalty` attribute in its results, NaN until the run wrote it.
    row.update(penalty=float("nan") if value == "auto" else float(value), status="missing",
               results=f"penalty_{value}.h5", given=value)
    summary_path = os.path.join(directory, f"penalty_{value}.json")
    if os.path.exists(summary_path):
        lines = [ln for ln in open(summary_path).read().splitlines() if ln.startswith("{")]
        if lines:
            s = json.loads(lines[-1])
            row.update(status=s.get("status", "?"), newton_iterations=s.get("newton_iterations", math.nan),
                       cutbacks=s.get("cutbacks", math.nan), wall_s=s.get("wall_s", math.nan))
        else:
            row["status"] = "error (see .err)"
    h5_path = os.path.join(directory, row["results"])
    if os.path.exists(h5_path):
        with h5py.File(h5_path, "r") as f:
            row["max_penetration"] = max_penetration(f, pair)
            contact = f["results"]["contact"] if "results" in f and "contact" in f["results"] else {}
            if value == "auto" and pair in contact and "penalty" in contact[pair].attrs:
                row["penalty"] = float(contact[pair].attrs["penalty"])
            if "reference" in f and pair in f["reference"]:
                attrs = f["reference"][pair].attrs
                for k in ("l2", "peak", "half_width", "gauss_l2"):
                    if k in attrs:
                        row[k] = float(attrs[k])
    return row


def cell(v, spec):
    if isinstance(v, str):
        return v
    return "-" if v is None or (isinstance(v, float) and math.isnan(v)) else format(v, spec)


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    directory, pair, values = argv[0], argv[1], argv[2:]
    rows = [read_one(directory, pair, v) for v in values]
    rows.sort(key=lambda r: (math.isnan(r["penalty"]), r["penalty"]))  # an auto run that wrote nothing: last
    has_reference = any(not math.isnan(r["l2"]) for r in rows)

    print(f"\nPenalty sweep of pair {pair} ({directory}); errors in % against /reference/{pair}"
          if has_reference else f"\nPenalty sweep of pair {pair} ({directory}); no analytic reference in the deck")
    print("| penalty | status | L2 % | peak % | half-width % | L2 Gauss % | max penetration | Newton | wall s |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        pct = {k: 100 * r[k] for k in ("l2", "peak", "half_width", "gauss_l2")}
        label = f"{r['penalty']:.2e} (auto)" if r["given"] == "auto" else f"{r['penalty']:.0e}"
        print(f"| {label} | {r['status']} | {cell(pct['l2'], '.2f')} | {cell(pct['peak'], '+.2f')} | "
              f"{cell(pct['half_width'], '+.2f')} | {cell(pct['gauss_l2'], '.2f')} | {cell(r['max_penetration'], '.3e')} | "
              f"{cell(r['newton_iterations'], 'd')} | {cell(r['wall_s'], '.3f')} |")
    with open(os.path.join(directory, "sweep.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS)
        w.writeheader()
        w.writerows(rows)

    done = [r for r in rows if r["status"] == "completed"]
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    if has_reference:
        ax.loglog([r["penalty"] for r in done], [100 * r["l2"] for r in done], "-o", label="L2, post-processed")
        ax.loglog([r["penalty"] for r in done], [100 * r["gauss_l2"] for r in done], ":x", label="L2, Gauss points")
        ax.set_ylabel(f"L2 error against /reference/{pair} [%]")
        ax.legend()
    else:
        ax.loglog([r["penalty"] for r in done], [r["max_penetration"] for r in done], "-o")
        ax.set_ylabel("max penetration")
    ax.set_xlabel(f"penalty (contact.{pair}.penalty)")
    ax.grid(True, which="both", alpha=0.3)
    ax.set_title(f"Penalty sweep: {os.path.basename(os.path.normpath(directory))}, pair {pair}")
    fig.tight_layout()
    png = os.path.join(directory, "sweep.png")
    fig.savefig(png, dpi=110)
    print(f"\nwrote {os.path.join(directory, 'sweep.csv')} and {png}")
    return 0 if len(done) == len(rows) else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
