#pragma once
// Random test patches for the nurbs tests: non-uniform open knot vectors with
// repeated interior knots, random control points and random positive weights.
// Deterministic for a given std::mt19937 seed (tests print their seed).

#include "nurbs/patch.hpp"

#include <algorithm>
#include <random>
#include <vector>

namespace iga::test {

/// Open knot vector on [0, 1] of degree p with n_spans non-uniform spans; some
/// interior knots repeated (multiplicity 1..p).
inline nurbs::KnotVector random_knots(std::mt19937& rng, int p, int n_spans)
{
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<double> breaks{0.0, 1.0};
    while (static_cast<int>(breaks.size()) < n_spans + 1) {
        const double b = 0.05 + 0.9 * unit(rng);
        breaks.push_back(b);
        std::sort(breaks.begin(), breaks.end());
        // Keep spans from becoming tiny, which would only test conditioning.
        for (std::size_t i = 1; i < breaks.size(); ++i)
            if (breaks[i] - breaks[i - 1] < 0.02) {
                breaks.erase(std::find(breaks.begin(), breaks.end(), b));
                break;
            }
    }
    std::uniform_int_distribution<int> mult(1, p);
    std::vector<double> knots(p + 1, 0.0);
    for (std::size_t i = 1; i + 1 < breaks.size(); ++i) {
        const int m = (i % 2 == 0) ? mult(rng) : 1;  // every other interior knot repeated
        knots.insert(knots.end(), m, breaks[i]);
    }
    knots.insert(knots.end(), p + 1, 1.0);
    return nurbs::KnotVector(p, std::move(knots));
}

/// Random patch with the given degrees (one per parametric direction) in `dim`
/// spatial dimensions; weights in [0.5, 2].
inline nurbs::Patch random_patch(std::mt19937& rng, const std::vector<int>& degrees, int n_spans, int dim)
{
    std::vector<nurbs::KnotVector> knots;
    int n_cp = 1;
    for (const int p : degrees) {
        knots.push_back(random_knots(rng, p, n_spans));
        n_cp *= knots.back().n_basis();
    }
    std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
    std::uniform_real_distribution<double> weight(0.5, 2.0);
    RowMatrix points(n_cp, dim);
    Vector weights(n_cp);
    for (int a = 0; a < n_cp; ++a) {
        for (int d = 0; d < dim; ++d)
            points(a, d) = coordinate(rng);
        weights(a) = weight(rng);
    }
    return nurbs::Patch(std::move(knots), std::move(points), std::move(weights));
}

/// Uniform random parameter point in the patch's domain.
inline VecN random_point(std::mt19937& rng, const nurbs::Patch& patch)
{
    VecN xi(patch.n_par());
    for (int d = 0; d < patch.n_par(); ++d) {
        std::uniform_real_distribution<double> u(patch.knots(d).front(), patch.knots(d).back());
        xi(d) = u(rng);
    }
    return xi;
}

}  // namespace iga::test
