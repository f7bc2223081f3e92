#!/usr/bin/python3
"""Cattaneo-Mindlin and Mindlin-Deresiewicz check of a results file of
verification/friction/cattaneo_mindlin_2d.yaml.

Two identical cylinders pressed by P, then sheared by Q* < mu P with P held, then
the shear taken back to Q: the normal and tangential problems decouple, the pressure
is Hertz's and the tangential traction (Johnson, Contact Mechanics, 7.1-7.2) is, with
q_Q(x) = mu p0 sqrt(1 - x^2/a^2) - mu p0 (c_Q/a) sqrt(1 - x^2/c_Q^2) (|x| <= c_Q) and
c_Q/a = sqrt(1 - Q/(mu P)):

    loading to Q* (Cattaneo-Mindlin):      q = q_{Q*},        stick zone c/a = sqrt(1 - Q*/(mu P));
    unloading to Q (Mindlin-Deresiewicz):  q = q_{Q*} - 2 q_{(Q* - Q)/2},
        stick zone c'/a = sqrt(1 - (Q* - Q)/(2 mu P)), the annulus c' < |x| < a slipping back (q = -mu p).

For each contact side (both carry Gauss points under two-half-pass) and each of the
peak step (largest |Q|) and, if the path goes on, the last step, this prints P and Q,
the stick zone measured as the half extent of the sticking Gauss points against the
contact half-width a measured the same way, and the L2 errors of q and p at the Gauss
points against the formulas (Hertz's a and p0 from the measured P). After unloading
it also counts the annulus points whose traction has not turned against the load.
With --plot FILE it draws p and q of both states against x.
Exit status 1 when a check fails: a stick zone off by more than --tolerance (5 %), the
L2 error of q, in units of mu p (the bound of the tangential traction), above
--l2-factor (3) times the relative L2 error of p plus 1 % ("comparable"), or an
unturned annulus point.

Usage: /usr/bin/python3 verification/friction/cattaneo_mindlin.py RESULTS.h5 [--plot FIGURE.png]
"""
import argparse
import sys

import h5py
import numpy as np

E, NU, R = 1000.0, 0.3, 1.0  # the deck's material and radii


def hertz(P):
    """Two identical cylinders, plane strain: half-width a and peak p0 per unit length."""
    E_star = E / (2.0 * (1.0 - NU**2))
    R_star = R / 2.0
    a = np.sqrt(4.0 * P * R_star / (np.pi * E_star))
    return a, 2.0 * P / (np.pi * a)


def q_loading(xs, Q, mu, P):
    """Cattaneo-Mindlin's traction for a monotonic shear Q (>= 0), as a function of x."""
    a, p0 = hertz(P)
    c = a * np.sqrt(max(1.0 - Q / (mu * P), 0.0))
    outer = mu * p0 * np.sqrt(np.clip(1 - xs**2 / a**2, 0, None))
    inner = np.where(np.abs(xs) < c, mu * p0 * (c / a) * np.sqrt(np.clip(1 - xs**2 / max(c, 1e-300)**2, 0, None)), 0.0)
    return np.where(np.abs(xs) < a, outer - inner, 0.0)


def read_side(g):
    return dict(x=g["coordinates"][:, 0], p=g["pressure"][:], w=g["weight"][:], status=g["status"][:],
                t=g["tangential_traction_vector"][:, 0])


def state_check(label, s, mu, q_exact_of, c_theory, sign):
    p, w, t, status = s["p"], s["w"], s["t"], s["status"]
    P = float(np.sum(p * w))
    active = p > 0
    xs = s["x"] - 0.5 * (s["x"][active].max() + s["x"][active].min())
    a_h = 0.5 * (s["x"][active].max() - s["x"][active].min())
    stick = active & (status == 1)
    c_h = 0.5 * (s["x"][stick].max() - s["x"][stick].min()) if stick.any() else 0.0
    a, p0 = hertz(P)
    inside = np.abs(xs) < a
    p_exact = np.where(inside, p0 * np.sqrt(np.clip(1 - xs**2 / a**2, 0, None)), 0.0)
    q_exact = sign * q_exact_of(xs, P)
    zone = inside | active
    l2 = lambda e, r: np.sqrt(np.sum(w[zone] * e[zone] ** 2) / np.sum(w[zone] * r[zone] ** 2))
    q_err, p_err = l2(t - q_exact, mu * p_exact), l2(p - p_exact, p_exact)
    print(f"  {label}: P = {P:.5g}; a = {a_h:.5f} (Hertz {a:.5f}); stick zone {c_h / a_h:.4f} a (theory {c_theory:.4f}, "
          f"{100 * (c_h / a_h / c_theory - 1):+.2f} %); L2 error of q {100 * q_err:.2f} % of mu p, of p {100 * p_err:.2f} %")
    return dict(xs=xs, a=a, p=p, t=t, p_exact=p_exact, q_exact=q_exact, ratio=c_h / a_h / c_theory,
                q_err=q_err, p_err=p_err, active=active, stick=stick)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("results")
    parser.add_argument("--pair", default="mate")
    parser.add_argument("--plot")
    parser.add_argument("--tolerance", type=float, default=0.05)
    parser.add_argument("--l2-factor", type=float, default=3.0)
    args = parser.parse_args()
    failures = []
    states = {}
    with h5py.File(args.results, "r") as f:
        steps = sorted(f["steps"])
        pair = lambda step: f["steps"][step]["contact"][args.pair]
        mu = float(pair(steps[-1]).attrs["friction_coefficient"])
        sides = [n for n in pair(steps[-1]) if "gauss_points" in pair(steps[-1])[n]]
        for name in sides:
            Q = [float(pair(s)[name].attrs["friction_force"][0]) for s in steps]
            peak = int(np.argmax(np.abs(Q)))
            Q_star, sign = abs(Q[peak]), np.sign(Q[peak])
            P = float(pair(steps[peak])[name].attrs["normal_force"])
            print(f"{name}: Q* = {Q[peak]:.5g} at step {steps[peak]} (Q*/(mu P) = {Q_star / (mu * P):.4f})")
            load = state_check("sheared (Cattaneo-Mindlin)", read_side(pair(steps[peak])[name]["gauss_points"]), mu,
                               lambda xs, P: q_loading(xs, Q_star, mu, P), np.sqrt(1 - Q_star / (mu * P)), sign)
            states[(name, "load")] = load
            if peak < len(steps) - 1:
                Q_end = sign * Q[-1]  # along the first shear's direction
                back = (Q_star - Q_end) / 2.0
                print(f"  unloaded to Q = {Q[-1]:.5g} ((Q* - Q)/(2 mu P) = {back / (mu * P):.4f})")
                unload = state_check("unloaded (Mindlin-Deresiewicz)", read_side(pair(steps[-1])[name]["gauss_points"]),
                                     mu, lambda xs, P: q_loading(xs, Q_star, mu, P) - 2 * q_loading(xs, back, mu, P),
                                     np.sqrt(1 - back / (mu * P)), sign)
                annulus = unload["active"] & ~unload["stick"]
                unturned = int(np.sum(annulus & (sign * unload["t"] > 0)))
                print(f"  slipping back: {int(annulus.sum())} Gauss points, {unturned} with the traction not turned")
                if unturned:
                    failures.append(f"{name}: {unturned} annulus points did not slip back")
                states[(name, "unload")] = unload
    for (name, state), s in states.items():
        if abs(s["ratio"] - 1) > args.tolerance:
            failures.append(f"{name}, {state}: stick zone off by more than {100 * args.tolerance:g} %")
        if s["q_err"] > args.l2_factor * s["p_err"] + 0.01:
            failures.append(f"{name}, {state}: L2 error of q not comparable to that of p")
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(2, 1, figsize=(7, 7), sharex=True)
        for (name, state), s in states.items():
            order = np.argsort(s["xs"])
            xs = s["xs"][order] / s["a"]
            if state == "load":
                ax[0].plot(xs, s["p"][order], ".", ms=3, label=f"{name} (Gauss points)")
            ax[1].plot(xs, s["t"][order], ".", ms=3, label=f"{name}, {'sheared' if state == 'load' else 'unloaded'}")
            ax[1].plot(xs, s["q_exact"][order], "k-" if state == "load" else "k--", lw=1)
        s = next(iter(states.values()))
        order = np.argsort(s["xs"])
        ax[0].plot(s["xs"][order] / s["a"], s["p_exact"][order], "k-", lw=1, label="Hertz")
        for sgn in (1, -1):
            ax[1].plot(s["xs"][order] / s["a"], sgn * mu * s["p_exact"][order], "k:", lw=1)
        ax[0].set_ylabel("pressure p")
        ax[1].set_ylabel("tangential traction q")
        ax[1].set_title("lines: Cattaneo-Mindlin (sheared), Mindlin-Deresiewicz (unloaded); dotted: ±μp", fontsize=8)
        ax[1].set_xlabel("x / a")
        ax[0].legend(fontsize=8)
        ax[1].legend(fontsize=7, ncol=2)
        ax[0].set_xlim(-1.3, 1.3)
        fig.suptitle("Two identical cylinders: pressed, sheared, unloaded")
        fig.tight_layout()
        fig.savefig(args.plot, dpi=120)
        print(f"plot: {args.plot}")
    for failure in failures:
        print("FAIL", failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
