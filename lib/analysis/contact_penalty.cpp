#include "analysis/contact_penalty.hpp"

#include "boundary/patch_side.hpp"
#include "core/error.hpp"
#include "quadrature/gauss.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace iga::analysis {

double contact_modulus(const mechanics::Material& material)
{
    return material.plane == mechanics::PlaneMode::stress ? material.E
                                                          : material.E / (1.0 - material.nu * material.nu);
}

double smallest_element_size(const nurbs::Patch& side)
{
    const int q = side.n_par();
    IGA_CHECK(q == 1 || q == 2, "contact: a side has 1 (2D) or 2 (3D) parameters");
    int max_degree = 0;
    for (int k = 0; k < q; ++k)
        max_degree = std::max(max_degree, side.degree(k));
    double smallest = std::numeric_limits<double>::infinity();
    for (const nurbs::Element& element : side.elements()) {
        // Exact for polynomial sides; a NURBS side's measure to many digits.
        const quadrature::TensorRule rule = quadrature::element_rule(side, element, max_degree + 2);
        double measure = 0.0;
        for (Index g = 0; g < rule.weights.size(); ++g) {
            const VecN xi = rule.points.row(g).transpose();
            const nurbs::PointDerivatives X = nurbs::combine(nurbs::rational_basis(side, element.span, xi, 1),
                                                             side.control_points());
            measure += rule.weights(g) * boundary::raw_normal(X.dx).norm();
        }
        const double size = q == 1 ? measure : std::sqrt(measure);
        if (size > 0.0)  // a collapsed element (a pole) says nothing about the mesh size
            smallest = std::min(smallest, size);
    }
    return smallest;
}

AutoPenalty auto_penalty(const std::vector<const contact::DeformableSide*>& sides,
                         const std::vector<const mechanics::Material*>& materials)
{
    IGA_CHECK(!sides.empty() && sides.size() == materials.size(),
              "auto penalty: one material per deformable side, at least one side");
    AutoPenalty out;
    out.modulus = std::numeric_limits<double>::infinity();
    out.element_size = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < sides.size(); ++k) {
        out.modulus = std::min(out.modulus, contact_modulus(*materials[k]));
        for (const contact::SidePiece& piece : sides[k]->pieces)  // every patch side of a named surface
            out.element_size = std::min(out.element_size, smallest_element_size(piece.side.patch));
    }
    IGA_CHECK(std::isfinite(out.element_size) && out.element_size > 0.0,
              "auto penalty: the contact sides have no element of positive size");
    out.penalty = auto_penalty_factor * out.modulus / out.element_size;
    return out;
}

}  // namespace iga::analysis
