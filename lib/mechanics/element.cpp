#include "mechanics/element.hpp"

#include "core/error.hpp"

#include <Eigen/LU>

#include <limits>

namespace iga::mechanics {

namespace {

ElementResponse failed(int n_dofs, ResponseStatus status, int point, double det_F)
{
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    return {Vector::Constant(n_dofs, nan), Matrix::Constant(n_dofs, n_dofs, nan), Vector::Constant(n_dofs, nan), nan,
            status, point, det_F};
}

/// B_F (n_voigt x n_local*d): Voigt variation of the strain per local dof, for a
/// deformation gradient F (F = I gives the small-strain B).
Matrix strain_displacement(const Matrix& dR_dX, const MatN& F)
{
    const int d = static_cast<int>(F.rows());
    const int n_local = static_cast<int>(dR_dX.rows());
    const int nv = n_voigt(d);
    Matrix B(nv, n_local * d);
    for (int a = 0; a < n_local; ++a)
        for (int i = 0; i < d; ++i)
            for (int I = 0; I < nv; ++I) {
                const auto [J, L] = voigt_pair(d, I);
                B(I, a * d + i) = J == L ? F(i, J) * dR_dX(a, J)
                                         : F(i, J) * dR_dX(a, L) + F(i, L) * dR_dX(a, J);
            }
    return B;
}

}  // namespace

VecN point_displacement(const QuadraturePoint& point, const Matrix& u_local)
{
    return u_local.transpose() * point.R;  // u_i = sum_a R_a u_ai
}

MatN displacement_gradient(const QuadraturePoint& point, const Matrix& u_local)
{
    return u_local.transpose() * point.dR_dX;  // (grad u)_iJ = sum_a u_ai dR_a/dX_J
}

ElementResponse element_response(const ElementGeometry& geometry, const Material& material, Kinematics kinematics,
                                 const Matrix& u_local, bool need_tangent)
{
    const int d = geometry.dim;
    const int n_local = geometry.n_local();
    const int n_dofs = n_local * d;
    IGA_CHECK(spatial_dim(material.plane) == d, "material plane mode does not match the element dimension");
    IGA_CHECK(u_local.rows() == n_local && u_local.cols() == d, "u_local must be n_local x d");

    ElementResponse out{Vector::Zero(n_dofs), need_tangent ? Matrix::Zero(n_dofs, n_dofs) : Matrix(),
                        Vector::Zero(n_dofs), 0.0, ResponseStatus::ok};
    const bool finite = kinematics == Kinematics::finite;
    const MatN identity = MatN::Identity(d, d);
    const Matrix u_size = u_local.cwiseAbs();  // |u_e|, n_local x d
    const Vector u_size_flat = u_size.transpose().reshaped();  // local dof a*d + i

    for (std::size_t g = 0; g < geometry.points.size(); ++g) {
        const QuadraturePoint& q = geometry.points[g];
        const MatN H = displacement_gradient(q, u_local);
        const MatN F = finite ? MatN(identity + H) : identity;
        const double det_F = F.determinant();
        if (finite && !(det_F > 0.0))
            return failed(n_dofs, ResponseStatus::inverted, static_cast<int>(g), det_F);
        const MatN strain = finite ? MatN(0.5 * (F.transpose() * F - identity)) : MatN(0.5 * (H + H.transpose()));
        const StressResponse s = stress_response(material, kinematics, strain);
        if (s.status != ResponseStatus::ok)
            return failed(n_dofs, s.status, static_cast<int>(g), det_F);

        const Matrix B = strain_displacement(q.dR_dX, F);
        out.f_int.noalias() += q.weight * (B.transpose() * stress_to_voigt(s.stress));
        out.energy += q.weight * s.energy;
        const Matrix B_size = B.cwiseAbs();
        out.cancellation.noalias() +=
            q.weight * (B_size.transpose() * (s.tangent.cwiseAbs() * (B_size * u_size_flat)));
        if (need_tangent)
            out.K.noalias() += q.weight * (B.transpose() * s.tangent * B);
        if (finite) {
            // Geometric stiffness: (dR_a . S dR_b) on every diagonal component i = k.
            const Matrix dR_size = q.dR_dX.cwiseAbs();  // n_local x d
            const Matrix geometric = dR_size * (s.stress.cwiseAbs() * (dR_size.transpose() * u_size));
            out.cancellation.noalias() += q.weight * geometric.transpose().reshaped();
            if (!need_tangent)
                continue;
            const Matrix G = q.dR_dX * s.stress * q.dR_dX.transpose();  // n_local x n_local
            for (int a = 0; a < n_local; ++a)
                for (int b = 0; b < n_local; ++b)
                    for (int i = 0; i < d; ++i)
                        out.K(a * d + i, b * d + i) += q.weight * G(a, b);
        }
    }
    return out;
}

}  // namespace iga::mechanics
