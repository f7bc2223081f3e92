#pragma once
// Plane-strain Hertz solution for two parallel cylinders (line contact), the
// analytic reference stored in /reference of the results file.
//
// Reference: Johnson, "Contact Mechanics", CUP 1985, ch. 4-5; formulas as in
// shared/physics.md §2.1. With P the force per unit thickness:
//   1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2,   1/R* = 1/R1 + 1/R2,
//   a = sqrt(4 P R* / (pi E*)),   p0 = 2P/(pi a) = sqrt(P E* / (pi R*)),
//   p(x) = p0 sqrt(1 - x^2/a^2) for |x| <= a, 0 outside;   int p dx = P.
// Small-strain, half-space theory: valid for a << R (see physics.md §2.2).
//
// Invariants of a HertzLineContact made by the two functions below: every
// member is finite and > 0. Inputs that would break this throw iga::Error
// (the deck reader validates user values first; these checks are a backstop).

namespace iga::analytic {

/// The Hertz line contact between two cylinders (or a cylinder and a plane).
struct HertzLineContact {
    double E_star;  ///< effective plane-strain modulus E*
    double R_star;  ///< effective radius R*
    double force;   ///< P: force per unit thickness on the whole contact (both halves of a symmetric model)
    double a;       ///< contact half-width
    double p0;      ///< peak pressure, at x = 0

    /// Hertz pressure at signed distance x from the contact centre:
    /// p0 sqrt(1 - x^2/a^2) for |x| < a, 0 otherwise; NaN for NaN x.
    double pressure(double x) const;
};

/// Elastic cylinder (E, nu, radius) on a rigid plane: E* = E/(1 - nu^2), R* = radius.
/// Requires E > 0, -1 < nu < 0.5, radius > 0, force > 0.
HertzLineContact hertz_cylinder_plane(double E, double nu, double radius, double force);

/// Two elastic cylinders. A negative radius denotes a concave surface (a
/// cylinder in a bore); 1/R1 + 1/R2 must stay > 0. A radius of +infinity is a
/// plane and a modulus of +infinity a rigid body, so
/// hertz_two_cylinders(E, nu, R, inf, 0, inf, P) == hertz_cylinder_plane(E, nu, R, P).
/// Requires E1, E2 > 0, -1 < nu1, nu2 < 0.5, non-zero radii with 1/R1 + 1/R2 > 0, force > 0.
HertzLineContact hertz_two_cylinders(double E1, double nu1, double R1, double E2, double nu2, double R2,
                                     double force);

}  // namespace iga::analytic
