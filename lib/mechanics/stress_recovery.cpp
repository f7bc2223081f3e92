#include "mechanics/stress_recovery.hpp"

#include "core/error.hpp"

#include <Eigen/LU>
#include "mechanics/element_geometry.hpp"

#include <cmath>
#include <limits>

namespace iga::mechanics {

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
        const StressResponse s = small_strain_response(material, MatN(0.5 * (H + H.transpose())));
        out.cauchy = s.stress;
        out.status = s.status;
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
    return out;
}

}  // namespace iga::mechanics
