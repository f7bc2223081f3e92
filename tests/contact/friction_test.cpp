// Regularized Coulomb friction against rigid obstacles (contact/friction.hpp):
// the return map's cases, and the consistent tangent of a slave Gauss point
// (normal kernel plus tangential traction) against central finite differences
// of its residual, in 2D and 3D, for a plane and a sphere, sticking and slipping,
// without and with a tangential multiplier (augmented Lagrangian); and what the
// multiplier does: it carries the traction, and the elastic slip is what is left.

#include "contact/friction.hpp"
#include "contact/gpts_friction.hpp"
#include "contact/gpts_kernel.hpp"
#include "contact/rigid_obstacle.hpp"

#include "support/finite_difference.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace iga::contact {
namespace {

// Central differences with h = 1e-7 on O(1e-2) offsets and eps ~ 1e3: truncation
// O(h^2) and round-off ~1e-16 eps |x| / h ~ 1e-6 of the O(1e3) entries; a wrong
// or missing term (the slip projector, dp/dy, the sphere's turning normal) is
// O(1e-2) of the tangent or more.
constexpr double fd_step = 1e-7;
constexpr double fd_tolerance = 1e-6;

constexpr double normal_penalty = 2.0e3;
constexpr double tangential_penalty = 1.5e3;
constexpr double coefficient = 0.4;

struct Point {
    Vector N;  ///< slave basis values at the Gauss point
    double W = 0.7;
    RowMatrix X;  ///< slave control points, n_s x d
};

/// Residual (and tangent) of the point against the obstacle with a committed anchor.
KernelResult evaluate(const RigidObstacle& obstacle, const Point& point, const RowMatrix& X,
                      const FrictionHistory& committed, const VecN& multiplier, bool need_tangent,
                      TangentialResponse* response = nullptr, const NormalLaw& law = NormalLaw::penalty(normal_penalty))
{
    const Index d = X.cols();
    VecN x = VecN::Zero(d);
    for (Index a = 0; a < X.rows(); ++a)
        x += point.N(a) * X.row(a).transpose();
    const ObstacleFoot foot = obstacle.foot(x, 0.0);
    const KernelSettings settings{.law = law, .need_tangent = need_tangent};
    KernelResult kr = gpts_rigid_kernel(point.N, point.W, foot.normal, foot.gap, settings, foot.radius);
    const VecN dp = kr.pressure > 0.0 ? VecN(-kr.slope * foot.normal) : VecN(VecN::Zero(d));  // dp/dx = -p' n
    const TangentialResponse t = coulomb_response({coefficient, tangential_penalty}, committed, multiplier, x,
                                                  foot.normal, kr.pressure, dp, foot.radius);
    add_tangential(kr, point.N, point.W, t);
    if (response)
        *response = t;
    return kr;
}

/// The point's control points shifted so that x sits `depth` inside the obstacle's
/// surface along -n and `slide` along a tangent from the anchor.
/// `multiplier`: the tangential multiplier lambda_T (empty: none, the penalty law).
void check_tangent(const RigidObstacle& obstacle, const Point& point, const FrictionHistory& committed,
                   StickSlip expected, VecN multiplier = VecN(), const NormalLaw& law = NormalLaw::penalty(normal_penalty))
{
    if (multiplier.size() == 0)
        multiplier = VecN::Zero(point.X.cols());
    TangentialResponse response;
    const KernelResult kr = evaluate(obstacle, point, point.X, committed, multiplier, true, &response, law);
    ASSERT_EQ(response.status, expected);
    const Index n = point.X.size();
    const Eigen::VectorXd x0 = Eigen::Map<const Eigen::VectorXd>(point.X.data(), n);
    auto residual = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
        const RowMatrix X = Eigen::Map<const RowMatrix>(v.data(), point.X.rows(), point.X.cols());
        return evaluate(obstacle, point, X, committed, multiplier, false, nullptr, law).residual;
    };
    const Eigen::MatrixXd fd = test::central_difference_jacobian(residual, x0, fd_step);
    const double scale = kr.tangent.norm();
    EXPECT_LE((kr.tangent - fd).norm(), fd_tolerance * scale) << "tangent\n" << kr.tangent << "\nfd\n" << fd;
    if (expected == StickSlip::slip) {  // a slipping point's tangent is not symmetric
        EXPECT_GT((kr.tangent - kr.tangent.transpose()).norm(), 1e-3 * scale);
    }
}

Point point_2d()
{
    Point p;
    p.N = Vector(3);
    p.N << 0.2, 0.5, 0.3;
    p.X = RowMatrix(3, 2);
    p.X << -0.1, -0.004, 0.0, -0.005, 0.12, -0.006;  // x ~ (0.016, -0.0051): pressed into y <= 0
    return p;
}

Point point_3d()
{
    Point p;
    p.N = Vector(4);
    p.N << 0.1, 0.4, 0.3, 0.2;
    p.X = RowMatrix(4, 3);
    p.X << -0.1, 0.02, -0.004, 0.05, -0.1, -0.005, 0.1, 0.05, -0.006, 0.0, 0.1, -0.003;
    return p;
}

VecN x_of(const Point& p)
{
    VecN x = VecN::Zero(p.X.cols());
    for (Index a = 0; a < p.X.rows(); ++a)
        x += p.N(a) * p.X.row(a).transpose();
    return x;
}

FrictionHistory anchored(const Point& p, const VecN& offset)
{
    return FrictionHistory{x_of(p) - offset, 0.0};
}

TEST(Friction, ReturnMapSticksInsideTheConeAndSlidesOnIt)
{
    const VecN n = (VecN(2) << 0.0, 1.0).finished();
    const VecN y = (VecN(2) << 0.0, 0.0).finished();
    const FrictionLaw law{0.5, 100.0};
    const VecN dp = VecN::Zero(2);
    const VecN none = VecN::Zero(2);  // no tangential multiplier: the penalty law
    // Anchor 1e-3 to the left: trial traction -0.1 along x, inside mu p = 0.5.
    const TangentialResponse stick = coulomb_response(law, {(VecN(2) << -1e-3, 0.0).finished(), 0.0}, none, y, n, 1.0, dp);
    EXPECT_EQ(stick.status, StickSlip::stick);
    EXPECT_NEAR(stick.traction(0), -0.1, 1e-15);
    EXPECT_EQ(stick.next.anchor, (VecN(2) << -1e-3, 0.0).finished());
    // Anchor 0.02 to the left: trial -2 > 0.5, slides with |t| = mu p, slip 0.02 - 0.5/100.
    const TangentialResponse slip = coulomb_response(law, {(VecN(2) << -0.02, 0.0).finished(), 0.1}, none, y, n, 1.0, dp);
    EXPECT_EQ(slip.status, StickSlip::slip);
    EXPECT_NEAR(slip.traction(0), -0.5, 1e-15);
    EXPECT_NEAR(slip.slip_increment, 0.015, 1e-15);
    EXPECT_NEAR(slip.next.slip, 0.115, 1e-15);
    // The committed anchor reproduces the traction on the cone: the next trial starts there.
    const TangentialResponse again = coulomb_response(law, slip.next, none, y, n, 1.0, dp);
    EXPECT_NEAR(again.traction(0), -0.5, 1e-14);
    EXPECT_NEAR(again.slip_increment, 0.0, 1e-14);
    // The normal part of the offset carries no traction; an open point re-anchors where it is.
    const TangentialResponse normal_only =
        coulomb_response(law, {(VecN(2) << 0.0, -0.3).finished(), 0.0}, none, y, n, 1.0, dp);
    EXPECT_NEAR(normal_only.traction.norm(), 0.0, 1e-15);
    const TangentialResponse open = coulomb_response(law, {(VecN(2) << -0.02, 0.0).finished(), 0.0}, none, y, n, 0.0, dp);
    EXPECT_EQ(open.status, StickSlip::open);
    EXPECT_EQ(open.next.anchor, y);
}

TEST(Friction, APointThatSlippedSlidesOnFromTheCone)
{
    // After a slipping increment the committed anchor reproduces |t_T| = mu p, so the
    // next increment starts with the trial traction on the cone to round-off. Read as
    // stick, its tangent (ds/dy = -eps_T along the slide) holds the point fast; it
    // must be the sliding one (no stiffness along the slide), for the predictor to let
    // the surface slide on.
    const VecN n = (VecN(2) << 0.0, 1.0).finished();
    const VecN y = (VecN(2) << 0.0, 0.0).finished();
    const FrictionLaw law{0.5, 100.0};
    const VecN dp = VecN::Zero(2);
    const VecN none = VecN::Zero(2);
    const TangentialResponse slid = coulomb_response(law, {(VecN(2) << -0.02, 0.0).finished(), 0.0}, none, y, n, 1.0, dp);
    ASSERT_EQ(slid.status, StickSlip::slip);
    EXPECT_TRUE(slid.next.slipping);
    for (const double shift : {-1e-13, 0.0, 1e-13}) {  // the round-off either side of the cone
        FrictionHistory committed = slid.next;
        committed.anchor(0) += shift;
        const TangentialResponse on = coulomb_response(law, committed, none, y, n, 1.0, dp);
        EXPECT_EQ(on.status, StickSlip::slip) << "anchor shifted by " << shift;
        EXPECT_NEAR(on.traction(0), -0.5, 1e-12);
        EXPECT_NEAR(on.d_traction(0, 0), 0.0, 1e-9) << "the sliding tangent has no stiffness along the slide";
        EXPECT_GE(on.slip_increment, 0.0);
    }
    // Sliding back inside the cone sticks again: the band is 1e-9 of mu p, not a slide.
    FrictionHistory back = slid.next;
    back.anchor(0) += 1e-6;
    EXPECT_EQ(coulomb_response(law, back, none, y, n, 1.0, dp).status, StickSlip::stick);
    // A point that stuck stays stuck on the cone itself: only a slip carries on.
    FrictionHistory stuck = slid.next;
    stuck.slipping = false;
    stuck.anchor(0) += 1e-13;
    EXPECT_EQ(coulomb_response(law, stuck, none, y, n, 1.0, dp).status, StickSlip::stick);
}

// The trial traction eps_T (y - a) is a difference of positions: at y = (4, 0) one unit in
// the last place of the anchor moves it by eps_T 8.9e-16, here 1.1e-8 of mu p (p small,
// eps_T large, as at the dragged block's slipping point that read stick under another
// thread count). Either side of the cone by a few such units a slipping point slips on;
// a slide back inside the cone by far more than its round-off sticks.
TEST(Friction, ThePositionsRoundOffOnTheConeIsNotAStick)
{
    const VecN n = (VecN(2) << 0.0, 1.0).finished();
    const VecN y = (VecN(2) << 4.0, 0.0).finished();
    const FrictionLaw law{0.3, 1.1e6};
    const double p = 0.29;
    const VecN dp = VecN::Zero(2);
    const VecN none = VecN::Zero(2);
    const TangentialResponse slid =
        coulomb_response(law, {(VecN(2) << 4.0 - 1e-6, 0.0).finished(), 0.0}, none, y, n, p, dp);
    ASSERT_EQ(slid.status, StickSlip::slip);
    for (const int units : {-4, -1, 1, 4}) {
        FrictionHistory committed = slid.next;
        for (int k = 0; k < std::abs(units); ++k)
            committed.anchor(0) = std::nextafter(committed.anchor(0), units > 0 ? 10.0 : -10.0);
        const TangentialResponse on = coulomb_response(law, committed, none, y, n, p, dp);
        EXPECT_EQ(on.status, StickSlip::slip) << "anchor moved by " << units << " units in the last place";
        EXPECT_TRUE(test::near_rel(on.traction.norm(), law.coefficient * p, 1e-6));
    }
    FrictionHistory back = slid.next;
    back.anchor(0) += 1e-12;  // |s| falls by 1.1e-6, 1.3e-5 of mu p: inside the cone
    EXPECT_EQ(coulomb_response(law, back, none, y, n, p, dp).status, StickSlip::stick);
}

TEST(Friction, TangentEqualsFiniteDifferences2DPlane)
{
    const RigidObstacle plane(RigidPlane::make((VecN(2) << 0.0, 0.0).finished(), (VecN(2) << 0.0, 1.0).finished()));
    const Point p = point_2d();
    // mu p ~ 0.4 * 2e3 * 5e-3 = 4; eps_T 1.5e3: stick below an offset of ~2.7e-3.
    check_tangent(plane, p, anchored(p, (VecN(2) << 1e-3, 0.0).finished()), StickSlip::stick);
    check_tangent(plane, p, anchored(p, (VecN(2) << 2e-2, 0.0).finished()), StickSlip::slip);
}

// The exponential (softened) law presses at an open gap: the floor 0.01 below, the point
// 4.9e-3 above it inside the clearance 0.01, p ~ 0.2 p0 = 10 (mu p ~ 4, as above). The
// tangent, with dp/dx = -p' n from the law, still matches finite differences.
TEST(Friction, TangentWithTheExponentialLawEqualsFiniteDifferences)
{
    const RigidObstacle plane(RigidPlane::make((VecN(2) << 0.0, -0.01).finished(), (VecN(2) << 0.0, 1.0).finished()));
    const NormalLaw softened = NormalLaw::exponential(0.01, 50.0);
    const Point p = point_2d();
    const VecN none = VecN::Zero(2);
    check_tangent(plane, p, anchored(p, (VecN(2) << 1e-3, 0.0).finished()), StickSlip::stick, none, softened);
    check_tangent(plane, p, anchored(p, (VecN(2) << 2e-2, 0.0).finished()), StickSlip::slip, none, softened);
}

TEST(Friction, TangentEqualsFiniteDifferences2DCircle)
{
    // The disc of radius 1 below the point: the normal turns with x.
    const RigidObstacle disc(RigidSphere::make((VecN(2) << 0.05, -0.99).finished(), 1.0));
    const Point p = point_2d();
    check_tangent(disc, p, anchored(p, (VecN(2) << 1e-3, 4e-4).finished()), StickSlip::stick);
    check_tangent(disc, p, anchored(p, (VecN(2) << -2e-2, 5e-3).finished()), StickSlip::slip);
}

TEST(Friction, TangentEqualsFiniteDifferences3DPlane)
{
    const RigidObstacle plane(
        RigidPlane::make((VecN(3) << 0.0, 0.0, 0.0).finished(), (VecN(3) << 0.0, 0.0, 1.0).finished()));
    const Point p = point_3d();
    check_tangent(plane, p, anchored(p, (VecN(3) << 1e-3, -5e-4, 0.0).finished()), StickSlip::stick);
    check_tangent(plane, p, anchored(p, (VecN(3) << 2e-2, -1e-2, 0.0).finished()), StickSlip::slip);
}

TEST(Friction, TangentEqualsFiniteDifferences3DSphere)
{
    const RigidObstacle ball(RigidSphere::make((VecN(3) << 0.05, 0.0, -0.99).finished(), 1.0));
    const Point p = point_3d();
    check_tangent(ball, p, anchored(p, (VecN(3) << 1e-3, 5e-4, 2e-4).finished()), StickSlip::stick);
    check_tangent(ball, p, anchored(p, (VecN(3) << -2e-2, 1e-2, 3e-3).finished()), StickSlip::slip);
}

// A tangential multiplier lambda_T, fixed within Newton, shifts the trial traction:
// the tangent is the penalty one with the anchor shifted by lambda_T / eps_T. Sizes:
// |lambda_T| ~ 1.5-2 against mu p ~ 4 (2D) and ~ 6 (3D), so the stick offsets (trial
// ~1.5 from the slide) stay inside the cone and the slip ones (~30) far outside it. On
// the curved obstacles lambda_T is given a normal part too (an update makes it tangent
// to the normal of its own state, which turns as the point moves): the (n . w) term of
// the turning normal then sees it.
TEST(Friction, TangentWithATangentialMultiplierEqualsFiniteDifferences)
{
    const RigidObstacle line(RigidPlane::make((VecN(2) << 0.0, 0.0).finished(), (VecN(2) << 0.0, 1.0).finished()));
    const RigidObstacle disc(RigidSphere::make((VecN(2) << 0.05, -0.99).finished(), 1.0));
    const RigidObstacle plane(
        RigidPlane::make((VecN(3) << 0.0, 0.0, 0.0).finished(), (VecN(3) << 0.0, 0.0, 1.0).finished()));
    const RigidObstacle ball(RigidSphere::make((VecN(3) << 0.05, 0.0, -0.99).finished(), 1.0));
    const Point p2 = point_2d(), p3 = point_3d();
    {
        SCOPED_TRACE("2D line");
        const VecN lambda = (VecN(2) << -1.5, 0.0).finished();
        check_tangent(line, p2, anchored(p2, (VecN(2) << 1e-3, 0.0).finished()), StickSlip::stick, lambda);
        check_tangent(line, p2, anchored(p2, (VecN(2) << 2e-2, 0.0).finished()), StickSlip::slip, lambda);
    }
    {
        SCOPED_TRACE("2D circle");
        const VecN lambda = (VecN(2) << 1.5, 0.2).finished();
        check_tangent(disc, p2, anchored(p2, (VecN(2) << 1e-3, 4e-4).finished()), StickSlip::stick, lambda);
        check_tangent(disc, p2, anchored(p2, (VecN(2) << -2e-2, 5e-3).finished()), StickSlip::slip, lambda);
    }
    {
        SCOPED_TRACE("3D plane");
        const VecN lambda = (VecN(3) << 1.0, 1.2, 0.0).finished();
        check_tangent(plane, p3, anchored(p3, (VecN(3) << 1e-3, -5e-4, 0.0).finished()), StickSlip::stick, lambda);
        check_tangent(plane, p3, anchored(p3, (VecN(3) << 2e-2, -1e-2, 0.0).finished()), StickSlip::slip, lambda);
    }
    {
        SCOPED_TRACE("3D sphere");
        const VecN lambda = (VecN(3) << -1.2, 1.0, 0.3).finished();
        check_tangent(ball, p3, anchored(p3, (VecN(3) << 1e-3, 5e-4, 2e-4).finished()), StickSlip::stick, lambda);
        check_tangent(ball, p3, anchored(p3, (VecN(3) << -2e-2, 1e-2, 3e-3).finished()), StickSlip::slip, lambda);
    }
}

// What the multiplier does, on a plane (P lambda_T = lambda_T for a tangent lambda_T):
// the trial is lambda_T - eps_T P (y - a); the elastic slip |t_T - lambda_T| / eps_T is
// the slide from the anchor while the point sticks; the Uzawa update's new multiplier
// (frame_traction) is the traction; a slipping point's anchor is moved with the
// multiplier kept so that the next trial reproduces the traction. Each number is a sum
// of two or three O(1) terms: round-off.
TEST(Friction, TheTangentialMultiplierCarriesTheTraction)
{
    constexpr double exact = 1e-14;
    const VecN n = (VecN(2) << 0.0, 1.0).finished();
    const VecN y = (VecN(2) << 0.3, 0.0).finished();
    const FrictionLaw law{0.5, 100.0};
    const VecN dp = VecN::Zero(2);
    const VecN lambda = (VecN(2) << -0.3, 0.0).finished();  // inside mu p = 0.5
    // At its anchor the point carries lambda_T exactly, with no elastic slip.
    const TangentialResponse held = coulomb_response(law, {y, 0.0}, lambda, y, n, 1.0, dp);
    EXPECT_EQ(held.status, StickSlip::stick);
    EXPECT_NEAR((held.traction - lambda).norm(), 0.0, exact);
    EXPECT_NEAR(held.elastic_slip, 0.0, exact);
    EXPECT_NEAR((held.frame_traction - held.traction).norm(), 0.0, exact);
    // 1e-3 past its anchor it adds eps_T 1e-3 = 0.1 against the slide: elastic slip 1e-3.
    const VecN past = (VecN(2) << 0.301, 0.0).finished();
    const TangentialResponse stick = coulomb_response(law, {y, 0.0}, lambda, past, n, 1.0, dp);
    EXPECT_EQ(stick.status, StickSlip::stick);
    EXPECT_NEAR(stick.traction(0), -0.4, exact);
    EXPECT_NEAR(stick.elastic_slip, 1e-3, exact);
    EXPECT_EQ(stick.next.anchor, y) << "a sticking point keeps its anchor";
    // 0.01 past: trial -1.3, slides on the cone at -0.5; elastic slip |-0.5 + 0.3| / 100.
    const VecN far = (VecN(2) << 0.31, 0.0).finished();
    const TangentialResponse slip = coulomb_response(law, {y, 0.0}, lambda, far, n, 1.0, dp);
    EXPECT_EQ(slip.status, StickSlip::slip);
    EXPECT_NEAR(slip.traction(0), -0.5, exact);
    EXPECT_NEAR(slip.elastic_slip, 2e-3, exact);
    EXPECT_NEAR(slip.slip_increment, (1.3 - 0.5) / 100.0, exact);
    const TangentialResponse again = coulomb_response(law, slip.next, lambda, far, n, 1.0, dp);
    EXPECT_NEAR((again.traction - slip.traction).norm(), 0.0, exact) << "the moved anchor reproduces t_T";
    EXPECT_NEAR(again.slip_increment, 0.0, exact);
    // After the Uzawa update lambda_T <- t_T (the committed anchor kept) the same state
    // slides on with that traction and no elastic slip is left.
    const TangentialResponse updated = coulomb_response(law, {y, 0.0}, slip.frame_traction, far, n, 1.0, dp);
    EXPECT_EQ(updated.status, StickSlip::slip);
    EXPECT_NEAR((updated.traction - slip.traction).norm(), 0.0, exact);
    EXPECT_NEAR(updated.elastic_slip, 0.0, exact);
}

TEST(Friction, TangentBasisIsOrthonormalAndNormalToN)
{
    const VecN n2 = (VecN(2) << 0.6, 0.8).finished();
    const Matrix t2 = tangent_basis(n2, VecN::Zero(2));
    EXPECT_NEAR(t2.col(0).dot(n2), 0.0, 1e-15);
    EXPECT_NEAR(t2.col(0).norm(), 1.0, 1e-15);
    const VecN n3 = (VecN(3) << 0.0, 0.6, 0.8).finished();
    for (const VecN& along : {VecN((VecN(3) << 1.0, 0.2, 0.0).finished()), VecN(n3)}) {
        const Matrix t = tangent_basis(n3, along);
        const Matrix frame = (Matrix(3, 3) << t.col(0), t.col(1), n3).finished();
        EXPECT_NEAR((frame.transpose() * frame - Matrix::Identity(3, 3)).norm(), 0.0, 1e-14);
        EXPECT_NEAR(frame.determinant(), 1.0, 1e-14);  // right-handed: t1 x t2 = n
    }
}

}  // namespace
}  // namespace iga::contact
