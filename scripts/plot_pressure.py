#!/usr/bin/python3
"""Plot the contact pressure of an igacontact results file against the Hertz reference.

Usage:  scripts/plot_pressure.py RESULTS.h5 [-o PNG] [--pair NAME] [--step KKKK] [--radial]

Reads only the documented layout (docs/results.md). Which increment: --step KKKK
(/steps/KKKK), else the last converged one (/results), unless its contact pressure is
zero everywhere (a load path that presses and releases ends with no contact): then the
stored step of largest total contact force (the sum of the sides' `normal_force` over
the plotted pairs). The title and stdout name the step drawn, its load factor (the
pseudo-time t with amplitudes) and why it was chosen. It plots the pair of
/reference if there is one (or --pair), else every pair, in deck order (the order
of `contact` in the /deck text; HDF5 lists groups alphabetically). For each side
carrying Gauss points it draws
  - gauss_points/reference_coordinates + pressure as markers,
  - postprocessed/reference_coordinates + pressure as a line ("post-processed (NURBS)"),
  - /reference/<pair>/pressure (analytic, dashed) when present.
With a reference, abscissae are x = (X - center) . tangent (attributes of
/reference/<pair>), plotted as x/a against p/p0 and zoomed to |x/a| <= 1.5; the
title quotes the stored errors (l2, peak, half_width). Without one, each side is
plotted against its first reference coordinate X when X is monotonic along the
side, else against its arc length in the reference configuration (measured along
the side's post-processed samples, the same for every pair that shares the side).
Each pair and side is its own series, sorted by its abscissa: a side touched by
two pairs gives two curves, never one zigzag. One-sided data (a quarter model)
are mirrored to negative x as a lighter copy (reference plots only).
A 3D result without a reference (a contact face, not a curve) is drawn as a
pressure map of each face: the post-processed samples (their grid, split into
triangles) in the reference configuration, projected onto the plane normal to the
contact resultant (the pair's obstacle_force, else the pressure-weighted normal of
the best-fit plane of the pressed Gauss points), zoomed to the contact zone, with
the pressed Gauss points as dots. --radial draws instead the pressure against the
distance r from the peak in that plane (Gauss points and samples).
A 2D pair with friction gets a second panel below the pressure: the tangential
traction (gauss_points/tangential_traction, markers by stick/slip status, and the
post-processed line) with the Coulomb bound +-mu p of the post-processed pressure.
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
    parser.add_argument("--step", help="increment KKKK under /steps (default: the last one, or the one of largest "
                                       "contact force when the last has no contact)")
    parser.add_argument("--radial", action="store_true",
                        help="3D without a reference: pressure against the distance from the peak, not a map")
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


def step_groups(h5):
    """The stored increments: [(name, group)] in increment order ('steps/0001', ...)."""
    if "steps" not in h5:
        return []
    return [(f"steps/{k}", h5["steps"][k]) for k in sorted(h5["steps"].keys())]


def load_factor(group):
    value = attribute(group.attrs, "load_factor")
    return None if value is None else float(value)


def describe(name, group):
    """'/steps/0010 (load factor 1)': the step's name and its load factor (pseudo-time)."""
    t = load_factor(group)
    return f"/{name}" + (f" (load factor {t:g})" if t is not None else "")


def contact_force(group, pair_filter):
    """Total contact force of one increment: the sum of the `normal_force` of every side
    carrying Gauss points (Σ pressure × weight where the attribute is missing), over the
    pairs pair_filter lets through; 0 without contact data."""
    if "contact" not in group:
        return 0.0
    total = 0.0
    for pair in group["contact"]:
        if not pair_filter(pair):
            continue
        for side in contact_sides(group, pair):
            force = attribute(side.attrs, "normal_force")
            if force is None:
                gauss = side["gauss_points"]
                pressure = np.asarray(gauss["pressure"][()], dtype=float)
                weight = np.asarray(gauss["weight"][()], dtype=float) if "weight" in gauss else np.ones(len(pressure))
                force = float(np.sum(pressure * weight))
            total += abs(float(force))
    return total


def has_pressure(group, pair_filter):
    """Whether any Gauss point of the plotted pairs carries a pressure > 0."""
    if "contact" not in group:
        return False
    return any(np.any(np.asarray(side["gauss_points"]["pressure"][()], dtype=float) > 0)
               for pair in group["contact"] if pair_filter(pair) for side in contact_sides(group, pair))


def results_group(h5, step, pair=None):
    """The increment to draw: (group, name, why). --step KKKK if given; else the last
    converged increment, unless its contact pressure is zero everywhere, then the stored
    increment of largest total contact force. `why` says which and why, for the title."""
    pair_filter = (lambda name: True) if pair is None else (lambda name: name == pair)
    if step is not None:
        key = f"steps/{int(step):04d}" if step.isdigit() else f"steps/{step}"
        if key not in h5:
            sys.exit(f"error: {key} not found in the results file")
        return h5[key], key, f"{describe(key, h5[key])}: the step asked for (--step)"
    steps = step_groups(h5)
    if "results" in h5:
        last, last_name = h5["results"], "results"
        for name, group in steps:  # /results is a second name of the last stored step
            if group == last:
                last_name = name
    elif steps:
        last_name, last = steps[-1]
    else:
        sys.exit("error: the results file has no /results and no /steps (did the run converge any increment?)")
    if has_pressure(last, pair_filter):
        return last, last_name, f"{describe(last_name, last)}: the last step"
    forces = [(contact_force(group, pair_filter), name, group) for name, group in steps]
    best = max(forces, key=lambda f: f[0], default=(0.0, None, None))
    if best[0] > 0:
        return best[2], best[1], (f"{describe(best[1], best[2])}: the step of largest total contact force "
                                  f"({best[0]:.4g}); the last step, {describe(last_name, last)}, has no contact")
    why = f"{describe(last_name, last)}: the last step; no contact pressure in it"
    if len(steps) > 1:
        return last, last_name, why + " or any stored step"
    peak = history_peak(h5, pair_filter)
    if peak is not None:  # output.every_step: false kept only the last increment
        why += (f"; the largest contact force ({peak[0]:.4g}) was at load factor {peak[1]:g}, not stored "
                "(output.every_step: false)")
    return last, last_name, why


def history_peak(h5, pair_filter):
    """(largest total contact force, its load factor) from /history, or None without one > 0."""
    if "history" not in h5 or "contact" not in h5["history"] or "load_factor" not in h5["history"]:
        return None
    t = np.asarray(h5["history"]["load_factor"][()], dtype=float)
    total = np.zeros(len(t))
    for pair, group in h5["history"]["contact"].items():
        if pair_filter(pair):
            for side in group.values():
                if isinstance(side, h5py.Group) and "normal_force" in side:
                    total += np.abs(np.asarray(side["normal_force"][()], dtype=float).reshape(len(t)))
    k = int(np.argmax(total)) if len(t) else 0
    return (float(total[k]), float(t[k])) if len(t) and total[k] > 0 else None


def deck_pair_order(h5):
    """Contact pair names in deck order, from the /deck text ([] when unreadable)."""
    if "deck" not in h5:
        return []
    text = h5["deck"][()]
    if isinstance(text, np.ndarray):  # a one-element string array
        text = text.reshape(-1)[0]
    if isinstance(text, bytes):
        text = text.decode()
    try:
        import yaml  # python3-yaml; optional
        deck = yaml.safe_load(text) or {}
        return [c["name"] for c in deck.get("contact") or [] if isinstance(c, dict) and "name" in c]
    except Exception:  # no yaml module or an unexpected shape: alphabetical order
        return []


def choose_pairs(h5, group, requested):
    """The pairs to plot: --pair, else the reference's pair, else all in deck order."""
    pairs = list(group["contact"].keys()) if "contact" in group else []
    if requested is not None:
        if requested not in pairs:
            sys.exit(f"error: pair '{requested}' not found; pairs: {', '.join(pairs) or 'none'}")
        return [requested]
    if "reference" in h5:
        for name in h5["reference"]:
            if name in pairs:
                return [name]
    if not pairs:
        sys.exit("error: no contact pairs in this increment")
    order = deck_pair_order(h5)
    return [p for p in order if p in pairs] + [p for p in pairs if p not in order]


class SideAbscissa:
    """Abscissa along one side without a reference: X if X is monotonic along the side's
    post-processed samples (stored in side order), else the arc length of that polyline."""

    def __init__(self, samples):
        self.samples = np.asarray(samples, dtype=float)
        x = self.samples[:, 0] if self.samples.size else np.zeros(0)
        steps = np.diff(x)
        self.use_x = x.size < 2 or bool(np.all(steps > 0) or np.all(steps < 0))
        lengths = np.linalg.norm(np.diff(self.samples, axis=0), axis=1) if x.size > 1 else np.zeros(0)
        self.s = np.concatenate([[0.0], np.cumsum(lengths)])
        self.label = "X  (first reference coordinate)" if self.use_x else "arc length s along the side (reference)"

    def __call__(self, coordinates):
        coordinates = np.asarray(coordinates, dtype=float)
        if self.use_x or len(self.samples) < 2:
            return coordinates[:, 0]
        # Arc length of the closest point on the sample polyline.
        a, b = self.samples[:-1], self.samples[1:]
        ab = b - a
        length2 = np.maximum(np.einsum("ij,ij->i", ab, ab), np.finfo(float).tiny)
        out = np.empty(len(coordinates))
        for k, point in enumerate(coordinates):
            t = np.clip(np.einsum("ij,ij->i", point - a, ab) / length2, 0.0, 1.0)
            distance = np.linalg.norm(a + t[:, None] * ab - point, axis=1)
            j = int(np.argmin(distance))
            out[k] = self.s[j] + t[j] * (self.s[j + 1] - self.s[j])
        return out


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
        # 3D point contact: the abscissa is the distance from the centre in the contact plane.
        self.normal = attribute(attrs, "normal")
        self.a = float(attribute(attrs, "a") or 1.0)
        self.p0 = float(attribute(attrs, "p0") or 1.0)

    def x(self, coordinates):
        coordinates = np.asarray(coordinates, dtype=float)
        if coordinates.ndim == 1:
            return coordinates / self.a
        if self.center is None or self.tangent is None:
            return coordinates[:, 0] / self.a
        if self.normal is not None and coordinates.shape[1] == 3:
            n = np.asarray(self.normal, dtype=float)
            n = n / np.linalg.norm(n)
            v = coordinates - np.asarray(self.center, dtype=float)
            return np.linalg.norm(v - np.outer(v @ n, n), axis=1) / self.a
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


def plot_with_reference(ax, h5, group, group_name, pair, args, colours):
    """The Hertz-style plot of one pair against its analytic reference; returns the title."""
    reference = h5["reference"][pair]
    axis = Abscissa(reference)
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
        if "postprocessed" in side:
            post = side["postprocessed"]
            # A face's samples form a grid, not a line along r: draw them as dots.
            line = dict(linewidth=1.5) if axis.normal is None else dict(marker=".", markersize=2, linestyle="none")
            plot_series(ax, axis.x(post["reference_coordinates"][()]), axis.p(post["pressure"][()]), mirror,
                        color=colour, label=f"{name}: post-processed (NURBS)", **line)
    title = f"{args.results.name}: pair {pair}, /{group_name}"
    xr = reference["x"][()] / axis.a if "x" in reference else axis.x(reference["coordinates"][()])
    kind = attribute(reference.attrs, "type") or "Hertz"
    plot_series(ax, np.asarray(xr), axis.p(reference["pressure"][()]), False, color="black",
                linestyle="--", linewidth=1.2, label=f"analytic ({kind})")
    errors = [(label, attribute(reference.attrs, *keys)) for label, keys in
              (("L2", ("l2", "L2")), ("peak", ("peak",)), ("half-width", ("half_width", "half-width")),
               ("contact radius", ("contact_radius",)))]
    quoted = ", ".join(f"{label} {100 * value:+.2f} %" if label != "L2" else f"{label} {100 * value:.2f} %"
                       for label, value in errors if value is not None)
    if quoted:
        title += "\n" + quoted
    ax.set_xlim(-ZOOM, ZOOM)
    ax.set_xlabel("x / a  (reference configuration)" if axis.normal is None
                  else "r / a, distance from the contact centre in the contact plane (reference configuration)")
    ax.set_ylabel("p / p0")
    return title


def plot_pairs(ax, group, group_name, pairs, args, colours):
    """Every side of every pair as its own series, against X or the side's arc length; returns the title."""
    abscissae = {}  # side name -> SideAbscissa, shared by the pairs touching that side
    labels = set()
    series = 0
    for pair in pairs:
        sides = [s for s in group["contact"][pair].values() if isinstance(s, h5py.Group) and "gauss_points" in s]
        for side in sides:
            name = side.name.rsplit("/", 1)[-1]
            if name not in abscissae:
                samples = (side["postprocessed"]["reference_coordinates"][()] if "postprocessed" in side
                           else side["gauss_points"]["reference_coordinates"][()])
                abscissae[name] = SideAbscissa(samples)
            axis = abscissae[name]
            labels.add(axis.label)
            colour = colours[series % len(colours)]
            series += 1
            gauss = side["gauss_points"]
            plot_series(ax, axis(gauss["reference_coordinates"][()]), np.asarray(gauss["pressure"][()], dtype=float),
                        False, color=colour, marker="o", markersize=3.5, linestyle="none",
                        label=f"{pair} {name}: Gauss points")
            if "postprocessed" in side:
                post = side["postprocessed"]
                plot_series(ax, axis(post["reference_coordinates"][()]), np.asarray(post["pressure"][()], dtype=float),
                            False, color=colour, linewidth=1.5, label=f"{pair} {name}: post-processed (NURBS)")
    if series == 0:
        sys.exit(f"error: no side with Gauss points in /{group_name}")
    ax.set_xlabel(" / ".join(sorted(labels)))
    ax.set_ylabel("contact pressure p")
    return f"{args.results.name}: " + (f"pair {pairs[0]}" if len(pairs) == 1 else "pairs " + ", ".join(pairs)) + \
        f", /{group_name}"


def has_friction(group, pairs):
    return any("tangential_traction" in side["gauss_points"] for pair in pairs for side in contact_sides(group, pair))


def plot_tangential(ax, group, pairs, colours):
    """The tangential traction (local tangent component) of every frictional side, with the Coulomb bound mu p."""
    series = 0
    for pair in pairs:
        mu = group["contact"][pair].attrs.get("friction_coefficient")
        for side in contact_sides(group, pair):
            gauss = side["gauss_points"]
            if "tangential_traction" not in gauss:
                continue
            name = side.name.rsplit("/", 1)[-1]
            axis = SideAbscissa(side["postprocessed"]["reference_coordinates"][()])
            colour = colours[series % len(colours)]
            series += 1
            x = axis(gauss["reference_coordinates"][()])
            t = np.asarray(gauss["tangential_traction"][()], dtype=float).reshape(len(x), -1)[:, 0]
            status = np.asarray(gauss["status"][()])
            for code, marker, what in ((1, "o", "stick"), (2, "x", "slip")):
                chosen = status == code
                if chosen.any():
                    ax.plot(x[chosen], t[chosen], marker=marker, linestyle="none", markersize=4, color=colour,
                            label=f"{pair} {name}: Gauss points, {what}")
            post = side["postprocessed"]
            xp = axis(post["reference_coordinates"][()])
            tp = np.asarray(post["tangential_traction"][()], dtype=float).reshape(len(xp), -1)[:, 0]
            order = np.argsort(xp)
            ax.plot(xp[order], tp[order], color=colour, linewidth=1.5, label=f"{pair} {name}: post-processed")
            if mu is not None:
                p = np.asarray(post["pressure"][()], dtype=float)
                ax.plot(xp[order], mu * p[order], color=colour, linestyle="--", linewidth=0.8, label=f"± μp (μ = {mu:g})")
                ax.plot(xp[order], -mu * p[order], color=colour, linestyle="--", linewidth=0.8)
    ax.set_ylabel("tangential traction t_T")
    ax.axhline(0.0, color="grey", linewidth=0.5)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)


def contact_sides(group, pair):
    return [s for s in group["contact"][pair].values() if isinstance(s, h5py.Group) and "gauss_points" in s]


def is_3d(group, pairs):
    for pair in pairs:
        for side in contact_sides(group, pair):
            return side["gauss_points"]["reference_coordinates"].shape[1] == 3
    return False


def contact_normal(pair_group, points, pressure, weight):
    """Unit direction of the contact resultant: the pair's obstacle_force if stored, else the
    normal of the plane that best fits the pressed points (weights p w; all points if fewer
    than three are pressed): the eigenvector of their weighted covariance with the smallest
    eigenvalue."""
    force = attribute(pair_group.attrs, "obstacle_force")
    if force is not None and np.linalg.norm(force) > 0:
        return np.asarray(force, dtype=float) / np.linalg.norm(force)
    w = np.asarray(pressure, dtype=float) * np.asarray(weight, dtype=float)
    if np.count_nonzero(w > 0) < 3:
        w = np.ones(len(points))
    w = np.clip(w, 0.0, None)
    centre = w @ points / w.sum()
    covariance = (points - centre).T @ ((points - centre) * w[:, None])
    return np.linalg.eigh(covariance)[1][:, 0]


def plane_basis(normal):
    """Two unit vectors spanning the plane normal to `normal`: e1 from the coordinate axis
    most nearly in the plane, e2 = +-(n x e1), its largest component positive (a map seen
    from either side of the plane reads the same way)."""
    axis = np.eye(3)[int(np.argmin(np.abs(normal)))]
    e1 = axis - (axis @ normal) * normal
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(normal, e1)
    return e1, e2 if e2[np.argmax(np.abs(e2))] > 0 else -e2


def grid_triangles(post, n_samples):
    """Triangles (k x 3 indices) of the post-processed samples: each cell of each grid (u
    fastest) split in two; None when the samples carry no grid shape."""
    if "patch_grid_shape" in post:
        shapes = np.asarray(post["patch_grid_shape"][()], dtype=int).reshape(-1, 2)
    elif "grid_shape" in post.attrs:
        shapes = np.asarray(post.attrs["grid_shape"], dtype=int).reshape(-1, 2)
    else:
        return None
    triangles, offset = [], 0
    for n_v, n_u in shapes:
        if n_v >= 2 and n_u >= 2:
            j, i = np.meshgrid(np.arange(n_v - 1), np.arange(n_u - 1), indexing="ij")
            a = (offset + j * n_u + i).ravel()
            triangles += [np.column_stack([a, a + 1, a + n_u + 1]), np.column_stack([a, a + n_u + 1, a + n_u])]
        offset += n_v * n_u
    if offset != n_samples or not triangles:
        return None
    return np.concatenate(triangles)


class FaceProjection:
    """A contact face seen along the contact resultant: in-plane coordinates of its points."""

    def __init__(self, pair_group, gauss):
        points = np.asarray(gauss["reference_coordinates"][()], dtype=float)
        self.normal = contact_normal(pair_group, np.asarray(gauss["coordinates"][()], dtype=float),
                                     gauss["pressure"][()], gauss["weight"][()] if "weight" in gauss
                                     else np.ones(len(points)))
        self.e1, self.e2 = plane_basis(self.normal)

    def __call__(self, coordinates):
        coordinates = np.asarray(coordinates, dtype=float)
        return coordinates @ self.e1, coordinates @ self.e2


def pressed_zone(x, y, pressure):
    """Centre and half-width of the box around the points with p > 0 (None if none)."""
    pressed = np.asarray(pressure) > 0
    if not np.any(pressed):
        return None
    lo = np.array([x[pressed].min(), y[pressed].min()])
    hi = np.array([x[pressed].max(), y[pressed].max()])
    return 0.5 * (lo + hi), 0.5 * np.max(hi - lo)


def plot_face_map(ax, fig, side, projection, title):
    """Pressure map of one face: filled contours of the post-processed samples over their
    grid triangles (Delaunay of the Gauss points without samples), front faces only."""
    import matplotlib.tri as mtri
    gauss = side["gauss_points"]
    xg, yg = projection(gauss["reference_coordinates"][()])
    pg = np.asarray(gauss["pressure"][()], dtype=float)
    if "postprocessed" in side:
        post = side["postprocessed"]
        x, y = projection(post["reference_coordinates"][()])
        p = np.asarray(post["pressure"][()], dtype=float)
        triangles = grid_triangles(post, len(p))
    else:
        x, y, p, triangles = xg, yg, pg, None
    if triangles is not None:
        # Keep the triangles facing the same way as those under pressure: a face that
        # curves beyond 90 degrees would otherwise lay its back over the contact zone.
        area = ((x[triangles[:, 1]] - x[triangles[:, 0]]) * (y[triangles[:, 2]] - y[triangles[:, 0]]) -
                (x[triangles[:, 2]] - x[triangles[:, 0]]) * (y[triangles[:, 1]] - y[triangles[:, 0]]))
        pressed = np.any(p[triangles] > 0, axis=1)
        front = np.sign(np.sum(area[pressed])) if np.any(pressed) else np.sign(np.sum(area))
        keep = area * (front if front != 0 else 1.0) > 1e-14 * np.max(np.abs(area))
        triangulation = mtri.Triangulation(x, y, triangles[keep])
    else:
        triangulation = mtri.Triangulation(x, y)
    levels = np.linspace(0.0, max(np.max(p), np.finfo(float).tiny), 21)
    filled = ax.tricontourf(triangulation, np.clip(p, 0.0, None), levels=levels, cmap="viridis")
    fig.colorbar(filled, ax=ax, label="contact pressure p (post-processed)" if "postprocessed" in side
                 else "contact pressure p (Gauss points)")
    ax.plot(xg[pg > 0], yg[pg > 0], linestyle="none", marker=".", markersize=1.5, color="black",
            label="Gauss points with p > 0")
    zone = pressed_zone(x, y, p) or pressed_zone(xg, yg, pg)
    if zone is not None:
        centre, half = zone
        half = ZOOM * max(half, 1e-12)
        ax.set_xlim(centre[0] - half, centre[0] + half)
        ax.set_ylim(centre[1] - half, centre[1] + half)
    ax.set_aspect("equal")
    e1, e2 = projection.e1, projection.e2
    ax.set_xlabel("along ({:.3g}, {:.3g}, {:.3g})  (reference configuration)".format(*(e1 + 0.0)), fontsize=8)
    ax.set_ylabel("along ({:.3g}, {:.3g}, {:.3g})".format(*(e2 + 0.0)), fontsize=8)
    ax.set_title(title + "\nseen along the contact resultant ({:.3g}, {:.3g}, {:.3g})".format(*projection.normal),
                 fontsize=9)


def plot_face_radial(ax, side, projection, title, colour):
    """Pressure against the in-plane distance r from the peak of the face."""
    gauss = side["gauss_points"]
    xg, yg = projection(gauss["reference_coordinates"][()])
    pg = np.asarray(gauss["pressure"][()], dtype=float)
    if "postprocessed" in side:
        xs, ys = projection(side["postprocessed"]["reference_coordinates"][()])
        ps = np.asarray(side["postprocessed"]["pressure"][()], dtype=float)
    else:
        xs, ys, ps = xg, yg, pg
    peak = int(np.argmax(ps))
    rg = np.hypot(xg - xs[peak], yg - ys[peak])
    rs = np.hypot(xs - xs[peak], ys - ys[peak])
    ax.plot(rs, ps, linestyle="none", marker=".", markersize=2, color=colour, alpha=0.5,
            label="post-processed (NURBS) samples")
    ax.plot(rg, pg, linestyle="none", marker="o", markersize=2.5, color="black", label="Gauss points")
    pressed = np.concatenate([rg[pg > 0], rs[ps > 0]])
    if pressed.size:
        ax.set_xlim(0.0, ZOOM * max(np.max(pressed), 1e-12))
    ax.set_xlabel("r, distance from the peak in the plane normal to the contact resultant (reference)", fontsize=8)
    ax.set_ylabel("contact pressure p")
    ax.set_title(title + "\nradial profile about the peak at ({:.4g}, {:.4g}, {:.4g})".format(
        *np.asarray(side["postprocessed"]["reference_coordinates"][peak] if "postprocessed" in side
                    else gauss["reference_coordinates"][peak])), fontsize=9)


def plot_faces(h5, group, group_name, pairs, args):
    """3D without a reference: one panel per contact face (map, or radial profile with --radial)."""
    faces = [(pair, side) for pair in pairs for side in contact_sides(group, pair)]
    if not faces:
        sys.exit(f"error: no side with Gauss points in /{group_name}")
    n_cols = min(len(faces), 2)
    n_rows = (len(faces) + n_cols - 1) // n_cols
    fig, axes = plt.subplots(n_rows, n_cols, figsize=(6.5 * n_cols, 5.5 * n_rows), squeeze=False)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for k, (pair, side) in enumerate(faces):
        ax = axes.flat[k]
        projection = FaceProjection(group["contact"][pair], side["gauss_points"])
        title = f"{args.results.name}: pair {pair}, {side.name.rsplit('/', 1)[-1]}, /{group_name}"
        if args.radial:
            plot_face_radial(ax, side, projection, title, colours[k % len(colours)])
            ax.legend(fontsize=8)
            ax.grid(True, alpha=0.3)
        else:
            plot_face_map(ax, fig, side, projection, title)
    for ax in axes.flat[len(faces):]:
        ax.set_visible(False)
    fig.tight_layout()
    return fig


def main(argv):
    args = parse_args(argv)
    output = args.output or args.results.with_name(args.results.stem + "_pressure.png")
    with h5py.File(args.results, "r") as h5:
        group, group_name, why = results_group(h5, args.step, args.pair)
        print(f"drawn: {why}")
        pairs = choose_pairs(h5, group, args.pair)
        with_reference = len(pairs) == 1 and "reference" in h5 and pairs[0] in h5["reference"]
        if not with_reference and is_3d(group, pairs):
            fig = plot_faces(h5, group, group_name, pairs, args)
            fig.suptitle(why.replace("; ", ";\n"), fontsize=9)
            fig.tight_layout()
            fig.savefig(output, dpi=120)
            print(output)
            return 0
        friction = has_friction(group, pairs)
        if friction:  # the tangential traction in a second panel below the pressure
            fig, (ax, ax_t) = plt.subplots(2, 1, figsize=(8, 8), sharex=True)
        else:
            fig, ax = plt.subplots(figsize=(8, 5))
        colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
        if with_reference:
            title = plot_with_reference(ax, h5, group, group_name, pairs[0], args, colours)
        else:
            title = plot_pairs(ax, group, group_name, pairs, args, colours)
        ax.set_title(title + "\n" + why.replace("; ", ";\n"), fontsize=9)
        ax.axhline(0.0, color="grey", linewidth=0.5)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
        if friction:
            plot_tangential(ax_t, group, pairs, colours)
            ax_t.set_xlabel(ax.get_xlabel())
            ax.set_xlabel("")
        fig.tight_layout()
        fig.savefig(output, dpi=120)
    print(output)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
