#include "mechanics/stress_recovery.hpp"

#include "core/error.hpp"

#include <Eigen/LU>
#include "mechanics/element_geometry.hpp"

#include <cmath>
#include <limits>

namespace iga::mechanics {

namespace {

/// The 3D law of a plane-strain material, for its out-of-plane stress.
Material three_dimensional(Material material)
{
    material.plane = PlaneMode::none;
    return material;
}

/// d x d -> 3 x 3 with zero third row and column.
MatN padded(const MatN& a)
{
    MatN out = MatN::Zero(3, 3);
    out.topLeftCorner(a.rows(), a.cols()) = a;
    return out;
}

}  // namespace

PointStress cauchy_stress(const nurbs::Patch& patch, const Material& material, Kinematics kinematics,
                          const RowMatrix& displacement, const VecN& xi)
{
    const int d = patch.dim();
    IGA_CHECK(patch.n_par() == d, "cauchy_stress needs a solid patch (n_par == d)");
    IGA_CHECK(spatial_dim(material.plane) == d, "material plane mode does not match the patch dimension");
    IGA_CHECK(displacement.rows() == patch.n_control_points() && displacement.cols() == d,
              "displacement must be n_cp x d");

    const nurbs::BasisValues basis = nurbs::rational_basis(patch, xi, 1);
    const ReferenceGradient ref = reference_gradient(patch, basis);
    if (!(ref.det_J > 0.0) || !std::isfinite(ref.det_J))
        throw NonPositiveJacobian(xi, ref.X, ref.det_J);

    const int n_local = static_cast<int>(basis.indices.size());
    Matrix u_local(n_local, d);
    for (int a = 0; a < n_local; ++a)
        u_local.row(a) = displacement.row(basis.indices[a]);
    const MatN H = u_local.transpose() * ref.dR_dX;

    PointStress out;
    out.X = ref.X;
    out.x = ref.X + VecN(u_local.transpose() * basis.R);
    const MatN identity = MatN::Identity(d, d);
    if (kinematics == Kinematics::small) {
        const MatN eps = 0.5 * (H + H.transpose());
        const StressResponse s = small_strain_response(material, eps);
        out.cauchy = s.stress;
        out.status = s.status;
        if (d == 3)
            out.cauchy33 = s.stress(2, 2);
        else if (material.plane == PlaneMode::strain)
            out.cauchy33 = small_strain_response(three_dimensional(material), padded(eps)).stress(2, 2);
        return out;
    }
    const MatN F = identity + H;
    const double det_F = F.determinant();
    if (!(det_F > 0.0)) {
        out.cauchy = MatN::Constant(d, d, std::numeric_limits<double>::quiet_NaN());
        out.status = ResponseStatus::inverted;
        return out;
    }
    const StressResponse s = finite_strain_response(material, MatN(0.5 * (F.transpose() * F - identity)));
    const double J = material.plane == PlaneMode::stress ? det_F * std::sqrt(1.0 + 2.0 * s.strain33) : det_F;
    out.cauchy = F * s.stress * F.transpose() / J;
    out.status = s.status;
    if (d == 3)
        out.cauchy33 = out.cauchy(2, 2);
    else if (material.plane == PlaneMode::strain)  // F33 = 1: sigma33 = S33 / J
        out.cauchy33 = finite_strain_response(three_dimensional(material), padded(MatN(0.5 * (F.transpose() * F - identity))))
                           .stress(2, 2) / J;
    return out;
}

}  // namespace iga::mechanics
