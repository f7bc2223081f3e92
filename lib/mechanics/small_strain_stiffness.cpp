#include "mechanics/small_strain_stiffness.hpp"

#include "core/error.hpp"
#include "mechanics/voigt.hpp"

#include <array>

namespace iga::mechanics {

namespace {

/// Voigt index of the tensor pair (i, j) (either order).
int voigt_index(int dim, int i, int j)
{
    for (int I = 0; I < n_voigt(dim); ++I) {
        const auto [p, q] = voigt_pair(dim, I);
        if ((p == i && q == j) || (p == j && q == i))
            return I;
    }
    IGA_CHECK(false, "voigt_index: no such pair");
    return -1;
}

}  // namespace

Matrix small_strain_stiffness(const ElementGeometry& geometry, const Material& material)
{
    const int d = geometry.dim;
    const int n = geometry.n_local();
    const int n_points = static_cast<int>(geometry.points.size());
    const int n_dofs = n * d;
    IGA_CHECK(spatial_dim(material.plane) == d, "material plane mode does not match the element dimension");
    // Hooke's law: the tangent does not depend on the strain.
    const VoigtMatrix D = small_strain_response(material, MatN::Zero(d, d)).tangent;

    // Gradients of all points side by side (n x n_points per direction J), and weighted.
    std::array<Matrix, 3> gradient, weighted;
    for (int J = 0; J < d; ++J) {
        gradient[J].resize(n, n_points);
        for (int g = 0; g < n_points; ++g)
            gradient[J].col(g) = geometry.points[static_cast<std::size_t>(g)].dR_dX.col(J);
        weighted[J] = gradient[J];
        for (int g = 0; g < n_points; ++g)
            weighted[J].col(g) *= geometry.points[static_cast<std::size_t>(g)].weight;
    }
    std::array<std::array<Matrix, 3>, 3> moment;  // A^JL
    for (int J = 0; J < d; ++J)
        for (int L = J; L < d; ++L) {
            moment[J][L].noalias() = weighted[J] * gradient[L].transpose();
            if (L != J)
                moment[L][J] = moment[J][L].transpose();
        }

    // K's (i, k) component block, rows a*d + i and columns b*d + k, seen as n x n.
    using Strided = Eigen::Map<Matrix, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>;
    Matrix K = Matrix::Zero(n_dofs, n_dofs);
    for (int i = 0; i < d; ++i)
        for (int k = 0; k < d; ++k) {
            Strided block(K.data() + i + static_cast<Index>(k) * n_dofs, n, n,
                          Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(static_cast<Index>(d) * n_dofs, d));
            for (int J = 0; J < d; ++J)
                for (int L = 0; L < d; ++L) {
                    const double c = D(voigt_index(d, i, J), voigt_index(d, k, L));
                    if (c != 0.0)
                        block += c * moment[J][L];
                }
        }
    return K;
}

}  // namespace iga::mechanics
