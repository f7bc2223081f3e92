#include "mechanics/element_geometry.hpp"
#include "core/text.hpp"

#include "quadrature/gauss.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace iga::mechanics {

namespace {

std::string jacobian_message(const VecN& xi, const VecN& X, double det_J)
{
    std::ostringstream out;
    out << "non-positive Jacobian det(dX/dxi) = " << det_J << " at parameter " << point_text(xi) << ", point "
        << point_text(X)
        << ": the patch is inverted or degenerate there, or its parametrization is left-handed (reverse the "
           "control-point order of one direction)";
    return out.str();
}

}  // namespace

NonPositiveJacobian::NonPositiveJacobian(const VecN& xi, const VecN& X, double det_J)
    : Error(jacobian_message(xi, X, det_J)), xi_(xi), X_(X), det_J_(det_J)
{
}

ReferenceGradient reference_gradient(const nurbs::Patch& patch, const nurbs::BasisValues& basis)
{
    const int d = patch.dim();
    IGA_ASSERT(patch.n_par() == d, "reference_gradient needs a solid patch (n_par == d)");
    IGA_ASSERT(basis.dR.cols() == d, "reference_gradient needs first derivatives of the basis");
    const nurbs::PointDerivatives p = nurbs::combine(basis, patch.control_points());
    const MatN J = p.dx;  // d x d, J_ij = dX_i / dxi_j
    ReferenceGradient out;
    out.X = p.x;
    out.det_J = J.determinant();
    // dR/dX_j = sum_k dR/dxi_k (J^-1)_kj; J is inverted only when it is regular.
    out.dR_dX = out.det_J != 0.0 ? Matrix(basis.dR * J.inverse()) : Matrix::Constant(basis.dR.rows(), d, 0.0);
    return out;
}

int default_gauss_points(const nurbs::Patch& patch)
{
    int p = 0;
    for (int dir = 0; dir < patch.n_par(); ++dir)
        p = std::max(p, patch.degree(dir));
    return p + 1;
}

ElementGeometry element_geometry(const nurbs::Patch& patch, const nurbs::Element& element, int n_per_direction)
{
    const int d = patch.dim();
    IGA_CHECK(patch.n_par() == d && (d == 2 || d == 3),
              "element_geometry needs a solid patch: 2 parametric directions in 2D, 3 in 3D");
    const int n = n_per_direction > 0 ? n_per_direction : default_gauss_points(patch);
    const quadrature::TensorRule rule = quadrature::element_rule(patch, element, n);

    ElementGeometry g;
    g.dim = d;
    g.points.reserve(static_cast<std::size_t>(rule.weights.size()));
    for (Index q = 0; q < rule.weights.size(); ++q) {
        const VecN xi = rule.points.row(q).transpose();
        const nurbs::BasisValues basis = nurbs::rational_basis(patch, element.span, xi, 1);
        if (g.indices.empty())
            g.indices = basis.indices;
        IGA_ASSERT(basis.indices == g.indices, "basis indices change within an element");
        ReferenceGradient ref = reference_gradient(patch, basis);
        if (!(ref.det_J > 0.0) || !std::isfinite(ref.det_J))
            throw NonPositiveJacobian(xi, ref.X, ref.det_J);
        g.points.push_back({xi, ref.X, basis.R, std::move(ref.dR_dX), rule.weights(q) * ref.det_J});
    }
    return g;
}

std::vector<ElementGeometry> patch_geometry(const nurbs::Patch& patch, int n_per_direction)
{
    std::vector<ElementGeometry> out;
    for (const nurbs::Element& e : patch.elements())
        out.push_back(element_geometry(patch, e, n_per_direction));
    return out;
}

}  // namespace iga::mechanics
