#!/usr/bin/python3
"""Writes the 3D scene decks of verification/scenes that need raw NURBS or computed knot
lists: two_spheres_ssnv104.yaml, one_sphere_ssnv104.yaml, hollow_sphere.yaml and
sphere_octant_on_slab.yaml. The other decks of the folder are written by hand.

Usage: /usr/bin/python3 verification/scenes/make_scenes.py      (rewrites the four decks beside it)

Octants are built as docs/deck.md ("Control points of the built-in shapes") builds the
sphere_octant: the quarter disc (here: a quarter annulus for the shell) revolved by 90
degrees about the x axis. Knot lists are graded by arc length: spans of a given arc h over
the contact zone, then growing geometrically to the end of the quarter circle.
"""
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
S = math.sqrt(0.5)


def quarter_angle(u):
    """Angle from the first end of the rational quadratic quarter circle (weights 1, s, 1)."""
    w = [1.0, S, 1.0]
    b = [(1 - u) ** 2, 2 * u * (1 - u), u * u]
    p = [(0.0, -1.0), (1.0, -1.0), (1.0, 0.0)]
    den = sum(bi * wi for bi, wi in zip(b, w))
    x = sum(bi * wi * pi[0] for bi, wi, pi in zip(b, w, p)) / den
    y = sum(bi * wi * pi[1] for bi, wi, pi in zip(b, w, p)) / den
    return math.atan2(x, -y)


def param_of_angle(theta):
    lo, hi = 0.0, 1.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if quarter_angle(mid) < theta:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def graded_knots(radius, h, zone, growth, edge=None):
    """Interior knots (parameters from the contact end, u = 0) of a quarter circle of this
    radius: spans of arc h up to the arc `zone`, then each span `growth` times the one before.
    With edge = (start, h_edge): spans of h_edge from the arc `start` on, up to `zone`."""
    arcs, s, step = [], 0.0, h
    total = radius * math.pi / 2
    while True:
        if edge and edge[0] <= s < zone:
            step = edge[1]
        if s >= zone:
            step *= growth
        s += step
        if s >= total - 0.5 * step:
            break
        arcs.append(s)
    return [round(param_of_angle(a / radius), 5) for a in arcs]


def radial_knots(first, growth, depth_max=0.999):
    out, v, step = [], 0.0, first
    while v + step < depth_max:
        v += step
        out.append(round(v, 4))
        step *= growth
    return out


def octant_rows(center, r_outer, r_inner=0.0):
    """Control points [x, y, z, w] of the lower octant x >= cx, y >= cy, z <= cz: of the
    built-in sphere_octant when r_inner = 0, else of the shell r_inner <= r <= r_outer
    (v0 the sphere r_outer, v1 the sphere r_inner). u fastest, then v, then w."""
    rows = []
    for ak, bk, wk in [(1, 0, 1.0), (1, -1, S), (0, -1, 1.0)]:
        for j, r in enumerate((r_outer, r_inner)):
            arc = [(0.0, -r, 1.0), (r, -r, S), (r, 0.0, 1.0)]
            if j == 1 and r_inner == 0.0:  # the quarter disc's top line, from the centre to (R, 0)
                arc = [(0.0, 0.0, 1.0), (r_outer, 0.0, S), (r_outer, 0.0, 1.0)]
            for (x, y, w) in arc:
                rho = -y
                rows.append([center[0] + x, center[1] + rho * ak, center[2] + rho * bk, w * wk])
    return rows


def fmt_rows(rows, indent):
    return "\n".join(indent + "- [" + ", ".join(repr(round(c, 15)) for c in row) + "]" for row in rows)


def fmt_list(xs):
    return "[" + ", ".join(repr(x) for x in xs) + "]"


def dofs(nu, nv, nw, p=2):
    return 3 * (nu + p) * (nv + p) * (nw + p)


def mirrored_ball_patches(rows, u_insert, names, comments, mirror_normal):
    """Two patches of the same octant rows, the second mirrored, as a `patches:` list at
    6 spaces. A transform keeps side names and `refine` in the patch as built, so both
    take the same u-insertions and name the same faces."""
    def patch(name, comment, transform, insert):
        return (f"""      - name: {name}{comment}
        nurbs:
          degrees: [2, 1, 2]
          knots: [[0, 0, 0, 1, 1, 1], [0, 0, 1, 1], [0, 0, 0, 1, 1, 1]]
          control_points:
{fmt_rows(rows, "            ")}
""" + transform + f"""        refine: {{insert: [{fmt_list(insert)}, [], []]}}
""")
    mirror = f"""          transform:
            - {{mirror: {{normal: {mirror_normal}}}}}
"""
    return (patch(names[0], comments[0], "", u_insert) + patch(names[1], comments[1], mirror, u_insert)).rstrip("\n")


def write(name, text):
    with open(os.path.join(HERE, name), "w") as f:
        f.write(text)
    print("wrote", name)


# ---------------------------------------------------------------- SSNV104
R, E, NU, F = 50.0, 20000.0, 0.3, 5.86e5
A = (3 * F * (R / 2) / (4 * E / (2 * (1 - NU**2)))) ** (1 / 3)
H = A / 3.5  # element arc over the contact zone, a/h = 3.5


H_EDGE = A / 12  # element arc over 0.6 a .. 1.4 a, where the pressure falls to zero


def ssnv104_knots(growth, first_radial, radial_growth):
    u = graded_knots(R, H, 1.4 * A, growth, edge=(0.6 * A, H_EDGE))
    v = radial_knots(first_radial, radial_growth)
    return u, v


TWO_GROWTH, TWO_RADIAL = 1.4, (0.02, 1.4)


def two_spheres():
    u, v = ssnv104_knots(TWO_GROWTH, *TWO_RADIAL)
    w_upper = [round(1 - x, 5) for x in reversed(u)]
    n = 2 * dofs(len(u) + 1, len(v) + 1, len(u) + 1)
    lower_rows = octant_rows([0.0, 0.0, 1.0], 1.0)
    # the lower octant of a unit sphere centred at (0, 0, 1), mirrored in z by the rows (z -> -z),
    # its w direction reversed so that the map stays right-handed, then placed by transform
    lower = []
    for k in (2, 1, 0):
        for row in lower_rows[6 * k:6 * k + 6]:
            lower.append([row[0], row[1], -row[2], row[3]])
    # with the rows mirrored and w reversed: w0 is the symmetry face y = 0, w1 the flat
    # bottom; the contact corner is u = 0, w = 0
    return f"""# Code_Aster SSNV104 (issue 31): two identical elastic spheres pressed together, the
# octants x >= 0, y >= 0 of each, with symmetry conditions on x = 0 and y = 0.
# R = 50, E = 20000, nu = 0.3, F = 5.86e5 on the whole sphere (a quarter on the octants):
# Hertz E* = E / (2 (1 - nu^2)) = 10989, R* = 25, a = {A:.4f}, p0 = {3 * F / (2 * math.pi * A * A):.1f}.
# Lower sphere: centre (0, 0, -50), the upper half of its octant as raw NURBS (the exact
# octant by revolution, mirrored in z, w reversed), held on its flat bottom z = -50 (u_z = 0).
# Upper sphere: the built-in sphere_octant, centre (0, 0, 50), loaded on its flat top z = 50
# by a quarter of F; nothing but contact holds it vertically. Small kinematics, one increment.
# Mesh: element arc a/3.5 = {H:.3f} up to 0.6 a from the contact point on both faces, a/12
# over 0.6 a .. 1.4 a (where the pressure falls to zero), then growing by {TWO_GROWTH} per span; radially {TWO_RADIAL[0]} R at the face growing by {TWO_RADIAL[1]}; degree 2; {n} dofs.
# Written by verification/scenes/make_scenes.py; graded by verification/scenes/run_scenes.py
# (with its companion one_sphere_ssnv104.yaml, a sphere on a rigid plane of about the same size).
format: 1
title: SSNV104, two deformable spheres (octant models)
analysis: {{dimension: 3, kinematics: small}}
materials:
  - {{name: steel, model: linear_elastic, E: {E}, nu: {NU}}}
bodies:
  - name: lower
    material: steel
    # sides: v0 = spherical face (contact), w1 = flat bottom z = -50, u0 = symmetry face x = 0,
    #        w0 = symmetry face y = 0, v1 = collapsed to the axis, u1 = collapsed to the pole
    nurbs:
      degrees: [2, 1, 2]
      knots: [[0, 0, 0, 1, 1, 1], [0, 0, 1, 1], [0, 0, 0, 1, 1, 1]]
      control_points:
{fmt_rows(lower, "        ")}
      transform:
        - {{scale: {R}}}
    refine:
      elevate: [0, 1, 0]
      insert:
        - {fmt_list(u)}
        - {fmt_list(v)}
        - {fmt_list(u)}
  - name: upper
    material: steel
    shape: {{type: sphere_octant, center: [0.0, 0.0, {R}], radius: {R}}}
    # sides: v0 = spherical face (contact), w0 = flat top z = 50, u0 = symmetry face x = 0,
    #        w1 = symmetry face y = 0
    refine:
      elevate: [0, 1, 0]
      insert:
        - {fmt_list(u)}
        - {fmt_list(v)}
        - {fmt_list(w_upper)}
constraints:
  - {{body: lower, side: w1, fix: [z]}}
  - {{body: lower, side: u0, fix: [x]}}
  - {{body: lower, side: w0, fix: [y]}}
  - {{body: upper, side: u0, fix: [x]}}
  - {{body: upper, side: w1, fix: [y]}}
loads:
  - {{body: upper, side: w0, force: [0.0, 0.0, {-F / 4}]}}
contact:
  - {{name: spheres, between: [upper.v0, lower.v0], formulation: two_half_pass, penalty: auto}}
steps: {{count: 1}}
output:
  every_step: false
  reference: {{pair: spheres, type: hertz_two_spheres, radii: [{R}, {R}], force: {F}}}
""", n


def one_sphere(target):
    best = None
    for g in [1.0 + 0.01 * i for i in range(80)]:
        u, v = ssnv104_knots(g, 0.015, 1.3)
        n = dofs(len(u) + 1, len(v) + 1, len(u) + 1)
        if best is None or abs(n - target) < abs(best[0] - target):
            best = (n, g, u, v)
    n, g, u, v = best
    w = [round(1 - x, 5) for x in reversed(u)]
    return f"""# Companion of two_spheres_ssnv104.yaml (issue 31): one sphere octant of the same
# SSNV104 data on a rigid plane, with about as many dofs as the two-sphere deck, for the
# run-time ratio. R = 50, E = 20000, nu = 0.3, F = 5.86e5 on the whole sphere: against a
# rigid plane E* = E / (1 - nu^2) and R* = R, so a = {A:.4f} and p0 = {3 * F / (2 * math.pi * A * A):.1f}, as for two spheres.
# Mesh: element arc a/3.5 up to 0.6 a, a/12 up to 1.4 a (as the two-sphere deck), then growing by {g:.3f} per
# span (finer than there, to reach the same size); radially 0.015 R growing by 1.3; {n} dofs.
# Written by verification/scenes/make_scenes.py.
format: 1
title: SSNV104 companion, one sphere on a rigid plane (octant model)
analysis: {{dimension: 3, kinematics: small}}
materials:
  - {{name: steel, model: linear_elastic, E: {E}, nu: {NU}}}
bodies:
  - name: ball
    material: steel
    shape: {{type: sphere_octant, center: [0.0, 0.0, {R}], radius: {R}}}
    refine:
      elevate: [0, 1, 0]
      insert:
        - {fmt_list(u)}
        - {fmt_list(v)}
        - {fmt_list(w)}
  - name: floor
    rigid: {{plane: {{point: [0.0, 0.0, 0.0], normal: [0.0, 0.0, 1.0]}}}}
constraints:
  - {{body: ball, side: u0, fix: [x]}}
  - {{body: ball, side: w1, fix: [y]}}
loads:
  - {{body: ball, side: w0, force: [0.0, 0.0, {-F / 4}]}}
contact:
  - {{name: ball_floor, between: [ball.v0, floor], formulation: two_half_pass, penalty: auto}}
steps: {{count: 1}}
output:
  every_step: false
  reference: {{pair: ball_floor, type: hertz_sphere_plane, radius: {R}, force: {F}}}
""", n


# ---------------------------------------------------------------- hollow sphere
def hollow_sphere():
    r_in, r_shell_in, r_shell_out = 0.6, 0.7, 2.0
    ball = octant_rows([0.0, 0.0, 0.0], r_in)
    shell = octant_rows([0.0, 0.0, 0.0], r_shell_out, r_shell_in)
    ub = graded_knots(r_in, 0.06, 0.5, 1.3)
    vb = radial_knots(0.1, 1.5)
    us = graded_knots(r_shell_in, 0.07, 0.6, 1.3)
    vs = [round(1 - x, 4) for x in reversed(radial_knots(0.05, 1.6))]
    return f"""# Puso & Laursen's sphere in a hollow sphere (issue 31), quarter model x >= 0, y >= 0
# with symmetry conditions on x = 0 and y = 0. A solid sphere R = 0.6 sits concentric in a
# shell 0.7 <= r <= 2.0 (a gap of 0.1 all round); a body force along -z carries it across
# the gap into the shell and presses it in. Both neo-Hookean, E = 1000, nu = 0.3 (the issue
# gives no moduli: equal bodies chosen), finite kinematics, frictionless, two-half-pass,
# penalty auto. The body force rho g = 200 (density 1, gravity 200) is a weight of
# {200 * 4 / 3 * math.pi * r_in**3:.1f} on the whole sphere, about the load that flattens
# it by ~10 % of its radius into the seat. Ramped over 20 increments.
# Ball: two patches (the lower octant as the built-in sphere_octant builds it, and its
# mirror in z); nothing but contact holds it in z. Shell: only its lower octant (the part
# the ball can reach), its outer sphere r = 2 held; v1 is its inner sphere r = 0.7.
# Written by verification/scenes/make_scenes.py.
format: 1
title: Sphere in a hollow sphere (Puso and Laursen), quarter model
analysis: {{dimension: 3, kinematics: finite}}
materials:
  - {{name: rubber, model: neo_hookean, E: 1000.0, nu: 0.3}}
bodies:
  - name: ball
    material: rubber
    patches:
{mirrored_ball_patches(ball, ub, ("lower", "upper"), (
    "   # v0 = sphere, w0 = z = 0 (the interface), u0 = x = 0, w1 = y = 0",
    "   # the same rows mirrored in z (the same side names)"), "[0, 0, 1]")}
    refine:
      elevate: [0, 1, 0]
      insert:
        - []
        - {fmt_list(vb)}
        - {fmt_list([round(1 - x, 5) for x in reversed(ub)])}
    surfaces:
      sym_x: [lower.u0, upper.u0]
      sym_y: [lower.w1, upper.w1]
      skin: [lower.v0, upper.v0]
  - name: shell
    material: rubber
    # sides: v0 = outer sphere r = 2 (held), v1 = inner sphere r = 0.7 (contact),
    #        w0 = z = 0 (free), u0 = x = 0, w1 = y = 0
    nurbs:
      degrees: [2, 1, 2]
      knots: [[0, 0, 0, 1, 1, 1], [0, 0, 1, 1], [0, 0, 0, 1, 1, 1]]
      control_points:
{fmt_rows(shell, "        ")}
    refine:
      elevate: [0, 1, 0]
      insert:
        - {fmt_list(us)}
        - {fmt_list(vs)}
        - {fmt_list([round(1 - x, 5) for x in reversed(us)])}
constraints:
  - {{body: ball, side: sym_x, fix: [x]}}
  - {{body: ball, side: sym_y, fix: [y]}}
  - {{body: shell, side: v0, fix: [x, y, z]}}
  - {{body: shell, side: u0, fix: [x]}}
  - {{body: shell, side: w1, fix: [y]}}
loads:
  - {{body: ball, gravity: [0.0, 0.0, -200.0], density: 1.0}}
contact:
  - {{name: seat, between: [ball.skin, shell.v1], formulation: two_half_pass, penalty: auto}}
steps: {{count: 20}}
output: {{every_step: false}}
"""


# ---------------------------------------------------------------- sphere on slab
def sphere_on_slab():
    ball = octant_rows([0.0, 0.0, 1.0], 1.0)
    u = graded_knots(1.0, 0.025, 0.2, 1.45)
    v = radial_knots(0.03, 1.6)
    w = [round(1 - x, 5) for x in reversed(u)]
    return f"""# Sphere pressed then pushed sideways on a deformable slab, with friction (issue 31):
# the refined version of verification/mpi/sphere_on_block.yaml. Half model y >= 0 (the push
# is along x, so only y = 0 is a symmetry plane): the ball is two octant patches (the
# built-in sphere_octant's rows and their mirror in x), R = 1, E = 1000, nu = 0.3; the slab
# x in [-1.2, 1.2], y in [0, 1], z in [-0.5, 0], E = 1000, nu = 0.3, held at its base.
# The ball's flat top (z = 1) is driven: pressed down 0.012 over pseudo-time [0, 1] (Hertz
# a ~ 0.1), then pushed 0.05 along x over [1, 2] with the press held (gross slip from a
# push of ~0.005). Coulomb mu = 0.3, two-half-pass, penalty auto; small kinematics;
# 20 increments. Graded meshes: element arc 0.025 (a/4) up to r = 0.2 on the ball, the
# slab's spans 0.025 over |x| <= 0.2, y <= 0.2.
# Written by verification/scenes/make_scenes.py.
format: 1
title: Sphere octant pressed then pushed on a deformable slab (half model, friction)
analysis: {{dimension: 3, kinematics: small}}
materials:
  - {{name: ball_mat, model: linear_elastic, E: 1000.0, nu: 0.3}}
  - {{name: slab_mat, model: linear_elastic, E: 1000.0, nu: 0.3}}
bodies:
  - name: ball
    material: ball_mat
    patches:
{mirrored_ball_patches(ball, u, ("east", "west"), (
    "    # x >= 0: v0 = sphere, w0 = top z = 1, u0 = x = 0 (interface), w1 = y = 0",
    "    # x <= 0: the same rows mirrored in x (the same side names: u0 is the interface)"), "[1, 0, 0]")}
    refine:
      elevate: [0, 1, 0]
      insert:
        - []
        - {fmt_list(v)}
        - {fmt_list(w)}
    surfaces:
      face: [east.v0, west.v0]
      top: [east.w0, west.w0]
      sym_y: [east.w1, west.w1]
  - name: slab
    material: slab_mat
    shape: {{type: box, corner: [-1.2, 0.0, -0.5], size: [2.4, 1.0, 0.5]}}
    refine:
      elevate: [1, 1, 1]
      insert:
        - {fmt_list(slab_x())}
        - {fmt_list(slab_y())}
        - [0.3, 0.55, 0.75, 0.88, 0.95]
constraints:
  - {{body: ball, side: sym_y, fix: [y]}}
  - {{body: ball, side: top, displacement: [~, ~, -0.012], amplitude: [[0, 0], [1, 1], [2, 1]]}}
  - {{body: ball, side: top, displacement: [0.05, ~, ~], amplitude: [[0, 0], [1, 0], [2, 1]]}}
  - {{body: slab, side: w0, fix: [x, y, z]}}
  - {{body: slab, side: v0, fix: [y]}}
contact:
  - name: ball_slab
    between: [ball.face, slab.w1]
    formulation: two_half_pass
    penalty: auto
    friction: {{coefficient: 0.3}}
steps: {{count: 20}}
output: {{every_step: false}}
"""


def slab_x():
    """Knots in [0, 1] of x in [-1.2, 1.2]: spans 0.025 over |x| <= 0.25, growing 1.5 outside."""
    xs, x, step = [0.0], 0.0, 0.025
    while x + step <= 0.25 + 1e-9:
        x += step
        xs.append(x)
    while x + step * 1.5 < 1.2 - 0.5 * step * 1.5:
        step *= 1.5
        x += step
        xs.append(x)
    both = sorted(set([-v for v in xs] + xs))
    return [round((v + 1.2) / 2.4, 5) for v in both]


def slab_y():
    ys, y, step = [], 0.0, 0.025
    while y + step <= 0.2 + 1e-9:
        y += step
        ys.append(y)
    while y + step * 1.5 < 1.0 - 0.5 * step * 1.5:
        step *= 1.5
        y += step
        ys.append(y)
    return [round(v, 5) for v in ys]


if __name__ == "__main__":
    text, n2 = two_spheres()
    write("two_spheres_ssnv104.yaml", text)
    text, n1 = one_sphere(n2)
    write("one_sphere_ssnv104.yaml", text)
    print("estimated dofs: two spheres", n2, "one sphere", n1)
    write("hollow_sphere.yaml", hollow_sphere())
    write("sphere_octant_on_slab.yaml", sphere_on_slab())
