// The tensor-form GPTS kernel in 3D: a slave Gauss point against a curved,
// rational biquadratic master surface. The tangent must equal the central
// finite difference of the residual with the projection re-solved each time
// (so the variation of the foot point and of the normal are both exercised),
// single pass must be symmetric, and the forces must balance. The projection
// here is a plain Newton written in the test, independent of contact/projection.

#include "contact/gpts_kernel.hpp"

#include "support/finite_difference.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <random>

namespace iga::contact {
namespace {

// Central differences, h = 1e-6 on O(1) geometry: ~1e-9 relative truncation and
// round-off; 1e-6 still exposes a missing curvature or normal-variation term
// (O(1e-2) here, checked below).
constexpr double fd_step = 1e-6;
constexpr double fd_tolerance = 1e-6;
// The single-pass tangent is a Hessian: symmetric to round-off.
constexpr double symmetry_tolerance = 1e-10;
// Sums of a few O(p W) terms: round-off.
constexpr double round_off = 1e-12;
// Leaving out the p-weighted geometric terms changes the tangent by more than this.
constexpr double geometric_term_share = 1e-2;
constexpr double noise = 2e-3;

/// A dome: biquadratic rational patch over [0,1]^2, z = bump, curved in both directions.
nurbs::Patch dome()
{
    RowMatrix P(9, 3);
    Vector w(9);
    int k = 0;
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i, ++k) {
            P.row(k) << 1.0 * i, 1.0 * j, (i == 1 ? 0.5 : 0.0) + (j == 1 ? 0.4 : 0.0) + 0.05 * i * j;
            w(k) = (i == 1 ? 0.9 : 1.0) * (j == 1 ? 1.2 : 1.0);
        }
    return nurbs::Patch({nurbs::KnotVector(2, {0, 0, 0, 1, 1, 1}), nurbs::KnotVector(2, {0, 0, 0, 1, 1, 1})},
                        std::move(P), std::move(w));
}

/// Foot point of x on the (single-element) surface by Newton on the distance;
/// the outward normal is +a_1 x a_2 normalized (pointing up, out of the dome's body).
MasterFoot foot_point(const nurbs::Patch& surface, const VecN& x)
{
    VecN xi(2);
    xi << 0.5, 0.5;
    nurbs::BasisValues basis;
    nurbs::PointDerivatives geo;
    for (int it = 0; it < 50; ++it) {
        basis = nurbs::rational_basis(surface, xi, 2);
        geo = nurbs::combine(basis, surface.control_points());
        const VecN r = x - geo.x;
        Eigen::Vector2d grad;
        Eigen::Matrix2d H;
        for (int a = 0; a < 2; ++a) {
            grad(a) = -r.dot(geo.dx.col(a));
            for (int b = 0; b < 2; ++b) {
                const int packed = a + b;  // uu = 0, uv = 1, vv = 2
                H(a, b) = geo.dx.col(a).dot(geo.dx.col(b)) - r.dot(geo.d2x.col(packed));
            }
        }
        const Eigen::Vector2d step = H.ldlt().solve(-grad);
        xi += step;
        if (step.norm() < 1e-15)
            break;
    }
    basis = nurbs::rational_basis(surface, xi, 2);
    geo = nurbs::combine(basis, surface.control_points());
    MasterFoot foot;
    const Eigen::Vector3d a1 = geo.dx.col(0), a2 = geo.dx.col(1);
    foot.normal = a1.cross(a2).normalized();
    foot.tangents = geo.dx;
    foot.metric = geo.dx.transpose() * geo.dx;
    foot.curvature.resize(2, 2);
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b)
            foot.curvature(a, b) = foot.normal.dot(geo.d2x.col(a + b));
    foot.gap = -(x - geo.x).dot(foot.normal);
    foot.R = basis.R;
    foot.dR = basis.dR;
    return foot;
}

struct Scene3d {
    RowMatrix slave;  // 4 slave control points, 3D
    Vector N;         // their basis values at the Gauss point
    double W = 0.23;
    nurbs::Patch master = dome();
};

Scene3d scene()
{
    Scene3d s;
    s.slave.resize(4, 3);
    // Below the dome's crest (z ~ 0.5 near the middle): penetrating by ~0.1.
    s.slave << 0.4, 0.45, 0.24, 0.6, 0.43, 0.27, 0.42, 0.62, 0.25, 0.61, 0.6, 0.28;
    s.N.resize(4);
    s.N << 0.2, 0.3, 0.1, 0.4;
    return s;
}

KernelResult kernel(const Scene3d& s, const Vector& u, const KernelSettings& settings, MasterFoot* out = nullptr)
{
    const Index n_s = s.slave.rows(), n_m = s.master.n_control_points();
    RowMatrix xm = s.master.control_points();
    for (Index b = 0; b < n_m; ++b)
        xm.row(b) += u.segment(3 * (n_s + b), 3).transpose();
    VecN x = VecN::Zero(3);
    for (Index a = 0; a < n_s; ++a)
        x += s.N(a) * (s.slave.row(a).transpose() + u.segment(3 * a, 3));
    const MasterFoot foot = foot_point(s.master.with_control_points(xm), x);
    if (out)
        *out = foot;
    return gpts_kernel(s.N, s.W, foot, settings);
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

TEST(Kernel3d, SinglePassTangentIsSymmetricDerivative)
{
    const Scene3d s = scene();
    const KernelSettings settings{.law = NormalLaw::penalty(1e3), .master_rows = true, .need_tangent = true};
    const Index n = 3 * (s.slave.rows() + s.master.n_control_points());
    for (const unsigned seed : {1u, 2u, 3u}) {
        const Vector u = random_state(n, seed);
        MasterFoot foot;
        const KernelResult k = kernel(s, u, settings, &foot);
        ASSERT_TRUE(k.ok);
        ASSERT_GT(foot.gap, 0.02) << "seed " << seed;
        ASSERT_GT(foot.curvature.norm(), 0.1) << "the master must be curved";
        const Matrix K_fd = test::central_difference_jacobian(
            [&](const Vector& v) { return kernel(s, v, settings).residual; }, u, fd_step);
        EXPECT_TRUE(test::at_most(relative_error(k.tangent, K_fd), fd_tolerance)) << "seed " << seed;
        EXPECT_TRUE(test::at_most((k.tangent - k.tangent.transpose()).norm() / k.tangent.norm(), symmetry_tolerance));
        // Without the geometric terms the tangent is visibly wrong: they are exercised.
        const Matrix K_main = [&] {
            Vector Nn(n);
            for (Index a = 0; a < s.slave.rows(); ++a)
                Nn.segment(3 * a, 3) = s.N(a) * foot.normal;
            for (Index b = 0; b < s.master.n_control_points(); ++b)
                Nn.segment(3 * (s.slave.rows() + b), 3) = -foot.R(b) * foot.normal;
            return Matrix(settings.law.stiffness() * s.W * Nn * Nn.transpose());
        }();
        EXPECT_TRUE(test::at_least(relative_error(K_main, K_fd), geometric_term_share)) << "seed " << seed;
    }
}

TEST(Kernel3d, HalfPassTangentIsDerivativeOfSlaveRows)
{
    const Scene3d s = scene();
    const KernelSettings settings{.law = NormalLaw::penalty(1e3), .master_rows = false, .need_tangent = true};
    const Index n_s = 3 * s.slave.rows();
    const Index n = n_s + 3 * s.master.n_control_points();
    const Vector u = random_state(n, 7);
    const KernelResult k = kernel(s, u, settings);
    ASSERT_TRUE(k.ok);
    EXPECT_EQ(k.residual.tail(n - n_s).norm(), 0.0);
    const Matrix K_fd = test::central_difference_jacobian(
        [&](const Vector& v) { return kernel(s, v, settings).residual; }, u, fd_step);
    EXPECT_TRUE(test::at_most(relative_error(k.tangent.topRows(n_s), K_fd.topRows(n_s)), fd_tolerance));
}

TEST(Kernel3d, ForcesBalanceAlongTheNormal)
{
    const Scene3d s = scene();
    const KernelSettings settings{.law = NormalLaw::penalty(2e3), .master_rows = true, .need_tangent = false};
    const Index n = 3 * (s.slave.rows() + s.master.n_control_points());
    MasterFoot foot;
    const KernelResult k = kernel(s, Vector::Zero(n), settings, &foot);
    ASSERT_GT(foot.gap, 0.0);
    VecN slave_force = VecN::Zero(3), total = VecN::Zero(3);
    for (Index a = 0; a < s.slave.rows(); ++a)
        slave_force -= k.residual.segment(3 * a, 3);
    for (Index i = 0; i < n / 3; ++i)
        total += k.residual.segment(3 * i, 3);
    EXPECT_TRUE(test::at_most((slave_force - k.pressure * s.W * foot.normal).norm(), round_off * k.pressure));
    EXPECT_TRUE(test::at_most(total.norm(), round_off * k.pressure));
}

// The exponential (softened) law: pressed at an open gap inside its clearance (the
// slave lifted 0.13 off its ~0.1 penetration) and on its linear branch beyond touch,
// the tangent with dp/dg in place of eps is the derivative of the residual.
TEST(Kernel3d, ExponentialLawTangentIsDerivative)
{
    constexpr double clearance = 0.05, pressure = 50.0;
    Scene3d s = scene();
    const NormalLaw law = NormalLaw::exponential(clearance, pressure);
    const Index n = 3 * (s.slave.rows() + s.master.n_control_points());
    const RowMatrix resting = s.slave;
    for (const double lift : {0.13, 0.0}) {
        SCOPED_TRACE(lift > 0.0 ? "open gap inside the clearance" : "penetrating: the linear branch");
        s.slave = resting;
        s.slave.col(2).array() += lift;
        const Vector u = random_state(n, 8);
        for (const bool master_rows : {true, false}) {
            const KernelSettings settings{.law = law, .master_rows = master_rows, .need_tangent = true};
            MasterFoot foot;
            const KernelResult k = kernel(s, u, settings, &foot);
            ASSERT_TRUE(k.ok);
            if (lift > 0.0)
                ASSERT_TRUE(foot.gap < -0.2 * clearance && foot.gap > -0.8 * clearance) << foot.gap;
            else
                ASSERT_GT(foot.gap, 0.02);
            ASSERT_GT(k.pressure, 0.0);
            const Index rows = master_rows ? n : 3 * s.slave.rows();
            const Matrix K_fd = test::central_difference_jacobian(
                [&](const Vector& v) { return kernel(s, v, settings).residual; }, u, fd_step);
            EXPECT_TRUE(test::at_most(relative_error(k.tangent.topRows(rows), K_fd.topRows(rows)), fd_tolerance))
                << "master rows " << master_rows;
        }
    }
}

}  // namespace
}  // namespace iga::contact
