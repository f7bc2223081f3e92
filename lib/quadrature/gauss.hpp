#pragma once
// Gauss-Legendre quadrature on [0, 1] and tensor rules on knot spans.
//
// An n-point rule integrates polynomials of degree 2n - 1 exactly. Points are
// computed by Newton on the Legendre polynomial (Golub-Welsch accuracy, ~1e-15).

#include "core/types.hpp"
#include "nurbs/patch.hpp"

#include <vector>

namespace iga::quadrature {

/// n points and weights on [0, 1], points increasing, weights summing to 1.
struct Rule1D {
    std::vector<double> points;
    std::vector<double> weights;
};
Rule1D gauss_legendre(int n);

/// Tensor rule on one element of a patch: points in parameter space
/// (n_points x n_par, u fastest) and weights including the parametric span
/// lengths (so sum of weights = parametric volume of the element).
struct TensorRule {
    Matrix points;
    Vector weights;
};
TensorRule element_rule(const nurbs::Patch& patch, const nurbs::Element& element, int n_per_direction);

}  // namespace iga::quadrature
