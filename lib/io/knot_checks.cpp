#include "io/knot_checks.hpp"

#include <fmt/format.h>

namespace iga::io {

std::vector<KnotProblem> knot_vector_problems(const std::vector<double>& u, int p)
{
    const std::size_t order = static_cast<std::size_t>(p) + 1;
    for (std::size_t i = 1; i < u.size(); ++i)
        if (u[i] < u[i - 1])
            return {{i, fmt::format("knots must be non-decreasing (the knot before is {})", u[i - 1])}};
    if (u.size() < 2 * order)
        return {{std::nullopt, fmt::format("too few knots for degree {}: an open knot vector has at least 2(p+1) = {}",
                                           p, 2 * order)}};
    const auto n = u.size();
    const bool open = u[order - 1] == u.front() && u[n - order] == u.back() && u[order] > u.front() &&
                      u[n - order - 1] < u.back();
    if (!open)
        return {{std::nullopt, fmt::format("not an open knot vector: the first and the last value must each appear "
                                           "exactly degree + 1 = {} times, with a parameter interval of positive "
                                           "length",
                                           order)}};
    std::vector<KnotProblem> problems;
    for (std::size_t i = order; i < n - order;) {
        std::size_t j = i;
        while (j < n - order && u[j] == u[i])
            ++j;
        if (j - i > order - 1)
            problems.push_back({i, fmt::format("interior knot {} appears {} times, more than the degree {}", u[i],
                                               j - i, p)});
        i = j;
    }
    return problems;
}

}  // namespace iga::io
