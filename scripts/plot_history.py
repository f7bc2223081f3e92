#!/usr/bin/python3
"""Plot the forces of an igacontact run against the load factor (or the prescribed displacement).

Usage:  scripts/plot_history.py RESULTS.h5 [-o PNG]

Reads /history (results.md, "Additions"): load_factor (n), reactions/<body.side>
and reactions/total/<body> (n x d) and contact/<pair>/<body.side>/normal_force (n), one row per converged
increment. Draws every reaction component that is not zero throughout and every
contact normal force. The abscissa is the load factor, or, when the deck (the
/deck text) prescribes a displacement, the prescribed displacement of the first
constraint with a non-zero prescribed component, else the first non-zero motion of a
rigid obstacle: x = load factor x that value (both scale with the load factor). Writes RESULTS_history.png
(or -o) with the Agg backend and prints its path.
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


def prescribed_displacement(deck):
    """(label, value) of the first non-zero prescribed displacement component of the deck, or None."""
    for c in deck.get("constraints") or []:
        if not isinstance(c, dict) or not isinstance(c.get("displacement"), list):
            continue
        for k, value in enumerate(c["displacement"]):
            if value is not None and float(value) != 0.0:
                where = c.get("side") or c.get("surface") or "?"
                return f"{c.get('body', '?')}.{where} u_{COMPONENTS[k]}", float(value)
    # No prescribed displacement: a moving rigid obstacle drives the scene.
    for b in deck.get("bodies") or []:
        rigid = b.get("rigid") if isinstance(b, dict) else None
        motion = rigid.get("motion") if isinstance(rigid, dict) else None
        if isinstance(motion, list):
            for k, value in enumerate(motion):
                if value is not None and float(value) != 0.0:
                    return f"{b.get('name', '?')} motion {COMPONENTS[k]}", float(value)
    return None


def history_series(h5):
    """(x, x_label, curves) with curves a list of (label, values), all of length n."""
    if "history" not in h5 or "load_factor" not in h5["history"]:
        sys.exit("error: the results file has no /history/load_factor (written by igacontact 2 and later)")
    history = h5["history"]
    load = np.asarray(history["load_factor"][()], dtype=float).reshape(-1)
    prescribed = prescribed_displacement(deck_of(h5))
    if prescribed is None:
        x, x_label = load, "load factor"
    else:
        label, value = prescribed
        x, x_label = load * value, f"imposed displacement {label} (load factor x {value:g})"

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
    return x, x_label, curves


def main(argv):
    args = parse_args(argv)
    output = args.output or args.results.with_name(args.results.stem + "_history.png")
    with h5py.File(args.results, "r") as h5:
        x, x_label, curves = history_series(h5)
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
