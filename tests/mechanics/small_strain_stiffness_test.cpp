// The moment form of the small-strain element stiffness equals B^T D B summed over
// the Gauss points (element_response), on curved rational elements of degree 1 to 3,
// in plane strain, plane stress and 3D.

#include "mechanics/element.hpp"
#include "mechanics/element_geometry.hpp"
#include "mechanics/small_strain_stiffness.hpp"
#include "support/tolerance.hpp"
#include "test_patches.hpp"

#include <gtest/gtest.h>

#include <random>

namespace iga::mechanics {
namespace {

TEST(SmallStrainStiffness, EqualsTheGaussPointSumOfBTransposeDB)
{
    // Both sum the same products in another order: round-off ~1e-16 per term, a few
    // hundred terms per entry; a wrong tensor component is O(1) relative.
    constexpr double tolerance = 1e-12;
    std::mt19937 rng(20261127);
    const struct {
        int d;
        PlaneMode plane;
    } cases[] = {{2, PlaneMode::strain}, {2, PlaneMode::stress}, {3, PlaneMode::none}};
    for (const auto& c : cases)
        for (int degree = 1; degree <= 3; ++degree) {
            const std::vector<int> degrees(static_cast<std::size_t>(c.d), degree),
                spans(static_cast<std::size_t>(c.d), 1);
            const nurbs::Patch patch =
                test::distorted(test::grid_patch(degrees, spans, VecN::Ones(c.d)), rng, 0.15, 0.3);
            const ElementGeometry g = element_geometry(patch, patch.elements().front());
            const Material m{MaterialModel::linear_elastic, 7.0, 0.35, c.plane};
            const Matrix expected = element_response(g, m, Kinematics::small, Matrix::Zero(g.n_local(), c.d)).K;
            const Matrix K = small_strain_stiffness(g, m);
            const double error = (K - expected).norm() / expected.norm();
            EXPECT_TRUE(test::at_most(error, tolerance)) << "d " << c.d << ", degree " << degree;
        }
}

}  // namespace
}  // namespace iga::mechanics
