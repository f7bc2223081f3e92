#!/usr/bin/python3
"""Plot of `igacontact study`: estimated relative error against wall time, per quantity.

Usage: /usr/bin/python3 scripts/plot_study.py DECK_study.csv [DECK_study.png]

Reads the CSV that `igacontact study` writes (columns level, dofs, wall_s, quantity,
value, extrapolated, observed_order, estimated_rel_error[, reference_value,
true_rel_error]) and draws, for every quantity with an error estimate, the
estimated relative discretization error of each level against the level's wall
time (log-log), and the true error where the deck has an analytic reference
(dashed). `igacontact study` calls it itself when python3 has matplotlib.
"""
import csv
import sys
from collections import OrderedDict


def main(argv):
    if len(argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    src = argv[1]
    out = argv[2] if len(argv) > 2 else src.rsplit(".", 1)[0] + ".png"
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("plot_study.py: matplotlib is missing (Debian: apt-get install python3-matplotlib)", file=sys.stderr)
        return 1
    series = OrderedDict()
    with open(src, newline="") as f:
        for row in csv.DictReader(f):
            s = series.setdefault(row["quantity"], {"t": [], "est": [], "t_true": [], "true": []})
            t = float(row["wall_s"])
            if row.get("estimated_rel_error"):
                e = float(row["estimated_rel_error"])
                if e > 0:
                    s["t"].append(t)
                    s["est"].append(e)
            if row.get("true_rel_error"):
                e = float(row["true_rel_error"])
                if e > 0:
                    s["t_true"].append(t)
                    s["true"].append(e)
    fig, ax = plt.subplots(figsize=(7.5, 5))
    drawn = 0
    for name, s in series.items():
        if not s["est"] and not s["true"]:
            continue
        line = None
        if s["est"]:
            (line,) = ax.loglog(s["t"], s["est"], "o-", label=name + " (estimated)")
            drawn += 1
        if s["true"]:
            color = line.get_color() if line is not None else None
            ax.loglog(s["t_true"], s["true"], "s--", color=color, label=name + " (true)")
            drawn += 1
    ax.set_xlabel("wall time per level [s]")
    ax.set_ylabel("relative error")
    ax.set_title("Refinement study: " + src.rsplit("/", 1)[-1])
    ax.grid(True, which="both", alpha=0.3)
    if drawn:
        ax.legend(fontsize=7)
    else:
        ax.text(0.5, 0.5, "no error estimate (one level, or every quantity converged)", ha="center",
                transform=ax.transAxes)
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
