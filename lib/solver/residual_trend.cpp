#include "solver/residual_trend.hpp"

#include <algorithm>
#include <cmath>

namespace iga::solver {

namespace {

struct Group {
    double min = INFINITY;
    double max = 0;
    double sum = 0;
    int n = 0;
    double mean() const { return n > 0 ? sum / n : 0.0; }
    bool tight() const { return n > 0 && min > 0 && std::isfinite(max) && max <= (1.0 + cycle_spread) * min; }
};

/// Even- and odd-placed groups of the last trend_window entries.
void split(const std::vector<double>& history, Group& even, Group& odd)
{
    const std::size_t first = history.size() - trend_window;
    for (int k = 0; k < trend_window; ++k) {
        const double value = history[first + static_cast<std::size_t>(k)];
        Group& g = k % 2 == 0 ? even : odd;
        g.min = std::min(g.min, value);
        g.max = std::max(g.max, value);
        g.sum += value;
        ++g.n;
    }
}

bool is_cycle(const std::vector<double>& history)
{
    if (history.size() < static_cast<std::size_t>(trend_window))
        return false;
    for (std::size_t k = history.size() - trend_window; k < history.size(); ++k)
        if (!std::isfinite(history[k]))
            return false;
    Group even, odd;
    split(history, even, odd);
    if (!even.tight() || !odd.tight())
        return false;
    const double high = std::max(even.mean(), odd.mean()), low = std::min(even.mean(), odd.mean());
    return high > (1.0 + cycle_spread) * low;
}

/// The rises of the whole history and its best entry before the window (see the header);
/// rises = 0 where the history is too short to say.
Wandering wander_facts(const std::vector<double>& history)
{
    Wandering w;
    if (history.size() < 2 * static_cast<std::size_t>(trend_window))
        return w;
    for (std::size_t k = 1; k < history.size(); ++k)
        w.rises += history[k] > history[k - 1] ? 1 : 0;
    const auto early_end = history.end() - trend_window;
    const auto best = std::min_element(history.begin(), early_end);
    w.best = *best;
    w.best_at = static_cast<int>(best - history.begin());
    return w;
}

bool is_wandering(const std::vector<double>& history)
{
    const Wandering w = wander_facts(history);
    return w.rises >= 2 && history.back() > wander_drop * w.best;
}

}  // namespace

const char* trend_name(ResidualTrend trend)
{
    switch (trend) {
    case ResidualTrend::none: return "none";
    case ResidualTrend::two_state_cycle: return "two_state_cycle";
    case ResidualTrend::stagnation: return "stagnation";
    case ResidualTrend::wandering: return "wandering";
    }
    return "unknown";
}

ResidualTrend residual_trend(const std::vector<double>& history)
{
    if (history.size() < static_cast<std::size_t>(trend_window))
        return ResidualTrend::none;
    for (double value : history)
        if (!std::isfinite(value))
            return ResidualTrend::none;
    if (is_cycle(history))
        return ResidualTrend::two_state_cycle;
    const std::size_t first = history.size() - trend_window;
    const double later_min = *std::min_element(history.begin() + static_cast<std::ptrdiff_t>(first) + 1, history.end());
    if (later_min >= stagnation_drop * history[first])
        return ResidualTrend::stagnation;
    return is_wandering(history) ? ResidualTrend::wandering : ResidualTrend::none;
}

Wandering wandering(const std::vector<double>& history)
{
    return residual_trend(history) == ResidualTrend::wandering ? wander_facts(history) : Wandering{};
}

CycleLevels cycle_levels(const std::vector<double>& history)
{
    if (!is_cycle(history))
        return {};
    Group even, odd;
    split(history, even, odd);
    return {std::max(even.mean(), odd.mean()), std::min(even.mean(), odd.mean())};
}

}  // namespace iga::solver
