#include "analysis/contact_penalty.hpp"

#include "boundary/patch_side.hpp"
#include "core/error.hpp"
#include "quadrature/gauss.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace iga::analysis {

double contact_modulus(const mechanics::Material& material)
{
    return material.plane == mechanics::PlaneMode::stress ? material.E
                                                          : material.E / (1.0 - material.nu * material.nu);
}

namespace {

/// The reference measure of every element of a side patch (length in 2D, area in 3D).
std::vector<double> element_measures(const nurbs::Patch& side)
{
    const int q = side.n_par();
    IGA_CHECK(q == 1 || q == 2, "contact: a side has 1 (2D) or 2 (3D) parameters");
    int max_degree = 0;
    for (int k = 0; k < q; ++k)
        max_degree = std::max(max_degree, side.degree(k));
    std::vector<double> measures;
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
        measures.push_back(measure);
    }
    return measures;
}

/// The reference measure of the whole side patch.
double side_measure(const nurbs::Patch& side)
{
    const std::vector<double> measures = element_measures(side);
    return std::accumulate(measures.begin(), measures.end(), 0.0);
}

/// A measure as a length: itself in 2D (q = 1), its square root in 3D.
double as_length(double measure, int q) { return q == 1 ? measure : std::sqrt(measure); }

}  // namespace

double smallest_element_size(const nurbs::Patch& side)
{
    double smallest = std::numeric_limits<double>::infinity();
    for (double measure : element_measures(side))
        if (measure > 0.0)  // a collapsed element (a pole) says nothing about the mesh size
            smallest = std::min(smallest, as_length(measure, side.n_par()));
    return smallest;
}

double side_size(const nurbs::Patch& side) { return as_length(side_measure(side), side.n_par()); }

AutoPenalty auto_penalty(const std::vector<const contact::DeformableSide*>& sides,
                         const std::vector<const mechanics::Material*>& materials)
{
    IGA_CHECK(!sides.empty() && sides.size() == materials.size(),
              "auto penalty: one material per deformable side, at least one side");
    AutoPenalty out;
    out.modulus = std::numeric_limits<double>::infinity();
    out.element_size = std::numeric_limits<double>::infinity();
    out.side_size = std::numeric_limits<double>::infinity();
    double compliance = 0.0;  // 1/E* = sum of 1/E' over the deformable sides
    for (std::size_t k = 0; k < sides.size(); ++k) {
        const double modulus = contact_modulus(*materials[k]);
        out.modulus = std::min(out.modulus, modulus);
        compliance += 1.0 / modulus;
        double measure = 0.0;  // of the whole surface, every patch side of a named surface
        for (const contact::SidePiece& piece : sides[k]->pieces) {
            out.element_size = std::min(out.element_size, smallest_element_size(piece.side.patch));
            measure += side_measure(piece.side.patch);
        }
        out.side_size = std::min(out.side_size, as_length(measure, sides[k]->pieces.front().side.patch.n_par()));
    }
    IGA_CHECK(std::isfinite(out.element_size) && out.element_size > 0.0,
              "auto penalty: the contact sides have no element of positive size");
    out.hertz_modulus = 1.0 / compliance;
    const double accuracy = auto_penalty_kappa_side * out.hertz_modulus / out.side_size;
    const double cap = auto_penalty_cap * out.modulus / out.element_size;
    out.capped = cap < accuracy;
    out.penalty = std::min(accuracy, cap);
    return out;
}

std::string describe(const AutoPenalty& rule)
{
    if (rule.capped)
        return fmt::format("{:.4g} = {:g} E'/h (the conditioning cap) with E' = {:.4g} (softer body), h = {:.4g} "
                           "(smallest contact-side element)",
                           rule.penalty, auto_penalty_cap, rule.modulus, rule.element_size);
    return fmt::format("{:.4g} = {:g} E*/l with E* = {:.4g} (the pair's Hertz modulus), l = {:.4g} (smallest "
                       "contact side); below the cap {:g} E'/h = {:.4g}",
                       rule.penalty, auto_penalty_kappa_side, rule.hertz_modulus, rule.side_size, auto_penalty_cap,
                       auto_penalty_cap * rule.modulus / rule.element_size);
}

}  // namespace iga::analysis
