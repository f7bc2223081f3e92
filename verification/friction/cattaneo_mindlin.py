#!/usr/bin/python3
"""Cattaneo-Mindlin check of a results file of verification/friction/cattaneo_mindlin_2d.yaml.

Two identical cylinders pressed by P, then sheared by Q < mu P with P held: the
normal and tangential problems decouple, the pressure is Hertz's and the tangential
traction (Johnson, Contact Mechanics, 7.1) is

    q(x) = mu p0 sqrt(1 - x^2/a^2) - mu p0 (c/a) sqrt(1 - x^2/c^2)   (|x| <= c),
    c/a  = sqrt(1 - Q/(mu P)).

For each contact side (both carry Gauss points under two-half-pass) this prints P and
Q (the side's normal and friction forces), the stick zone c measured as the half
extent of the sticking Gauss points against the contact half-width a measured the same
way, and the L2 errors of q and of p at the Gauss points against the formulas, with
Hertz's a and p0 from the measured P. With --plot FILE it draws q and p against x.
Exit status 1 when a check fails: c/a off by more than --tolerance (5 %), or the
L2 error of q, in units of mu p (the bound of the tangential traction), above
--l2-factor (3) times the relative L2 error of p plus 1 % ("comparable").

Usage: /usr/bin/python3 verification/friction/cattaneo_mindlin.py RESULTS.h5 [--plot FIGURE.png]
"""
import argparse
import sys

import h5py
import numpy as np


def hertz(P, R1, R2, E, nu):
    """Two cylinders, plane strain: half-width a and peak p0 per unit length."""
    E_star = 1.0 / (2.0 * (1.0 - nu**2) / E)
    R_star = 1.0 / (1.0 / R1 + 1.0 / R2)
    a = np.sqrt(4.0 * P * R_star / (np.pi * E_star))
    return a, 2.0 * P / (np.pi * a)


def side_check(name, g, mu, E, nu, R):
    x = g["coordinates"][:, 0]
    p = g["pressure"][:]
    w = g["weight"][:]
    status = g["status"][:]
    t = g["tangential_traction_vector"][:, 0]
    P = float(np.sum(p * w))
    Q = float(np.sum(t * w))
    active = p > 0
    centre = 0.5 * (x[active].max() + x[active].min())
    xs = x - centre
    a_h = 0.5 * (x[active].max() - x[active].min())
    stick = active & (status == 1)
    c_h = 0.5 * (x[stick].max() - x[stick].min()) if stick.any() else 0.0
    ratio = abs(Q) / (mu * P)
    c_over_a = np.sqrt(max(1.0 - ratio, 0.0))
    a, p0 = hertz(P, R, R, E, nu)
    c = c_over_a * a
    inside = np.abs(xs) < a
    p_exact = np.where(inside, p0 * np.sqrt(np.clip(1 - xs**2 / a**2, 0, None)), 0.0)
    q_exact = mu * p0 * np.sqrt(np.clip(1 - xs**2 / a**2, 0, None)) - np.where(
        np.abs(xs) < c, mu * p0 * (c / a) * np.sqrt(np.clip(1 - xs**2 / c**2, 0, None)), 0.0)
    q_exact = np.sign(Q) * np.where(inside, q_exact, 0.0)
    zone = inside | active
    l2 = lambda e, r: np.sqrt(np.sum(w[zone] * e[zone] ** 2) / np.sum(w[zone] * r[zone] ** 2))
    q_err = l2(t - q_exact, q_exact)
    p_err = l2(p - p_exact, p_exact)
    q_err_mu_p = l2(t - q_exact, mu * p_exact)  # in units of the friction bound mu p
    print(f"{name}: P = {P:.5g}, Q = {Q:.5g}, Q/(mu P) = {ratio:.4f}; a = {a_h:.5f} (Hertz {a:.5f}), "
          f"c = {c_h:.5f}; c/a = {c_h / a_h:.4f} (theory {c_over_a:.4f}, {100 * (c_h / a_h / c_over_a - 1):+.2f} %); "
          f"L2 error of q {100 * q_err:.2f} % ({100 * q_err_mu_p:.2f} % of mu p), of p {100 * p_err:.2f} %")
    return dict(xs=xs, p=p, t=t, p_exact=p_exact, q_exact=q_exact, status=status, c_over_a=c_h / a_h,
                theory=c_over_a, q_err=q_err, q_err_mu_p=q_err_mu_p, p_err=p_err, a=a)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("results")
    parser.add_argument("--pair", default="mate")
    parser.add_argument("--plot")
    parser.add_argument("--tolerance", type=float, default=0.05)
    parser.add_argument("--l2-factor", type=float, default=3.0)
    args = parser.parse_args()
    with h5py.File(args.results, "r") as f:
        last = sorted(f["steps"])[-1]  # the end of the shear
        pair = f["steps"][last]["contact"][args.pair]
        mu = float(pair.attrs["friction_coefficient"])
        E, nu, R = 1000.0, 0.3, 1.0  # the deck's material and radii
        sides = {name: side_check(name, pair[name]["gauss_points"], mu, E, nu, R)
                 for name in pair if isinstance(pair[name], h5py.Group) and "gauss_points" in pair[name]}
    ok = True
    for name, s in sides.items():
        if abs(s["c_over_a"] / s["theory"] - 1) > args.tolerance:
            print(f"FAIL {name}: c/a off by more than {100 * args.tolerance:g} %")
            ok = False
        if s["q_err_mu_p"] > args.l2_factor * s["p_err"] + 0.01:
            print(f"FAIL {name}: L2 error of q not comparable to that of p")
            ok = False
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(2, 1, figsize=(7, 7), sharex=True)
        for name, s in sides.items():
            order = np.argsort(s["xs"])
            xs = s["xs"][order] / s["a"]
            ax[0].plot(xs, s["p"][order], ".", ms=3, label=f"{name} (Gauss points)")
            ax[1].plot(xs, s["t"][order], ".", ms=3, label=f"{name}")
        first = next(iter(sides.values()))
        order = np.argsort(first["xs"])
        ax[0].plot(first["xs"][order] / first["a"], first["p_exact"][order], "k-", lw=1, label="Hertz")
        ax[1].plot(first["xs"][order] / first["a"], first["q_exact"][order], "k-", lw=1, label="Cattaneo-Mindlin")
        ax[1].plot(first["xs"][order] / first["a"], np.sign(first["q_exact"].sum()) * mu * first["p_exact"][order],
                   "k:", lw=1, label="±μp")
        ax[0].set_ylabel("pressure p")
        ax[1].set_ylabel("tangential traction q")
        ax[1].set_xlabel("x / a")
        ax[0].legend(fontsize=8)
        ax[1].legend(fontsize=8)
        ax[0].set_xlim(-1.3, 1.3)
        fig.suptitle(f"Cattaneo-Mindlin: c/a = {first['c_over_a']:.3f} (theory {first['theory']:.3f})")
        fig.tight_layout()
        fig.savefig(args.plot, dpi=120)
        print(f"plot: {args.plot}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
