#include "analytic/hertz.hpp"

#include "core/error.hpp"

#include <cmath>
#include <numbers>
#include <string>

namespace iga::analytic {

namespace {

// Compliance (1 - nu^2)/E of one body (line and point contact alike); 0 for a rigid body (E = +inf).
double plane_strain_compliance(double E, double nu, const char* which)
{
    // Written as !(cond) so that NaN inputs fail too.
    IGA_CHECK(E > 0, std::string("Hertz: ") + which + " Young's modulus must be > 0");
    IGA_CHECK(nu > -1.0 && nu < 0.5, std::string("Hertz: ") + which + " Poisson's ratio must lie in (-1, 0.5)");
    return (1.0 - nu * nu) / E;
}

HertzLineContact make_contact(double E_star, double R_star, double force)
{
    IGA_CHECK(force > 0 && std::isfinite(force), "Hertz: the force per unit thickness must be finite and > 0");
    IGA_CHECK(E_star > 0 && std::isfinite(E_star), "Hertz: E* must be finite and > 0 (are both bodies rigid?)");
    IGA_CHECK(R_star > 0 && std::isfinite(R_star), "Hertz: R* must be finite and > 0 (1/R1 + 1/R2 > 0)");
    const double a = std::sqrt(4.0 * force * R_star / (std::numbers::pi * E_star));
    const double p0 = 2.0 * force / (std::numbers::pi * a);
    return {.E_star = E_star, .R_star = R_star, .force = force, .a = a, .p0 = p0};
}

HertzPointContact make_point_contact(double E_star, double R_star, double force)
{
    IGA_CHECK(force > 0 && std::isfinite(force), "Hertz: the force must be finite and > 0");
    IGA_CHECK(E_star > 0 && std::isfinite(E_star), "Hertz: E* must be finite and > 0 (are both bodies rigid?)");
    IGA_CHECK(R_star > 0 && std::isfinite(R_star), "Hertz: R* must be finite and > 0 (1/R1 + 1/R2 > 0)");
    const double a = std::cbrt(3.0 * force * R_star / (4.0 * E_star));
    const double p0 = 3.0 * force / (2.0 * std::numbers::pi * a * a);
    return {.E_star = E_star, .R_star = R_star, .force = force, .a = a, .p0 = p0, .approach = a * a / R_star};
}

/// 1/R1 + 1/R2 as R*, with the checks shared by cylinders and spheres.
double effective_radius(double R1, double R2)
{
    IGA_CHECK(R1 != 0 && R2 != 0 && !std::isnan(R1) && !std::isnan(R2), "Hertz: radii must be non-zero numbers");
    const double curvature = 1.0 / R1 + 1.0 / R2;  // 1/inf = 0: a plane
    IGA_CHECK(curvature > 0, "Hertz: 1/R1 + 1/R2 must be > 0 (a concave radius must exceed the convex one)");
    return 1.0 / curvature;
}

/// p0 sqrt(1 - (x/a)^2) inside |x| < a, 0 outside, NaN for NaN x.
double elliptic_pressure(double p0, double a, double x)
{
    if (std::isnan(x))
        return x;
    const double t = x / a;
    return std::abs(t) < 1.0 ? p0 * std::sqrt((1.0 - t) * (1.0 + t)) : 0.0;
}

}  // namespace

double HertzPointContact::pressure(double r) const
{
    return elliptic_pressure(p0, a, r);
}

HertzPointContact hertz_sphere_plane(double E, double nu, double radius, double force)
{
    const double compliance = plane_strain_compliance(E, nu, "sphere");
    IGA_CHECK(radius > 0, "Hertz: the sphere radius must be > 0");
    return make_point_contact(1.0 / compliance, radius, force);
}

HertzPointContact hertz_two_spheres(double E1, double nu1, double R1, double E2, double nu2, double R2, double force)
{
    const double compliance = plane_strain_compliance(E1, nu1, "first body") +
                              plane_strain_compliance(E2, nu2, "second body");
    return make_point_contact(1.0 / compliance, effective_radius(R1, R2), force);
}

double HertzLineContact::pressure(double x) const
{
    return elliptic_pressure(p0, a, x);
}

HertzLineContact hertz_cylinder_plane(double E, double nu, double radius, double force)
{
    const double compliance = plane_strain_compliance(E, nu, "cylinder");
    IGA_CHECK(radius > 0, "Hertz: the cylinder radius must be > 0");
    return make_contact(1.0 / compliance, radius, force);
}

HertzLineContact hertz_two_cylinders(double E1, double nu1, double R1, double E2, double nu2, double R2,
                                     double force)
{
    const double compliance = plane_strain_compliance(E1, nu1, "first body") +
                              plane_strain_compliance(E2, nu2, "second body");
    return make_contact(1.0 / compliance, effective_radius(R1, R2), force);
}

}  // namespace iga::analytic
