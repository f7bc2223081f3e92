#include "contact/gpts_kernel.hpp"

#include "contact/gap.hpp"
#include "core/error.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include <optional>

namespace iga::contact {

namespace {

/// The law at the kernel's gap: p and p' of g_N - s with the point's multiplier,
/// or nullopt where the point is inactive (p = 0: nothing to assemble).
std::optional<NormalResponse> pressure_at(const KernelSettings& settings, double g_N)
{
    const double gap = g_N - settings.gap_offset;
    if (settings.touching)
        return NormalResponse{0.0, settings.law.stiffness()};
    if (!settings.law.active(gap, settings.multiplier))
        return std::nullopt;
    return settings.law.response(gap, settings.multiplier);
}

}  // namespace

KernelResult gpts_kernel(const Vector& N, double W, const MasterFoot& master, const KernelSettings& settings,
                         const Vector& dW)
{
    const Index d = master.normal.size();
    const Index q = d - 1;  // parametric dimension of the master side
    IGA_CHECK((d == 2 || d == 3) && master.tangents.rows() == d && master.tangents.cols() == q,
              "contact: GPTS kernel needs a d x (d-1) tangent basis, d = 2 or 3");
    IGA_CHECK(master.metric.rows() == q && master.metric.cols() == q && master.curvature.rows() == q &&
                  master.curvature.cols() == q,
              "contact: GPTS kernel needs (d-1) x (d-1) metric and curvature");
    IGA_CHECK(master.dR.rows() == master.R.size() && master.dR.cols() == q,
              "contact: GPTS kernel needs the master basis derivatives");
    IGA_CHECK(dW.size() == 0 || dW.size() == N.size() * d,
              "contact: the variation of the slave weight needs one entry per slave dof");
    const Vector& R = master.R;
    const Index n_s = N.size();
    const Index n_m = R.size();
    const Index n_dofs = (n_s + n_m) * d;

    KernelResult out;
    out.residual = Vector::Zero(n_dofs);
    if (settings.need_tangent)
        out.tangent = Matrix::Zero(n_dofs, n_dofs);
    const std::optional<NormalResponse> law = pressure_at(settings, master.gap);
    if (!law)
        return out;
    out.pressure = law->pressure;
    out.slope = law->slope;

    const FootVariation v = foot_variation(N, master);
    if (!v.ok) {
        out.ok = false;
        return out;
    }
    const Eigen::LLT<Matrix> m_llt(master.metric);
    const double p = out.pressure;
    const double slope = out.slope;  // dp/dg_N
    const Vector& Nn = v.Nn;
    const Matrix& T = v.T;
    const Matrix& Nd = v.Nd;
    const Matrix& D = v.D;

    const Index n_rows = settings.master_rows ? n_dofs : n_s * d;
    // r = p W dg_N/du: slave -p W N_a n, master +p W R_b n.
    out.residual.head(n_rows) = -p * W * Nn.head(n_rows);
    if (!settings.need_tangent)
        return out;

    // Variation of the normal: dn = -a_be m^be,al (Nd_al + b_al,ga D_ga) . du.
    // Second variation of g_N (docs/theory.md, "GPTS tangent"):
    //   D2g = Nd D^T + T m^-1 (Nd + D b)^T   (symmetric: equal to its transpose up to round-off)
    const Matrix T_m = m_llt.solve(T.transpose()).transpose();                      // T m^-1
    const Matrix turn = Nd + D * master.curvature;                                  // Nd + D b (b symmetric)
    out.tangent.topRows(n_rows) = slope * W * Nn.head(n_rows) * Nn.transpose();
    out.tangent.topRows(n_rows) += p * W * (Nd.topRows(n_rows) * D.transpose() + T_m.topRows(n_rows) * turn.transpose());
    // W = w_g j(u): the current area element stretches with the slave's control points.
    if (dW.size() > 0)
        out.tangent.topLeftCorner(n_rows, n_s * d) -= p * Nn.head(n_rows) * dW.transpose();
    return out;
}

FootVariation foot_variation(const Vector& N, const MasterFoot& master)
{
    const Index d = master.normal.size();
    const Index q = d - 1;
    const Vector& R = master.R;
    const Index n_s = N.size();
    const Index n_m = R.size();
    const Index n_dofs = (n_s + n_m) * d;
    FootVariation v;
    // A = m + g_N b: the Hessian of the distance at the foot point; positive
    // definite at a distance minimum (else the projection is not one).
    const Matrix A = master.metric + master.gap * master.curvature;
    const Eigen::LLT<Matrix> A_llt(A);
    const Eigen::LLT<Matrix> m_llt(master.metric);
    if (A_llt.info() != Eigen::Success || m_llt.info() != Eigen::Success ||
        !(A.determinant() > 0.0 && master.metric.determinant() > 0.0)) {
        v.ok = false;
        return v;
    }
    const VecN& n = master.normal;
    // Vectors over the dofs [slave cps ; master cps] (a column each):
    //   Nn:      N_a n ; -R_b n            (dg_N/du = -Nn)
    //   T_al:    N_a a_al ; -R_b a_al      (T_al . du = (du_s - du_m) . a_al)
    //   Nd_al:   0 ; R_b,al n              (Nd_al . du = n . du_m,al)
    v.Nn.resize(n_dofs);
    v.T = Matrix::Zero(n_dofs, q);
    v.Nd = Matrix::Zero(n_dofs, q);
    for (Index a = 0; a < n_s; ++a) {
        v.Nn.segment(a * d, d) = N(a) * n;
        for (Index al = 0; al < q; ++al)
            v.T.col(al).segment(a * d, d) = N(a) * master.tangents.col(al);
    }
    for (Index b = 0; b < n_m; ++b) {
        const Index k = (n_s + b) * d;
        v.Nn.segment(k, d) = -R(b) * n;
        for (Index al = 0; al < q; ++al) {
            v.T.col(al).segment(k, d) = -R(b) * master.tangents.col(al);
            v.Nd.col(al).segment(k, d) = master.dR(b, al) * n;
        }
    }
    // Variation of the foot point: A dxi = T^T du - g_N Nd^T du, so dxi = D^T du with
    // D = (T - g_N Nd) A^-1.
    v.D = A_llt.solve((v.T - master.gap * v.Nd).transpose()).transpose();  // n_dofs x q
    return v;
}

MasterFoot master_foot(const Projection& projection)
{
    MasterFoot foot;
    foot.normal = projection.normal;
    foot.tangents = projection.tangents;
    foot.metric = projection.metric;
    foot.curvature = projection.curvature;
    foot.gap = projection.gap;
    foot.R = projection.basis.R;
    foot.dR = projection.basis.dR;
    foot.second = projection.second;
    return foot;
}

KernelResult gpts_kernel(const Vector& N, double W, const Projection& master, const KernelSettings& settings,
                         const Vector& dW)
{
    IGA_CHECK(master.basis.dR.cols() >= 1, "contact: GPTS kernel needs the master basis derivatives");
    return gpts_kernel(N, W, master_foot(master), settings, dW);
}

KernelResult gpts_rigid_kernel(const Vector& N, double W, const VecN& normal, double gap,
                               const KernelSettings& settings, double normal_radius)
{
    const Index d = normal.size();
    IGA_CHECK(d == 2 || d == 3, "contact: rigid obstacle normal needs 2 or 3 components");
    const Index n_dofs = N.size() * d;
    KernelResult out;
    out.residual = Vector::Zero(n_dofs);
    if (settings.need_tangent)
        out.tangent = Matrix::Zero(n_dofs, n_dofs);
    const std::optional<NormalResponse> law = pressure_at(settings, gap);
    if (!law)
        return out;
    out.pressure = law->pressure;
    out.slope = law->slope;
    Vector Nn(n_dofs);
    for (Index a = 0; a < N.size(); ++a)
        Nn.segment(a * d, d) = N(a) * normal;
    out.residual = -out.pressure * W * Nn;
    if (!settings.need_tangent)
        return out;
    out.tangent = out.slope * W * Nn * Nn.transpose();
    if (std::isfinite(normal_radius)) {
        // r_a = -p W N_a n(x): the normal turns with x, dn/dx = (I - n n) / normal_radius.
        const Matrix turning = (out.pressure * W / normal_radius) *
                               (Matrix::Identity(d, d) - normal * normal.transpose());
        for (Index a = 0; a < N.size(); ++a)
            for (Index b = 0; b < N.size(); ++b)
                out.tangent.block(a * d, b * d, d, d) -= N(a) * N(b) * turning;
    }
    return out;
}

}  // namespace iga::contact
