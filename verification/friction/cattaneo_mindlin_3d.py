#!/usr/bin/python3
"""Cattaneo-Mindlin (and Mindlin-Deresiewicz) check of a results file of
verification/friction/cattaneo_mindlin_3d.yaml: two identical bodies with paraboloid
ends z = +-(x^2 + y^2)/(2R), half model y >= 0, pressed by P, sheared along x by Q*
with P held, optionally unsheared to Q.

Identical bodies decouple the normal and tangential problems (Johnson, Contact
Mechanics, 7.1-7.2): the pressure is Hertz's and, in Mindlin's approximation (slip
along x everywhere; the neglected coupling is of order nu / (2 - nu) in the
traction's direction), with

    q_Q(r) = mu p0 sqrt(1 - r^2/a^2) - mu p0 (c_Q/a) sqrt(1 - r^2/c_Q^2) (r <= c_Q),
    c_Q/a  = (1 - Q/(mu P))^(1/3),

    sheared to Q* (Cattaneo-Mindlin):     q = q_{Q*},             stick zone c/a = (1 - Q*/(mu P))^(1/3);
    unsheared to Q (Mindlin-Deresiewicz): q = q_{Q*} - 2 q_{(Q* - Q)/2},
        stick zone c'/a = (1 - (Q* - Q)/(2 mu P))^(1/3), the annulus c' < r < a slipping back.

P and Q are read from the contact forces (the sides' normal_force and friction_force, x2
for the half model), a and p0 of Hertz from P: a = (3 P R* / (4 E*))^(1/3), R* = R/2,
E* = E / (2 (1 - nu^2)), p0 = 3P / (2 pi a^2). The centre of the contact is the
pressure's centroid in x (current configuration; y = 0 by symmetry).

Measured zones: a half disc of radius r has the area pi r^2 / 2, so the contact radius
and the stick radius are measured from the areas of the Gauss points that press and
that stick (sum of their weights): a_m = sqrt(2 A_p / pi), c_m = sqrt(2 A_stick / pi).
The extents of those points along x are printed too (they sit inside the true edge by
up to one Gauss spacing). L2 errors are over the union of the Hertz disc and the
pressed points, with the Gauss weights: of p relative to the L2 norm of p_Hertz, and of
the tangential traction vector against q e_x relative to the L2 norm of mu p_Hertz (the
2D script's convention); "rms/(mu p0)" is the same error as a root mean square over the
Hertz disc in units of mu p0 (= the former x sqrt(1/2)).

For each contact side with Gauss points (both under two-half-pass) this prints the
states pressed (t = 1), sheared (largest |Q|) and, if the path goes on, unsheared (the
last step), and a summary table. --plot FILE draws, for the first side, the pressure and
the traction along the x axis (the row of Gauss points nearest y = 0) against Hertz
and Mindlin, and the stick/slip map of the contact face.

Exit status 1 when a check fails: a stick zone off its theory by more than
--tolerance (8 %), tangential traction while only pressed above 2 % of mu p0, or
(after unloading) a slipping point outside the theory's c' whose traction has not
turned. Slipping points inside c' that still slip forward are counted and located, not
failed: they sit at the sheared state's stick edge, where the stick traction oscillates
on these meshes (verification/friction/README.md).

Usage: /usr/bin/python3 verification/friction/cattaneo_mindlin_3d.py RESULTS.h5 [--plot FIGURE.png]
"""
import argparse
import math
import sys

import h5py
import numpy as np

E, NU = 1000.0, 0.3  # the deck's material (make_cattaneo_mindlin_3d.py)


def hertz(P, R):
    """Two identical spheres (paraboloids) of radius R under the whole force P: a, p0."""
    e_star = E / (2.0 * (1.0 - NU**2))
    a = (3.0 * P * (R / 2.0) / (4.0 * e_star)) ** (1.0 / 3.0)
    return a, 3.0 * P / (2.0 * math.pi * a * a)


def q_mindlin(r, Q, mu, a, p0, P):
    """Cattaneo-Mindlin's traction magnitude (along the shear) for a monotonic shear Q >= 0."""
    c = a * max(1.0 - Q / (mu * P), 0.0) ** (1.0 / 3.0)
    outer = mu * p0 * np.sqrt(np.clip(1 - r**2 / a**2, 0, None))
    inner = np.where(r < c, mu * p0 * (c / a) * np.sqrt(np.clip(1 - r**2 / max(c, 1e-300) ** 2, 0, None)), 0.0)
    return np.where(r < a, outer - inner, 0.0)


def read_side(g):
    gp = g["gauss_points"]
    return dict(x=gp["coordinates"][:, 0], y=gp["coordinates"][:, 1], Y=gp["reference_coordinates"][:, 1],
                p=gp["pressure"][:], w=gp["weight"][:],
                status=gp["status"][:], t=gp["tangential_traction_vector"][:, :],
                P=2.0 * float(g.attrs["normal_force"]), Q=2.0 * float(g.attrs["friction_force"][0]))


def measure(s, mu, R, q_exact_of, c_theory):
    """Zones and errors of one side at one state; q_exact_of(r, a, p0, P) along the first shear."""
    p, w, t, status = s["p"], s["w"], s["t"], s["status"]
    active = p > 0
    P = s["P"]
    x0 = float(np.sum(p * w * s["x"]) / np.sum(p * w))
    xs, ys = s["x"] - x0, s["y"]
    r = np.hypot(xs, ys)
    stick = active & (status == 1)
    a_m = math.sqrt(2.0 * np.sum(w[active]) / math.pi)
    c_m = math.sqrt(2.0 * np.sum(w[stick]) / math.pi)
    a_x = 0.5 * (xs[active].max() - xs[active].min())
    c_x = 0.5 * (xs[stick].max() - xs[stick].min()) if stick.any() else 0.0
    a, p0 = hertz(P, R)
    inside = r < a
    p_exact = np.where(inside, p0 * np.sqrt(np.clip(1 - r**2 / a**2, 0, None)), 0.0)
    q_exact = q_exact_of(r, a, p0, P)
    zone = inside | active
    err_q = np.sum(w[zone] * ((t[zone, 0] - q_exact[zone]) ** 2 + t[zone, 1] ** 2 + t[zone, 2] ** 2))
    norm_mp = np.sum(w[zone] * (mu * p_exact[zone]) ** 2)
    q_err = math.sqrt(err_q / norm_mp) if norm_mp > 0 else float("nan")
    p_err = math.sqrt(np.sum(w[zone] * (p[zone] - p_exact[zone]) ** 2) / np.sum(w[zone] * p_exact[zone] ** 2))
    disc = math.pi * a * a / 2.0
    q_rms = math.sqrt(err_q / disc) / (mu * p0)
    ty = math.sqrt(np.sum(w[zone] * t[zone, 1] ** 2) / norm_mp) if norm_mp > 0 else float("nan")
    return dict(P=P, Q=s["Q"], x0=x0, xs=xs, ys=ys, Y=s["Y"], w=w, r=r, a=a, p0=p0, a_m=a_m, c_m=c_m, a_x=a_x, c_x=c_x,
                ratio=c_m / a_m, theory=c_theory, q_err=q_err, q_rms=q_rms, p_err=p_err, ty=ty,
                p=p, t=t, p_exact=p_exact, q_exact=q_exact, active=active, stick=stick, status=status,
                tmax=float(np.max(np.linalg.norm(t, axis=1))))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("results")
    parser.add_argument("--pair", default="mate")
    parser.add_argument("--radius", type=float, default=1.0, help="R of the paraboloids (the deck's)")
    parser.add_argument("--plot")
    parser.add_argument("--tolerance", type=float, default=0.08)
    parser.add_argument("--press-share", type=float, default=0.02)
    args = parser.parse_args()
    R = args.radius
    failures, rows, plotted = [], [], {}
    with h5py.File(args.results, "r") as f:
        if f.attrs.get("status") not in ("completed", b"completed"):
            print(f"run status: {f.attrs.get('status')}: {f.attrs.get('message')}")
        steps = sorted(f["steps"])
        times = [float(f["steps"][s].attrs["load_factor"]) for s in steps]
        pair = lambda step: f["steps"][step]["contact"][args.pair]
        mu = float(pair(steps[-1]).attrs["friction_coefficient"])
        sides = [n for n in pair(steps[-1]) if "gauss_points" in pair(steps[-1])[n]]
        print(f"{args.results}: {len(steps)} increments, t = {times[0]:g} .. {times[-1]:g}, mu = {mu:g}, sides {sides}")
        for name in sides:
            Q = [2.0 * float(pair(s)[name].attrs["friction_force"][0]) for s in steps]
            peak = int(np.argmax(np.abs(Q)))
            Q_star, sign = abs(Q[peak]), float(np.sign(Q[peak]))
            press = [k for k, t in enumerate(times) if abs(t - 1.0) < 1e-12]
            states = []
            if press:
                k = press[0]
                s = read_side(pair(steps[k])[name])
                states.append(("pressed", k, measure(s, mu, R, lambda r, a, p0, P: 0.0 * r, float("nan"))))
            s = read_side(pair(steps[peak])[name])
            ratio = Q_star / (mu * s["P"])
            states.append(("sheared", peak, measure(s, mu, R, lambda r, a, p0, P: sign * q_mindlin(r, Q_star, mu, a, p0, P),
                                                    (1 - ratio) ** (1 / 3))))
            if peak < len(steps) - 1:
                s = read_side(pair(steps[-1])[name])
                back = (Q_star - sign * Q[-1]) / 2.0
                states.append(("unsheared", len(steps) - 1, measure(
                    s, mu, R, lambda r, a, p0, P: sign * (q_mindlin(r, Q_star, mu, a, p0, P) - 2 * q_mindlin(r, back, mu, a, p0, P)),
                    (1 - back / (mu * s["P"])) ** (1 / 3))))
                states[-1][2]["back"] = back
            for label, k, m in states:
                if label == "pressed":
                    share = m["tmax"] / (mu * m["p0"])
                    print(f"{name}, pressed (t = {times[k]:g}): P = {m['P']:.5g}, a = {m['a_m']:.5f} (Hertz {m['a']:.5f}, "
                          f"{100 * (m['a_m'] / m['a'] - 1):+.1f} %), p0 {m['p0']:.4g}; max |t_T| = {100 * share:.2f} % of mu p0; "
                          f"L2 error of p {100 * m['p_err']:.2f} %")
                    if share > args.press_share:
                        failures.append(f"{name}: tangential traction while pressed {100 * share:.2f} % of mu p0")
                    rows.append((name, label, m, float("nan")))
                    continue
                x = abs(m["Q"]) / (mu * m["P"]) if label == "sheared" else m["back"] / (mu * m["P"])
                err = m["ratio"] / m["theory"] - 1
                print(f"{name}, {label} (t = {times[k]:g}): P = {m['P']:.5g}, Q = {m['Q']:.5g}, "
                      f"{'Q/(mu P)' if label == 'sheared' else '(Q* - Q)/(2 mu P)'} = {x:.4f}; "
                      f"a = {m['a_m']:.5f} (Hertz {m['a']:.5f}, x extent {m['a_x']:.5f}), "
                      f"c = {m['c_m']:.5f} (x extent {m['c_x']:.5f}); c/a = {m['ratio']:.4f} vs {m['theory']:.4f} "
                      f"({100 * err:+.2f} %); L2 error of q {100 * m['q_err']:.2f} % (rms {100 * m['q_rms']:.2f} % of mu p0; "
                      f"t_y {100 * m['ty']:.2f} %), of p {100 * m['p_err']:.2f} %")
                if abs(err) > args.tolerance:
                    failures.append(f"{name}, {label}: stick zone off by {100 * err:+.2f} % (> {100 * args.tolerance:g} %)")
                if label == "unsheared":
                    slipping = m["active"] & ~m["stick"]
                    annulus = slipping & (m["r"] > m["theory"] * m["a"])
                    unturned = int(np.sum(annulus & (sign * m["t"][:, 0] > 0)))
                    forward = slipping & (sign * m["t"][:, 0] > 0)
                    share = np.sum(m["w"][forward]) / np.sum(m["w"][slipping])
                    print(f"  slipping back: {int(annulus.sum())} Gauss points outside the theory's c', {unturned} with the "
                          f"traction not turned; anywhere: {int(slipping.sum())} slipping, {int(forward.sum())} of them "
                          f"forward ({100 * share:.1f} % of the slipping area, at r/a = "
                          f"{m['r'][forward].min() / m['a'] if forward.any() else 0:.2f} .. "
                          f"{m['r'][forward].max() / m['a'] if forward.any() else 0:.2f})")
                    if unturned:
                        failures.append(f"{name}: {unturned} annulus points did not slip back")
                rows.append((name, label, m, x))
            plotted.setdefault(name, states)
    print()
    print("| side | state | P | Q | mu | a Hertz | a measured | load ratio | c/a measured | c/a theory | error | "
          "L2 q (of mu p) | rms q / (mu p0) | L2 p |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for name, label, m, x in rows:
        if label == "pressed":
            print(f"| {name} | {label} | {m['P']:.4g} | {m['Q']:.2g} | {mu:g} | {m['a']:.4f} | {m['a_m']:.4f} | 0 | "
                  f"| | | max {100 * m['tmax'] / (mu * m['p0']):.2f} % of mu p0 | | {100 * m['p_err']:.1f} % |")
        else:
            print(f"| {name} | {label} | {m['P']:.4g} | {m['Q']:.4g} | {mu:g} | {m['a']:.4f} | {m['a_m']:.4f} | {x:.3f} | "
                  f"{m['ratio']:.4f} | {m['theory']:.4f} | {100 * (m['ratio'] / m['theory'] - 1):+.1f} % | "
                  f"{100 * m['q_err']:.1f} % | {100 * m['q_rms']:.1f} % | {100 * m['p_err']:.1f} % |")
    if args.plot:
        plot(args.plot, plotted, mu)
    for failure in failures:
        print("FAIL", failure)
    return 1 if failures else 0


def plot(path, plotted, mu):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    name, states = next(iter(plotted.items()))
    shown = [(label, m) for label, _, m in states if label != "pressed"]
    fig = plt.figure(figsize=(5.0 * (1 + len(shown)), 6.2))
    grid = fig.add_gridspec(2, 1 + len(shown), height_ratios=[1, 1.25])
    ax_p = fig.add_subplot(grid[0, 0])
    ax_q = fig.add_subplot(grid[1, 0], sharex=ax_p)
    # Along the x axis: the row of Gauss points nearest y = 0 (one row of the reference grid).
    for label, m in shown:
        row = np.abs(m["Y"] - m["Y"].min()) < 1e-9 * m["a"]
        order = np.argsort(m["xs"][row])
        xa = m["xs"][row][order] / m["a"]
        if label == "sheared":
            ax_p.plot(xa, m["p"][row][order] / m["p0"], "o", ms=2.5, color="0.45", label="Gauss points, sheared")
            ax_p.plot(xa, m["p_exact"][row][order] / m["p0"], "k-", lw=1, label="Hertz")
        mark = "o" if label == "sheared" else "s"
        ax_q.plot(xa, m["t"][row, 0][order] / (mu * m["p0"]), mark, ms=2.5, label=f"Gauss points, {label}")
        ax_q.plot(xa, m["q_exact"][row][order] / (mu * m["p0"]), "k-" if label == "sheared" else "k--", lw=1,
                  label="Cattaneo-Mindlin" if label == "sheared" else "Mindlin-Deresiewicz")
    m = shown[0][1]
    for sgn in (1, -1):
        ax_q.plot(xa, sgn * m["p_exact"][row][order] / m["p0"], ":", color="0.5", lw=1, label="±μp" if sgn > 0 else None)
    ax_p.set_ylabel("p / p0")
    ax_p.set_title(f"{name}, along the shear direction (row nearest y = 0)", fontsize=9)
    ax_p.legend(fontsize=7)
    ax_q.axhline(0, color="0.8", lw=0.5)
    ax_q.set_ylabel("q_x / (μ p0)")
    ax_q.set_xlabel("x / a")
    ax_q.set_xlim(-1.3, 1.3)
    ax_q.legend(fontsize=6.5, ncol=2, loc="upper center")
    for k, (label, m) in enumerate(shown, start=1):
        ax = fig.add_subplot(grid[:, k])
        kind = np.where(m["stick"], 0, np.where(m["active"], 1, 2))
        for value, color, text in ((2, "0.85", "open"), (1, "tab:red", "slip"), (0, "tab:blue", "stick")):
            sel = kind == value
            ax.scatter(m["xs"][sel] / m["a"], m["ys"][sel] / m["a"], s=2, c=color, label=text, linewidths=0)
        th = np.linspace(0, np.pi, 200)
        c_measured = m["c_m"] / m["a"]
        ax.plot(np.cos(th), np.sin(th), "k-", lw=1, label="Hertz a")
        ax.plot(m["theory"] * np.cos(th), m["theory"] * np.sin(th), "k--", lw=1, label="c of the theory")
        ax.plot(c_measured * np.cos(th), c_measured * np.sin(th), ":", color="tab:green", lw=1.5,
                label="c measured (stick area)")
        ax.set_aspect("equal")
        ax.set_xlim(-1.3, 1.3)
        ax.set_ylim(0, 1.3)
        ax.set_xlabel("x / a")
        ax.set_ylabel("y / a")
        ratio = "Q/(μP)" if label == "sheared" else "(Q*−Q)/(2μP)"
        load = abs(m["Q"]) / (mu * m["P"]) if label == "sheared" else m["back"] / (mu * m["P"])
        ax.set_title(f"{label}, {ratio} = {load:.3f}:\nc/a = {m['ratio']:.3f} (theory {m['theory']:.3f})", fontsize=9)
        ax.legend(fontsize=7, loc="upper right", markerscale=3, ncol=2)
    fig.suptitle("Cattaneo-Mindlin in 3D: two identical paraboloid-ended bodies (half model y ≥ 0), "
                 "pressed, sheared along x, unsheared", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print(f"plot: {path}")


if __name__ == "__main__":
    sys.exit(main())
