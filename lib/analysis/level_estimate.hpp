#pragma once
// What one level of `accuracy:` measures, and how far it is from the limit
// (docs/accuracy_on_demand.md): the contact quantity of a level, the difference of two levels,
// and the error estimate that difference gives.
//
// Each level halves the spans where the pressure changed most (span_marking.hpp), once:
// the element size there falls by 2, and an error of order 1 in h by about 2.
// Level k's estimate is
//   e_k = max(d_k, min(e_{k-1}, 1) / largest_fall(quantity)),
// d_k the relative difference of the quantity to level k - 1. The difference alone is
// Richardson's |q_k - q_{k-1}| / (2^p - 1) with p = 1; the floor keeps a level whose
// refinement happened not to move the answer much (the error fell by 1.2 where the levels
// average 1.6-2) from claiming an error it has not shown: a difference measures a change,
// not an error. The floor's fall is what the levels' errors were measured to do: the
// pressure's L2 error fell by 1.2-2.6 per level on the 2D Hertz starts and by 1.3-2.0 on
// the 3D sphere octant (largest_fall 2); the stick zone's by 2.2-2.8 on the 2D and 2.5-2.6
// on the 3D Cattaneo-Mindlin levels once it spans several Gauss points (3: with 2 the
// floor, not the difference, set its estimate from level 5 on, 2-3.6 times the error).
// Both are measured, not assumed: on the 2D Hertz start of
// inputs/hertz_accuracy_2d.yaml the estimates are within 0.53-1.6 of the error against
// Hertz; on the 3D sphere octant within 0.62-1.5 of it (docs/accuracy_on_demand.md). Two
// successive levels' errors are partly aligned (then d_k = (r - 1) e_k, r the fall per
// level) and partly not (up to d_k = sqrt(1 + r^2) e_k): in 3D, where a level adds twice
// the dofs and r is about 2, the second dominates and the estimate is high by up to 2.
//
// A zone measured from Gauss points (contact_radius, stick_zone) moves only when a point
// at its edge changes state: its difference is floored at its resolution (zone_resolution),
// so a level whose one or two pressed points stay the same does not claim it converged.
//
// Where the differences fall more slowly than by slow_ratio over slow_levels levels in a
// row (a flat punch's corner: 4.3, 3.1, 2.2, 1.5 % of
// inputs/press_then_shear_friction_2d.yaml under uniform halving), e_k is low: the run
// also reports the bound d_k / (rate - 1), and judges the target by it. It is never used
// to stop earlier.
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

/// The safety factor of the band (see above).
inline constexpr double safety_factor = 1.25;

/// The recovered contact pressure of one level on one patch side.
struct SidePressure {
    nurbs::Patch side;        ///< the analysed side, reference configuration
    Vector control_pressure;  ///< p_A, one per control point of `side`
};

/// The recovered contact pressure of one level on a contact surface: its patch sides in the
/// surface's order, one or the pieces of a named surface (a control point two pieces share
/// carries the same p_A in both). Norms and differences are sums over the pieces.
using SurfacePressure = std::vector<SidePressure>;

/// gauss_points/status of a sticking point (docs/results.md).
inline constexpr int stick_status = 1;

/// The value of `quantity` on one side: the normal force; for contact_radius the whole
/// zone's half-width (2D) or the radius of a disc of its area (3D), from the pressed Gauss
/// points' weights, the modelled part mirrored across the `mirrors` symmetry planes that cut
/// it (zone_symmetry.hpp); for stick_zone the same of the pressed points that stick, its
/// length in 2D; for pressure_l2 the L2 norm of the recovered pressure (of the modelled part).
double side_quantity(io::AccuracyQuantity quantity, const io::ContactSideResult& side, const SurfacePressure& field,
                     int mirrors = 0);

/// The difference of two levels' pressures over the fine level's surface.
struct PressureDifference {
    double relative = 0.0;  ///< || fine - coarse ||_L2 / || fine ||_L2
    /// Per piece: || fine - coarse ||^2_L2 on each element of the piece's side (rows,
    /// elements() order), split over the side's directions (columns) by the share of the
    /// fine pressure's change across the element along each: the edge of a disc-shaped zone
    /// crosses a span of u where it runs along u, and that span needs refining in v, not in u.
    std::vector<RowMatrix> element2;
};
/// Piece k of `coarse` and of `fine` are the same patch side on two levels.
PressureDifference pressure_difference(const SurfacePressure& coarse, const SurfacePressure& fine);

/// || p - p_ref ||_L2 / || p_ref ||_L2 over the side, p_ref the reference's Hertz pressure
/// p0 sqrt(1 - s^2/a^2) at each point's reference coordinates X: s the distance from the
/// reference's centre along its tangent (line contact) or in its contact plane (point
/// contact). The error in the estimate's own norm, over the whole modelled side: the
/// reference's stored l2 is measured on |x| <= 1.2a and normalized by p0 sqrt(a), and in
/// 3D on the ring-averaged radial curve, which leaves out every error that varies around
/// the ring (on the 3D sphere levels about half of it).
double reference_pressure_error(const io::ReferenceData& reference, const SurfacePressure& field);

/// The rate by which the last differences shrank per level, where it shows slower
/// convergence than the estimate assumes: the last slow_levels ratios d_{j-1}/d_j all
/// between 1 and slow_ratio (the largest of them returned); nullopt otherwise, or with
/// fewer differences. The estimate d_k is then low by up to 1 / (rate - 1): where the
/// error falls by rate per level, e_k = d_k / (rate - 1) for aligned errors.
inline constexpr double slow_ratio = 1.6;
inline constexpr std::size_t slow_levels = 3;
std::optional<double> slow_convergence(const std::vector<double>& differences);

/// The floor's largest fall of the error per level for `quantity` (see above).
inline double largest_fall(io::AccuracyQuantity quantity)
{
    return quantity == io::AccuracyQuantity::stick_zone ? 3.0 : 2.0;
}

/// The estimated relative error of a level from its relative difference d_k to the level
/// before and the estimate of that level: max(d_k, min(e_{k-1}, 1) / fall). An estimate
/// above 100 % says only that the quantity is not resolved yet (a coarse level's force
/// 0.14 after 1.32: d = 848 %); as a floor it carries no more than that, else one such
/// level would hold the next ones' estimates far above their own differences.
inline double level_error(double difference, std::optional<double> previous, double fall)
{
    return previous ? std::max(difference, std::min(*previous, 1.0) / fall) : difference;
}

/// The Gauss points of `side` whose weights make the zone of `quantity` (contact_radius:
/// the pressed points; stick_zone: the pressed points that stick).
std::vector<Index> zone_points(io::AccuracyQuantity quantity, const io::ContactSideResult& side);

/// The relative resolution of the zone of `quantity` (contact_radius or stick_zone)
/// measured on `side` (side_quantity): whether a Gauss point at its edge is in the zone
/// changes the measure by that point's weight. In 2D (a curve) the weights of its first and
/// last points over the zone's length, leaving out an end that is the side's own (a
/// symmetry line: it does not move); in 3D the width sqrt(w) of the point farthest from the
/// zone's centroid over that distance. A curve of several patch sides (gauss_points/patch)
/// has no one parameter along it: it is measured as a surface is, with the width w of the
/// point farthest from the centroid (up to twice the resolution of a zone that ends at the
/// side's end: conservative). 1 with one point or none.
double zone_resolution(io::AccuracyQuantity quantity, const io::ContactSideResult& side);

}  // namespace iga::analysis
