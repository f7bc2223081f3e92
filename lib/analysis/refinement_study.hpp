#pragma once
// Error estimates of `igacontact study` from a sequence of uniformly h-refined
// runs: level k has every knot span of level 0 halved k times (h_k = h_0 / 2^k,
// refinement ratio r = 2).
//
// Richardson extrapolation, for a quantity q_h = q + C h^p + (higher order):
//   observed order   p = log2(|q_{N-2} - q_{N-3}| / |q_{N-1} - q_{N-2}|)  from the
//                    three finest levels, when both differences are non-zero, of the
//                    same sign and shrinking (the sequence converges monotonically);
//   extrapolated     q_extr = q_{N-1} + (q_{N-1} - q_{N-2}) / (r^p - 1);
//   estimated error  |q_k - q_extr| / |q_extr| for every level k.
// Otherwise (two levels only, or differences that change sign while shrinking) the
// order is not observed (empty in the CSV) and the formal order is assumed: the
// lowest polynomial degree of the bodies' patches (the rate of a degree-p
// discretization is p for energy-type errors; contact limits the regularity, so no
// more is assumed). When the two finest levels agree (to 1e-9, the solver's noise),
// q_extr is the finest value.
//
// How far to trust q_extr (Roache's grid convergence index, Roache 1998,
// "Verification and Validation in Computational Science and Engineering"):
//   band  GCI = Fs |q_{N-1} - q_{N-2}| / (r^p - 1), relative to |q_extr|: the
//         distance from the finest value to q_extr times a safety factor Fs, 1.25
//         with an observed order, 3 with an assumed one;
//   asymptotic range: the observed order of the three levels ending at level k lies
//         within 10 % of the formal order (Oberkampf and Roy 2010 take Fs = 1.25
//         only there); outside it the extrapolated digits are not an estimate, the
//         band is;
//   not converging: the finest difference is no smaller than the one before: no
//         extrapolation and no error estimate at all;
//   zero limit: the band reaches zero (GCI >= |q_extr|, e.g. a penetration that
//         vanishes as h -> 0 under an auto penalty ~ 1/h): relative errors have no
//         meaning and are left empty.

#include "io/study_csv.hpp"

#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace iga::analysis {

/// Refinement ratio of consecutive levels: every knot span halved.
constexpr double refinement_ratio = 2.0;
/// Roache's safety factors: three levels with an observed order, or an assumed order.
constexpr double safety_factor_observed = 1.25;
constexpr double safety_factor_assumed = 3.0;
/// Observed order within this fraction of the formal order: the asymptotic range.
constexpr double asymptotic_order_tolerance = 0.1;
/// Two finest levels closer than this fraction of the value agree: Newton stops at a
/// relative residual of 1e-10 (the default), which leaves differences of about that
/// size in a quantity the discretization resolves exactly (a force-controlled normal
/// force); they are not a trend to extrapolate.
constexpr double solver_noise = 1e-9;

/// How far the levels support the extrapolation of a quantity (CSV column `estimate`).
enum class EstimateSupport {
    asymptotic,      ///< order observed, within 10 % of the formal order
    not_asymptotic,  ///< order observed, far from the formal order
    assumed_order,   ///< two levels, or shrinking differences that change sign
    converged,       ///< the two finest levels agree to the solver's noise
    not_converging,  ///< the finest difference is no smaller than the one before
    zero_limit       ///< the band reaches zero: no relative error
};

/// The CSV spelling: asymptotic, not_asymptotic, assumed_order, converged, not_converging, zero_limit.
std::string support_name(EstimateSupport support);

struct Extrapolation {
    EstimateSupport support = EstimateSupport::assumed_order;
    std::optional<double> extrapolated;    ///< empty when not converging
    std::optional<double> observed_order;  ///< empty when the levels do not show one
    double order_used = 0.0;               ///< observed, else formal (unused when the finest levels agree)
    double safety_factor = 0.0;            ///< Fs of the band (0 when there is no band)
    std::optional<double> rel_band;        ///< GCI / |q_extr|; empty when not converging or zero limit
};

/// Observed order of three consecutive values (coarsest first), when they converge
/// monotonically: differences non-zero, of one sign, shrinking.
std::optional<double> observed_order(double coarse, double medium, double fine);

/// Richardson extrapolation of values on consecutive levels (h halved each time),
/// coarsest first, with its band and support. nullopt with fewer than two values.
std::optional<Extrapolation> richardson(std::span<const double> values, double formal_order);

/// One completed level of a study.
struct StudyLevel {
    int level = 0;
    long long dofs = 0;
    double wall_s = 0.0;
    std::vector<std::pair<std::string, double>> quantities;  ///< io::LevelResults::quantities
    std::map<std::string, double> reference_values;          ///< io::LevelResults::reference_values
};

/// The rows of the study table (quantity by quantity, levels in order) from the
/// completed levels, coarsest first. Richardson uses the longest run of
/// consecutive levels that ends at the finest completed one. Reaction components
/// that are zero to 1e-6 of the largest reaction or contact normal force at every
/// level (a symmetry side's reaction, a constrained side's free directions) are
/// left out. A level's `asymptotic` flag is set where it ends three consecutive levels:
/// their observed order lies within 10 % of `formal_order`.
std::vector<io::StudyRow> study_rows(const std::vector<StudyLevel>& levels, double formal_order);

}  // namespace iga::analysis
