// Tests of the pressure error measures (lib/analytic/pressure_errors.hpp):
// exact data give ~0, scaled and stretched curves give the closed-form
// errors, mirror data equal their reflection, and NaN propagates.
#include "analytic/pressure_errors.hpp"

#include "core/error.hpp"
#include "support/tolerance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

namespace iga::analytic {
namespace {

using test::at_most;
using test::near;
using test::near_rel;

// Closed-form expectations evaluated from a few doubles, or exact identities
// of the measures (same crossing, same segments): round-off only.
constexpr double round_off = 1e-12;
// Dense samples: 6001 points on [-1.5a, 1.5a], spacing h = 5e-4 a.
constexpr int n_dense = 6001;
constexpr double dense_spacing = 3.0 / (n_dense - 1);  // in units of a
// Linear interpolation of the ellipse when +-a are sample points: each edge cell
// [a - h, a] contributes int_0^h (sqrt(2s/a) - sqrt(2h/a) s/h)^2 ds p0^2 = p0^2 h^2/(15 a),
// so the two edges give l2 = sqrt(2/15) h/a = 1.83e-4. The next cells add
// sum_k h^5 p''^2/120 ~ 2 % of l2^2, i.e. ~1 % of l2.
const double dense_edge_l2 = std::sqrt(2.0 / 15.0) * dense_spacing;
constexpr double next_cells_fraction = 0.02;
// The bound used where the sampling error enters by the triangle inequality.
constexpr double dense_l2_bound = 2e-4;

HertzLineContact benchmark() { return hertz_cylinder_plane(1000.0, 0.3, 1.0, 10.0); }

struct Samples {
    std::vector<double> x, p;
};

// n equally spaced samples of scale * p_H(x / stretch) on [-1.5a, 1.5a] * stretch.
Samples dense_samples(const HertzLineContact& h, double scale = 1.0, double stretch = 1.0)
{
    Samples s;
    for (int i = 0; i < n_dense; ++i) {
        const double x = h.a * (-1.5 + dense_spacing * i);  // i = 1000, 3000, 5000: x = -a, 0, a
        s.x.push_back(stretch * x);
        s.p.push_back(scale * h.pressure(x));
    }
    return s;
}

TEST(PressureErrors, ExactCurveMeasuresZero)
{
    const HertzLineContact h = benchmark();
    const Samples s = dense_samples(h);
    const PressureErrors e = pressure_errors(h, s.x, s.p, false);
    EXPECT_TRUE(near(e.peak, 0.0, round_off));  // a sample sits at x = 0
    EXPECT_TRUE(near_rel(e.l2, dense_edge_l2, next_cells_fraction));
    EXPECT_TRUE(at_most(e.l2, dense_l2_bound));
    // The 1 % crossing of the ellipse is at 0.99995 a (bias -5e-5); the linear
    // interpolant of samples h apart near the edge moves it by less than h.
    EXPECT_TRUE(near(e.half_width, -5e-5, dense_spacing));
}

TEST(PressureErrors, ScaledCurve)
{
    const HertzLineContact h = benchmark();
    constexpr double s = 0.01;
    const Samples d = dense_samples(h, 1.0 + s);
    const PressureErrors e = pressure_errors(h, d.x, d.p, false);
    EXPECT_TRUE(near(e.peak, s, round_off));
    // 1.01 I p_H - p_H = 0.01 p_H + 1.01 (I p_H - p_H) and ||p_H|| = sqrt(4/3) p0 sqrt(a):
    // by the triangle inequality l2 is within 1.01 * (sampling error) of 0.01 sqrt(4/3).
    EXPECT_TRUE(near(e.l2, s * std::sqrt(4.0 / 3.0), (1.0 + s) * dense_l2_bound));
    // Scaling p does not move the 1 % crossing.
    const Samples d0 = dense_samples(h);
    EXPECT_TRUE(near(e.half_width, pressure_errors(h, d0.x, d0.p, false).half_width, round_off));
}

TEST(PressureErrors, StretchedCurve)
{
    const HertzLineContact h = benchmark();
    constexpr double stretch = 1.02;
    const Samples d0 = dense_samples(h);
    const Samples d = dense_samples(h, 1.0, stretch);
    const PressureErrors e0 = pressure_errors(h, d0.x, d0.p, false);
    const PressureErrors e = pressure_errors(h, d.x, d.p, false);
    // Same samples at stretched abscissae: the crossing moves exactly by the stretch.
    EXPECT_TRUE(near(1.0 + e.half_width, stretch * (1.0 + e0.half_width), round_off));
    // And so it reads +2 % up to the -5e-5 bias and the sampling (spacing h).
    EXPECT_TRUE(near(e.half_width, stretch - 1.0, 5e-5 + stretch * dense_spacing));
    EXPECT_TRUE(near(e.peak, 0.0, round_off));
}

TEST(PressureErrors, ZeroCurve)
{
    // No contact at all: the whole Hertz curve is missing, l2 = ||p_H|| = sqrt(4/3).
    const HertzLineContact h = benchmark();
    const std::vector<double> x = {-2.0 * h.a, -0.3 * h.a, 0.1 * h.a, 2.0 * h.a};
    const std::vector<double> p(x.size(), 0.0);
    const PressureErrors e = pressure_errors(h, x, p, false);
    EXPECT_TRUE(near(e.peak, -1.0, round_off));
    EXPECT_TRUE(near(e.half_width, -1.0, round_off));
    EXPECT_TRUE(near(e.l2, std::sqrt(4.0 / 3.0), round_off));
}

TEST(PressureErrors, TentCurveClosedForm)
{
    // p_h = p0 (1 - |x|/a) from three samples. With t = x/a:
    // l2^2 = int_{-1}^{1} (1 - |t| - sqrt(1 - t^2))^2 dt = 10/3 - pi; the 1 % crossing is at 0.99 a.
    const HertzLineContact h = benchmark();
    const std::vector<double> x = {h.a, -h.a, 0.0};  // unsorted on purpose
    const std::vector<double> p = {0.0, 0.0, h.p0};
    const PressureErrors e = pressure_errors(h, x, p, false);
    EXPECT_TRUE(near(e.peak, 0.0, round_off));
    EXPECT_TRUE(near(e.half_width, -0.01, round_off));
    EXPECT_TRUE(near(e.l2, std::sqrt(10.0 / 3.0 - std::numbers::pi), round_off));
}

TEST(PressureErrors, CurveIsZeroOutsideTheData)
{
    // Exact data on |x| <= a/2 only: l2^2 = 2 int_{1/2}^{1} (1 - t^2) dt = 5/12, up to sampling;
    // the curve is still above 1 % at the ends of the data, so a_h = a/2.
    const HertzLineContact h = benchmark();
    Samples s;
    for (int i = 0; i <= 2000; ++i) {
        const double x = h.a * (-0.5 + 0.0005 * i);
        s.x.push_back(x);
        s.p.push_back(h.pressure(x));
    }
    const PressureErrors e = pressure_errors(h, s.x, s.p, false);
    // Away from the edges the interpolation error is ~ h^2 p'' / 8 ~ 1e-8 p0, far below this.
    constexpr double interior_sampling = 1e-6;
    EXPECT_TRUE(near(e.l2, std::sqrt(5.0 / 12.0), interior_sampling));
    EXPECT_TRUE(near(e.half_width, -0.5, round_off));
}

TEST(PressureErrors, MirrorEqualsReflectedFullData)
{
    // Gauss-point-like half data: irregular x > 0 (none at 0) of a perturbed curve.
    const HertzLineContact h = benchmark();
    std::mt19937 rng(12345);  // fixed seed
    std::uniform_real_distribution<double> jitter(0.2, 1.0);
    Samples half;
    double x = 0.0;
    while (x < 1.6 * h.a) {
        x += 0.01 * h.a * jitter(rng);
        half.x.push_back(x);
        half.p.push_back(1.03 * h.pressure(1.05 * x) + 0.4 * std::sin(40.0 * x / h.a));
    }
    Samples full = half;
    Samples left;
    for (std::size_t i = 0; i < half.x.size(); ++i) {
        full.x.push_back(-half.x[i]);
        full.p.push_back(half.p[i]);
        left.x.push_back(-half.x[i]);
        left.p.push_back(half.p[i]);
    }
    const PressureErrors from_full = pressure_errors(h, full.x, full.p, false);
    for (const Samples* one_side : {&half, &left}) {
        const PressureErrors from_half = pressure_errors(h, one_side->x, one_side->p, true);
        EXPECT_TRUE(near_rel(from_half.peak, from_full.peak, round_off));
        EXPECT_TRUE(near_rel(from_half.half_width, from_full.half_width, round_off));
        EXPECT_TRUE(near_rel(from_half.l2, from_full.l2, round_off));
    }
    // Guard against a vacuous comparison: the perturbation is visible.
    EXPECT_TRUE(test::at_least(from_full.l2, 0.01));

    // A sample on the symmetry line is shared by both halves, not doubled.
    half.x.push_back(0.0);
    half.p.push_back(h.p0);
    full.x.push_back(0.0);
    full.p.push_back(h.p0);
    EXPECT_TRUE(near_rel(pressure_errors(h, half.x, half.p, true).l2,
                         pressure_errors(h, full.x, full.p, false).l2, round_off));
}

TEST(PressureErrors, DuplicatesAveragedAndOrderIrrelevant)
{
    const HertzLineContact h = benchmark();
    const Samples d = dense_samples(h, 0.97, 1.01);
    Samples shuffled = d;
    std::mt19937 rng(777);  // fixed seed
    std::vector<std::size_t> order(d.x.size());
    for (std::size_t i = 0; i < order.size(); ++i)
        order[i] = i;
    std::shuffle(order.begin(), order.end(), rng);
    Samples dup;
    for (std::size_t i : order) {
        // Each point twice, p +- 1: the mean is the original value.
        dup.x.push_back(d.x[i]);
        dup.p.push_back(d.p[i] + 1.0);
        dup.x.push_back(d.x[i]);
        dup.p.push_back(d.p[i] - 1.0);
    }
    const PressureErrors ref = pressure_errors(h, d.x, d.p, false);
    const PressureErrors got = pressure_errors(h, dup.x, dup.p, false);
    EXPECT_TRUE(near_rel(got.peak, ref.peak, round_off));
    EXPECT_TRUE(near_rel(got.half_width, ref.half_width, round_off));
    EXPECT_TRUE(near_rel(got.l2, ref.l2, round_off));
}

TEST(PressureErrors, NonFiniteDataGiveNaN)
{
    const HertzLineContact h = benchmark();
    const Samples d = dense_samples(h);
    for (const double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
        Samples in_p = d;
        in_p.p[4000] = bad;  // both indices lie in the x >= 0 half used with mirror
        Samples in_x = d;
        in_x.x[4321] = bad;
        for (const Samples* s : {&in_p, &in_x}) {
            for (const bool mirror : {false, true}) {
                Samples data = *s;
                if (mirror) {  // keep the x >= 0 half, with the bad value in it
                    data.x.assign(s->x.begin() + 3000, s->x.end());
                    data.p.assign(s->p.begin() + 3000, s->p.end());
                }
                const PressureErrors e = pressure_errors(h, data.x, data.p, mirror);
                EXPECT_TRUE(std::isnan(e.peak));
                EXPECT_TRUE(std::isnan(e.half_width));
                EXPECT_TRUE(std::isnan(e.l2));
            }
        }
    }
}

TEST(PressureErrors, RejectsMisuse)
{
    const HertzLineContact h = benchmark();
    EXPECT_THROW(pressure_errors(h, {0.0, 1.0}, {1.0}, false), iga::Error);
    EXPECT_THROW(pressure_errors(h, {}, {}, false), iga::Error);
    // mirror = true on data that covers both sides of the centre
    EXPECT_THROW(pressure_errors(h, {-0.05, 0.0, 0.05}, {1.0, 2.0, 1.0}, true), iga::Error);
}

}  // namespace
}  // namespace iga::analytic
