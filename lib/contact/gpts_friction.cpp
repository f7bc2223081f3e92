#include "contact/gpts_friction.hpp"

#include "core/error.hpp"

#include <Eigen/Cholesky>

namespace iga::contact {
namespace {

/// Column of x,ab in second derivatives packed like BasisValues::d2R.
Index packed(Index a, Index b, Index q)
{
    return nurbs::second_column(static_cast<int>(q), static_cast<int>(a), static_cast<int>(b));
}

}  // namespace

FrictionHistory open_history(const FrictionHistory& committed, const MasterReference& reference)
{
    // Not anchored: where an open point will touch is not the foot it has now (on a
    // curved master the closest point moves as the gap closes), so it sticks where it
    // touches, at the end of the increment in which it first presses.
    return FrictionHistory{reference.point, committed.slip, false, false};
}

TangentialResponse gpts_friction(KernelResult& result, const Vector& N, double W, const MasterFoot& master,
                                 const MasterReference& reference, const FrictionLaw& law,
                                 const FrictionHistory& committed, const VecN& multiplier,
                                 const KernelSettings& settings, const Vector& dW)
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
    if (!(result.pressure > 0.0) || !law.active()) {
        out.next = open_history(committed, reference);
        return out;
    }
    if (!committed.anchored) {  // first touch: it sticks where it touches
        out.status = StickSlip::stick;
        out.next = FrictionHistory{reference.point, committed.slip, true, false};
        return out;
    }
    const FootVariation v = foot_variation(N, master);
    IGA_CHECK(v.ok, "friction: the foot point is not a distance minimum (the normal kernel reports it first)");

    // c = M^-1 G^T (A + Lambda / eps_T - Xbar): the anchor's offset in the foot's
    // reference tangent frame, shifted by the multiplier.
    const double eps_T = law.tangential_penalty;
    const Matrix& G = reference.tangents;
    const Matrix& a = master.tangents;
    const Matrix M = G.transpose() * G;
    const Eigen::LLT<Matrix> M_llt(M);
    const VecN offset = committed.anchor - reference.point + multiplier / eps_T;
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
    Matrix d_trial = eps_T * (Xc + a * C) * v.D.transpose();
    for (Index b = 0; b < n_m; ++b)
        d_trial.block(0, (n_s + b) * d, d, d).diagonal().array() += eps_T * master.dR.row(b).dot(c);
    const Vector d_pressure = -result.slope * v.Nn;  // dp/du = p' dg_N/du

    out = coulomb_return_map(law, eps_T * a * c, d_trial, result.pressure, d_pressure, committed.slipping);
    out.next = committed;
    out.next.slipping = out.status == StickSlip::slip;
    // t_T pulled back to the master's reference space (F_s of it is t_T again).
    const Eigen::LLT<Matrix> m_llt(master.metric);
    out.frame_traction = G * m_llt.solve(a.transpose() * out.traction);
    // lambda_T = F_s Lambda = a M^-1 G^T Lambda in space.
    out.elastic_slip = (out.traction - a * M_llt.solve(G.transpose() * multiplier)).norm() / eps_T;
    if (out.status == StickSlip::slip) {  // move the anchor to reproduce the traction
        out.next.anchor = reference.point + (out.frame_traction - multiplier) / eps_T;
        out.next.slip = committed.slip + out.slip_increment;
    }

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
