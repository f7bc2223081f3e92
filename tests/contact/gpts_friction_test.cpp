// Coulomb friction against a DEFORMABLE master (contact/gpts_friction.hpp): the
// consistent tangent of a slave Gauss point (normal kernel plus tangential
// traction, projection re-solved at every perturbation) against central finite
// differences of its residual, in 2D and 3D, sticking and slipping, for a half
// pass (slave rows, current-measure weight) and a single pass (slave and master
// rows). The master is deformed (stretched and sheared) so that its reference and
// current tangents differ, and the anchor lies off the foot, so every term of the
// linearization -- the turning tangents, dc/dxibar, dp/du, the moving foot of the
// master rows -- is exercised; the same with a tangential multiplier (augmented
// Lagrangian). Also: the anchor update reproduces the traction, a rigid motion of
// both bodies leaves a sticking traction unchanged, and the multiplier an Uzawa
// update adopts carries the traction with no elastic slip left.

#include "contact/gpts_friction.hpp"
#include "contact/gpts_kernel.hpp"
#include "contact/projection.hpp"

#include "support/finite_difference.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

namespace iga::contact {
namespace {

// Central differences with h = 1e-7 on O(1) geometry and penalties ~1e3:
// truncation O(h^2) and round-off ~1e-16 |r| / h ~ 1e-8 of the O(1e3) entries;
// a missing term of the linearization is O(1e-3) of the tangent or more
// (MissingTermsAreSeen below checks that the test can see one).
constexpr double fd_step = 1e-7;
constexpr double fd_tolerance = 1e-6;

constexpr double normal_penalty = 2.0e3;
constexpr double tangential_penalty = 1.5e3;
constexpr double coefficient = 0.4;
constexpr double depth = 0.01;  // penetration: p = 20, mu p = 8

/// The master of the scene: a rational quadratic arc (2D) or a rational dome (3D).
nurbs::Patch master_patch(int d)
{
    if (d == 2) {
        RowMatrix P(3, 2);
        P << 0.0, 0.0, 0.5, 0.3, 1.0, 0.05;
        Vector w(3);
        w << 1.0, 0.8, 1.1;
        return nurbs::Patch({nurbs::KnotVector(2, {0, 0, 0, 1, 1, 1})}, std::move(P), std::move(w));
    }
    RowMatrix P(9, 3);
    Vector w(9);
    int k = 0;
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i, ++k) {
            P.row(k) << 0.5 * i, 0.5 * j, (i == 1 ? 0.25 : 0.0) + (j == 1 ? 0.2 : 0.0) + 0.02 * i * j;
            w(k) = (i == 1 ? 0.9 : 1.0) * (j == 1 ? 1.2 : 1.0);
        }
    return nurbs::Patch({nurbs::KnotVector(2, {0, 0, 0, 1, 1, 1}), nurbs::KnotVector(2, {0, 0, 0, 1, 1, 1})},
                        std::move(P), std::move(w));
}

struct Scene {
    nurbs::Patch master = master_patch(2);  ///< reference configuration
    RowMatrix master_disp; ///< the master's deformation (before the perturbation)
    int outward_sign = 1;
    RowMatrix slave;       ///< current slave control points
    Vector N;              ///< slave basis at the Gauss point
    double W0 = 0.7;
    Vector dW;             ///< W = W0 + dW . u_slave (a stand-in for the current area element); empty: fixed
    bool master_rows = false;
    /// A first touch: the converged slave point y_n and master control points (all of
    /// them, fixed under the perturbation); empty otherwise.
    VecN slave_before;
    RowMatrix master_before;
};

/// The residual over [all slave cps ; all master cps] (and the tangent), with the
/// response at the point.
struct Evaluation {
    Vector residual;
    Matrix tangent;
    TangentialResponse response;
    Vector foot_xi;
    VecN reference_foot;  ///< Xbar: the master's material point under the slave point
};

/// `multiplier`: the tangential multiplier Lambda (master reference space); empty: none.
Evaluation evaluate(const Scene& s, const FrictionHistory& committed, const Vector& u, bool need_tangent,
                    VecN multiplier = VecN())
{
    const Index d = s.slave.cols();
    const Index n_s = s.slave.rows();
    const Index n_m = s.master.n_control_points();
    if (multiplier.size() == 0)
        multiplier = VecN::Zero(d);
    RowMatrix xs = s.slave, xm = s.master.control_points() + s.master_disp;
    for (Index a = 0; a < n_s; ++a)
        xs.row(a) += u.segment(a * d, d).transpose();
    for (Index b = 0; b < n_m; ++b)
        xm.row(b) += u.segment((n_s + b) * d, d).transpose();
    VecN x = VecN::Zero(d);
    for (Index a = 0; a < n_s; ++a)
        x += s.N(a) * xs.row(a).transpose();
    const Projection proj = project_to_surface(s.master.with_control_points(xm), s.outward_sign, x);
    EXPECT_EQ(proj.status, Projection::Status::ok);
    const MasterFoot foot = master_foot(proj);
    MasterReference reference{VecN::Zero(d), Matrix::Zero(d, d - 1), Matrix::Zero(d, proj.basis.d2R.cols())};
    for (std::size_t b = 0; b < proj.basis.indices.size(); ++b) {
        const VecN X = s.master.control_points().row(proj.basis.indices[b]).transpose();
        reference.point += proj.basis.R(static_cast<Index>(b)) * X;
        reference.tangents += X * proj.basis.dR.row(static_cast<Index>(b));
        reference.second += X * proj.basis.d2R.row(static_cast<Index>(b));
    }
    const double W = s.dW.size() ? s.W0 + s.dW.dot(u.head(n_s * d)) : s.W0;
    const KernelSettings settings{
        .law = NormalLaw::penalty(normal_penalty), .master_rows = s.master_rows, .need_tangent = need_tangent};
    KernelResult kr = gpts_kernel(s.N, W, foot, settings, need_tangent ? s.dW : Vector());
    Evaluation out;
    ConvergedPositions before;
    if (s.master_before.size() > 0) {
        before.slave = s.slave_before;
        before.master.resize(static_cast<Index>(proj.basis.indices.size()), d);
        for (std::size_t b = 0; b < proj.basis.indices.size(); ++b)
            before.master.row(static_cast<Index>(b)) = s.master_before.row(proj.basis.indices[b]);
    }
    out.response = gpts_friction(kr, s.N, W, foot, reference, {coefficient, tangential_penalty}, committed,
                                 multiplier, settings, need_tangent ? s.dW : Vector(), before);
    out.foot_xi = proj.xi;
    out.reference_foot = reference.point;
    // Kernel numbering [slave ; the foot's master basis] -> [all slave ; all master].
    std::vector<Index> dof;
    for (Index a = 0; a < n_s; ++a)
        for (Index i = 0; i < d; ++i)
            dof.push_back(a * d + i);
    for (const int b : proj.basis.indices)
        for (Index i = 0; i < d; ++i)
            dof.push_back((n_s + b) * d + i);
    const Index n = (n_s + n_m) * d;
    out.residual = Vector::Zero(n);
    for (std::size_t k = 0; k < dof.size(); ++k)
        out.residual(dof[k]) += kr.residual(static_cast<Index>(k));
    if (need_tangent) {
        out.tangent = Matrix::Zero(n, n);
        for (std::size_t k = 0; k < dof.size(); ++k)
            for (std::size_t l = 0; l < dof.size(); ++l)
                out.tangent(dof[k], dof[l]) += kr.tangent(static_cast<Index>(k), static_cast<Index>(l));
    }
    return out;
}

/// Slave control points whose N-weighted point is `x` (offsets that average to zero).
RowMatrix slave_around(const VecN& x, const Vector& N)
{
    const Index d = x.size();
    RowMatrix X(N.size(), d);
    for (Index a = 0; a < N.size(); ++a)
        for (Index i = 0; i < d; ++i)
            X(a, i) = x(i) + 0.05 * std::cos(1.3 * static_cast<double>(a) + 0.7 * static_cast<double>(i));
    VecN mean = VecN::Zero(d);
    for (Index a = 0; a < N.size(); ++a)
        mean += N(a) * X.row(a).transpose();
    for (Index a = 0; a < N.size(); ++a)
        X.row(a) += (x - mean).transpose() / N.sum();
    return X;
}

/// A stretched and sheared master (F != I), displacement of each control point.
RowMatrix deformation(const RowMatrix& X)
{
    RowMatrix U(X.rows(), X.cols());
    for (Index b = 0; b < X.rows(); ++b) {
        U(b, 0) = 0.06 * X(b, 0) + 0.03 * X(b, 1) + 0.004 * std::sin(3.0 * static_cast<double>(b));
        U(b, 1) = -0.04 * X(b, 0) + 0.02 * X(b, 1);
        if (X.cols() == 3) {
            U(b, 1) += 0.01 * X(b, 2);
            U(b, 2) = 0.02 * X(b, 0) - 0.03 * X(b, 1) + 0.003 * std::cos(2.0 * static_cast<double>(b));
        }
    }
    return U;
}

/// A slave point `depth` inside the deformed master (upper side, outward normal up)
/// near parameter xi; the anchor is the master material point at reference offset
/// `slide` (in the reference tangent frame at the foot) plus a little off the surface.
struct Case {
    Scene scene;
    FrictionHistory anchor;
};

Case make_case(int d, double slide, bool half_pass)
{
    Case out;
    out.scene.master = master_patch(d);
    Scene& s = out.scene;
    s.master_disp = deformation(s.master.control_points());
    s.outward_sign = d == 2 ? -1 : 1;  // the body lies below: its outward normal points up
    const nurbs::Patch current = s.master.with_control_points(s.master.control_points() + s.master_disp);
    VecN xi(d - 1);
    xi.setConstant(0.45);
    if (d == 3)
        xi(1) = 0.55;
    const nurbs::PointDerivatives at = nurbs::combine(nurbs::rational_basis(current, xi, 1), current.control_points());
    VecN up(d);
    if (d == 2)
        up << -at.dx(1, 0), at.dx(0, 0);
    else
        up = Eigen::Vector3d(at.dx.col(0)).cross(Eigen::Vector3d(at.dx.col(1)));
    up.normalize();
    s.N = Vector(d == 2 ? 3 : 4);
    if (d == 2)
        s.N << 0.2, 0.5, 0.3;
    else
        s.N << 0.1, 0.4, 0.3, 0.2;
    s.slave = slave_around(at.x - depth * up, s.N);
    if (half_pass) {
        s.dW = Vector(s.slave.size());
        for (Index k = 0; k < s.dW.size(); ++k)
            s.dW(k) = 0.3 * std::sin(1.0 + static_cast<double>(k));
    }
    s.master_rows = !half_pass;
    // The anchor: reference point of the foot moved by `slide` along the reference tangents.
    const nurbs::PointDerivatives ref = nurbs::combine(nurbs::rational_basis(s.master, xi, 1), s.master.control_points());
    VecN along = VecN::Zero(d);
    for (Index al = 0; al < d - 1; ++al)
        along += (al == 0 ? 1.0 : -0.6) * ref.dx.col(al);
    VecN off_surface = VecN::Zero(d);
    off_surface(d - 1) = 0.3 * std::abs(slide);
    out.anchor = FrictionHistory{ref.x + slide * along + off_surface, 0.1, true};
    return out;
}

/// A first touch: the point was open at the converged state, at gap -2 depth, so it
/// touched at theta = 2/3 of the increment. The master was elsewhere then: 3 `slide`
/// back along the surface and a little bent (1e-3, so that its converged shape differs
/// from the current one), and the slave point 2 depth out along the current normal
/// from where it is: relative to the master it slid (1 - theta) P (X_n(xibar) - y_n)
/// since touching, about -3 (1 - theta) slide along the surface.
constexpr double touch_gap = -2.0 * depth;
constexpr double touch_theta = touch_gap / (touch_gap - depth);

/// The outward normal of the case's current master at xi.
VecN current_normal(const Scene& s, const VecN& xi)
{
    const nurbs::Patch current = s.master.with_control_points(s.master.control_points() + s.master_disp);
    const nurbs::PointDerivatives at = nurbs::combine(nurbs::rational_basis(current, xi, 1), current.control_points());
    const Index d = xi.size() + 1;
    VecN normal(d);
    if (d == 2)
        normal << -at.dx(1, 0), at.dx(0, 0);
    else
        normal = Eigen::Vector3d(at.dx.col(0)).cross(Eigen::Vector3d(at.dx.col(1)));
    return normal.normalized();
}

/// The direction the master slides in touching(), projected on the plane normal to n.
Vector master_slide(Index d, const VecN& normal)
{
    Vector along = Vector::Zero(d);
    along(0) = 1.0;
    if (d == 3)
        along(1) = -0.6;
    const Vector n = normal;
    return along - n.dot(along) * n;
}

Case touching(Case st, double slide)
{
    Scene& s = st.scene;
    const Index d = s.slave.cols();
    st.anchor.anchored = false;
    st.anchor.open_gap = touch_gap;
    VecN along = VecN::Zero(d);
    along(0) = 1.0;
    if (d == 3)
        along(1) = -0.6;
    s.master_before = s.master.control_points() + s.master_disp;
    for (Index b = 0; b < s.master_before.rows(); ++b)
        for (Index i = 0; i < d; ++i)
            s.master_before(b, i) += -3.0 * slide * along(i) + 1e-3 * std::sin(1.7 * static_cast<double>(b + 2 * i));
    VecN x = VecN::Zero(d);
    for (Index a = 0; a < s.N.size(); ++a)
        x += s.N(a) * s.slave.row(a).transpose();
    VecN xi = VecN::Constant(d - 1, 0.45);
    if (d == 3)
        xi(1) = 0.55;
    s.slave_before = x + 2.0 * depth * current_normal(s, xi);
    return st;
}

/// `multiplier`: the tangential multiplier Lambda (empty: none); `touch`: a first touch.
void expect_tangent_is_derivative(int d, double slide, bool half_pass, StickSlip expected,
                                  const VecN& multiplier = VecN(), bool touch = false)
{
    const Case st = touch ? touching(make_case(d, slide, half_pass), slide) : make_case(d, slide, half_pass);
    const Index n = (st.scene.slave.rows() + st.scene.master.n_control_points()) * d;
    const Vector u0 = Vector::Zero(n);
    const Evaluation ev = evaluate(st.scene, st.anchor, u0, true, multiplier);
    ASSERT_EQ(ev.response.status, expected) << "|t_T| = " << ev.response.traction.norm();
    auto residual = [&](const Eigen::VectorXd& u) -> Eigen::VectorXd {
        return evaluate(st.scene, st.anchor, u, false, multiplier).residual;
    };
    const Matrix fd = test::central_difference_jacobian(residual, u0, fd_step);
    const double scale = ev.tangent.norm();
    EXPECT_LE((ev.tangent - fd).norm(), fd_tolerance * scale) << "tangent\n" << ev.tangent << "\nfd\n" << fd;
    if (!half_pass && expected == StickSlip::slip) {  // friction makes even a single pass non-symmetric
        EXPECT_GT((ev.tangent - ev.tangent.transpose()).norm(), 1e-3 * scale);
    }
}

// slide 0.002: |s| ~ 3 < mu p = 8 (stick); 0.03: |s| ~ 45 (slip).
constexpr double stick_slide = 0.002;
constexpr double slip_slide = 0.03;

TEST(GptsFriction, HalfPassStickTangentIsDerivative2d) { expect_tangent_is_derivative(2, stick_slide, true, StickSlip::stick); }
TEST(GptsFriction, HalfPassSlipTangentIsDerivative2d) { expect_tangent_is_derivative(2, slip_slide, true, StickSlip::slip); }
TEST(GptsFriction, SinglePassStickTangentIsDerivative2d) { expect_tangent_is_derivative(2, stick_slide, false, StickSlip::stick); }
TEST(GptsFriction, SinglePassSlipTangentIsDerivative2d) { expect_tangent_is_derivative(2, -slip_slide, false, StickSlip::slip); }
TEST(GptsFriction, HalfPassStickTangentIsDerivative3d) { expect_tangent_is_derivative(3, stick_slide, true, StickSlip::stick); }
TEST(GptsFriction, HalfPassSlipTangentIsDerivative3d) { expect_tangent_is_derivative(3, slip_slide, true, StickSlip::slip); }
TEST(GptsFriction, SinglePassStickTangentIsDerivative3d) { expect_tangent_is_derivative(3, -stick_slide, false, StickSlip::stick); }
TEST(GptsFriction, SinglePassSlipTangentIsDerivative3d) { expect_tangent_is_derivative(3, slip_slide, false, StickSlip::slip); }

// With a tangential multiplier Lambda (a vector of the master's reference space, off
// its tangent plane as any vector may be): |F_s Lambda| ~ 2 against mu p = 8, so the
// stick slides (trial ~3) stay inside the cone and the slip ones (~45) outside it.
VecN multiplier(int d)
{
    return d == 2 ? VecN((VecN(2) << 1.6, -0.9).finished()) : VecN((VecN(3) << -1.2, 1.4, 0.5).finished());
}

TEST(GptsFriction, TangentWithATangentialMultiplierIsDerivative2d)
{
    for (const bool half_pass : {true, false}) {
        SCOPED_TRACE(half_pass ? "half pass" : "single pass");
        expect_tangent_is_derivative(2, stick_slide, half_pass, StickSlip::stick, multiplier(2));
        expect_tangent_is_derivative(2, half_pass ? slip_slide : -slip_slide, half_pass, StickSlip::slip,
                                     multiplier(2));
    }
}

TEST(GptsFriction, TangentWithATangentialMultiplierIsDerivative3d)
{
    for (const bool half_pass : {true, false}) {
        SCOPED_TRACE(half_pass ? "half pass" : "single pass");
        expect_tangent_is_derivative(3, half_pass ? stick_slide : -stick_slide, half_pass, StickSlip::stick,
                                     multiplier(3));
        expect_tangent_is_derivative(3, slip_slide, half_pass, StickSlip::slip, multiplier(3));
    }
}

// The Uzawa update adopts Lambda = G m^-1 a^T t_T, whose image F_s Lambda is t_T again:
// a point that sticks with traction t_T and is then held at the master's material point
// under it (anchor = Xbar) with that multiplier carries the same traction, with no
// elastic slip; without the multiplier its elastic slip is |t_T| / eps_T. A few
// products of O(1) matrices: round-off of the O(3) traction.
TEST(GptsFriction, TheUpdatedMultiplierCarriesTheTractionWithoutElasticSlip)
{
    constexpr double round_off = 1e-12;
    for (const int d : {2, 3}) {
        SCOPED_TRACE(d);
        const Case st = make_case(d, stick_slide, true);
        const Vector u0 = Vector::Zero((st.scene.slave.rows() + st.scene.master.n_control_points()) * d);
        const Evaluation stick = evaluate(st.scene, st.anchor, u0, false);
        ASSERT_EQ(stick.response.status, StickSlip::stick);
        const VecN t = stick.response.traction;
        ASSERT_GT(t.norm(), 1.0);
        EXPECT_NEAR(stick.response.elastic_slip, t.norm() / tangential_penalty, round_off);
        const FrictionHistory at_foot{stick.reference_foot, 0.0, true};
        const Evaluation held = evaluate(st.scene, at_foot, u0, false, stick.response.frame_traction);
        EXPECT_EQ(held.response.status, StickSlip::stick);
        EXPECT_LE((held.response.traction - t).norm(), round_off * t.norm());
        EXPECT_LE(held.response.elastic_slip, round_off * t.norm() / tangential_penalty);
    }
}

TEST(GptsFriction, SlipMovesTheAnchorToReproduceTheTraction)
{
    // With a tangential multiplier the anchor moves so that, with the multiplier kept,
    // the traction is reproduced.
    for (const auto& [d, lambda] : {std::pair{2, VecN()}, std::pair{3, VecN()}, std::pair{2, multiplier(2)},
                                    std::pair{3, multiplier(3)}}) {
        SCOPED_TRACE(lambda.size() ? "with a tangential multiplier" : "penalty");
        const Case st = make_case(d, slip_slide, true);
        const Vector u0 = Vector::Zero((st.scene.slave.rows() + st.scene.master.n_control_points()) * d);
        const Evaluation slip = evaluate(st.scene, st.anchor, u0, false, lambda);
        ASSERT_EQ(slip.response.status, StickSlip::slip);
        EXPECT_NEAR(slip.response.traction.norm(), coefficient * normal_penalty * depth, 1e-9);
        EXPECT_NEAR(slip.response.next.slip, st.anchor.slip + slip.response.slip_increment, 1e-15);
        // Evaluated again from the moved anchor, the point sits on the cone's edge: no further slip.
        const Evaluation again = evaluate(st.scene, slip.response.next, u0, false, lambda);
        EXPECT_LE(again.response.slip_increment, 1e-12 * slip.response.slip_increment);
        EXPECT_LE((again.response.traction - slip.response.traction).norm(), 1e-9 * slip.response.traction.norm());
    }
}

TEST(GptsFriction, ARigidTranslationOfBothBodiesKeepsTheTraction)
{
    for (const int d : {2, 3}) {
        const Case st = make_case(d, stick_slide, true);
        const Index n_cp = st.scene.slave.rows() + st.scene.master.n_control_points();
        const Evaluation at_rest = evaluate(st.scene, st.anchor, Vector::Zero(n_cp * d), false);
        Vector shift(n_cp * d);
        for (Index k = 0; k < n_cp; ++k)
            for (Index i = 0; i < d; ++i)
                shift(k * d + i) = 0.3 + 0.2 * static_cast<double>(i);
        const Evaluation moved = evaluate(st.scene, st.anchor, shift, false);
        EXPECT_EQ(moved.response.status, StickSlip::stick);
        EXPECT_LE((moved.response.traction - at_rest.response.traction).norm(),
                  1e-10 * at_rest.response.traction.norm());
    }
}

// A first touch carries (1 - theta) of the increment's tangential relative motion: its
// tangent, with theta moving with the gap, the normal turning and the master's
// converged point following the foot, against central differences. The master moved
// 3 slide along the surface: |s| ~ 1 (stick_slide) and ~ 15 (slip_slide) against mu p = 8.
TEST(GptsFriction, ATouchingPointsTangentIsDerivative)
{
    for (const int d : {2, 3})
        for (const bool half_pass : {true, false}) {
            SCOPED_TRACE(std::to_string(d) + (half_pass ? "D half pass" : "D single pass"));
            expect_tangent_is_derivative(d, stick_slide, half_pass, StickSlip::stick, VecN(), true);
            expect_tangent_is_derivative(d, slip_slide, half_pass, StickSlip::slip, VecN(), true);
        }
}

// The increment a point first presses in: it carries eps_T (1 - theta) P (y_n - X_n(xibar)),
// the traction that opposes its slide since touching (the master slid 3 slide along the
// surface under it, so it is dragged along), and is anchored where that traction is
// reproduced. Round-off of O(1) products.
TEST(GptsFriction, ATouchingPointCarriesTheTractionOfItsSlideSinceTouching)
{
    constexpr double round_off = 1e-12;
    for (const int d : {2, 3}) {
        SCOPED_TRACE(d);
        const Case st = touching(make_case(d, stick_slide, true), stick_slide);
        const Index n = (st.scene.slave.rows() + st.scene.master.n_control_points()) * d;
        const Evaluation touch = evaluate(st.scene, st.anchor, Vector::Zero(n), false);
        ASSERT_EQ(touch.response.status, StickSlip::stick);
        // The expected traction from the converged positions at the foot's parameters.
        const VecN X_n = nurbs::combine(nurbs::rational_basis(st.scene.master, touch.foot_xi, 0),
                                        st.scene.master_before).x;
        const VecN normal = current_normal(st.scene, touch.foot_xi);
        const VecN w = st.scene.slave_before - X_n;
        const VecN expected = tangential_penalty * (1.0 - touch_theta) * (w - normal.dot(w) * normal);
        EXPECT_GT(expected.norm(), 0.5);
        const Vector slid = master_slide(d, normal);
        EXPECT_GT(touch.response.traction.dot(slid), 0.5 * touch.response.traction.norm() * slid.norm())
            << "the traction does not drag the slave along with the master";
        EXPECT_LE((touch.response.traction - expected).norm(), 1e-9 * expected.norm());
        EXPECT_TRUE(touch.response.next.anchored);
        const Evaluation anchored = evaluate(st.scene, touch.response.next, Vector::Zero(n), false);
        EXPECT_LE((anchored.response.traction - touch.response.traction).norm(),
                  round_off * touch.response.traction.norm());
    }
}

// Two surfaces that approached along the normal only (the slave point straight above the
// master's material point under it, neither slid) take no traction at their first touch:
// identical bodies pressed together stay free of tangential traction.
TEST(GptsFriction, ATouchAlongTheNormalCarriesNoTraction)
{
    for (const int d : {2, 3}) {
        SCOPED_TRACE(d);
        Case st = touching(make_case(d, stick_slide, true), 0.0);
        const Index n = (st.scene.slave.rows() + st.scene.master.n_control_points()) * d;
        st.scene.master_before = st.scene.master.control_points() + st.scene.master_disp;  // the master stayed
        const Evaluation first = evaluate(st.scene, st.anchor, Vector::Zero(n), false);
        const nurbs::Patch current = st.scene.master.with_control_points(st.scene.master_before);
        const VecN foot = nurbs::combine(nurbs::rational_basis(current, first.foot_xi, 0), current.control_points()).x;
        st.scene.slave_before = foot + 3.0 * depth * current_normal(st.scene, first.foot_xi);  // straight down the normal
        const Evaluation touch = evaluate(st.scene, st.anchor, Vector::Zero(n), false);
        EXPECT_EQ(touch.response.status, StickSlip::stick);
        EXPECT_LE(touch.response.traction.norm(), 1e-9 * coefficient * normal_penalty * depth);
    }
}

// Without a converged gap (it came from out of reach) it sticks where it touches, with
// no traction in that increment.
TEST(GptsFriction, AFirstTouchWithoutAFootSticksWithoutTraction)
{
    Case st = make_case(2, slip_slide, true);
    st.anchor.anchored = false;
    const Vector u0 = Vector::Zero((st.scene.slave.rows() + st.scene.master.n_control_points()) * 2);
    const Evaluation ev = evaluate(st.scene, st.anchor, u0, true);
    EXPECT_EQ(ev.response.status, StickSlip::stick);
    EXPECT_EQ(ev.response.traction.norm(), 0.0);
    EXPECT_TRUE(ev.response.next.anchored);
}

}  // namespace
}  // namespace iga::contact
