// inputs/softened_contact_2d.yaml: an elastic block floats on a rigid floor through
// the exponential (softened) pressure-overclosure law (clearance c0 = 0.01, pressure
// p0 = 5 at touch) under a uniform top traction q = 2 < p0. The stress is uniform and
// exact in the discrete space (linear displacements), so every Gauss point of the
// bottom carries p = q and sits at the same gap h, the root of p(h) = q, which is
// NEGATIVE: the law presses at a distance and a clearance of ~3.1e-3 remains. The test
// solves p(h) = q by bisection on the law written out here (not the solver's).

#include "run_support.hpp"

#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace iga::test {
namespace {


constexpr double c0 = 0.01, p0 = 5.0, q = 2.0, width = 1.0;

/// p(h) = p0/(e-1) x (e^x - 1), x = h/c0 + 1, on -c0 < h <= 0 (docs/theory.md "Softened contact").
double softened_pressure(double h)
{
    const double x = h / c0 + 1.0;
    return p0 / (std::numbers::e - 1.0) * x * (std::exp(x) - 1.0);
}

/// dp/dh on the same branch.
double softened_slope(double h)
{
    const double x = h / c0 + 1.0;
    return p0 / ((std::numbers::e - 1.0) * c0) * (std::exp(x) - 1.0 + x * std::exp(x));
}

/// The root of p(h) = q on (-c0, 0): p rises monotonically from 0 to p0 there.
double gap_under(double pressure)
{
    double low = -c0, high = 0.0;
    for (int k = 0; k < 200 && high - low > 0.0; ++k) {
        const double mid = 0.5 * (low + high);
        (softened_pressure(mid) > pressure ? high : low) = mid;
    }
    return 0.5 * (low + high);
}

TEST(SoftenedContact, UniformPressureFloatsTheBlockAtTheGapOfTheLaw)
{
    const auto file = scratch_dir("softened_contact") / "run.h5";
    const analysis::RunOutcome outcome = run_deck(source_path("inputs/softened_contact_2d.yaml"), {}, file);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    const Results results(file);
    const std::string pair = "results/contact/pad";
    EXPECT_EQ(results.text(pair, "law"), "exponential");
    EXPECT_EQ(results.number(pair, "law_clearance"), c0);
    EXPECT_EQ(results.number(pair, "law_pressure"), p0);

    const double h = gap_under(q);
    ASSERT_TRUE(h < -0.1 * c0 && h > -0.9 * c0) << "a clearance remains, inside the law's reach: h = " << h;
    // Newton stops at a residual of 1e-10 of the force scale; the pressures, a uniform
    // field read off that state, carry it amplified by the conditioning of a small
    // system: 1e-8 of q leaves a factor 100. A law with p(0) != p0, a wrong exponent
    // or the linear branch used at h < 0 moves p or h by percents.
    constexpr double pressure_tolerance = 1e-8;
    // The gap follows from the pressure through the law's slope there (~690):
    // dh = dp / p'(h), plus the round-off of a difference of O(1) coordinates.
    const double gap_tolerance = pressure_tolerance * q / softened_slope(h) + 1e-14;

    const std::vector<double> gap = results.reals(pair + "/block.v0/gauss_points/gap");
    const std::vector<double> pressure = results.reals(pair + "/block.v0/gauss_points/pressure");
    ASSERT_EQ(gap.size(), 16u) << "4 spans x (degree 2 + 2) Gauss points";
    ASSERT_EQ(pressure.size(), gap.size());
    for (std::size_t g = 0; g < gap.size(); ++g) {
        EXPECT_TRUE(near(gap[g], h, gap_tolerance)) << "Gauss point " << g << ": gap " << gap[g] << ", h " << h;
        EXPECT_TRUE(near_rel(pressure[g], q, pressure_tolerance)) << "Gauss point " << g;
    }
    // The floor carries the whole load: q times the width, to the same tolerance.
    EXPECT_TRUE(near_rel(results.number(pair + "/block.v0", "normal_force"), q * width, pressure_tolerance));
    EXPECT_TRUE(at_most(results.number(pair, "max_penetration"), 0.0)) << "nowhere in penetration";
}

}  // namespace
}  // namespace iga::test
