#!/usr/bin/python3
"""Plot the contact pressure of an igacontact results file against the Hertz reference.

Usage:  scripts/plot_pressure.py RESULTS.h5 [-o PNG] [--pair NAME] [--step KKKK]

Reads only the documented layout (shared/spec/results.md). For the chosen pair
(default: the pair of /reference if there is one, else the first pair under
/results/contact) and each side carrying Gauss points it draws
  - gauss_points/reference_coordinates + pressure as markers,
  - postprocessed/reference_coordinates + pressure as a line ("post-processed (NURBS)"),
  - /reference/<pair>/pressure (analytic, dashed) when present.
With a reference, abscissae are x = (X - center) . tangent (attributes of
/reference/<pair>), plotted as x/a against p/p0 and zoomed to |x/a| <= 1.5; the
title quotes the stored errors (l2, peak, half_width). Without one, the first
reference coordinate and the raw pressure are plotted. One-sided data (a
quarter model) are mirrored to negative x as a lighter copy.
Writes RESULTS_pressure.png (or -o) with the Agg backend and prints its path.
Needs numpy, h5py and matplotlib (/usr/bin/python3 on the project machines).
"""

import argparse
import pathlib
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)
import numpy as np  # noqa: E402

ZOOM = 1.5  # |x/a| shown when a reference gives the scale
ONE_SIDED_SLACK = 1e-8  # relative round-off allowed on the "empty" side of x = 0


def parse_args(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("results", type=pathlib.Path, help="igacontact results file (.h5)")
    parser.add_argument("-o", "--output", type=pathlib.Path, help="PNG to write (default: RESULTS_pressure.png)")
    parser.add_argument("--pair", help="contact pair to plot (default: the reference's pair, else the first)")
    parser.add_argument("--step", help="increment KKKK under /steps instead of /results (the last one)")
    return parser.parse_args(argv)


def attribute(attrs, *names):
    """The first of `names` present in `attrs`, as a Python scalar or array; None if none is."""
    for name in names:
        if name in attrs:
            value = attrs[name]
            if isinstance(value, bytes):
                return value.decode()
            return value.item() if np.ndim(value) == 0 and hasattr(value, "item") else value
    return None


def results_group(h5, step):
    if step is not None:
        key = f"steps/{int(step):04d}" if step.isdigit() else f"steps/{step}"
        if key not in h5:
            sys.exit(f"error: {key} not found in the results file")
        return h5[key], key
    if "results" in h5:
        return h5["results"], "results"
    if "steps" in h5 and len(h5["steps"]) > 0:
        last = sorted(h5["steps"].keys())[-1]
        return h5["steps"][last], f"steps/{last}"
    sys.exit("error: the results file has no /results and no /steps (did the run converge any increment?)")


def choose_pair(h5, group, requested):
    pairs = list(group["contact"].keys()) if "contact" in group else []
    if requested is not None:
        if requested not in pairs:
            sys.exit(f"error: pair '{requested}' not found; pairs: {', '.join(pairs) or 'none'}")
        return requested
    if "reference" in h5:
        for name in h5["reference"]:
            if name in pairs:
                return name
    if not pairs:
        sys.exit("error: no contact pairs in this increment")
    return pairs[0]


class Abscissa:
    """Maps reference coordinates (n x d) to the plotted abscissa, and pressures to the ordinate."""

    def __init__(self, reference):
        self.reference = reference
        if reference is None:
            self.center, self.tangent, self.a, self.p0 = None, None, 1.0, 1.0
            return
        attrs = reference.attrs
        self.center = attribute(attrs, "center", "centre")
        self.tangent = attribute(attrs, "tangent")
        self.a = float(attribute(attrs, "a") or 1.0)
        self.p0 = float(attribute(attrs, "p0") or 1.0)

    def x(self, coordinates):
        coordinates = np.asarray(coordinates, dtype=float)
        if coordinates.ndim == 1:
            return coordinates / self.a
        if self.center is None or self.tangent is None:
            return coordinates[:, 0] / self.a
        tangent = np.asarray(self.tangent, dtype=float)
        tangent = tangent / np.linalg.norm(tangent)
        return (coordinates - np.asarray(self.center, dtype=float)) @ tangent / self.a

    def p(self, pressure):
        return np.asarray(pressure, dtype=float) / self.p0


def one_sided(x):
    if x.size == 0:
        return False
    slack = ONE_SIDED_SLACK * np.max(np.abs(x))
    return bool(np.all(x >= -slack) or np.all(x <= slack))


def plot_series(ax, x, p, mirror, **style):
    order = np.argsort(x)
    ax.plot(x[order], p[order], **style)
    if mirror:
        faded = dict(style, alpha=0.3, label=None)
        ax.plot(-x[order], p[order], **faded)


def main(argv):
    args = parse_args(argv)
    output = args.output or args.results.with_name(args.results.stem + "_pressure.png")
    with h5py.File(args.results, "r") as h5:
        group, group_name = results_group(h5, args.step)
        pair = choose_pair(h5, group, args.pair)
        reference = h5["reference"][pair] if "reference" in h5 and pair in h5["reference"] else None
        axis = Abscissa(reference)

        fig, ax = plt.subplots(figsize=(8, 5))
        colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
        extent = 0.0
        sides = [s for s in group["contact"][pair].values() if isinstance(s, h5py.Group) and "gauss_points" in s]
        if not sides:
            sys.exit(f"error: pair '{pair}' has no side with Gauss points in /{group_name}")
        for colour, side in zip(colours * 4, sides):
            name = side.name.rsplit("/", 1)[-1]
            gauss = side["gauss_points"]
            xg = axis.x(gauss["reference_coordinates"][()])
            mirror = one_sided(xg)
            pg = axis.p(gauss["pressure"][()])
            plot_series(ax, xg, pg, mirror, color=colour, marker="o", markersize=3.5, linestyle="none",
                        label=f"{name}: Gauss points" + (" (lighter: mirrored)" if mirror else ""))
            if pg.size and np.max(pg) > 0:  # the loaded zone, for the zoom without a reference
                loaded = np.abs(xg[pg > 0.01 * np.max(pg)])
                extent = max(extent, float(np.max(loaded)))
            if "postprocessed" in side:
                post = side["postprocessed"]
                plot_series(ax, axis.x(post["reference_coordinates"][()]), axis.p(post["pressure"][()]), mirror,
                            color=colour, linewidth=1.5, label=f"{name}: post-processed (NURBS)")

        title = f"{args.results.name}: pair {pair}, /{group_name}"
        if reference is not None:
            xr = reference["x"][()] / axis.a if "x" in reference else axis.x(reference["coordinates"][()])
            kind = attribute(reference.attrs, "type") or "Hertz"
            plot_series(ax, np.asarray(xr), axis.p(reference["pressure"][()]), False, color="black",
                        linestyle="--", linewidth=1.2, label=f"analytic ({kind})")
            errors = [(label, attribute(reference.attrs, *keys)) for label, keys in
                      (("L2", ("l2", "L2")), ("peak", ("peak",)), ("half-width", ("half_width", "half-width")))]
            quoted = ", ".join(f"{label} {100 * value:+.2f} %" if label != "L2" else f"{label} {100 * value:.2f} %"
                               for label, value in errors if value is not None)
            if quoted:
                title += "\n" + quoted
            ax.set_xlim(-ZOOM, ZOOM)
            ax.set_xlabel("x / a  (reference configuration)")
            ax.set_ylabel("p / p0")
        else:
            if extent > 0:
                ax.set_xlim(-ZOOM * extent if ax.get_xlim()[0] < 0 else ax.get_xlim()[0], ZOOM * extent)
            ax.set_xlabel("X  (first reference coordinate)")
            ax.set_ylabel("contact pressure p")
        ax.set_title(title, fontsize=10)
        ax.axhline(0.0, color="grey", linewidth=0.5)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(output, dpi=120)
    print(output)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
