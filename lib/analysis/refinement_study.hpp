#pragma once
// Error estimates of `igacontact study` from a sequence of uniformly h-refined
// runs: level k has every knot span of level 0 halved k times (h_k = h_0 / 2^k).
//
// Richardson extrapolation, for a quantity q_h = q + C h^p + (higher order):
//   observed order   p = log2(|q_{N-2} - q_{N-3}| / |q_{N-1} - q_{N-2}|)  from the
//                    three finest levels, when both differences are non-zero, of the
//                    same sign and shrinking (the sequence converges monotonically);
//   extrapolated     q_extr = q_{N-1} + (q_{N-1} - q_{N-2}) / (2^p - 1);
//   estimated error  |q_k - q_extr| / |q_extr| for every level k.
// Otherwise (two levels only, or differences that change sign, grow, or vanish
// below the finest), the order is not observed (empty in the CSV) and the assumed
// order is used: the lowest polynomial degree of the bodies' patches (the rate of
// a degree-p discretization is p for energy-type errors; contact limits the
// regularity, so no more is assumed). When the two finest levels agree exactly,
// q_extr is their value. A quantity whose extrapolated value is zero (to 1e-12 of
// its largest value) has no relative error (empty).

#include "io/study_csv.hpp"

#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace iga::analysis {

struct Extrapolation {
    double extrapolated = 0.0;
    std::optional<double> observed_order;  ///< empty when the levels do not show one
    double order_used = 0.0;               ///< observed, else assumed (unused when the finest levels agree)
};

/// Richardson extrapolation of values on consecutive levels (h halved each time),
/// coarsest first. nullopt with fewer than two values.
std::optional<Extrapolation> richardson(std::span<const double> values, double assumed_order);

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
/// left out.
std::vector<io::StudyRow> study_rows(const std::vector<StudyLevel>& levels, double assumed_order);

}  // namespace iga::analysis
