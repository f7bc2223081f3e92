#pragma once
// Error measures of a computed contact pressure on a 3D contact surface against
// the Hertz point contact (hertz.hpp): the 3D counterpart of pressure_errors.hpp,
// with the same three numbers and the same formulas, applied to a radial curve.
//
// Input: scattered samples (r_i, p_i), e.g. post-processed pressures on a grid
// of each contact face or Gauss-point values, with r_i >= 0 the distance from
// the contact centre in the REFERENCE configuration, measured in the contact
// plane (in_plane_distances below); Hertz is axisymmetric, so p depends on r only.
//
// The radial curve. The samples are binned on the radial grid of bin width
// h = radial_bin_fraction * a (bins [k h, (k+1) h), k = 0, 1, ..., over the
// whole data range, not only r <= 1.2a, so that a too wide contact zone is
// seen); each non-empty bin gives one point (mean r, mean p) of its samples,
// and empty bins are skipped. The curve is the piecewise-linear interpolant of
// these points (pressure_errors.hpp "The discrete curve").
// Why the mean position and not the bin centre: the mean of a linear p(r) over
// the samples is its value at their mean r, whatever their distribution in the
// bin, so the binning adds no first-order error (also in the first bin, whose
// samples all lie on one side of its centre).
// Why it is fair to a symmetric part of the model: samples of an octant cover
// the quarter x, y >= 0 of the contact disc; a bin is a quarter ring, and by the
// two symmetry planes the full model's solution on the whole ring consists of
// mirror images of the quarter's values, so the quarter-ring mean equals the
// full-ring mean. No weighting or doubling is needed for a half, a quarter or a
// full model; a non-uniform sample density along the ring (e.g. a NURBS
// parametrization) matters only where p varies along the ring, which for an
// axisymmetric solution is discretization error.
//
// The measures, on the radial curve, as in 2D with the curve read as the
// symmetric section p_h(|x|) through the contact centre (pressure_errors with
// mirror = true):
//  - peak   = (max over the curve points of p - p0) / p0;
//  - radius = (a_h - a) / a, a_h the outermost r where the curve crosses 1 % of
//             its maximum (the 2D half-width rule; exact data measure about
//             -5e-5 plus the binning and interpolation error);
//  - l2     = sqrt( int_{-1.2a}^{1.2a} (p_h(|x|) - p_H(x))^2 dx ) / (p0 sqrt(a))
//           = sqrt( 2 int_0^{1.2a} (p_h(r) - p_H(r))^2 dr ) / (p0 sqrt(a)),
//             the same number as the 2D definition for a diameter of the disc
//             (p_h = 0 gives sqrt(4/3), p_h = (1 + s) p_H gives s sqrt(4/3)).
// NaN or infinity anywhere in r or p gives NaN in all three; sizes must agree
// and be non-zero and r must be >= 0 (throws iga::Error).

#include "analytic/hertz.hpp"
#include "core/types.hpp"

#include <vector>

namespace iga::analytic {

/// Width of the radial bins as a fraction of the Hertz contact radius a: fine
/// enough that binning smooths the square-root edge at r = a over a/100 only
/// (<= 0.5 % on the contact radius), coarse enough that post-processed samples
/// (16 per knot span, spans ~a/10) put tens to hundreds of samples in each bin.
constexpr double radial_bin_fraction = 0.01;

struct RadialPressureErrors {
    double peak;    ///< (max p_h - p0) / p0, signed
    double radius;  ///< (a_h - a) / a, signed
    double l2;      ///< sqrt(2 int_0^{1.2a} (p_h - p_H)^2 dr) / (p0 sqrt(a)), >= 0
};

/// The radial curve of the samples: one point (mean r, mean p) per non-empty bin
/// of width radial_bin_fraction * a, increasing r. Requires finite r >= 0.
struct RadialCurve {
    std::vector<double> r;
    std::vector<double> p;
};
RadialCurve radial_curve(double a, const std::vector<double>& r, const std::vector<double>& p);

/// Errors of the scattered samples (r[i], p[i]) against `hertz`, as defined above.
RadialPressureErrors radial_pressure_errors(const HertzPointContact& hertz, const std::vector<double>& r,
                                            const std::vector<double>& p);

/// Distances of points (rows, 3 columns) from `center` measured in the plane
/// through it normal to `normal` (any length > 0): |(X - c) - ((X - c).n) n|.
std::vector<double> in_plane_distances(const RowMatrix& points, const VecN& center, const VecN& normal);

}  // namespace iga::analytic
