#include "analytic/pressure_errors.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <numeric>

namespace iga::analytic {

namespace {

// Samples closer than this fraction of the data extent are one sample: the
// same point written twice (e.g. a knot shared by two spans) up to round-off.
constexpr double duplicate_fraction = 1e-12;
// Mirror data may stray this far (relative to the extent) to the other side of
// x = 0: round-off of points on the symmetry line, far below any sample spacing.
constexpr double mirror_side_fraction = 1e-8;
// The crossing level of the half-width, as a fraction of the curve's maximum.
constexpr double half_width_level = 0.01;
// l2 integrates over |x| <= l2_extent * a: covers the whole Hertz zone plus a
// margin where a too wide computed zone shows up.
constexpr double l2_extent = 1.2;
// Longest theta-subinterval of the l2 quadrature inside |x| < a; the integrand
// there is an entire function of theta with frequencies <= 3, so 5-point Gauss
// on pi/64 is exact to round-off.
constexpr double max_theta_step = std::numbers::pi / 64.0;

// 5-point Gauss-Legendre on [-1, 1] (exact for degree 9).
constexpr std::array<double, 5> gauss_nodes = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                                               0.9061798459386640};
constexpr std::array<double, 5> gauss_weights = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                                 0.4786286704993665, 0.2369268850561891};

// The elliptic profile p0 sqrt(1 - x^2/a^2) measured against.
struct Profile {
    double a;
    double p0;
};

// The merged, sorted samples: strictly increasing x.
struct Curve {
    std::vector<double> x;
    std::vector<double> p;
};

Curve make_curve(const std::vector<double>& x, const std::vector<double>& p, bool mirror)
{
    double extent = 0.0;
    for (double xi : x)
        extent = std::max(extent, std::abs(xi));

    std::vector<double> xs = x;
    std::vector<double> ps = p;
    if (mirror) {
        const double slack = mirror_side_fraction * extent;
        const bool all_right = std::all_of(x.begin(), x.end(), [&](double xi) { return xi >= -slack; });
        const bool all_left = std::all_of(x.begin(), x.end(), [&](double xi) { return xi <= slack; });
        IGA_CHECK(all_right || all_left, "pressure_errors: mirror = true needs data on one side of x = 0");
        // Fold onto x >= 0, then append the reflection.
        for (double& xi : xs)
            xi = std::abs(xi);
        const std::size_t n = xs.size();
        for (std::size_t i = 0; i < n; ++i) {
            xs.push_back(-xs[i]);
            ps.push_back(ps[i]);
        }
    }

    std::vector<std::size_t> order(xs.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return xs[i] < xs[j]; });

    const double merge_gap = duplicate_fraction * extent;
    Curve curve;
    std::size_t k = 0;
    while (k < order.size()) {
        const double start = xs[order[k]];
        double sum_x = 0.0;
        double sum_p = 0.0;
        std::size_t count = 0;
        for (; k < order.size() && xs[order[k]] - start <= merge_gap; ++k, ++count) {
            sum_x += xs[order[k]];
            sum_p += ps[order[k]];
        }
        curve.x.push_back(sum_x / static_cast<double>(count));
        curve.p.push_back(sum_p / static_cast<double>(count));
    }
    return curve;
}

// a_h: half the distance between the outermost crossings of half_width_level * max.
double measured_half_width(const Curve& c)
{
    const std::size_t n = c.x.size();
    const double top = *std::max_element(c.p.begin(), c.p.end());
    if (!(top > 0))
        return 0.0;
    const double level = half_width_level * top;

    std::size_t right = n - 1;
    while (c.p[right] < level)
        --right;  // stops: the maximum is >= level
    double x_right = c.x[right];
    if (right + 1 < n)
        x_right += (c.p[right] - level) / (c.p[right] - c.p[right + 1]) * (c.x[right + 1] - c.x[right]);

    std::size_t left = 0;
    while (c.p[left] < level)
        ++left;
    double x_left = c.x[left];
    if (left > 0)
        x_left -= (c.p[left] - level) / (c.p[left] - c.p[left - 1]) * (c.x[left] - c.x[left - 1]);

    return 0.5 * (x_right - x_left);
}

// int_{-l2_extent a}^{l2_extent a} (curve - p_H)^2 dx, segment by segment.
double squared_error_integral(const Profile& hertz, const Curve& c)
{
    const double a = hertz.a;
    const double bound = l2_extent * a;

    std::vector<double> breaks = {-bound, -a, a, bound};
    for (double xi : c.x)
        if (xi > -bound && xi < bound)
            breaks.push_back(xi);
    std::sort(breaks.begin(), breaks.end());
    breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());

    double total = 0.0;
    for (std::size_t s = 0; s + 1 < breaks.size(); ++s) {
        const double x0 = breaks[s];
        const double x1 = breaks[s + 1];
        const double mid = 0.5 * (x0 + x1);

        // The curve on (x0, x1) is one linear piece: p_lo + slope (x - x_lo), or 0 outside the data.
        double x_lo = 0.0, p_lo = 0.0, slope = 0.0;
        if (c.x.size() > 1 && mid > c.x.front() && mid < c.x.back()) {
            const auto hi = static_cast<std::size_t>(std::upper_bound(c.x.begin(), c.x.end(), mid) - c.x.begin());
            x_lo = c.x[hi - 1];
            p_lo = c.p[hi - 1];
            slope = (c.p[hi] - p_lo) / (c.x[hi] - x_lo);
        }
        const auto curve_at = [&](double x) { return p_lo + slope * (x - x_lo); };

        if (std::abs(mid) < a) {
            // x = a sin(theta): p_H = p0 cos(theta), dx = a cos(theta) dtheta.
            const double t0 = std::asin(std::clamp(x0 / a, -1.0, 1.0));
            const double t1 = std::asin(std::clamp(x1 / a, -1.0, 1.0));
            const int n_sub = std::max(1, static_cast<int>(std::ceil((t1 - t0) / max_theta_step)));
            const double h = (t1 - t0) / n_sub;
            for (int q = 0; q < n_sub; ++q) {
                const double centre = t0 + (q + 0.5) * h;
                for (std::size_t g = 0; g < gauss_nodes.size(); ++g) {
                    const double theta = centre + 0.5 * h * gauss_nodes[g];
                    const double diff = curve_at(a * std::sin(theta)) - hertz.p0 * std::cos(theta);
                    total += 0.5 * h * gauss_weights[g] * diff * diff * a * std::cos(theta);
                }
            }
        } else {
            // p_H = 0: the integrand is the square of a linear function, integrated exactly.
            const double h = x1 - x0;
            for (std::size_t g = 0; g < gauss_nodes.size(); ++g) {
                const double value = curve_at(mid + 0.5 * h * gauss_nodes[g]);
                total += 0.5 * h * gauss_weights[g] * value * value;
            }
        }
    }
    return total;
}

}  // namespace

PressureErrors pressure_errors(const HertzLineContact& hertz, const std::vector<double>& x,
                               const std::vector<double>& p, bool mirror)
{
    return elliptic_pressure_errors(hertz.a, hertz.p0, x, p, mirror);
}

PressureErrors elliptic_pressure_errors(double a, double p0, const std::vector<double>& x,
                                        const std::vector<double>& p, bool mirror)
{
    IGA_CHECK(x.size() == p.size(), "pressure_errors: x and p must have the same length");
    IGA_CHECK(!x.empty(), "pressure_errors: no samples");
    IGA_CHECK(a > 0 && p0 > 0, "pressure_errors: the Hertz solution needs a > 0 and p0 > 0");
    const Profile hertz{a, p0};

    const auto finite = [](double v) { return std::isfinite(v); };
    if (!std::all_of(x.begin(), x.end(), finite) || !std::all_of(p.begin(), p.end(), finite)) {
        constexpr double nan = std::numeric_limits<double>::quiet_NaN();
        return {.peak = nan, .half_width = nan, .l2 = nan};
    }

    const Curve curve = make_curve(x, p, mirror);
    const double top = *std::max_element(curve.p.begin(), curve.p.end());
    const double a_h = measured_half_width(curve);
    const double squared = squared_error_integral(hertz, curve);
    return {.peak = (top - hertz.p0) / hertz.p0,
            .half_width = (a_h - hertz.a) / hertz.a,
            .l2 = std::sqrt(squared) / (hertz.p0 * std::sqrt(hertz.a))};
}

}  // namespace iga::analytic
