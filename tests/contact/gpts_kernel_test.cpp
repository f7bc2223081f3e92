// GPTS penalty kernel: the tangent is the derivative of the residual (with the
// projection re-solved inside the residual), the single-pass tangent is the
// symmetric Hessian of Pi_c, forces balance, and the signs follow gap.hpp.

#include "contact/gpts_kernel.hpp"

#include "fixtures.hpp"
#include "support/finite_difference.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>
#include <random>

namespace iga::contact {
namespace {

using test::vec2;

// Central differences with h = 1e-6 on O(1) geometry: truncation ~h^2 |r'''| and
// round-off ~eps |r| / h give ~1e-9 relative; 1e-6 still exposes a wrong sign or
// a missing curvature term, which are O(1e-2) or larger here.
constexpr double fd_step = 1e-6;
constexpr double fd_tolerance = 1e-6;
// The single-pass tangent is a Hessian: symmetric up to round-off of its sums.
constexpr double symmetry_tolerance = 1e-10;
// Closed-form identities (p = eps g, sums of a few O(p W) terms): round-off.
constexpr double round_off = 1e-12;
// Dropping the p-weighted geometric terms changes the tangent by percents here
// (docs/theory.md "Verification problems" reports 13 % for a similar set-up).
constexpr double geometric_term_share = 1e-2;
// Random state: control points moved by up to this, small against the 0.08 penetration.
constexpr double noise = 2e-3;

/// A slave curve: its reference control points and the basis values at one
/// Gauss point eta (held fixed, as in the pair).
struct Slave {
    nurbs::Patch curve;
    double eta;
    double W;
};

Slave linear_slave()
{
    // A segment below the arch's crest (y ~ 0.25): penetrating by ~0.08 at eta.
    return {test::make_curve(1, {0, 0, 1, 1}, {{0.6, 0.18}, {1.5, 0.15}}, {1.0, 1.0}), 0.45, 0.37};
}

Slave quadratic_slave()
{
    return {test::make_curve(2, {0, 0, 0, 1, 1, 1}, {{0.5, 0.14}, {1.1, 0.20}, {1.7, 0.10}}, {1.0, 1.4, 0.9}), 0.6,
            0.29};
}

Vector slave_basis(const Slave& s)
{
    VecN eta(1);
    eta(0) = s.eta;
    return nurbs::rational_basis(s.curve, eta, 0).R;
}

/// Kernel at the dof vector u = [slave cp displacements ; master cp displacements].
KernelResult evaluate_kernel(const Slave& slave, const nurbs::Patch& master, const Vector& u,
                             const KernelSettings& settings, Projection* projection = nullptr)
{
    const Index n_s = slave.curve.n_control_points(), n_m = master.n_control_points();
    RowMatrix xs = slave.curve.control_points(), xm = master.control_points();
    for (Index a = 0; a < n_s; ++a)
        xs.row(a) += u.segment(2 * a, 2).transpose();
    for (Index b = 0; b < n_m; ++b)
        xm.row(b) += u.segment(2 * (n_s + b), 2).transpose();
    const Vector N = slave_basis(slave);
    VecN x = VecN::Zero(2);
    for (Index a = 0; a < n_s; ++a)
        x += N(a) * xs.row(a).transpose();
    const Projection p = project_to_surface(master.with_control_points(xm), test::rational_arch_sign, x);
    EXPECT_EQ(p.status, Projection::Status::ok);
    EXPECT_EQ(p.basis.indices.size(), static_cast<std::size_t>(n_m));  // one span: local = global numbering
    if (projection)
        *projection = p;
    return gpts_kernel(N, slave.W, p, settings);
}

Vector random_state(Index n, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    Vector u(n);
    for (Index i = 0; i < n; ++i)
        u(i) = noise * unit(rng);
    return u;
}

double relative_error(const Matrix& K, const Matrix& K_ref) { return (K - K_ref).norm() / K_ref.norm(); }

class KernelFd : public ::testing::TestWithParam<int> {};

TEST_P(KernelFd, SinglePassTangentIsSymmetricDerivative)
{
    const Slave slave = GetParam() == 1 ? linear_slave() : quadratic_slave();
    const nurbs::Patch master = test::rational_arch();
    const KernelSettings settings{.law = NormalLaw::penalty(1e3), .master_rows = true, .need_tangent = true};
    const Index n = 2 * (slave.curve.n_control_points() + master.n_control_points());
    for (const unsigned seed : {1u, 2u, 3u}) {
        const Vector u = random_state(n, seed);
        Projection p;
        const KernelResult k = evaluate_kernel(slave, master, u, settings, &p);
        ASSERT_TRUE(k.ok);
        ASSERT_GT(p.gap, 0.02) << "the state must penetrate clearly (seed " << seed << ")";
        ASSERT_GT(std::abs(p.curvature(0, 0)), 0.1) << "the master must be curved here";
        const Matrix K_fd = test::central_difference_jacobian(
            [&](const Vector& v) { return evaluate_kernel(slave, master, v, settings).residual; }, u, fd_step);
        const double err = relative_error(k.tangent, K_fd);
        EXPECT_TRUE(test::at_most(err, fd_tolerance)) << "seed " << seed;
        const double asym = (k.tangent - k.tangent.transpose()).norm() / k.tangent.norm();
        EXPECT_TRUE(test::at_most(asym, symmetry_tolerance)) << "seed " << seed;

        // The geometric (p-weighted) terms matter: dropping them is visibly wrong,
        // so this test would catch their absence.
        Vector Nn(n);
        const Vector N = slave_basis(slave);
        const Index n_s = slave.curve.n_control_points();
        for (Index a = 0; a < n_s; ++a)
            Nn.segment(2 * a, 2) = N(a) * p.normal;
        for (Index b = 0; b < master.n_control_points(); ++b)
            Nn.segment(2 * (n_s + b), 2) = -p.basis.R(b) * p.normal;
        const Matrix K_main = settings.law.stiffness() * slave.W * Nn * Nn.transpose();
        EXPECT_TRUE(test::at_least(relative_error(K_main, K_fd), geometric_term_share)) << "seed " << seed;
    }
}

TEST_P(KernelFd, HalfPassTangentIsDerivativeOfSlaveRows)
{
    const Slave slave = GetParam() == 1 ? linear_slave() : quadratic_slave();
    const nurbs::Patch master = test::rational_arch();
    const KernelSettings settings{.law = NormalLaw::penalty(1e3), .master_rows = false, .need_tangent = true};
    const Index n_s = 2 * slave.curve.n_control_points();
    const Index n = n_s + 2 * master.n_control_points();
    for (const unsigned seed : {4u, 5u}) {
        const Vector u = random_state(n, seed);
        const KernelResult k = evaluate_kernel(slave, master, u, settings);
        ASSERT_TRUE(k.ok);
        EXPECT_TRUE(test::at_most(k.residual.tail(n - n_s).norm(), 0.0));  // master rows are not assembled
        EXPECT_TRUE(test::at_most(k.tangent.bottomRows(n - n_s).norm(), 0.0));
        const Matrix K_fd = test::central_difference_jacobian(
            [&](const Vector& v) { return evaluate_kernel(slave, master, v, settings).residual; }, u, fd_step);
        EXPECT_TRUE(test::at_most(relative_error(k.tangent.topRows(n_s), K_fd.topRows(n_s)), fd_tolerance))
            << "seed " << seed;
    }
}

INSTANTIATE_TEST_SUITE_P(SlaveDegree, KernelFd, ::testing::Values(1, 2));

TEST(Kernel, ForcesPushTheSlaveOutAndBalance)
{
    const Slave slave = quadratic_slave();
    const nurbs::Patch master = test::rational_arch();
    const KernelSettings settings{.law = NormalLaw::penalty(2e3), .master_rows = true, .need_tangent = false};
    const Index n = 2 * (slave.curve.n_control_points() + master.n_control_points());
    Projection p;
    const KernelResult k = evaluate_kernel(slave, master, Vector::Zero(n), settings, &p);
    ASSERT_GT(p.gap, 0.0);
    EXPECT_TRUE(test::near_rel(k.pressure, settings.law.stiffness() * p.gap, round_off));
    EXPECT_TRUE(k.tangent.size() == 0);
    // Force on the slave = -(sum of slave rows) = p W n (partition of unity), along
    // the master's outward normal (up, out of the arch's body).
    VecN slave_force = VecN::Zero(2), total = VecN::Zero(2);
    for (Index a = 0; a < slave.curve.n_control_points(); ++a)
        slave_force -= k.residual.segment(2 * a, 2);
    for (Index i = 0; i < n / 2; ++i)
        total += k.residual.segment(2 * i, 2);
    EXPECT_TRUE(test::at_most((slave_force - k.pressure * slave.W * p.normal).norm(), round_off * k.pressure));
    EXPECT_TRUE(test::at_least(slave_force(1), 0.0));
    EXPECT_TRUE(test::at_most(total.norm(), round_off * k.pressure));  // action = reaction
}

TEST(Kernel, OpenGapGivesNothing)
{
    const Slave slave = linear_slave();
    const nurbs::Patch master = test::rational_arch();
    const Index n = 2 * (slave.curve.n_control_points() + master.n_control_points());
    Vector u = Vector::Zero(n);
    for (Index a = 0; a < slave.curve.n_control_points(); ++a)
        u(2 * a + 1) = 0.5;  // lift the slave well above the arch
    Projection p;
    const KernelResult k =
        evaluate_kernel(slave, master, u, {.law = NormalLaw::penalty(1e3), .master_rows = true, .need_tangent = true}, &p);
    EXPECT_LT(p.gap, 0.0);
    EXPECT_EQ(k.pressure, 0.0);
    EXPECT_EQ(k.residual.norm(), 0.0);
    EXPECT_EQ(k.tangent.norm(), 0.0);
}

TEST(Kernel, RigidPlaneTangentIsDerivative)
{
    const Slave slave = quadratic_slave();
    const RigidPlane plane = RigidPlane::make(vec2(0.0, 0.0), vec2(0.1, -1.0));  // obstacle above, tilted
    const KernelSettings settings{.law = NormalLaw::penalty(5e2), .master_rows = false, .need_tangent = true};
    const Vector N = slave_basis(slave);
    const Index n = 2 * slave.curve.n_control_points();
    auto kernel = [&](const Vector& u) {
        VecN x = VecN::Zero(2);
        for (Index a = 0; a < slave.curve.n_control_points(); ++a)
            x += N(a) * (slave.curve.control_points().row(a).transpose() + u.segment(2 * a, 2));
        return gpts_rigid_kernel(N, slave.W, plane.normal, plane.gap(x), settings);
    };
    const Vector u = random_state(n, 9) + Vector::Constant(n, 0.05);  // pushed up into the obstacle
    const KernelResult k = kernel(u);
    ASSERT_GT(k.pressure, 0.0);
    const Matrix K_fd = test::central_difference_jacobian([&](const Vector& v) { return kernel(v).residual; }, u,
                                                          fd_step);
    EXPECT_TRUE(test::at_most(relative_error(k.tangent, K_fd), fd_tolerance));
    // Force on the slave points along the plane normal, out of the obstacle.
    VecN force = VecN::Zero(2);
    for (Index a = 0; a < n / 2; ++a)
        force -= k.residual.segment(2 * a, 2);
    EXPECT_TRUE(test::at_least(force.dot(plane.normal), 0.0));
    EXPECT_TRUE(test::near_rel(force.norm(), k.pressure * slave.W, round_off));
}

/// A rigid circle (2D) or sphere (3D) as obstacle: the normal turns with the slave
/// point, so the tangent carries -(p W / |x - c|) N_a N_b (I - n n) besides the
/// penalty term; both must match the finite-difference derivative of the residual.
void expect_sphere_tangent_is_derivative(int d)
{
    // Three slave control points around (0, 0.95[, 0]) below a ball of radius 1 about (0.1, 1.9[, 0.05]).
    RowMatrix points(3, d);
    points.setZero();
    points(0, 0) = -0.3, points(1, 0) = 0.05, points(2, 0) = 0.4;
    points(0, 1) = 0.93, points(1, 1) = 0.97, points(2, 1) = 0.92;
    if (d == 3)
        points(0, 2) = 0.02, points(1, 2) = -0.03, points(2, 2) = 0.04;
    Vector N(3);
    N << 0.25, 0.5, 0.25;
    constexpr double W = 0.31;
    VecN center = VecN::Zero(d);
    center(0) = 0.1, center(1) = 1.9;
    if (d == 3)
        center(2) = 0.05;
    const RigidObstacle ball(RigidSphere::make(center, 1.0));
    const KernelSettings settings{.law = NormalLaw::penalty(7e2), .master_rows = false, .need_tangent = true};
    auto kernel = [&](const Vector& u) {
        VecN x = VecN::Zero(d);
        for (Index a = 0; a < 3; ++a)
            x += N(a) * (points.row(a).transpose() + u.segment(d * a, d));
        const ObstacleFoot foot = ball.foot(x, 0.0);
        return gpts_rigid_kernel(N, W, foot.normal, foot.gap, settings, foot.radius);
    };
    const Vector u = random_state(3 * d, 11);
    const KernelResult k = kernel(u);
    ASSERT_GT(k.pressure, 0.0) << "the state must penetrate the ball";
    const Matrix K_fd = test::central_difference_jacobian([&](const Vector& v) { return kernel(v).residual; }, u,
                                                          fd_step);
    EXPECT_TRUE(test::at_most(relative_error(k.tangent, K_fd), fd_tolerance)) << "d = " << d;
    // Without the turning of the normal the tangent is measurably wrong: the term is real.
    const KernelResult flat = [&] {
        VecN x = VecN::Zero(d);
        for (Index a = 0; a < 3; ++a)
            x += N(a) * (points.row(a).transpose() + u.segment(d * a, d));
        const ObstacleFoot foot = ball.foot(x, 0.0);
        return gpts_rigid_kernel(N, W, foot.normal, foot.gap, settings);
    }();
    EXPECT_TRUE(test::at_least(relative_error(flat.tangent, K_fd), geometric_term_share)) << "d = " << d;
}

TEST(Kernel, RigidCircleTangentIsDerivative) { expect_sphere_tangent_is_derivative(2); }

TEST(Kernel, RigidSphereTangentIsDerivative) { expect_sphere_tangent_is_derivative(3); }

TEST(RigidObstacle, SphereFootAndMotion)
{
    // Disc of radius 1 about (0, 2), moving by (0, -0.5) at load factor 1.
    const RigidObstacle disc(RigidSphere::make(vec2(0, 2), 1.0), vec2(0, -0.5));
    const ObstacleFoot at_rest = disc.foot(vec2(0, 0.9), 0.0);  // 0.1 below the disc: open
    EXPECT_TRUE(test::near(at_rest.gap, -0.1, round_off));
    EXPECT_TRUE(test::near((at_rest.normal - vec2(0, -1)).norm(), 0.0, round_off));
    EXPECT_TRUE(test::near(at_rest.radius, 1.1, round_off));
    const ObstacleFoot moved = disc.foot(vec2(0, 0.9), 0.4);  // centre now at y = 1.8: 0.1 inside
    EXPECT_TRUE(test::near(moved.gap, 0.1, round_off));
    EXPECT_FALSE(disc.foot(vec2(0, 1.5), 1.0).ok);  // at the centre: no normal, a status
    // A moving plane: the gap changes by the motion along the normal.
    const RigidObstacle lid(RigidPlane::make(vec2(0, 1), vec2(0, -1)), vec2(0.3, -0.2));
    EXPECT_TRUE(test::near(lid.foot(vec2(5, 0.9), 0.0).gap, -0.1, round_off));
    EXPECT_TRUE(test::near(lid.foot(vec2(5, 0.9), 1.0).gap, 0.1, round_off));
}

TEST(RigidPlane, GapSign)
{
    const RigidPlane floor = RigidPlane::make(vec2(0, 0), vec2(0, 2));  // normalized by make
    EXPECT_TRUE(test::near(floor.normal.norm(), 1.0, round_off));
    EXPECT_TRUE(test::near(floor.gap(vec2(3, 0.5)), -0.5, round_off));  // above: open
    EXPECT_TRUE(test::near(floor.gap(vec2(3, -0.2)), 0.2, round_off));  // inside: penetration
    EXPECT_THROW(RigidPlane::make(vec2(0, 0), vec2(0, 0)), Error);
}

}  // namespace
}  // namespace iga::contact

namespace iga::contact {
namespace {

// Augmented Lagrangian: with a multiplier lambda the pressure is <lambda + eps g_N>,
// so a point stays active at a small OPEN gap while lambda + eps g_N > 0; the
// tangent keeps the penalty form with that pressure (K = eps H W Nn Nn^T + p W (...)),
// which must still be the derivative of the residual.
TEST(Kernel, MultiplierKeepsAnOpenPointActiveWithTheAugmentedPressure)
{
    const Slave slave = quadratic_slave();
    const nurbs::Patch master = test::rational_arch();
    const Index n = 2 * (slave.curve.n_control_points() + master.n_control_points());
    Vector u = Vector::Zero(n);
    for (Index a = 0; a < slave.curve.n_control_points(); ++a)
        u(2 * a + 1) = 0.1;  // lift the slave just above the arch: a small open gap
    Projection p;
    const KernelResult penalty_only =
        evaluate_kernel(slave, master, u, {.law = NormalLaw::penalty(1e3), .master_rows = true, .need_tangent = true}, &p);
    ASSERT_TRUE(p.gap < -1e-3 && p.gap > -0.05) << "a small open gap, g_N = " << p.gap;
    EXPECT_EQ(penalty_only.pressure, 0.0) << "penalty alone: an open gap carries nothing";

    const double eps = 1e3, lambda = 60.0;  // lambda + eps g_N > 0 at g_N > -0.06
    const KernelSettings settings{
        .law = NormalLaw::penalty(eps), .multiplier = lambda, .master_rows = true, .need_tangent = true};
    const KernelResult k = evaluate_kernel(slave, master, u, settings);
    ASSERT_TRUE(k.ok);
    EXPECT_TRUE(test::near_rel(k.pressure, lambda + eps * p.gap, round_off)) << "p = <lambda + eps g_N>";
    const Matrix K_fd = test::central_difference_jacobian(
        [&](const Vector& v) { return evaluate_kernel(slave, master, v, settings).residual; }, u, fd_step);
    EXPECT_TRUE(test::at_most(relative_error(k.tangent, K_fd), fd_tolerance));

    // Far enough above, lambda + eps g_N < 0: nothing again.
    for (Index a = 0; a < slave.curve.n_control_points(); ++a)
        u(2 * a + 1) = 0.5;
    const KernelResult open = evaluate_kernel(slave, master, u, settings);
    EXPECT_EQ(open.pressure, 0.0);
    EXPECT_EQ(open.residual.norm(), 0.0);
}

TEST(Kernel, RigidKernelUsesTheAugmentedPressure)
{
    const Slave slave = quadratic_slave();
    const Vector N = slave_basis(slave);
    VecN normal(2);
    normal << 0.0, 1.0;
    const double eps = 5e2, lambda = 3.0, gap = -2e-3;  // open, yet lambda + eps g = 2 > 0
    const KernelResult k =
        gpts_rigid_kernel(N, slave.W, normal, gap,
                          {.law = NormalLaw::penalty(eps), .multiplier = lambda, .need_tangent = true});
    EXPECT_TRUE(test::near_rel(k.pressure, lambda + eps * gap, round_off));
    EXPECT_TRUE(test::near_rel(k.residual.norm(), k.pressure * slave.W * N.norm(), round_off));
    EXPECT_TRUE(test::near_rel(k.tangent.norm(), eps * slave.W * N.squaredNorm(), round_off));
}

}  // namespace
}  // namespace iga::contact

namespace iga::contact {
namespace {

// The exponential (softened) law presses inside its clearance, at an open gap, and
// continues linearly beyond touch: on both branches the kernel's tangent, with
// dp/dg in place of eps, is the derivative of its residual (single pass and half
// pass). The slave is lifted 0.1 off its ~0.08 penetration for the open case.
constexpr double softened_clearance = 0.05, softened_pressure = 50.0;

TEST(Kernel, ExponentialLawTangentIsDerivative)
{
    const Slave slave = quadratic_slave();
    const nurbs::Patch master = test::rational_arch();
    const NormalLaw law = NormalLaw::exponential(softened_clearance, softened_pressure);
    const Index n_s = 2 * slave.curve.n_control_points();
    const Index n = n_s + 2 * master.n_control_points();
    for (const double lift : {0.1, 0.0}) {
        SCOPED_TRACE(lift > 0.0 ? "open gap inside the clearance" : "penetrating: the linear branch");
        Vector u = random_state(n, 21);
        for (Index a = 0; a < slave.curve.n_control_points(); ++a)
            u(2 * a + 1) += lift;
        for (const bool master_rows : {true, false}) {
            const KernelSettings settings{.law = law, .master_rows = master_rows, .need_tangent = true};
            Projection p;
            const KernelResult k = evaluate_kernel(slave, master, u, settings, &p);
            ASSERT_TRUE(k.ok);
            if (lift > 0.0)
                ASSERT_TRUE(p.gap < -0.2 * softened_clearance && p.gap > -0.8 * softened_clearance) << p.gap;
            else
                ASSERT_GT(p.gap, 0.02);
            EXPECT_TRUE(test::near_rel(k.pressure, law.response(p.gap, 0.0).pressure, round_off));
            ASSERT_GT(k.pressure, 0.0);
            const Index rows = master_rows ? n : n_s;
            const Matrix K_fd = test::central_difference_jacobian(
                [&](const Vector& v) { return evaluate_kernel(slave, master, v, settings).residual; }, u, fd_step);
            EXPECT_TRUE(test::at_most(relative_error(k.tangent.topRows(rows), K_fd.topRows(rows)), fd_tolerance))
                << "master rows " << master_rows;
        }
    }
}

// The same for a rigid plane, where the kernel is p W N n and p' W Nn Nn^T.
TEST(Kernel, ExponentialLawRigidTangentIsDerivative)
{
    const Slave slave = quadratic_slave();
    const NormalLaw law = NormalLaw::exponential(softened_clearance, softened_pressure);
    const KernelSettings settings{.law = law, .master_rows = false, .need_tangent = true};
    const Vector N = slave_basis(slave);
    const Index n = 2 * slave.curve.n_control_points();
    // The slave's Gauss point sits at y ~ 0.17: planes (outward normal down) just above
    // it and just below it give an open gap inside the clearance and a penetration.
    for (const double height : {0.2, 0.15}) {
        const RigidPlane plane = RigidPlane::make(vec2(1.185, height), vec2(0.1, -1.0));
        auto kernel = [&](const Vector& u) {
            VecN x = VecN::Zero(2);
            for (Index a = 0; a < slave.curve.n_control_points(); ++a)
                x += N(a) * (slave.curve.control_points().row(a).transpose() + u.segment(2 * a, 2));
            return gpts_rigid_kernel(N, slave.W, plane.normal, plane.gap(x), settings);
        };
        const Vector u = random_state(n, 22);
        VecN x = VecN::Zero(2);
        for (Index a = 0; a < slave.curve.n_control_points(); ++a)
            x += N(a) * (slave.curve.control_points().row(a).transpose() + u.segment(2 * a, 2));
        const double gap = plane.gap(x);
        if (height > 0.17)
            ASSERT_TRUE(gap < 0.0 && gap > -softened_clearance) << gap;
        else
            ASSERT_GT(gap, 0.0);
        const KernelResult k = kernel(u);
        ASSERT_GT(k.pressure, 0.0);
        EXPECT_TRUE(test::near_rel(k.slope, law.response(gap, 0.0).slope, round_off));
        const Matrix K_fd = test::central_difference_jacobian([&](const Vector& v) { return kernel(v).residual; }, u,
                                                              fd_step);
        EXPECT_TRUE(test::at_most(relative_error(k.tangent, K_fd), fd_tolerance)) << "gap " << gap;
    }
}

}  // namespace
}  // namespace iga::contact
