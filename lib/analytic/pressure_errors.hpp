#pragma once
// Error measures of a computed contact-pressure curve against the Hertz
// solution (hertz.hpp); the numbers stored in /reference/<pair> and quoted in
// docs/theory.md "Error measures against Hertz". Notation: p_h the computed pressure, p_H the Hertz pressure,
// a and p0 the Hertz half-width and peak, x the signed distance from the
// contact centre measured in the reference configuration (Hertz is a
// small-strain theory, docs/theory.md "The Hertz benchmark").
//
// The discrete curve. The samples (x_i, p_i) are sorted by x; samples whose x
// agree to 1e-12 of the data extent max|x_i| are merged into one with the
// mean of their p. The curve is the piecewise-linear interpolant of the merged
// samples, and 0 outside [min x_i, max x_i]. Gauss-point data (the scattered
// penalty pressures eps_N <g_N>) and post-processed NURBS samples are
// measured by the same definitions: Gauss-point values are interpolated
// linearly like any other samples.
//
// Mirror. With mirror = true the data cover one half (all x >= 0 or all
// x <= 0, up to round-off 1e-8 max|x_i|) of a model symmetric about x = 0,
// e.g. a quarter cylinder. The samples are then reflected about x = 0 and
// the measures below are those of the symmetric full data set; in
// particular the curve is interpolated across x = 0 between the innermost
// samples, l2 integrates the covered half and doubles it, and half_width is
// the crossing on the covered side. mirror = true on half data gives the
// same numbers as mirror = false on the reflected full data.
//
// The measures (all dimensionless and signed where it matters):
//  - peak       = (max_i p_i - p0) / p0  (max over the merged samples);
//  - half_width = (a_h - a) / a, where a_h is half the distance between the
//                 outermost left and right points at which the curve crosses
//                 1 % of its maximum (linearly interpolated within a segment;
//                 at the end of the data when the curve is still above 1 %
//                 there), i.e. the mean of |x_left| and |x_right| for data
//                 on both sides of the centre. For the exact ellipse the
//                 crossing sits at sqrt(1 - 1e-4) a = 0.99995 a, so exact
//                 data measure half_width = -5e-5 (plus interpolation error).
//                 A curve whose maximum is <= 0 has a_h = 0 (half_width = -1);
//  - l2         = sqrt( int_{-1.2a}^{1.2a} (p_h - p_H)^2 dx ) / (p0 sqrt(a)).
//                 The integral is evaluated per segment between consecutive
//                 breakpoints (the samples, +-a, +-1.2a) with 5-point
//                 Gauss-Legendre; inside |x| < a in the variable theta with
//                 x = a sin(theta), where p_H = p0 cos(theta) is smooth, so
//                 the square-root edge of p_H costs no accuracy (relative
//                 error ~1e-12 and below). For reference: p_h = 0 gives
//                 l2 = sqrt(4/3), and p_h = (1 + s) p_H gives l2 = s sqrt(4/3).
//
// NaN or infinity anywhere in x or p gives NaN in all three measures (never a
// silently finite number). Sizes of x and p must agree and be non-zero, and
// mirror data must be one-sided; violations throw iga::Error.
#include "analytic/hertz.hpp"

#include <vector>

namespace iga::analytic {

struct PressureErrors {
    double peak;        ///< (max p_h - p0) / p0, signed
    double half_width;  ///< (a_h - a) / a, signed
    double l2;          ///< sqrt(int_{|x|<=1.2a} (p_h - p_H)^2 dx) / (p0 sqrt(a)), >= 0
};

/// Errors of the sampled pressure (x[i], p[i]) against `hertz`, as defined above.
/// x: signed distances from the contact centre (reference configuration), any
/// order; p: pressures, same length; mirror: the data cover one half of a
/// symmetric model and count twice.
PressureErrors pressure_errors(const HertzLineContact& hertz, const std::vector<double>& x,
                               const std::vector<double>& p, bool mirror);

/// The same measures against any elliptic profile p0 sqrt(1 - x^2/a^2), a > 0,
/// p0 > 0: the line contact above, or the radial curve of a point contact
/// (radial_pressure_errors.hpp).
PressureErrors elliptic_pressure_errors(double a, double p0, const std::vector<double>& x,
                                        const std::vector<double>& p, bool mirror);

}  // namespace iga::analytic
