// Contact pairs in 3D: the pair's tangent (all Gauss points, projections re-solved)
// equals the central finite difference of its residual, for a sphere face against
// a tilted rigid plane and against a curved deformable face (two half passes and
// single pass), and forces balance.

#include "contact/contact_pair.hpp"

#include "fixtures.hpp"
#include "nurbs/refine.hpp"
#include "nurbs/shapes.hpp"
#include "support/finite_difference.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <random>

namespace iga::contact {
namespace {

// Central differences with h = 1e-7 on O(1) geometry and penalty 1e3: ~1e-8 relative
// truncation and round-off; 1e-6 exposes any missing term (O(1e-2) and more).
constexpr double fd_step = 1e-7;
constexpr double fd_tolerance = 1e-6;
// Gauss points this close to zero gap could switch under the FD step: the states
// below keep every point farther (asserted).
constexpr double min_gap_distance = 100 * fd_step;
constexpr double noise = 1e-3;

VecN vec3(double x, double y, double z)
{
    VecN v(3);
    v << x, y, z;
    return v;
}

/// The spherical face (v0) of a refined sphere octant, R = 1, lowest point (0, 0, 0).
DeformableSide sphere_face()
{
    nurbs::Patch ball = nurbs::sphere_octant(vec3(0, 0, 1), 1.0);
    ball = nurbs::elevate_degree(ball, 1, 1);
    ball = nurbs::refine_uniform(ball, 0, 4);
    ball = nurbs::refine_uniform(ball, 2, 4);
    return DeformableSide::make(ball, Side::v0);
}

/// The top face (w1) of a quadratic box [-0.4, 0.4]^2 x [-0.5, 0.015], domed by 0.01.
DeformableSide domed_top()
{
    nurbs::Patch b = nurbs::box(vec3(-0.4, -0.4, -0.5), vec3(0.8, 0.8, 0.515));
    for (int dir = 0; dir < 3; ++dir)
        b = nurbs::elevate_degree(b, dir, 1);
    b = nurbs::refine_uniform(b, 0, 3);
    b = nurbs::refine_uniform(b, 1, 3);
    RowMatrix P = b.control_points();
    for (Index a = 0; a < P.rows(); ++a)
        if (P(a, 2) > 0.0)
            P(a, 2) += 0.01 * (1.0 - 4.0 * P(a, 0) * P(a, 0)) * (1.0 - 4.0 * P(a, 1) * P(a, 1));
    return DeformableSide::make(b.with_control_points(P), Side::w1);
}

RowMatrix noisy(int n, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    RowMatrix u(n, 3);
    for (Index k = 0; k < u.size(); ++k)
        u(k) = noise * unit(rng);
    return u;
}

Vector stack(const RowMatrix& a, const RowMatrix& b)
{
    Vector v(a.size() + b.size());
    Index k = 0;
    for (Index r = 0; r < a.rows(); ++r)
        for (Index i = 0; i < 3; ++i)
            v(k++) = a(r, i);
    for (Index r = 0; r < b.rows(); ++r)
        for (Index i = 0; i < 3; ++i)
            v(k++) = b(r, i);
    return v;
}

std::pair<RowMatrix, RowMatrix> unstack(const Vector& v, int n1, int n2)
{
    RowMatrix a(n1, 3), b(n2, 3);
    Index k = 0;
    for (int r = 0; r < n1; ++r)
        for (int i = 0; i < 3; ++i)
            a(r, i) = v(k++);
    for (int r = 0; r < n2; ++r)
        for (int i = 0; i < 3; ++i)
            b(r, i) = v(k++);
    return {a, b};
}

double smallest_gap_magnitude(const PairEvaluation& ev)
{
    double smallest = std::numeric_limits<double>::infinity();
    for (const CarrierResult& c : ev.carriers)
        for (Index g = 0; g < c.gap.size(); ++g)
            if (c.state[static_cast<std::size_t>(g)] == PointState::ok)
                smallest = std::min(smallest, std::abs(c.gap(g)));
    return smallest;
}

void expect_tangent_is_derivative(const ContactPair& pair, const RowMatrix& u1, const RowMatrix& u2,
                                  const std::string& what)
{
    const int n1 = pair.n_control_points(0), n2 = pair.n_control_points(1);
    const PairEvaluation ev = pair.evaluate(u1, u2, true);
    ASSERT_TRUE(ev.ok) << ev.message;
    ASSERT_GE(ev.n_active, 4) << what;
    ASSERT_TRUE(test::at_least(smallest_gap_magnitude(ev), min_gap_distance)) << what;
    const Matrix K = test::dense(ev.tangent, pair.n_local_dofs());
    auto residual = [&](const Vector& v) {
        const auto [a, b] = unstack(v, n1, n2);
        const PairEvaluation e = pair.evaluate(a, b, false);
        EXPECT_TRUE(e.ok) << e.message;
        EXPECT_EQ(e.n_active, ev.n_active) << what << ": active set changed under the FD step";
        return e.residual;
    };
    const Matrix K_fd = test::central_difference_jacobian(residual, stack(u1, u2), fd_step);
    EXPECT_TRUE(test::at_most((K - K_fd).norm() / K_fd.norm(), fd_tolerance)) << what;
}

TEST(ContactPair3d, SphereAgainstTiltedPlaneTangentIsDerivative)
{
    const DeformableSide face = sphere_face();
    const RigidPlane floor = RigidPlane::make(vec3(0.0, 0.0, 0.05), vec3(0.05, -0.03, 1.0));
    const ContactPair pair({.law = NormalLaw::penalty(1e3)}, face, floor);
    EXPECT_EQ(pair.dim(), 3);
    expect_tangent_is_derivative(pair, noisy(pair.n_control_points(0), 1), RowMatrix(0, 3), "sphere on plane");
    // The body's contact force is -(sum of the residual): along the plane's normal, up.
    const PairEvaluation ev = pair.evaluate(noisy(pair.n_control_points(0), 1), RowMatrix(0, 3), false);
    VecN force = VecN::Zero(3);
    for (Index a = 0; a < ev.residual.size() / 3; ++a)
        force -= ev.residual.segment(3 * a, 3);
    EXPECT_TRUE(test::at_least(force.dot(floor.normal), 0.0));
    EXPECT_TRUE(test::at_most((force - force.dot(floor.normal) * floor.normal).norm(), 1e-12 * force.norm()));
}

TEST(ContactPair3d, SphereAgainstDomedFaceTangentIsDerivative)
{
    const DeformableSide face = sphere_face(), top = domed_top();
    for (const Formulation f : {Formulation::two_half_pass, Formulation::single_pass}) {
        const ContactPair pair({.formulation = f, .law = NormalLaw::penalty(1e3)}, face, top);
        expect_tangent_is_derivative(pair, noisy(pair.n_control_points(0), 2), noisy(pair.n_control_points(1), 3),
                                     f == Formulation::two_half_pass ? "two half passes" : "single pass");
    }
}

}  // namespace
}  // namespace iga::contact
