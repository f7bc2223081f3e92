#include "contact/gpts_kernel.hpp"

#include "contact/gap.hpp"
#include "core/error.hpp"

namespace iga::contact {

KernelResult gpts_kernel(const Vector& N, double W, const Projection& master, const KernelSettings& settings)
{
    constexpr int d = 2;
    IGA_CHECK(master.normal.size() == d && master.tangents.rows() == d && master.tangents.cols() == 1,
              "contact: GPTS kernel is 2D only");
    IGA_CHECK(master.basis.dR.cols() >= 1, "contact: GPTS kernel needs the master basis derivatives");
    const Vector& R = master.basis.R;
    const Vector dR = master.basis.dR.col(0);
    const Index n_s = N.size();
    const Index n_m = R.size();
    const Index n_dofs = (n_s + n_m) * d;

    KernelResult out;
    out.residual = Vector::Zero(n_dofs);
    if (settings.need_tangent)
        out.tangent = Matrix::Zero(n_dofs, n_dofs);
    const double g_N = master.gap;
    out.pressure = settings.penalty * macaulay(g_N);
    if (heaviside(g_N) == 0.0)
        return out;

    const VecN& n = master.normal;
    const VecN tau = master.tangents.col(0);
    const double m = master.metric(0, 0);
    const double b = master.curvature(0, 0);
    const double c = m + g_N * b;
    if (!(c > 0.0) || !(m > 0.0)) {
        out.ok = false;
        return out;
    }
    const double p = out.pressure;
    const double eps = settings.penalty;

    // Nn, T, D and the row vectors (N_a tau / m ; R_b' n ; R_b tau / m) over all dofs.
    Vector Nn(n_dofs), T(n_dofs), D = Vector::Zero(n_dofs);
    Vector tau_rows = Vector::Zero(n_dofs), dRn_rows = Vector::Zero(n_dofs);
    for (Index a = 0; a < n_s; ++a)
        for (int i = 0; i < d; ++i) {
            Nn(a * d + i) = N(a) * n(i);
            T(a * d + i) = N(a) * tau(i);
            tau_rows(a * d + i) = N(a) * tau(i) / m;
        }
    for (Index bb = 0; bb < n_m; ++bb)
        for (int i = 0; i < d; ++i) {
            const Index k = (n_s + bb) * d + i;
            Nn(k) = -R(bb) * n(i);
            T(k) = -R(bb) * tau(i) - g_N * dR(bb) * n(i);
            D(k) = dR(bb) * n(i);
            dRn_rows(k) = dR(bb) * n(i);
            tau_rows(k) = -R(bb) * tau(i) / m;  // sign of the master row term -(R_b tau / m) (x) D
        }
    D += (b / c) * T;

    const Index n_rows = settings.master_rows ? n_dofs : n_s * d;
    // r = -p W Nn: slave -p W N_a n, master +p W R_b n.
    out.residual.head(n_rows) = -p * W * Nn.head(n_rows);
    if (!settings.need_tangent)
        return out;

    // eps H W Nn (x) Nn covers K_a's first term and K_b's -eps H W (R_b n) (x) Nn.
    out.tangent.topRows(n_rows) = eps * W * Nn.head(n_rows) * Nn.transpose();
    // p W (N_a tau / m) (x) D on slave rows, -p W (R_b tau / m) (x) D on master rows.
    out.tangent.topRows(n_rows) += p * W * tau_rows.head(n_rows) * D.transpose();
    if (settings.master_rows)
        out.tangent.bottomRows(n_m * d) += (p * W / c) * dRn_rows.tail(n_m * d) * T.transpose();
    return out;
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
    out.pressure = settings.penalty * macaulay(gap);
    if (heaviside(gap) == 0.0)
        return out;
    Vector Nn(n_dofs);
    for (Index a = 0; a < N.size(); ++a)
        Nn.segment(a * d, d) = N(a) * normal;
    out.residual = -out.pressure * W * Nn;
    if (!settings.need_tangent)
        return out;
    out.tangent = settings.penalty * W * Nn * Nn.transpose();
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
