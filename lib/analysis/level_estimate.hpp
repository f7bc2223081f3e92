#pragma once
// What one level of `accuracy:` measures, and how far it is from the limit
// (docs/accuracy_on_demand.md): the contact quantity of a level, the difference of two levels,
// and the error estimate that difference gives.
//
// Each level halves the spans over and around the contact zone (zone_refinement.hpp),
// so the zone's element size falls by r = 2 per level. For a quantity q_h = q + C h^p,
// the error of the finer of two levels is (Richardson; refinement_study.hpp)
//   e_k = |q_k - q_{k-1}| / (2^p - 1),
// and with p = 1 that is the difference itself. p = 1 is measured, not assumed from
// theory: from 8 x 4 uniform spans of the 2D Hertz quarter disc the pressure's L2 error
// against Hertz falls by 1.5-2.3 per level (46.8, 30.3, 18.7, 9.31, 4.95, 2.19, 1.27 %),
// and the differences d_k estimate it within 0.76-1.23 at every level. An order observed
// from two differences is no guide before the asymptotic range: there it came out at
// 0.55 and 2, and the estimates missed by factors of 2.7 and 3.
//
// Where the errors fall more slowly than by 2 per level (a flat punch's corner: the
// differences 4.3, 3.1, 2.2, 1.5 % of inputs/press_then_shear_friction_2d.yaml), d_k
// underestimates: where two successive ratios are below slow_ratio (slow_convergence),
// the run also reports the bound d_k / (rate - 1), and judges the target by it. Hertz's
// first levels shrink by 1.45 twice and then by 2.5: the bound there is 2.7 times the
// error, which costs a level at most; it is never used to stop earlier.
//
// The target is met when the band Fs e_k, Fs = 1.25 (Roache's safety factor), is within
// it: an estimate that is low by up to a quarter does not end the levels early.
//
// The pressure's difference is a field's: with p_k the recovered pressure of level k
// on its contact side (Sauer's control-point averages times the side's basis; every
// level has the same parametrization, knot insertion keeps it),
//   d_k = || p_k - p_{k-1} ||_L2 / || p_k ||_L2   over the side in its reference
// configuration, by Gauss quadrature on level k's spans (degree + 2 points per span
// and direction). A scalar's is |q_k - q_{k-1}| / |q_k|.

#include "io/deck.hpp"
#include "io/results_data.hpp"
#include "nurbs/patch.hpp"

#include <cmath>
#include <optional>
#include <vector>

namespace iga::analysis {

/// The order of convergence the estimate uses (see above) and the safety factor of the band.
inline constexpr double convergence_order = 1.0;
inline constexpr double safety_factor = 1.25;

/// The recovered contact pressure of one level on its side.
struct SidePressure {
    nurbs::Patch side;        ///< the analysed side, reference configuration
    Vector control_pressure;  ///< p_A, one per control point of `side`
};

/// The value of `quantity` on one side: the normal force; the zone's length (2D) or the
/// radius of a disc of its area (3D) from the pressed Gauss points' weights; for
/// pressure_l2 the L2 norm of the recovered pressure.
double side_quantity(io::AccuracyQuantity quantity, const io::ContactSideResult& side, const SidePressure& field);

/// || fine - coarse ||_L2 / || fine ||_L2 over the fine level's side.
double relative_pressure_difference(const SidePressure& coarse, const SidePressure& fine);

/// The rate by which the last differences shrank per level, where it shows slower
/// convergence than the estimate assumes: d_{k-2}/d_{k-1} and d_{k-1}/d_k both below
/// slow_ratio (the smaller of the two returned); nullopt otherwise, or with fewer than
/// three differences. The estimate d_k is then low by up to 1 / (rate - 1): where the
/// error falls by rate per level, e_k = d_k / (rate - 1) for aligned errors.
inline constexpr double slow_ratio = 1.6;
std::optional<double> slow_convergence(const std::vector<double>& differences);

/// The estimated relative error of a level from its relative difference d_k to the level before.
inline double level_error(double difference) { return difference / (std::exp2(convergence_order) - 1.0); }

}  // namespace iga::analysis
