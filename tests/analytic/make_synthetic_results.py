#!/usr/bin/python3
"""Write a small synthetic igacontact results file (docs/results.md) to try scripts/plot_pressure.py.

Usage:  make_synthetic_results.py OUT.h5 [--full] [--no-reference]

The benchmark of docs/theory.md "The Hertz benchmark" (E = 1000, nu = 0.3, R = 1, F = 10, so
a = 0.10764, p0 = 59.143), faked as a penalty solution: a Hertz curve 1 % wider
and 0.5 % lower. Default: a quarter model (Gauss points on x >= 0 only);
--full: both halves of the contact arc. --no-reference leaves out /reference.
The numbers are made up; only the layout matters.
"""

import argparse
import math

import h5py
import numpy as np

E_STAR = 1000.0 / (1.0 - 0.3**2)
RADIUS, FORCE = 1.0, 10.0
A = math.sqrt(4.0 * FORCE * RADIUS / (math.pi * E_STAR))
P0 = 2.0 * FORCE / (math.pi * A)


def hertz(x, a=A, p0=P0):
    t = np.clip(np.abs(x) / a, 0.0, 1.0)
    return p0 * np.sqrt(1.0 - t * t)


def arc(x):
    """Reference points on the lower arc of the cylinder touching y = 0 at the origin."""
    return np.column_stack([x, RADIUS - np.sqrt(RADIUS**2 - x**2)])


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("out")
    parser.add_argument("--full", action="store_true")
    parser.add_argument("--no-reference", action="store_true")
    args = parser.parse_args()

    lo = -0.5 if args.full else 0.0
    # Gauss points: 3 per span on spans graded towards the contact edge.
    edges = np.concatenate([np.linspace(lo, 0.3, 41 if args.full else 16), [0.4, 0.5]])
    g = np.array([-math.sqrt(0.6), 0.0, math.sqrt(0.6)])
    xg = np.concatenate([0.5 * (e0 + e1) + 0.5 * (e1 - e0) * g for e0, e1 in zip(edges[:-1], edges[1:])])
    xs = np.linspace(edges[0], edges[-1], 16 * (len(edges) - 1) + 1)
    fake = lambda x: hertz(x, 1.01 * A, 0.995 * P0)  # noqa: E731

    with h5py.File(args.out, "w") as h5:
        h5.attrs.update(format="igacontact-results", format_version=1, program_version="synthetic",
                        status="completed", message="")
        h5["deck"] = "# synthetic file written by tests/analytic/make_synthetic_results.py\n"
        step = h5.create_group("steps/0001")
        step.attrs.update(load_factor=1.0, newton_iterations=5, residual_norm=1e-12, cutbacks=0, wall_s=0.1)
        side = step.create_group("contact/cyl_floor/cylinder.u0")
        side.attrs["normal_force"] = FORCE / (1 if args.full else 2)
        gp = side.create_group("gauss_points")
        gp["reference_coordinates"] = arc(xg)
        gp["coordinates"] = arc(xg) * [0.98, 1.0]
        gp["parameter"] = np.linspace(0.0, 1.0, xg.size)
        gp["pressure"] = fake(xg)
        gp["gap"] = fake(xg) / 1e6
        post = side.create_group("postprocessed")
        post["reference_coordinates"] = arc(xs)
        post["coordinates"] = arc(xs) * [0.98, 1.0]
        post["pressure"] = fake(xs) * (1.0 + 0.01 * np.cos(60.0 * xs))
        post["control_point_pressure"] = fake(edges)
        h5["results"] = h5["steps/0001"]  # hard link, as the spec allows
        if not args.no_reference:
            ref = h5.create_group("reference/cyl_floor")
            xr = np.linspace(-1.5 * A, 1.5 * A, 601)
            ref["x"] = xr
            ref["coordinates"] = np.column_stack([xr, np.zeros_like(xr)])
            ref["pressure"] = hertz(xr)
            ref.attrs.update(type="hertz_cylinder_plane", a=A, p0=P0, E=1000.0, nu=0.3, radius=RADIUS,
                             force=FORCE, center=[0.0, 0.0], tangent=[1.0, 0.0],
                             l2=0.0123, peak=-0.005, half_width=0.0099)
        t = h5.create_group("timings")
        t.attrs.update(total=1.0, assembly=0.5, contact_search=0.1, projection=0.1, linear_solve=0.2, output=0.1)
        h5["convergence"] = np.array([[1, 1, 1.0, 1.0], [1, 5, 1e-12, 1.0]])


if __name__ == "__main__":
    main()
