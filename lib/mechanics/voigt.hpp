#pragma once
// Voigt notation for symmetric d x d tensors (d = 2 or 3).
//
// Component order: d = 2: (11, 22, 12); d = 3: (11, 22, 33, 23, 13, 12), so
// n_voigt = d (d + 1) / 2 = 3 or 6. Strains use engineering shear (the shear
// entry is 2 E_12 = gamma_12), stresses the tensor component (S_12), so that
// S : dE = S_voigt . dE_voigt and a 4th-order tangent C_ijkl with minor
// symmetries becomes the matrix D_IJ = C_ijkl with I = (ij), J = (kl):
// dS_voigt = D dE_voigt.

#include "core/types.hpp"

#include <array>
#include <utility>

namespace iga::mechanics {

/// Voigt vectors and matrices: at most 6 entries / 6 x 6 (stack storage).
using VoigtVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;
using VoigtMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;

constexpr int n_voigt(int dim) { return dim * (dim + 1) / 2; }

/// Tensor indices (i, j), i <= j, of Voigt component I for dimension dim.
constexpr std::pair<int, int> voigt_pair(int dim, int I)
{
    constexpr std::array<std::pair<int, int>, 3> pairs_2d{{{0, 0}, {1, 1}, {0, 1}}};
    constexpr std::array<std::pair<int, int>, 6> pairs_3d{{{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}}};
    return dim == 2 ? pairs_2d[I] : pairs_3d[I];
}

/// Symmetric stress tensor -> Voigt (tensor shear components).
inline VoigtVector stress_to_voigt(const MatN& s)
{
    const int d = static_cast<int>(s.rows());
    VoigtVector v(n_voigt(d));
    for (int I = 0; I < n_voigt(d); ++I) {
        const auto [i, j] = voigt_pair(d, I);
        v(I) = s(i, j);
    }
    return v;
}

/// Symmetric strain tensor -> Voigt (engineering shear: 2 E_ij off the diagonal).
inline VoigtVector strain_to_voigt(const MatN& e)
{
    const int d = static_cast<int>(e.rows());
    VoigtVector v(n_voigt(d));
    for (int I = 0; I < n_voigt(d); ++I) {
        const auto [i, j] = voigt_pair(d, I);
        v(I) = i == j ? e(i, j) : 2.0 * e(i, j);
    }
    return v;
}

/// Voigt strain (engineering shear) -> symmetric tensor.
inline MatN strain_from_voigt(const VoigtVector& v, int dim)
{
    MatN e(dim, dim);
    for (int I = 0; I < n_voigt(dim); ++I) {
        const auto [i, j] = voigt_pair(dim, I);
        const double value = i == j ? v(I) : 0.5 * v(I);
        e(i, j) = value;
        e(j, i) = value;
    }
    return e;
}

}  // namespace iga::mechanics
