#!/usr/bin/python3
"""Write the 3D Cattaneo-Mindlin deck: two identical elastic blocks with paraboloid
ends, pressed together, then sheared with the press held, then (optionally) unsheared.

Each body is one degree-2 B-spline patch (no weights): x in [-L, L], y in [0, L] (the
half model; symmetry plane y = 0, which contains the shear direction x), between its
contact face z = +-(x^2 + y^2) / (2R) and a flat end z = +-H. A quadratic polynomial is
a degree-2 spline, so the face is the paraboloid exactly: on one span per direction,
x(u) = -L + 2L u has the control values (-L, 0, L) and x(u)^2 the values of its blossom
x(t_1) x(t_2) = (L^2, -L^2, L^2) (for y: (0, 0, L^2)); the tensor product of
(x^2 + y^2) / (2R) is then the sum of the two, and the body is linear in w between the
face and the flat end. The mesh is graded by `refine.insert`, which keeps the geometry:
spans of h over |x|, y < zone a_H, then growing by `growth` out to the body's size, in
x, y and in depth from the face. Hertz assumes exactly this paraboloid profile, and the
face has no degenerate point (the sphere octant's pole, where an earlier attempt put
the contact, had one).

The upper body's flat end is driven: down by `press` over t in [0, 1] (P is measured),
then along x by `shear` over t in [1, 2] with the press held, then back to zero over
[2, 3] (not with --no-unload). The lower body's flat end is held; y = 0 is a symmetry plane of
both. The bodies are mirror images across z = 0 (meshes and supports too), which is
what decouples the normal and tangential problems (Johnson, Contact Mechanics, 7.1).

Usage:
  /usr/bin/python3 verification/friction/make_cattaneo_mindlin_3d.py > verification/friction/cattaneo_mindlin_3d.yaml
  /usr/bin/python3 verification/friction/make_cattaneo_mindlin_3d.py --coarse > tests/analysis/decks/cattaneo_mindlin_coarse_3d.yaml
Options change the sizes (--help).
"""
import argparse
import math
import sys

E, NU = 1000.0, 0.3


def hertz_two_spheres(P, R):
    """Contact radius and peak pressure of two identical spheres (radius R) under P."""
    e_star = E / (2.0 * (1.0 - NU**2))
    r_star = R / 2.0
    a = (3.0 * P * r_star / (4.0 * e_star)) ** (1.0 / 3.0)
    return a, 3.0 * P / (2.0 * math.pi * a * a)


def graded(zone, h, extent, growth):
    """Breakpoints 0 < s_1 < ... < extent: spans of h up to zone, then growing by growth."""
    n = max(1, round(zone / h))
    points = [zone * k / n for k in range(1, n + 1)]
    step = zone / n
    while points[-1] < extent:
        step *= growth
        points.append(points[-1] + step)
    # Stretch the graded part so that the last breakpoint lands on extent, and drop it
    # (it is the patch's end); a last span shorter than the one before is merged.
    if len(points) > n + 1 and points[-1] - extent > 0.5 * step:
        points.pop()
    tail = points[n:]
    scale = (extent - zone) / (tail[-1] - zone)
    points = points[:n] + [zone + (p - zone) * scale for p in tail]
    return points[:-1]


def fmt(v):
    return f"{v:.10g}"


def knot_list(values):
    return "[" + ", ".join(fmt(v) for v in values) + "]"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--radius", type=float, default=1.0, help="R of the paraboloid faces")
    ap.add_argument("--half-size", type=float, default=0.6, help="L: x in [-L, L], y in [0, L]")
    ap.add_argument("--height", type=float, default=0.6, help="H: the flat ends at z = +-H")
    ap.add_argument("--a", type=float, default=0.1, help="the contact radius the mesh is graded for")
    ap.add_argument("--coarse", action="store_true",
                    help="the fast test's mesh: h = a/4, zone and depth zone 1.25 a, growth 2")
    ap.add_argument("--h", type=float, default=None, help="span size over the zone (default a/8; --coarse a/4)")
    ap.add_argument("--zone", type=float, default=None, help="the fine zone in x and y, in units of a (default 1.2; --coarse 1.25)")
    ap.add_argument("--depth-zone", type=float, default=None, help="the fine zone in depth, in units of a (default 0.5; --coarse 1.25)")
    ap.add_argument("--growth", type=float, default=None, help="span growth beyond the zone (default 1.6; --coarse 2)")
    ap.add_argument("--press", type=float, default=0.0175, help="downward travel of the upper end")
    ap.add_argument("--shear", type=float, default=0.0030, help="travel of the upper end along x")
    ap.add_argument("--no-unload", action="store_true", help="stop at t = 2, sheared")
    ap.add_argument("--press-only", action="store_true", help="stop at t = 1 (a quick look at the press)")
    ap.add_argument("--steps", type=int, default=None, help="steps.count (default 2 per unit of time)")
    ap.add_argument("--mu", type=float, default=0.3)
    ap.add_argument("--penalty", default="1.0e6", help="kappa = eps a / E* = 180 at a = 0.1")
    ap.add_argument("--formulation", default="two_half_pass", choices=["two_half_pass", "single_pass"])
    args = ap.parse_args()

    def pick(value, fine, coarse):
        return value if value is not None else (coarse if args.coarse else fine)

    R, L, H, a = args.radius, args.half_size, args.height, args.a
    h = pick(args.h, a / 8.0, a / 4.0)
    growth = pick(args.growth, 1.6, 2.0)
    zone = pick(args.zone, 1.2, 1.25) * a
    depth_zone = pick(args.depth_zone, 0.5, 1.25) * a
    xs = graded(zone, h, L, growth)                 # breakpoints in x > 0 (and mirrored), y > 0
    zs = graded(depth_zone, h, H, growth)           # depth below the face at the centre
    u = sorted([(L - x) / (2 * L) for x in xs] + [0.5] + [(L + x) / (2 * L) for x in xs])
    v = [y / L for y in xs]
    w_upper = [z / H for z in zs]                   # the face is w = 0, the end w = 1
    w_lower = sorted(1.0 - z / H for z in zs)       # the face is w = 1, the end w = 0
    T = 1 if args.press_only else 2 if args.no_unload else 3
    steps = args.steps if args.steps else 2 * T
    shear_path = {1: "[[0, 0], [1, 0]]", 2: "[[0, 0], [1, 0], [2, 1]]", 3: "[[0, 0], [1, 0], [2, 1], [3, 0]]"}[T]

    # Control values of x^2 and y^2 on one degree-2 span: the blossom x(t_1) x(t_2).
    cx = [(-L, L * L), (0.0, -L * L), (L, L * L)]
    cy = [(0.0, 0.0), (0.5 * L, 0.0), (L, L * L)]

    def patch(sign):
        """Rows [x, y, z, w], u fastest, then v, then w; sign +1 the upper body."""
        rows = []
        for k in range(3):                           # w: 0, 1/2, 1 along the body's height
            for (y, y2) in cy:
                for (x, x2) in cx:
                    face = (x2 + y2) / (2 * R)
                    if sign > 0:   # w = 0 the face, w = 1 the end z = H
                        z = face + 0.5 * k * (H - face)
                    else:          # w = 0 the end z = -H, w = 1 the face
                        z = -H + 0.5 * k * (H - face)
                    rows.append(f"          - [{fmt(x)}, {fmt(y)}, {fmt(z)}, 1.0]")
        return "\n".join(rows)

    n_spans = (len(u) + 1, len(v) + 1, len(w_upper) + 1)
    n_dofs = 3 * 2 * (n_spans[0] + 2) * (n_spans[1] + 2) * (n_spans[2] + 2)
    ratio_words = "pressed, sheared, unsheared" if T == 3 else "pressed, then sheared"
    cmd = " ".join(["make_cattaneo_mindlin_3d.py"] + sys.argv[1:])
    coarse_note = ("\n# The coarse copy for the fast test tests/analysis/friction_test.cpp (FrictionBetweenBodies);"
                   "\n# the fine deck: verification/friction/cattaneo_mindlin_3d.yaml.") if args.coarse else ""
    out = []
    out.append(f"""# Cattaneo-Mindlin in 3D: two identical elastic bodies with paraboloid ends
# z = +-(x^2 + y^2) / (2R), R = {fmt(R)} (Hertz's profile, exact in a degree-2 B-spline patch),
# E = {fmt(E)}, nu = {fmt(NU)}, mu = {fmt(args.mu)}; half model y >= 0 (symmetry plane y = 0 holds
# the shear direction x). The upper body's flat end z = {fmt(H)} is driven down by {fmt(args.press)}
# (t in [0, 1]; P is measured: 1.36 with the defaults, a = 0.098), then along x by {fmt(args.shear)} with the
# press held (t in [1, 2], Q ~ 0.5 mu P){', then back to 0 (t in [2, 3], Mindlin-Deresiewicz)' if T == 3 else ''}.
# The lower body's flat end z = -{fmt(H)} is held. The bodies are mirror images across z = 0, so
# the normal and tangential problems decouple (Johnson, Contact Mechanics, 7.1): the
# pressure is Hertz's (a = (3 P R* / (4 E*))^(1/3), R* = R/2, E* = E / (2 (1 - nu^2))) and
# the shear leaves a central stick zone c/a = (1 - Q/(mu P))^(1/3) (0.794 at Q = 0.5 mu P)
# with q(r) = mu p0 sqrt(1 - r^2/a^2) - mu p0 (c/a) sqrt(1 - r^2/c^2) (r <= c) along x.
# Mesh: spans of {fmt(h)} (a/{fmt(a / h)} for a = {fmt(a)}) over |x|, y < {fmt(zone)} and depth < {fmt(depth_zone)}, growing by
# {fmt(growth)} beyond; spans {n_spans[0]} x {n_spans[1]} x {n_spans[2]} per body, {n_dofs} dofs.
# Sides of both bodies: u0/u1 the faces x = -+L, v0 the symmetry plane y = 0, v1 y = L;
# upper: w0 the contact face, w1 the flat end; lower: w0 the flat end, w1 the contact face.
# Written by verification/friction/{cmd} (change sizes there).{coarse_note}
# Run:   build/bin/igacontact THIS_DECK.yaml -o RESULTS.h5 --threads 1
# Check: /usr/bin/python3 verification/friction/cattaneo_mindlin_3d.py RESULTS.h5 --plot FIG.png
# Measured stick zones, errors and run times: verification/friction/README.md.
format: 1
title: Cattaneo-Mindlin 3D, two identical paraboloid-ended bodies {ratio_words}

analysis: {{dimension: 3, kinematics: small}}

materials:
  - {{name: rubber, model: linear_elastic, E: {fmt(E)}, nu: {fmt(NU)}}}

bodies:
  - name: upper
    material: rubber
    nurbs:
      degrees: [2, 2, 2]
      knots: [[0, 0, 0, 1, 1, 1], [0, 0, 0, 1, 1, 1], [0, 0, 0, 1, 1, 1]]
      control_points:   # [x, y, z, w], u fastest, then v, then w
{patch(+1)}
    refine:
      insert:
        - {knot_list(u)}
        - {knot_list(v)}
        - {knot_list(w_upper)}
  - name: lower
    material: rubber
    nurbs:
      degrees: [2, 2, 2]
      knots: [[0, 0, 0, 1, 1, 1], [0, 0, 0, 1, 1, 1], [0, 0, 0, 1, 1, 1]]
      control_points:
{patch(-1)}
    refine:
      insert:
        - {knot_list(u)}
        - {knot_list(v)}
        - {knot_list(w_lower)}

constraints:
  - {{body: lower, side: w0, fix: [x, y, z]}}     # flat end held
  - {{body: lower, side: v0, fix: [y]}}           # symmetry plane y = 0
  - {{body: upper, side: v0, fix: [y]}}
  # The flat end of the upper body is driven (its mirror image is held): a force there
  # would let it tip (in 2D it did), a driven end keeps both far fields from turning.
  - {{body: upper, side: w1, fix: [y], displacement: [~, ~, {fmt(-args.press)}], amplitude: {"[[0, 0], [1, 1]]" if T == 1 else f"[[0, 0], [1, 1], [{T}, 1]]"}}}
  - {{body: upper, side: w1, displacement: [{fmt(args.shear)}, ~, ~], amplitude: {shear_path}}}

contact:
  - name: mate
    between: [upper.w0, lower.w1]
    formulation: {args.formulation}
    penalty: {args.penalty}
    friction: {{coefficient: {fmt(args.mu)}}}

steps: {{count: {steps}}}
""")
    sys.stdout.write("".join(out))


if __name__ == "__main__":
    main()
