#!/usr/bin/python3
"""Table and plot of a penalty sweep made by scripts/sweep_penalty.sh.

Usage:  scripts/sweep_penalty.py DIR PAIR V1 V2 ...   (a V may be `auto`: the penalty the run chose)

Reads DIR/penalty_<V>.json (the `--summary json` line) and DIR/penalty_<V>.h5 for each
value V, prints a Markdown table with one row per value and per side of the pair that
carries Gauss points (one side against a rigid obstacle; both sides of a two-half-pass
pair between two bodies, in the order of `between`): penalty, side, status, that side's
errors against the analytic reference of /reference/<PAIR> when there is one (the first
side's unprefixed attributes, the second side's prefixed with its name, e.g.
`lower.v1.l2`), the side's `max_penetration` and `normal_force` under
/results/contact/<PAIR>/<side>, Newton iterations, wall time. A row given as `auto` is
labelled so, with the penalty the run used (the pair's `penalty` attribute). The table
is written also as DIR/sweep.csv, and DIR/sweep.png plots the L2 errors against penalty
when a reference exists, otherwise the max penetration against penalty (both log-log),
one curve per side. A value whose run failed is listed with its status and left out of
the plot. Needs /usr/bin/python3 with numpy, h5py and matplotlib (python3-yaml to order
the sides as in the deck; alphabetical without it).
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

COLUMNS = ["penalty", "side", "status", "l2", "peak", "half_width", "gauss_l2", "max_penetration",
           "normal_force", "newton_iterations", "cutbacks", "wall_s", "results", "given"]
ERRORS = ("l2", "peak", "half_width", "gauss_l2")


def deck_side_order(h5, pair):
    """The pair's `between` from the /deck text ([] when unreadable)."""
    if "deck" not in h5:
        return []
    text = h5["deck"][()]
    if isinstance(text, bytes):
        text = text.decode()
    try:
        import yaml  # python3-yaml; optional
        deck = yaml.safe_load(str(text)) or {}
        for c in deck.get("contact") or []:
            if isinstance(c, dict) and c.get("name") == pair:
                return [str(b) for b in c.get("between") or []]
    except Exception:  # no yaml module or an unexpected shape: alphabetical order
        pass
    return []


def carrying_sides(h5, pair):
    """The pair's side groups that carry Gauss points, first carrying side first: the
    side whose reference errors are unprefixed (the others are stored as `<side>.l2`),
    else the order of `between` in the deck, else alphabetical."""
    if "results" not in h5 or "contact" not in h5["results"] or pair not in h5["results"]["contact"]:
        return []
    group = h5["results"]["contact"][pair]
    sides = sorted(k for k in group if isinstance(group[k], h5py.Group))
    order = deck_side_order(h5, pair)
    sides.sort(key=lambda k: order.index(k) if k in order else len(order))
    if "reference" in h5 and pair in h5["reference"]:
        attrs = h5["reference"][pair].attrs
        sides.sort(key=lambda k: f"{k}.l2" in attrs)  # stable: the unprefixed (first) side leads
    return sides


def read_run(directory, value):
    """What every side of one run shares: penalty as given, status and counters of the summary."""
    run = {c: float("nan") for c in COLUMNS}
    # `auto` (the deck's documented value) is the penalty the run chose: the pair's
    # `penalty` attribute in its results, NaN until the run wrote it.
    run.update(penalty=float("nan") if value == "auto" else float(value), side="-", status="missing",
               results=f"penalty_{value}.h5", given=value)
    summary_path = os.path.join(directory, f"penalty_{value}.json")
    if os.path.exists(summary_path):
        with open(summary_path) as f:
            lines = [ln for ln in f.read().splitlines() if ln.startswith("{")]
        if lines:
            s = json.loads(lines[-1])
            run.update(status=s.get("status", "?"), newton_iterations=s.get("newton_iterations", math.nan),
                       cutbacks=s.get("cutbacks", math.nan), wall_s=s.get("wall_s", math.nan))
        else:
            run["status"] = "error (see .err)"
    return run


def read_one(directory, pair, value):
    """The rows of one run: one per side of the pair that carries Gauss points (one row with
    side "-" when the results file or the pair is missing)."""
    run = read_run(directory, value)
    h5_path = os.path.join(directory, run["results"])
    if not os.path.exists(h5_path):
        return [run]
    rows = []
    with h5py.File(h5_path, "r") as f:
        contact = f["results"]["contact"] if "results" in f and "contact" in f["results"] else {}
        if value == "auto" and pair in contact and "penalty" in contact[pair].attrs:
            run["penalty"] = float(contact[pair].attrs["penalty"])
        reference = f["reference"][pair].attrs if "reference" in f and pair in f["reference"] else {}
        for k, side in enumerate(carrying_sides(f, pair)):
            row = dict(run, side=side)
            attrs = contact[pair][side].attrs
            for key in ("max_penetration", "normal_force"):
                if key in attrs:
                    row[key] = float(attrs[key])
            prefix = "" if k == 0 else f"{side}."  # docs/results.md: the second side's errors carry its name
            for key in ERRORS:
                if prefix + key in reference:
                    row[key] = float(reference[prefix + key])
            rows.append(row)
    return rows or [run]


def cell(v, spec):
    if isinstance(v, str):
        return v
    return "-" if v is None or (isinstance(v, float) and math.isnan(v)) else format(v, spec)


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    directory, pair, values = argv[0], argv[1], argv[2:]
    rows = [row for v in values for row in read_one(directory, pair, v)]
    sides = list(dict.fromkeys(r["side"] for r in rows if r["side"] != "-"))
    # By penalty (an auto run that wrote nothing: last), then the sides in pair order.
    rows.sort(key=lambda r: (math.isnan(r["penalty"]), r["penalty"],
                             sides.index(r["side"]) if r["side"] in sides else len(sides)))
    has_reference = any(not math.isnan(r["l2"]) for r in rows)

    print(f"\nPenalty sweep of pair {pair} ({directory}); errors in % against /reference/{pair}"
          if has_reference else f"\nPenalty sweep of pair {pair} ({directory}); no analytic reference in the deck")
    if len(sides) > 1:
        print(f"Both sides carry Gauss points ({', '.join(sides)}): each has its own pressure and its own errors.")
    print("| penalty | side | status | L2 % | peak % | half-width % | L2 Gauss % | max penetration | normal force "
          "| Newton | wall s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        pct = {k: 100 * r[k] for k in ERRORS}
        label = f"{r['penalty']:.2e} (auto)" if r["given"] == "auto" else f"{r['penalty']:.0e}"
        print(f"| {label} | {r['side']} | {r['status']} | {cell(pct['l2'], '.2f')} | {cell(pct['peak'], '+.2f')} | "
              f"{cell(pct['half_width'], '+.2f')} | {cell(pct['gauss_l2'], '.2f')} | {cell(r['max_penetration'], '.3e')} | "
              f"{cell(r['normal_force'], '.4g')} | {cell(r['newton_iterations'], 'd')} | {cell(r['wall_s'], '.3f')} |")
    with open(os.path.join(directory, "sweep.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS)
        w.writeheader()
        w.writerows(rows)

    done = [r for r in rows if r["status"] == "completed"]
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    for side in sides:
        mine = [r for r in done if r["side"] == side]
        penalty = [r["penalty"] for r in mine]
        name = f"{side}: " if len(sides) > 1 else ""
        if has_reference:
            ax.loglog(penalty, [100 * r["l2"] for r in mine], "-o", label=f"{name}L2, post-processed")
            ax.loglog(penalty, [100 * r["gauss_l2"] for r in mine], ":x", label=f"{name}L2, Gauss points")
        else:
            ax.loglog(penalty, [r["max_penetration"] for r in mine], "-o", label=f"{side}")
    if has_reference:
        ax.set_ylabel(f"L2 error against /reference/{pair} [%]")
    else:
        ax.set_ylabel("max penetration")
    if sides:
        ax.legend(fontsize=8)
    ax.set_xlabel(f"penalty (contact.{pair}.penalty)")
    ax.grid(True, which="both", alpha=0.3)
    ax.set_title(f"Penalty sweep: {os.path.basename(os.path.normpath(directory))}, pair {pair}")
    fig.tight_layout()
    png = os.path.join(directory, "sweep.png")
    fig.savefig(png, dpi=110)
    print(f"\nwrote {os.path.join(directory, 'sweep.csv')} and {png}")
    return 0 if done and all(r["status"] == "completed" for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
