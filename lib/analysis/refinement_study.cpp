#include "analysis/refinement_study.hpp"

#include <algorithm>
#include <cmath>

namespace iga::analysis {

std::optional<Extrapolation> richardson(std::span<const double> values, double assumed_order)
{
    const std::size_t n = values.size();
    if (n < 2)
        return std::nullopt;
    Extrapolation e;
    const double finest = values[n - 1];
    const double d2 = finest - values[n - 2];
    if (d2 == 0.0) {
        e.extrapolated = finest;
        return e;
    }
    e.order_used = assumed_order;
    if (n >= 3) {
        const double d1 = values[n - 2] - values[n - 3];
        if (d1 != 0.0 && (d1 > 0) == (d2 > 0) && std::abs(d1) > std::abs(d2)) {
            e.observed_order = std::log2(std::abs(d1) / std::abs(d2));
            e.order_used = *e.observed_order;
        }
    }
    e.extrapolated = finest + d2 / (std::exp2(e.order_used) - 1.0);
    return e;
}

std::vector<io::StudyRow> study_rows(const std::vector<StudyLevel>& levels, double assumed_order)
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
        const std::optional<Extrapolation> e = richardson(chain, assumed_order);
        for (const StudyLevel& level : levels) {
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
                row.extrapolated = e->extrapolated;
                row.observed_order = e->observed_order;
                if (std::abs(e->extrapolated) > zero_fraction * largest)
                    row.estimated_rel_error = std::abs(*v - e->extrapolated) / std::abs(e->extrapolated);
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
