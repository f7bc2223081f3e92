#!/usr/bin/python3
"""Graded knot vectors for the quarter-cylinder Hertz deck (inputs/hertz.yaml).

u runs along the quarter arc from the lowest point; the Hertz half-width a sits at
u_a = 0.0747 (x(u_a) = a = 0.10764 for R = 1, F = 10, E = 1000, nu = 0.3). Spans are
h_in inside the contact zone, h_edge over [0.7, 1.3] u_a where the pressure drops to
zero, then grow geometrically; v is graded geometrically from the arc.

Usage as a script: hertz_mesh.py H_IN H_EDGE [V0]  ->  prints the --set override
    bodies.cylinder.refine.insert=[[...],[...]]
"""
import sys

U_A = 0.0746653661110271  # parameter of the contact edge on the quarter arc (see above)


def knots(h_in, h_edge, v0=0.003, v_growth=1.3, u_growth=1.35, band=(0.7, 1.3), u_max=1.6):
    u, x = [], 0.0
    while True:
        h = h_edge if band[0] * U_A <= x <= band[1] * U_A else h_in
        x += h
        if x > u_max * U_A:
            break
        u.append(round(x, 6))
    h = h_edge if u_max <= band[1] else h_in
    while True:
        h *= u_growth
        x += h
        if x > 0.97:
            break
        u.append(round(x, 6))
    v, x, h = [], 0.0, v0
    while True:
        x += h
        h *= v_growth
        if x > 0.95:
            break
        v.append(round(x, 6))
    return u, v


def insert_override(h_in, h_edge, v0=0.003):
    u, v = knots(h_in, h_edge, v0)
    return "bodies.cylinder.refine.insert=[{},{}]".format(u, v).replace(" ", "")


if __name__ == "__main__":
    args = [float(a) for a in sys.argv[1:]]
    print(insert_override(*args))
