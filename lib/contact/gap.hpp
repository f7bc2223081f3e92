#pragma once
// The normal gap and its sign convention, pinned once for the whole solver.
//
//   g_N = -(x - xbar) . nbar        (Kopacka, Gabriel, Kolman, Plesek, eq. 1)
//
// x is a point of the slave (carrying) surface, xbar its closest point on the
// master, nbar the unit OUTWARD normal of the master at xbar. A POSITIVE gap is
// a penetration, a negative gap is open. The penalty pressure is
// p = eps_N <g_N> (eq. 3) with the Macaulay bracket <a> = (|a| + a) / 2. The same
// sign is stored in results files (/steps/*/contact/*/gauss_points/gap).
//
// Much of the contact literature writes the opposite sign (g = (x - xbar) . n < 0 for
// penetration, p = eps <-g>); the kernels translate g = -g_N at their boundary,
// nowhere else.
//
// In 2D the outward normal of a side is n = s (t_y, -t_x) / |t|, t = dx/dxi the
// tangent along the side's parameter and s = +1 or -1 the side's orientation
// sign (boundary/patch_side.hpp); s is fixed for a run because deformations with
// det F > 0 preserve orientation.

#include "core/types.hpp"

#include <cmath>

namespace iga::contact {

/// <a> = max(a, 0), the Macaulay bracket (eq. 3).
inline double macaulay(double a) { return a > 0.0 ? a : 0.0; }

/// H(a) = d<a>/da: 1 for a > 0, else 0 (a gap of exactly zero is inactive).
inline double heaviside(double a) { return a > 0.0 ? 1.0 : 0.0; }

/// g_N = -(x - xbar) . nbar: positive = penetration.
inline double normal_gap(const VecN& x, const VecN& xbar, const VecN& nbar) { return -(x - xbar).dot(nbar); }

/// Unit normal s (t_y, -t_x) / |t| of a 2D curve with tangent t (non-zero) and
/// orientation sign s = +1 / -1.
inline VecN curve_normal_2d(const VecN& tangent, int sign)
{
    VecN n(2);
    n << tangent(1), -tangent(0);
    return (static_cast<double>(sign) / tangent.norm()) * n;
}

}  // namespace iga::contact
