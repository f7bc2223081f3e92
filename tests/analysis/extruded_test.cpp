// 3D contact against 2D: the Hertz quarter cylinder extruded to a slab with u_z = 0
// on both faces is plane strain exactly, and with one linear element through the
// thickness its discretization contains the 2D one: the 3D pressure on every line
// z = const must equal the 2D run's, point by point (issue 10: "A 2D Hertz cylinder
// extruded in z with z fixed on both faces reproduces the 2D plane-strain pressure").

#include "run_support.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

namespace iga::test {

namespace {

// The two runs solve the same discrete equations (each to Newton's 1e-10 relative
// residual), with the 3D assembly summing over z in a different order: pressures agree
// to ~1e-8 of the peak; 1e-6 leaves room and still catches any 3D geometry error
// (a wrong weight or normal moves them by per cents).
constexpr double same_pressure = 1e-6;

}  // namespace

TEST(Extruded, SlabReproducesThePlaneStrainPressure)
{
    const auto dir = scratch_dir("extruded");
    const auto two_d = run_deck(source_path("inputs/hertz.yaml"), {}, dir / "plane.h5");
    const auto three_d = run_deck(source_path("inputs/hertz_cylinder_extruded_3d.yaml"), {}, dir / "slab.h5");
    ASSERT_EQ(two_d.status, "completed") << two_d.message;
    ASSERT_EQ(three_d.status, "completed") << three_d.message;
    const Results r2(dir / "plane.h5"), r3(dir / "slab.h5");
    const std::string side = "results/contact/cyl_floor/cylinder.v0/postprocessed/";
    const RowMatrix X2 = r2.matrix(side + "reference_coordinates"), X3 = r3.matrix(side + "reference_coordinates");
    const RowMatrix p2 = r2.matrix(side + "pressure"), p3 = r3.matrix(side + "pressure");
    ASSERT_EQ(X3.cols(), 3);
    const double peak = p2.maxCoeff();
    ASSERT_GT(peak, 50.0);  // Hertz p0 = 59.1
    // The face's samples are an n_v x n_u grid, u fastest; each row z = const is the 2D curve.
    const Index n_u = X2.rows();
    ASSERT_EQ(X3.rows() % n_u, 0);
    for (Index row = 0; row < X3.rows() / n_u; ++row) {
        double worst = 0.0;
        for (Index i = 0; i < n_u; ++i) {
            const Index k = row * n_u + i;
            ASSERT_TRUE(near(X3(k, 0), X2(i, 0), 1e-12)) << "sample " << k;
            ASSERT_TRUE(near(X3(k, 1), X2(i, 1), 1e-12)) << "sample " << k;
            worst = std::max(worst, std::abs(p3(k) - p2(i)));
        }
        EXPECT_TRUE(at_most(worst / peak, same_pressure)) << "z row " << row;
    }
    // The slab carries the 2D load per unit thickness times 0.2.
    const double f2 = r2.number("results/contact/cyl_floor/cylinder.v0", "normal_force");
    const double f3 = r3.number("results/contact/cyl_floor/cylinder.v0", "normal_force");
    EXPECT_TRUE(near(f3, 0.2 * f2, same_pressure * f2));
}

}  // namespace iga::test
