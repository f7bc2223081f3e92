#include "contact/gpts_friction.hpp"

#include "core/error.hpp"

#include <Eigen/Cholesky>

#include <algorithm>

namespace iga::contact {
namespace {

/// Column of x,ab in second derivatives packed like BasisValues::d2R.
Index packed(Index a, Index b, Index q)
{
    return nurbs::second_column(static_cast<int>(q), static_cast<int>(a), static_cast<int>(b));
}

}  // namespace

FrictionHistory open_history(const FrictionHistory& committed, const MasterReference& reference, double gap)
{
    // Not anchored: where an open point will touch is not the foot it has now (on a
    // curved master the closest point moves as the gap closes). Its gap tells the
    // increment in which it presses when the gap closed.
    return FrictionHistory{reference.point, committed.slip, false, false, std::min(gap, 0.0)};
}

namespace {

/// A trial traction s (d) and ds/du over the kernel's dofs (d x n_dofs).
struct Trial {
    VecN s;
    Matrix ds;
};

/// An anchored point: s = eps_T a c, c = M^-1 G^T (A + Lambda / eps_T - Xbar) (the header).
Trial anchored_trial(const MasterFoot& master, const MasterReference& reference, const FootVariation& v,
                     const VecN& anchor, const VecN& multiplier, double eps_T, Index n_s)
{
    const Index d = master.normal.size();
    const Index q = d - 1;
    const Matrix& G = reference.tangents;
    const Matrix& a = master.tangents;
    const Eigen::LLT<Matrix> M_llt(G.transpose() * G);
    // c: the anchor's offset in the foot's reference tangent frame, shifted by the multiplier.
    const VecN offset = anchor - reference.point + multiplier / eps_T;
    const Vector c = M_llt.solve(G.transpose() * offset);
    // C = dc/dxibar, column ga: -e_ga + M^-1 (X,al ga . offset - dM/dxi^ga c).
    Matrix C(q, q);
    for (Index ga = 0; ga < q; ++ga) {
        Vector y(q);
        Matrix dM(q, q);
        for (Index al = 0; al < q; ++al) {
            y(al) = reference.second.col(packed(al, ga, q)).dot(offset);
            for (Index be = 0; be < q; ++be)
                dM(al, be) = reference.second.col(packed(al, ga, q)).dot(G.col(be)) +
                             G.col(al).dot(reference.second.col(packed(be, ga, q)));
        }
        C.col(ga) = M_llt.solve(y - dM * c);
        C(ga, ga) -= 1.0;
    }
    // ds/du: the current tangents a_al move with the master's control points and the foot.
    Matrix Xc = Matrix::Zero(d, q);  // column ga: x_m,al ga c^al
    for (Index ga = 0; ga < q; ++ga)
        for (Index al = 0; al < q; ++al)
            Xc.col(ga) += master.second.col(packed(al, ga, q)) * c(al);
    Trial out{eps_T * a * c, eps_T * (Xc + a * C) * v.D.transpose()};
    for (Index b = 0; b < master.R.size(); ++b)
        out.ds.block(0, (n_s + b) * d, d, d).diagonal().array() += eps_T * master.dR.row(b).dot(c);
    return out;
}

/// A point in the increment it first presses (the header, "First touch"):
/// s = eps_T (1 - theta) P w, w = y_n - X_n(xibar), theta = g_n / (g_n - g), and
///   ds/du = eps_T [ (theta^2 / g_n) P w Nn^T
///                   + (1 - theta) ((n . w) I + n w^T) a m^-1 (Nd + D b)^T   (dP w, the normal turning)
///                   - (1 - theta) P a_n D^T ]                             (X_n follows the foot)
/// with dg/du = -Nn, dn/du = -a m^-1 (Nd + D b)^T and a_n = dX_n/dxi.
Trial touch_trial(const MasterFoot& master, const FootVariation& v, const ConvergedPositions& before, double g_n,
                  double gap, double eps_T)
{
    const Index d = master.normal.size();
    const VecN& n = master.normal;
    const Matrix& a = master.tangents;
    const Matrix P = Matrix::Identity(d, d) - n * n.transpose();
    const VecN w = before.slave - before.master.transpose() * master.R;  // y_n - X_n(xibar)
    const Matrix a_n = before.master.transpose() * master.dR;            // d x q
    const double theta = g_n / (g_n - gap);
    const Eigen::LLT<Matrix> m_llt(master.metric);
    const Matrix turn = m_llt.solve((v.Nd + v.D * master.curvature).transpose());  // m^-1 (Nd + D b)^T
    const VecN Pw = P * w;
    Trial out{eps_T * (1.0 - theta) * Pw, Matrix()};
    out.ds = eps_T * ((theta * theta / g_n) * Pw * v.Nn.transpose() +
                      (1.0 - theta) * (n.dot(w) * Matrix::Identity(d, d) + n * w.transpose()) * a * turn +
                      -(1.0 - theta) * P * a_n * v.D.transpose());
    return out;
}

}  // namespace

TangentialResponse gpts_friction(KernelResult& result, const Vector& N, double W, const MasterFoot& master,
                                 const MasterReference& reference, const FrictionLaw& law,
                                 const FrictionHistory& committed, const VecN& multiplier,
                                 const KernelSettings& settings, const Vector& dW, const ConvergedPositions& before)
{
    const Index d = master.normal.size();
    const Index q = d - 1;
    const Index n_s = N.size();
    const Index n_m = master.R.size();
    const Index n_dofs = (n_s + n_m) * d;
    IGA_CHECK(result.residual.size() == n_dofs, "friction: the kernel result has another size");
    IGA_CHECK(master.second.rows() == d && master.second.cols() == q * (q + 1) / 2 &&
                  reference.tangents.rows() == d && reference.tangents.cols() == q &&
                  reference.second.cols() == q * (q + 1) / 2,
              "friction: a deformable master needs its current and reference derivatives at the foot");
    IGA_CHECK(multiplier.size() == d, "friction: the tangential multiplier needs the point's dimension");
    TangentialResponse out;
    out.traction = VecN::Zero(d);
    out.d_traction = Matrix::Zero(d, n_dofs);
    out.frame_traction = VecN::Zero(d);
    const double gap = master.gap - settings.gap_offset;  // the law's g_N, > 0 pressed
    const bool at_kink = settings.touching && committed.anchored && law.active();
    if ((!(result.pressure > 0.0) || !law.active()) && !at_kink) {
        out.next = open_history(committed, reference, gap);
        return out;
    }
    // A first touch measures its slide since touching from the converged positions;
    // without them, or without a converged gap, it sticks where it touches.
    const bool touching = !committed.anchored;
    if (touching && !(committed.open_gap < 0.0 && gap > 0.0 && before.slave.size() == d &&
                      before.master.rows() == n_m && before.master.cols() == d)) {
        out.status = StickSlip::stick;
        out.next = FrictionHistory{reference.point, committed.slip, true, false};
        return out;
    }
    const FootVariation v = foot_variation(N, master);
    IGA_CHECK(v.ok, "friction: the foot point is not a distance minimum (the normal kernel reports it first)");
    const double eps_T = law.tangential_penalty;
    const Trial trial = touching ? touch_trial(master, v, before, committed.open_gap, gap, eps_T)
                                 : anchored_trial(master, reference, v, committed.anchor, multiplier, eps_T, n_s);
    const Vector d_pressure = -result.slope * v.Nn;  // dp/du = p' dg_N/du

    if (at_kink) {
        // Touching at rest (KernelSettings::touching): no traction in a cone of zero size,
        // but the tangent of pressing is that of sticking, the cone's limit as p -> 0+.
        out.next = open_history(committed, reference, gap);
        if (result.tangent.size() == 0)
            return out;
        for (Index k = 0; k < n_s; ++k)
            result.tangent.middleRows(k * d, d) -= W * N(k) * trial.ds;
        if (settings.master_rows)
            for (Index b = 0; b < n_m; ++b)
                result.tangent.middleRows((n_s + b) * d, d) += W * master.R(b) * trial.ds;
        return out;
    }
    out = coulomb_return_map(law, trial.s, trial.ds, result.pressure, d_pressure, !touching && committed.slipping,
                             trial_round_off(law, std::max(reference.point.norm(), committed.anchor.norm())));
    out.next = FrictionHistory{committed.anchor, committed.slip, true, out.status == StickSlip::slip};
    // t_T pulled back to the master's reference space (F_s of it is t_T again).
    const Matrix& G = reference.tangents;
    const Matrix& a = master.tangents;
    const Eigen::LLT<Matrix> m_llt(master.metric);
    out.frame_traction = G * m_llt.solve(a.transpose() * out.traction);
    // lambda_T = F_s Lambda = a M^-1 G^T Lambda in space.
    const Eigen::LLT<Matrix> M_llt(G.transpose() * G);
    out.elastic_slip = (out.traction - a * M_llt.solve(G.transpose() * multiplier)).norm() / eps_T;
    if (out.status == StickSlip::slip || touching)  // anchor where the traction is reproduced
        out.next.anchor = reference.point + (out.frame_traction - multiplier) / eps_T;
    if (out.status == StickSlip::slip)
        out.next.slip = committed.slip + out.slip_increment;

    const VecN& t = out.traction;
    for (Index k = 0; k < n_s; ++k)
        result.residual.segment(k * d, d) -= W * N(k) * t;
    if (settings.master_rows)
        for (Index b = 0; b < n_m; ++b)
            result.residual.segment((n_s + b) * d, d) += W * master.R(b) * t;
    if (result.tangent.size() == 0)
        return out;
    for (Index k = 0; k < n_s; ++k) {
        result.tangent.middleRows(k * d, d) -= W * N(k) * out.d_traction;
        if (dW.size() > 0)
            result.tangent.block(k * d, 0, d, n_s * d) -= N(k) * t * dW.transpose();
    }
    if (settings.master_rows)
        for (Index b = 0; b < n_m; ++b) {
            // r_b = W R_b(xibar) t_T: the foot point slides under the force.
            const Vector dRb = v.D * master.dR.row(b).transpose();
            result.tangent.middleRows((n_s + b) * d, d) += W * master.R(b) * out.d_traction + W * t * dRb.transpose();
            if (dW.size() > 0)
                result.tangent.block((n_s + b) * d, 0, d, n_s * d) += master.R(b) * t * dW.transpose();
        }
    return out;
}

void add_tangential(KernelResult& result, const Vector& N, double W, const TangentialResponse& friction)
{
    if (friction.status == StickSlip::open)
        return;
    const Index d = friction.traction.size();
    IGA_CHECK(result.residual.size() == N.size() * d, "friction: the kernel result has another size");
    for (Index a = 0; a < N.size(); ++a)
        result.residual.segment(a * d, d) -= W * N(a) * friction.traction;
    if (result.tangent.size() == 0)
        return;
    for (Index a = 0; a < N.size(); ++a)
        for (Index b = 0; b < N.size(); ++b)
            result.tangent.block(a * d, b * d, d, d) -= W * N(a) * N(b) * friction.d_traction;
}

}  // namespace iga::contact
