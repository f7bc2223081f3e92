#!/usr/bin/python3
"""Plot the forces of an igacontact run against the load factor (or the prescribed displacement).

Usage:  scripts/plot_history.py RESULTS.h5 [-o PNG]

Usage:  scripts/plot_history.py RESULTS.h5 [-o PNG] [--constraint K]

Reads /history (results.md, "Additions"): load_factor (n, the pseudo-time t),
reactions/<body.side> and reactions/total/<body> (n x d), and per contact side
normal_force (n) and friction_force (n x d), one row per converged increment. Draws
every reaction and friction component that is not zero throughout and every contact
normal force. The abscissa is the pseudo-time, or, when the deck (the /deck text)
prescribes a displacement, the prescribed displacement of constraint item K
(--constraint; default: the first with a non-zero prescribed component; its largest
component), else the first non-zero motion of a rigid obstacle: x = a(t) x that
value, a the item's amplitude (docs/deck.md "Load paths"; without one the ramp
min(t, 1)). A press-then-slide deck plotted against the slide gives the
force-displacement loop. Writes RESULTS_history.png (or -o) with the Agg backend
and prints its path.
Needs numpy, h5py, matplotlib and yaml (/usr/bin/python3 on the project machines).
"""

import argparse
import pathlib
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)
import numpy as np  # noqa: E402

COMPONENTS = "xyz"


def parse_args(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("results", type=pathlib.Path, help="igacontact results file (.h5)")
    parser.add_argument("-o", "--output", type=pathlib.Path, help="PNG to write (default: RESULTS_history.png)")
    parser.add_argument("--constraint", type=int, help="constraint item whose prescribed displacement is the abscissa")
    return parser.parse_args(argv)


def deck_of(h5):
    """The resolved deck as a dict ({} when absent or unreadable)."""
    if "deck" not in h5:
        return {}
    text = h5["deck"][()]
    if isinstance(text, np.ndarray):
        text = text.reshape(-1)[0]
    if isinstance(text, bytes):
        text = text.decode()
    try:
        import yaml
        deck = yaml.safe_load(text)
        return deck if isinstance(deck, dict) else {}
    except Exception:
        return {}


def amplitude_of(item, t):
    """a(t) of a deck item: its amplitude [[t, a], ...] (held beyond the ends), else the ramp min(t, 1)."""
    points = item.get("amplitude") if isinstance(item, dict) else None
    if isinstance(points, list) and len(points) >= 2:
        times, values = zip(*[(float(p[0]), float(p[1])) for p in points])
        return np.interp(t, times, values)
    return np.interp(t, [0.0, 1.0], [0.0, 1.0])


def prescribed_displacement(deck, which=None):
    """(label, value, item) of a prescribed displacement component of the deck (constraint item
    `which`, else the first with a non-zero component), or a moving obstacle's; None when there is none."""
    constraints = deck.get("constraints") or []
    for index, c in enumerate(constraints):
        if which is not None and index != which:
            continue
        if not isinstance(c, dict) or not isinstance(c.get("displacement"), list):
            continue
        values = [0.0 if v is None else float(v) for v in c["displacement"]]
        k = int(np.argmax(np.abs(values)))
        if values[k] != 0.0:
            where = c.get("side") or c.get("surface") or "?"
            return f"{c.get('body', '?')}.{where} u_{COMPONENTS[k]}", values[k], c
    if which is not None:
        sys.exit(f"error: constraint item {which} prescribes no non-zero displacement")
    # No prescribed displacement: a moving rigid obstacle drives the scene.
    for b in deck.get("bodies") or []:
        rigid = b.get("rigid") if isinstance(b, dict) else None
        motion = rigid.get("motion") if isinstance(rigid, dict) else None
        if isinstance(motion, list):
            for k, value in enumerate(motion):
                if value is not None and float(value) != 0.0:
                    return f"{b.get('name', '?')} motion {COMPONENTS[k]}", float(value), rigid
    return None


def history_series(h5, which=None):
    """(x, x_label, curves) with curves a list of (label, values), all of length n."""
    if "history" not in h5 or "load_factor" not in h5["history"]:
        sys.exit("error: the results file has no /history/load_factor (written by igacontact 2 and later)")
    history = h5["history"]
    load = np.asarray(history["load_factor"][()], dtype=float).reshape(-1)
    prescribed = prescribed_displacement(deck_of(h5), which)
    if prescribed is None:
        x, x_label = load, "pseudo-time t (load factor)"
    else:
        label, value, item = prescribed
        x, x_label = amplitude_of(item, load) * value, f"imposed displacement {label} (a(t) x {value:g})"

    curves = []
    if "reactions" in history:
        # Sides and total/<body>; items/<k> repeat the same forces split by constraint item.
        reactions = history["reactions"]
        names = [n for n in reactions if isinstance(reactions[n], h5py.Dataset)]
        if "total" in reactions:
            names += [f"total/{n}" for n in reactions["total"]]
        for name in names:
            r = np.asarray(reactions[name][()], dtype=float).reshape(len(load), -1)
            for k in range(r.shape[1]):
                if np.any(r[:, k] != 0.0):
                    curves.append((f"reaction {name} ({COMPONENTS[k]})", r[:, k]))
    if "contact" in history:
        for pair in history["contact"]:
            for side in history["contact"][pair]:
                group = history["contact"][pair][side]
                if "normal_force" in group:
                    curves.append((f"contact {pair} {side}: normal force",
                                   np.asarray(group["normal_force"][()], dtype=float).reshape(-1)))
                if "friction_force" in group:
                    f = np.asarray(group["friction_force"][()], dtype=float).reshape(len(load), -1)
                    for k in range(f.shape[1]):
                        if np.any(f[:, k] != 0.0):
                            curves.append((f"contact {pair} {side}: friction force ({COMPONENTS[k]})", f[:, k]))
    return x, x_label, curves


def main(argv):
    args = parse_args(argv)
    output = args.output or args.results.with_name(args.results.stem + "_history.png")
    with h5py.File(args.results, "r") as h5:
        x, x_label, curves = history_series(h5, args.constraint)
    if not curves:
        sys.exit("error: /history has no reactions and no contact forces to plot")
    fig, ax = plt.subplots(figsize=(8, 5))
    for label, values in curves:
        ax.plot(x, values, marker="o", markersize=3, linewidth=1.5, label=label)
    ax.set_xlabel(x_label)
    ax.set_ylabel("force")
    ax.set_title(f"{args.results.name}: forces over the increments", fontsize=10)
    ax.axhline(0.0, color="grey", linewidth=0.5)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(output, dpi=120)
    print(output)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
