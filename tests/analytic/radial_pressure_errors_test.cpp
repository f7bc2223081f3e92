// Tests of the radial pressure error measures of a point contact
// (lib/analytic/radial_pressure_errors.hpp) on synthetic scattered samples of an
// octant's contact face: exact Hertz samples give ~0, scaled and stretched
// curves the closed-form errors, a quarter and the full disc the same numbers,
// and NaN propagates.
#include "analytic/radial_pressure_errors.hpp"

#include "core/error.hpp"
#include "support/tolerance.hpp"

#include <cmath>
#include <limits>
#include <vector>

namespace iga::analytic {
namespace {

using test::at_most;
using test::near;

// Identities of the measures (same bins, same crossings): round-off only.
constexpr double round_off = 1e-12;
// Samples on a Cartesian grid of spacing a/200 over the quarter x, y in (0, 1.5a),
// at cell centres (no sample on the symmetry lines).
constexpr int n_grid = 300;
constexpr double grid_spacing = 1.5 / n_grid;  // in units of a
// Exact Hertz samples: the bins of width h = a/100 smooth the square-root edge
// at r = a. The linear interpolant through bin means costs, as in 2D with
// spacing h (pressure_errors_test: l2 = sqrt(2/15) h/a = 3.7e-3 for h = a/100),
// about that much in l2; 5e-3 bounds it with the binning of the edge bin.
constexpr double exact_l2_bound = 5e-3;
// Peak: the first bin [0, h) averages p_H = p0 (1 - r^2/(2a^2) + ...) over r < h,
// which lies below p0 by less than (h/a)^2 / 2 = 5e-5.
constexpr double exact_peak_bound = 0.5 * radial_bin_fraction * radial_bin_fraction;
// Contact radius: the 1 % crossing is found between bin points h apart.
constexpr double exact_radius_bound = radial_bin_fraction;

HertzPointContact benchmark() { return hertz_sphere_plane(1000.0, 0.3, 1.0, 1.47); }

struct Samples {
    std::vector<double> r, p;
};

/// scale * p_H(r / stretch) on the quarter grid (full = true: on the whole square
/// (-1.5a, 1.5a)^2, i.e. the quarter's samples and their three mirror images).
Samples grid_samples(const HertzPointContact& h, double scale = 1.0, double stretch = 1.0, bool full = false)
{
    Samples s;
    const int lo = full ? -n_grid : 0;
    for (int i = lo; i < n_grid; ++i)
        for (int j = lo; j < n_grid; ++j) {
            const double x = (i + 0.5) * grid_spacing * h.a;
            const double y = (j + 0.5) * grid_spacing * h.a;
            const double r = std::hypot(x, y);
            s.r.push_back(r);
            s.p.push_back(scale * h.pressure(r / stretch));
        }
    return s;
}

TEST(RadialPressureErrors, ExactSamplesMeasureNearZero)
{
    const HertzPointContact h = benchmark();
    const Samples s = grid_samples(h);
    const RadialPressureErrors e = radial_pressure_errors(h, s.r, s.p);
    EXPECT_TRUE(at_most(std::abs(e.peak), exact_peak_bound));
    EXPECT_TRUE(at_most(std::abs(e.radius), exact_radius_bound));
    EXPECT_TRUE(at_most(e.l2, exact_l2_bound));
}

TEST(RadialPressureErrors, ScaledCurve)
{
    const HertzPointContact h = benchmark();
    constexpr double s = 0.03;
    const Samples exact = grid_samples(h);
    const Samples scaled = grid_samples(h, 1.0 + s);
    const RadialPressureErrors e0 = radial_pressure_errors(h, exact.r, exact.p);
    const RadialPressureErrors e = radial_pressure_errors(h, scaled.r, scaled.p);
    // Bin means scale with p: the peak reads (1 + s)(1 + peak_0) - 1.
    EXPECT_TRUE(near(e.peak, (1.0 + s) * (1.0 + e0.peak) - 1.0, round_off));
    // As in 2D: l2 = s sqrt(4/3) up to (1 + s) times the sampling error (triangle inequality).
    EXPECT_TRUE(near(e.l2, s * std::sqrt(4.0 / 3.0), (1.0 + s) * exact_l2_bound));
    // Scaling p does not move the 1 % crossing.
    EXPECT_TRUE(near(e.radius, e0.radius, round_off));
}

TEST(RadialPressureErrors, StretchedCurve)
{
    const HertzPointContact h = benchmark();
    constexpr double stretch = 1.05;
    const Samples d = grid_samples(h, 1.0, stretch);
    const RadialPressureErrors e = radial_pressure_errors(h, d.r, d.p);
    EXPECT_TRUE(near(e.radius, stretch - 1.0, exact_radius_bound));
    EXPECT_TRUE(at_most(std::abs(e.peak), exact_peak_bound));
    // p_h(r) = p_H(r / 1.05) differs from p_H by O(5 %) near the edge: l2 well above the sampling error.
    EXPECT_TRUE(test::at_least(e.l2, 10.0 * exact_l2_bound));
}

TEST(RadialPressureErrors, ZeroCurve)
{
    const HertzPointContact h = benchmark();
    Samples s = grid_samples(h);
    std::fill(s.p.begin(), s.p.end(), 0.0);
    const RadialPressureErrors e = radial_pressure_errors(h, s.r, s.p);
    EXPECT_TRUE(near(e.peak, -1.0, round_off));
    EXPECT_TRUE(near(e.radius, -1.0, round_off));
    // The 2D definition on a diameter: int_{-a}^{a} p0^2 (1 - x^2/a^2) dx = 4/3 p0^2 a.
    EXPECT_TRUE(near(e.l2, std::sqrt(4.0 / 3.0), round_off));
}

TEST(RadialPressureErrors, QuarterAndFullDiscMeasureTheSame)
{
    const HertzPointContact h = benchmark();
    for (double scale : {1.0, 0.9}) {
        const Samples quarter = grid_samples(h, scale, 1.02);
        const Samples full = grid_samples(h, scale, 1.02, true);
        const RadialPressureErrors q = radial_pressure_errors(h, quarter.r, quarter.p);
        const RadialPressureErrors f = radial_pressure_errors(h, full.r, full.p);
        EXPECT_TRUE(near(q.peak, f.peak, round_off));
        EXPECT_TRUE(near(q.radius, f.radius, round_off));
        EXPECT_TRUE(near(q.l2, f.l2, round_off));
    }
}

TEST(RadialPressureErrors, BinsAreMeansInIncreasingRadius)
{
    // Bin width a/100 = 1e-3 for a = 0.1 (HertzPointContact's a is only used for the width).
    const RadialCurve c = radial_curve(0.1, {0.0025, 0.0001, 0.0003, 0.0012, 0.0018, 0.0105}, {1, 4, 2, 6, 8, 3});
    ASSERT_EQ(c.r.size(), 4u);
    EXPECT_TRUE(near(c.r[0], (0.0001 + 0.0003) / 2, round_off * 1e-3));
    EXPECT_TRUE(near(c.p[0], 3.0, round_off));
    EXPECT_TRUE(near(c.r[1], (0.0012 + 0.0018) / 2, round_off * 1e-3));  // 0.0025 is in the third bin
    EXPECT_TRUE(near(c.p[1], 7.0, round_off));
    EXPECT_TRUE(near(c.r[2], 0.0025, round_off * 1e-3));
    // 0.0105 is bin 10: the empty bins between are skipped, not filled with zeros.
    EXPECT_TRUE(near(c.r[3], 0.0105, round_off * 1e-3));
    EXPECT_TRUE(near(c.p[3], 3.0, 0.0));
}

TEST(RadialPressureErrors, NonFiniteDataGiveNaNAndMisuseThrows)
{
    const HertzPointContact h = benchmark();
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    constexpr double inf = std::numeric_limits<double>::infinity();
    for (double bad : {nan, inf}) {
        const RadialPressureErrors in_p = radial_pressure_errors(h, {0.0, 0.05, 0.1}, {70.0, bad, 0.0});
        EXPECT_TRUE(std::isnan(in_p.peak) && std::isnan(in_p.radius) && std::isnan(in_p.l2));
        const RadialPressureErrors in_r = radial_pressure_errors(h, {0.0, bad, 0.1}, {70.0, 50.0, 0.0});
        EXPECT_TRUE(std::isnan(in_r.peak) && std::isnan(in_r.radius) && std::isnan(in_r.l2));
    }
    EXPECT_THROW(radial_pressure_errors(h, {0.0, 0.1}, {1.0}), Error);
    EXPECT_THROW(radial_pressure_errors(h, {}, {}), Error);
    EXPECT_THROW(radial_pressure_errors(h, {0.0, -0.01}, {1.0, 1.0}), Error);
}

TEST(RadialPressureErrors, InPlaneDistances)
{
    // Contact plane through c with normal (0, 0, 2): r is the horizontal distance.
    RowMatrix points(3, 3);
    points << 1.0, 2.0, 5.0,  //
        4.0, 6.0, -1.0,       //
        1.0, 2.0, 0.0;
    const VecN c = (VecN(3) << 1.0, 2.0, 0.0).finished();
    const std::vector<double> r = in_plane_distances(points, c, (VecN(3) << 0.0, 0.0, 2.0).finished());
    EXPECT_TRUE(near(r[0], 0.0, round_off));
    EXPECT_TRUE(near(r[1], 5.0, round_off));
    EXPECT_TRUE(near(r[2], 0.0, round_off));
    // A tilted normal: the offset along it does not count.
    const VecN n = (VecN(3) << 1.0, 1.0, 1.0).finished();
    RowMatrix along(1, 3);
    along.row(0) = (c + 3.0 * n).transpose();
    EXPECT_TRUE(near(in_plane_distances(along, c, n)[0], 0.0, round_off));
    EXPECT_THROW(in_plane_distances(points, c, VecN::Zero(3)), Error);
}

}  // namespace
}  // namespace iga::analytic
