#include "boundary/gauss_points.hpp"

#include "quadrature/gauss.hpp"

#include <algorithm>

namespace iga::boundary {

std::vector<GaussPoint> gauss_points(const PatchSide& side, int n_per_direction)
{
    const nurbs::Patch& patch = side.patch();
    int n = n_per_direction;
    if (n <= 0) {
        int p = 0;
        for (int dir = 0; dir < patch.n_par(); ++dir)
            p = std::max(p, patch.degree(dir));
        n = p + 1;
    }
    std::vector<GaussPoint> out;
    for (int e = 0; e < side.n_elements(); ++e) {
        const quadrature::TensorRule rule = quadrature::element_rule(patch, side.elements()[e], n);
        for (Index q = 0; q < rule.weights.size(); ++q) {
            GaussPoint gp;
            gp.element = e;
            gp.xi = rule.points.row(q).transpose();
            nurbs::BasisValues basis;
            gp.reference = side.evaluate(patch.control_points(), e, gp.xi, 1, &basis);
            gp.parametric_weight = rule.weights(q);
            gp.weight = gp.parametric_weight * gp.reference.jacobian;
            gp.indices = std::move(basis.indices);
            gp.N = std::move(basis.R);
            gp.dN = std::move(basis.dR);
            out.push_back(std::move(gp));
        }
    }
    return out;
}

double reference_measure(const std::vector<GaussPoint>& points)
{
    double total = 0.0;
    for (const GaussPoint& gp : points)
        total += gp.weight;
    return total;
}

double reference_measure(const PatchSide& side, int n_per_direction)
{
    return reference_measure(gauss_points(side, n_per_direction));
}

}  // namespace iga::boundary
