#include "analysis/refinement_study.hpp"

#include <algorithm>
#include <cmath>

namespace iga::analysis {

std::string support_name(EstimateSupport support)
{
    switch (support) {
    case EstimateSupport::asymptotic: return "asymptotic";
    case EstimateSupport::not_asymptotic: return "not_asymptotic";
    case EstimateSupport::assumed_order: return "assumed_order";
    case EstimateSupport::converged: return "converged";
    case EstimateSupport::not_converging: return "not_converging";
    case EstimateSupport::zero_limit: return "zero_limit";
    }
    return "";
}

std::optional<double> observed_order(double coarse, double medium, double fine)
{
    const double d1 = medium - coarse, d2 = fine - medium;
    if (d1 == 0.0 || d2 == 0.0 || (d1 > 0) != (d2 > 0) || std::abs(d2) >= std::abs(d1))
        return std::nullopt;
    return std::log(std::abs(d1) / std::abs(d2)) / std::log(refinement_ratio);
}

namespace {

bool in_asymptotic_range(double observed, double formal)
{
    return std::abs(observed - formal) <= asymptotic_order_tolerance * formal;
}

}  // namespace

std::optional<Extrapolation> richardson(std::span<const double> values, double formal_order)
{
    const std::size_t n = values.size();
    if (n < 2)
        return std::nullopt;
    Extrapolation e;
    const double finest = values[n - 1];
    const double d2 = finest - values[n - 2];
    if (std::abs(d2) <= solver_noise * std::abs(finest)) {
        e.support = EstimateSupport::converged;
        e.extrapolated = finest;
        e.rel_band = finest == 0.0 ? 0.0 : std::abs(d2) / std::abs(finest);
        return e;
    }
    e.order_used = formal_order;
    e.safety_factor = safety_factor_assumed;
    e.support = EstimateSupport::assumed_order;
    if (n >= 3) {
        const double d1 = values[n - 2] - values[n - 3];
        if (std::abs(d2) >= std::abs(d1)) {  // growing (or from zero): nothing to extrapolate
            e.support = EstimateSupport::not_converging;
            e.safety_factor = 0.0;
            return e;
        }
        e.observed_order = observed_order(values[n - 3], values[n - 2], finest);
        if (e.observed_order) {
            e.order_used = *e.observed_order;
            e.safety_factor = safety_factor_observed;
            e.support = in_asymptotic_range(*e.observed_order, formal_order) ? EstimateSupport::asymptotic
                                                                              : EstimateSupport::not_asymptotic;
        }
    }
    const double shift = d2 / (std::pow(refinement_ratio, e.order_used) - 1.0);  // q_extr - q_{N-1}
    e.extrapolated = finest + shift;
    const double band = e.safety_factor * std::abs(shift);  // Roache's GCI, absolute
    if (band >= std::abs(*e.extrapolated))
        e.support = EstimateSupport::zero_limit;
    else
        e.rel_band = band / std::abs(*e.extrapolated);
    return e;
}

std::vector<io::StudyRow> study_rows(const std::vector<StudyLevel>& levels, double formal_order)
{
    std::vector<io::StudyRow> rows;
    if (levels.empty())
        return rows;
    // Longest run of consecutive levels ending at the finest completed one.
    std::size_t first = levels.size() - 1;
    while (first > 0 && levels[first - 1].level == levels[first].level - 1)
        --first;

    // Quantity names in first-seen order, and the largest force (for the noise rule).
    std::vector<std::string> names;
    double largest_force = 0.0;
    for (const StudyLevel& level : levels)
        for (const auto& [name, value] : level.quantities) {
            if (std::find(names.begin(), names.end(), name) == names.end())
                names.push_back(name);
            if (name.rfind("reaction:", 0) == 0 || name.rfind("normal_force:", 0) == 0)
                largest_force = std::max(largest_force, std::abs(value));
        }
    // A reaction component below this fraction of the largest force is round-off (it
    // grows with the dofs: 2e-9 of the load on a symmetry line at 176k dofs).
    constexpr double reaction_noise = 1e-6;
    // An extrapolated value below this fraction of the quantity's largest value is zero.
    constexpr double zero_fraction = 1e-12;

    for (const std::string& name : names) {
        auto value_at = [&](const StudyLevel& level) -> std::optional<double> {
            for (const auto& [n, v] : level.quantities)
                if (n == name)
                    return v;
            return std::nullopt;
        };
        double largest = 0.0;
        for (const StudyLevel& level : levels)
            if (const auto v = value_at(level))
                largest = std::max(largest, std::abs(*v));
        if (name.rfind("reaction:", 0) == 0 && largest <= reaction_noise * largest_force)
            continue;
        std::vector<double> chain;
        for (std::size_t k = first; k < levels.size(); ++k) {
            const auto v = value_at(levels[k]);
            if (!v) {
                chain.clear();
                break;
            }
            chain.push_back(*v);
        }
        const std::optional<Extrapolation> e = richardson(chain, formal_order);
        for (std::size_t k = 0; k < levels.size(); ++k) {
            const StudyLevel& level = levels[k];
            const auto v = value_at(level);
            if (!v)
                continue;
            io::StudyRow row;
            row.level = level.level;
            row.dofs = level.dofs;
            row.wall_s = level.wall_s;
            row.quantity = name;
            row.value = *v;
            if (e) {
                row.estimate = support_name(e->support);
                row.extrapolated = e->extrapolated;
                row.observed_order = e->observed_order;
                const bool relative = e->extrapolated && e->support != EstimateSupport::zero_limit &&
                                      std::abs(*e->extrapolated) > zero_fraction * largest;
                if (relative) {
                    row.estimated_rel_error = std::abs(*v - *e->extrapolated) / std::abs(*e->extrapolated);
                    row.extrapolated_rel_band = e->rel_band;
                }
            }
            // The three levels ending here: in the asymptotic range or not (nothing to
            // judge when the last two agree to the solver's noise).
            if (k >= first + 2 && !chain.empty() &&
                std::abs(chain[k - first] - chain[k - first - 1]) > solver_noise * std::abs(chain[k - first])) {
                const std::size_t i = k - first;
                const std::optional<double> p = observed_order(chain[i - 2], chain[i - 1], chain[i]);
                row.asymptotic = p && in_asymptotic_range(*p, formal_order);
            }
            if (const auto it = level.reference_values.find(name); it != level.reference_values.end()) {
                row.reference_value = it->second;
                if (it->second != 0.0)
                    row.true_rel_error = std::abs(*v - it->second) / std::abs(it->second);
            }
            rows.push_back(std::move(row));
        }
    }
    return rows;
}

}  // namespace iga::analysis
