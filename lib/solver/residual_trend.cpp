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

}  // namespace

const char* trend_name(ResidualTrend trend)
{
    switch (trend) {
    case ResidualTrend::none: return "none";
    case ResidualTrend::two_state_cycle: return "two_state_cycle";
    case ResidualTrend::stagnation: return "stagnation";
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
    return later_min >= stagnation_drop * history[first] ? ResidualTrend::stagnation : ResidualTrend::none;
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
