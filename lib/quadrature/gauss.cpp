#include "quadrature/gauss.hpp"

#include "core/error.hpp"

#include <cmath>
#include <numbers>
#include <string>

namespace iga::quadrature {

Rule1D gauss_legendre(int n)
{
    IGA_CHECK(n >= 1, "gauss_legendre: number of points must be >= 1, got " + std::to_string(n));
    // Roots t of P_n on [-1, 1] by Newton from the Tricomi-type guess
    // cos(pi (i + 3/4) / (n + 1/2)); the three-term recurrence gives P_n and
    // P_n' = n (t P_n - P_{n-1}) / (t^2 - 1). Only the roots t > 0 are computed;
    // the rule is mirrored so that it is exactly symmetric.
    constexpr double newton_tolerance = 1e-15;  // |dt| below this: converged to round-off
    constexpr int max_newton_iterations = 100;
    Rule1D rule;
    rule.points.resize(n);
    rule.weights.resize(n);
    for (int i = 0; i < (n + 1) / 2; ++i) {
        double t = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
        double dp = 0.0;
        for (int iteration = 0; iteration < max_newton_iterations; ++iteration) {
            double p0 = 1.0, p1 = t;
            for (int k = 2; k <= n; ++k) {
                const double p2 = ((2.0 * k - 1.0) * t * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            // For n = 1, p1 = P_1 = t and p0 = P_0 = 1.
            dp = n * (t * p1 - p0) / (t * t - 1.0);
            const double step = p1 / dp;
            t -= step;
            if (std::abs(step) < newton_tolerance)
                break;
        }
        if (n % 2 == 1 && i == n / 2)
            t = 0.0;  // the middle root of an odd rule is exactly 0
        // Recompute P_n' at the converged root for the weight 2 / ((1 - t^2) P_n'^2).
        double p0 = 1.0, p1 = t;
        for (int k = 2; k <= n; ++k) {
            const double p2 = ((2.0 * k - 1.0) * t * p1 - (k - 1.0) * p0) / k;
            p0 = p1;
            p1 = p2;
        }
        dp = (n == 1) ? 1.0 : n * (t * p1 - p0) / (t * t - 1.0);
        const double w = 2.0 / ((1.0 - t * t) * dp * dp);
        // Map [-1, 1] -> [0, 1]: x = (1 -+ t) / 2, weight w / 2; t > 0 gives the low point.
        rule.points[i] = 0.5 * (1.0 - t);
        rule.points[n - 1 - i] = 0.5 * (1.0 + t);
        rule.weights[i] = 0.5 * w;
        rule.weights[n - 1 - i] = 0.5 * w;
    }
    return rule;
}

TensorRule element_rule(const nurbs::Patch& patch, const nurbs::Element& element, int n_per_direction)
{
    const int n_par = patch.n_par();
    const Rule1D rule = gauss_legendre(n_per_direction);
    const int q = n_per_direction;
    int n_points = 1;
    for (int d = 0; d < n_par; ++d)
        n_points *= q;
    TensorRule out;
    out.points.resize(n_points, n_par);
    out.weights.resize(n_points);
    for (int a = 0; a < n_points; ++a) {
        int rest = a;
        double weight = 1.0;
        for (int d = 0; d < n_par; ++d) {
            const int i = rest % q;  // u fastest
            rest /= q;
            const double length = element.upper[d] - element.lower[d];
            out.points(a, d) = element.lower[d] + length * rule.points[i];
            weight *= length * rule.weights[i];
        }
        out.weights(a) = weight;
    }
    return out;
}

}  // namespace iga::quadrature
