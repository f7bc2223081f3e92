#pragma once
// Hertz solutions, the analytic references stored in /reference of the results
// file: plane-strain line contact of two parallel cylinders (2D decks) and
// point contact of two spheres (3D decks).
//
// Line contact.
//
// Reference: Johnson, "Contact Mechanics", CUP 1985, ch. 4-5; formulas as in
// docs/theory.md "Hertz formulas". With P the force per unit thickness:
//   1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2,   1/R* = 1/R1 + 1/R2,
//   a = sqrt(4 P R* / (pi E*)),   p0 = 2P/(pi a) = sqrt(P E* / (pi R*)),
//   p(x) = p0 sqrt(1 - x^2/a^2) for |x| <= a, 0 outside;   int p dx = P.
// Small-strain, half-space theory: valid for a << R (docs/theory.md "Hertz formulas").
//
// Point contact (Johnson, ch. 4.2). With F the total normal force:
//   1/E* and 1/R* as above (R1, R2 the sphere radii),
//   a = (3 F R* / (4 E*))^(1/3),   p0 = 3F / (2 pi a^2),   approach delta = a^2 / R*,
//   p(r) = p0 sqrt(1 - r^2/a^2) for r <= a, 0 outside;   int p dA = 2 pi int p r dr = F.
// r is the distance from the contact centre in the contact plane. Same
// small-strain half-space validity (a << R).
//
// Invariants of a HertzLineContact or HertzPointContact made by the functions
// below: every member is finite and > 0. Inputs that would break this throw iga::Error
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

/// The Hertz point contact between two spheres (or a sphere and a plane).
struct HertzPointContact {
    double E_star;    ///< effective modulus E*
    double R_star;    ///< effective radius R*
    double force;     ///< F: total force on the whole contact (the whole sphere, also for a symmetric part of it)
    double a;         ///< contact radius
    double p0;        ///< peak pressure, at r = 0
    double approach;  ///< delta = a^2 / R*: how far the distant points of the two bodies approach

    /// Hertz pressure at distance r >= 0 from the contact centre:
    /// p0 sqrt(1 - r^2/a^2) for |r| < a, 0 otherwise; NaN for NaN r.
    double pressure(double r) const;
};

/// Elastic sphere (E, nu, radius) on a rigid plane: E* = E/(1 - nu^2), R* = radius.
/// Requires E > 0, -1 < nu < 0.5, radius > 0, force > 0.
HertzPointContact hertz_sphere_plane(double E, double nu, double radius, double force);

/// Two elastic spheres; radii and moduli as in hertz_two_cylinders (negative radius:
/// concave; +infinity: a plane or a rigid body), so
/// hertz_two_spheres(E, nu, R, inf, 0, inf, F) == hertz_sphere_plane(E, nu, R, F).
HertzPointContact hertz_two_spheres(double E1, double nu1, double R1, double E2, double nu2, double R2,
                                    double force);

}  // namespace iga::analytic
