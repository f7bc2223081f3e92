// A deformable-deformable pair whose BOTH surfaces span several patches
// (contact_pair.hpp "Multi-piece master surfaces"): projection crosses patch
// ends. Every Gauss point is checked against the closed-form gap, in particular
// those whose closest point lies just past one patch's end, on its neighbour:
// they must be projected (state ok), active and exact, never dropped as off_end
// or at_kink.
//
// Geometry (2D): the lower body is a ring sector of two patches (centre
// c = (0, -2), radii 1 and R = 2, angles 120..80 and 80..60 degrees, exact
// rational quadratic arcs), glued at 80 degrees (x = 2 cos 80 = 0.347 on the
// outer arc, its contact side v1). The upper body is a block [-1, 1] x [0, 0.5]
// of two patches glued at x = -0.2, its contact side the bottom v0. The
// interfaces of the two surfaces lie at different x. The upper block is moved by
// (s, -delta): then
//   upper Gauss point x = (x, -delta) on the arc:  g = R - |x - c|
//   arc Gauss point q on the flat bottom y = -delta: g = q_y + delta
// (positive = penetration), as long as the foot lies inside the other surface.

#include "contact/contact_pair.hpp"

#include "fixtures.hpp"
#include "nurbs/refine.hpp"
#include "nurbs/topology.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace iga::contact {
namespace {

using test::vec2;

constexpr double R = 2.0, r_inner = 1.0, delta = 0.05;
const VecN centre = vec2(0.0, -2.0);
constexpr double interface_angle = 80.0;  // degrees: the ring's interface
constexpr double block_interface_x = -0.2;
// Closest-point Newton converges to round-off of O(1) coordinates; the gap is a
// difference of O(1) distances: 1e-10 leaves a wide margin yet catches a wrong
// foot (O(1e-3) and more here).
constexpr double gap_tolerance = 1e-10;
// How far past a patch end a foot counts as "just past" it (in length units): a
// few Gauss-point spacings of the finer surface.
constexpr double just_past = 0.08;

double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

/// Ring sector patch between angles a0 and a1 (degrees, u runs from a0 to a1):
/// u an exact rational quadratic arc, v from the inner radius (v0) to R (v1).
nurbs::Patch ring_sector(double a0, double a1, int n_spans)
{
    const double t0 = radians(a0), t1 = radians(a1), half = 0.5 * (t1 - t0), tm = 0.5 * (t0 + t1);
    RowMatrix P(6, 2);
    Vector w(6);
    const double radii[2] = {r_inner, R};
    for (int j = 0; j < 2; ++j) {
        const double rho = radii[j];
        P.row(3 * j + 0) = (centre + rho * vec2(std::cos(t0), std::sin(t0))).transpose();
        P.row(3 * j + 1) = (centre + rho / std::cos(half) * vec2(std::cos(tm), std::sin(tm))).transpose();
        P.row(3 * j + 2) = (centre + rho * vec2(std::cos(t1), std::sin(t1))).transpose();
        w(3 * j + 0) = 1.0;
        w(3 * j + 1) = std::cos(half);
        w(3 * j + 2) = 1.0;
    }
    const nurbs::Patch patch({nurbs::KnotVector(2, {0, 0, 0, 1, 1, 1}), nurbs::KnotVector(1, {0, 0, 1, 1})}, P, w);
    return nurbs::refine_uniform(patch, 0, n_spans);
}

/// Block [x0, x1] x [0, 0.5], degree (2, 1), n_spans along x.
nurbs::Patch block(double x0, double x1, int n_spans)
{
    RowMatrix P(6, 2);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 3; ++i)
            P.row(3 * j + i) << x0 + (x1 - x0) * i / 2.0, 0.5 * j;
    const nurbs::Patch patch({nurbs::KnotVector(2, {0, 0, 0, 1, 1, 1}), nurbs::KnotVector(1, {0, 0, 1, 1})}, P,
                             Vector::Ones(6));
    return nurbs::refine_uniform(patch, 0, n_spans);
}

/// Side `side` of every patch, glued into one surface as a multi-patch body would.
DeformableSide glued_surface(std::vector<nurbs::Patch>& patches, Side side)
{
    constexpr double coincident = 1e-12;  // control points computed from the same formulas
    const nurbs::Topology topology = nurbs::glue_patches(patches, coincident);
    EXPECT_EQ(topology.interfaces.size(), 1u);
    std::vector<const nurbs::Patch*> parents;
    for (const nurbs::Patch& p : patches)
        parents.push_back(&p);
    std::vector<int> surface_node;
    return DeformableSide::make(parents, std::vector<Side>(patches.size(), side), topology.node, surface_node);
}

struct Scene {
    std::vector<nurbs::Patch> upper_patches, lower_patches;
    DeformableSide upper, lower;
};

Scene make_scene()
{
    Scene s;
    s.upper_patches = {block(-1.0, block_interface_x, 5), block(block_interface_x, 1.0, 7)};
    s.lower_patches = {ring_sector(120.0, interface_angle, 6), ring_sector(interface_angle, 60.0, 4)};
    s.upper = glued_surface(s.upper_patches, Side::v0);
    s.lower = glued_surface(s.lower_patches, Side::v1);
    return s;
}

/// The upper surface moved rigidly by (shift, -delta); the lower one fixed.
std::pair<RowMatrix, RowMatrix> state(const ContactPair& pair, double shift)
{
    RowMatrix u_upper(pair.n_control_points(0), 2);
    u_upper.col(0).setConstant(shift);
    u_upper.col(1).setConstant(-delta);
    return {u_upper, RowMatrix::Zero(pair.n_control_points(1), 2)};
}

struct Counts {
    int checked = 0, active = 0, just_past_active = 0;
};

/// Checks every Gauss point of both carriers against the closed form at upper shift `shift`.
Counts check_against_closed_form(const ContactPair& pair, double shift)
{
    Counts counts;
    const auto [u_upper, u_lower] = state(pair, shift);
    const PairEvaluation ev = pair.evaluate(u_upper, u_lower, false);
    EXPECT_TRUE(ev.ok) << ev.message;
    EXPECT_EQ(ev.carriers.size(), 2u);
    for (const CarrierResult& c : ev.carriers) {
        const bool upper_slave = c.surface == 0;
        for (Index g = 0; g < c.gap.size(); ++g) {
            const VecN x = c.coordinates.row(g).transpose();
            double gap = 0.0, past = 0.0;  // past: how far past the master's interface the foot lies (< 0: before)
            if (upper_slave) {
                const VecN d = x - centre;
                gap = R - d.norm();
                const double angle = std::atan2(d(1), d(0)) * 180.0 / std::numbers::pi;
                past = R * radians(interface_angle - angle);  // arc length into the right ring patch
            } else {
                gap = x(1) + delta;
                past = x(0) - (block_interface_x + shift);    // into the right block patch
            }
            const bool foot_inside = upper_slave ? std::abs(x(0)) < 1.0 : std::abs(x(0) - shift) < 1.0;
            if (!foot_inside || gap < -0.5 * pair.search_distance())
                continue;  // the foot is off the master surface, or the point may be pruned
            SCOPED_TRACE(::testing::Message() << (upper_slave ? "upper" : "lower") << " Gauss point " << g << " at ("
                                              << x(0) << ", " << x(1) << "), shift " << shift);
            ++counts.checked;
            EXPECT_EQ(c.state[static_cast<std::size_t>(g)], PointState::ok) << "the foot is inside the surface";
            EXPECT_TRUE(test::near(c.gap(g), gap, gap_tolerance));
            if (gap > 0.0) {
                ++counts.active;
                const double eps = pair.settings().law.stiffness();
                EXPECT_TRUE(test::near(c.pressure(g), eps * gap, gap_tolerance * eps));
                if (past > 0.0 && past < just_past)
                    ++counts.just_past_active;
            }
        }
    }
    return counts;
}

TEST(MultiPatchPair, FeetJustPastAPatchEndAreProjectedOnTheNeighbour)
{
    const Scene s = make_scene();
    ASSERT_EQ(s.upper.pieces.size(), 2u);
    ASSERT_EQ(s.lower.pieces.size(), 2u);
    const ContactPair pair(PairSettings{.formulation = Formulation::two_half_pass, .law = NormalLaw::penalty(1.0e3)}, s.upper, s.lower);
    // The two glued pieces share one control point at their interface.
    EXPECT_EQ(pair.n_control_points(0), s.upper.pieces[0].side.patch.n_control_points() +
                                            s.upper.pieces[1].side.patch.n_control_points() - 1);

    // Straight down, then slid both ways: the feet of some points cross the
    // interfaces (warm starts from the previous evaluation sit on the other piece).
    for (const double shift : {0.0, 0.03, -0.03, 0.0}) {
        const Counts counts = check_against_closed_form(pair, shift);
        EXPECT_GT(counts.checked, 20) << "shift " << shift;
        EXPECT_GT(counts.active, 10) << "shift " << shift;
        EXPECT_GE(counts.just_past_active, 2) << "shift " << shift << ": active points with feet just past an interface";
    }
}

}  // namespace
}  // namespace iga::contact
