// Stress fields at the tessellation points (analysis/fields.hpp) on a patch with
// a collapsed corner (the Hertz deck's quarter disc, det(dX/dxi) = 0 at its
// centre): a linear displacement u = G X is reproduced exactly by the NURBS basis
// (sum_A R_A X_A = X), so the stress is the same constant at every point,
// the singular corner included, and must never be NaN.

#include "run_support.hpp"
#include "support/tolerance.hpp"

#include "analysis/fields.hpp"
#include "analysis/scene.hpp"
#include "analysis/tessellation.hpp"
#include "mechanics/element_geometry.hpp"
#include "mechanics/material.hpp"
#include "mechanics/stress_recovery.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace iga::test {
namespace {

// The basis reproduces u = G X to round-off; near the collapsed edge the gradient
// divides by a small Jacobian, and the extrapolated corner value (u1 meets v0) was
// measured 1.3e-8 off, so allow 1e-7 of the stress scale E |G| (a corner evaluated
// at the singular point itself is off by O(1), an unshifted neighbour by 1e-5).
constexpr double reproduction_tolerance = 1e-7;

TEST(Fields, LinearDisplacementGivesConstantStressAlsoAtTheCollapsedCorner)
{
    const io::Deck deck = io::read_deck(source_path("inputs/hertz.yaml"), {});
    const analysis::Scene scene = analysis::build_scene(deck);
    const analysis::BodyModel& body = scene.bodies.at(0);
    ASSERT_EQ(body.material.plane, mechanics::PlaneMode::strain);

    Eigen::Matrix2d G;
    G << 1e-3, 4e-4, -2e-4, -5e-4;
    const RowMatrix X = body.node_points;
    const RowMatrix u = X * G.transpose();  // rows u_A = G X_A

    const mechanics::Lame lame = mechanics::lame_parameters(body.material);
    const Eigen::Matrix2d eps = 0.5 * (G + G.transpose());
    const Eigen::Matrix2d sigma = lame.lambda * eps.trace() * Eigen::Matrix2d::Identity() + 2.0 * lame.mu * eps;
    const double sigma_zz = lame.lambda * eps.trace();  // plane strain
    const double scale = body.material.E * G.cwiseAbs().maxCoeff();

    const analysis::TessellatedBody t = analysis::tessellate(body, 4);
    const analysis::FieldsResult r = analysis::body_fields(body, t, mechanics::Kinematics::small, u);
    EXPECT_EQ(r.n_unevaluated, 0);
    const double expected[6] = {sigma(0, 0), sigma(1, 1), sigma_zz, sigma(0, 1), 0.0, 0.0};
    const double vm = analysis::von_mises(Eigen::Map<const Eigen::Matrix<double, 1, 6>>(expected));
    int singular_points = 0;  // where the stress cannot be evaluated at the parameter itself
    for (Index k = 0; k < r.fields.stress.rows(); ++k) {
        const VecN& xi = t.parameters[static_cast<std::size_t>(k)];
        try {
            mechanics::cauchy_stress(body.patches.at(0).patch, body.material, mechanics::Kinematics::small, u, xi);
        } catch (const mechanics::NonPositiveJacobian&) {
            ++singular_points;
        }
        for (int c = 0; c < 6; ++c)
            EXPECT_TRUE(near(r.fields.stress(k, c), expected[c], reproduction_tolerance * scale))
                << "component " << c << " at xi = " << xi.transpose();
        EXPECT_TRUE(near(r.fields.von_mises(k), vm, reproduction_tolerance * scale));
        EXPECT_TRUE(near(r.fields.displacement(k, 0), (G * r.fields.reference_coordinates.row(k).transpose())(0),
                         1e-12));
    }
    EXPECT_GT(singular_points, 0) << "the deck no longer has a collapsed corner: the test lost its point";
}

TEST(Fields, VonMisesOfUniaxialAndPureShear)
{
    // Uniaxial s: von Mises s; pure shear t: sqrt(3) t (definitions, exact up to round-off).
    constexpr double round_off = 1e-14;
    EXPECT_TRUE(near(analysis::von_mises(Eigen::Matrix<double, 1, 6>{2.0, 0, 0, 0, 0, 0}), 2.0, round_off));
    EXPECT_TRUE(near(analysis::von_mises(Eigen::Matrix<double, 1, 6>{0, 0, 0, 0, 0, 1.5}), std::sqrt(3.0) * 1.5,
                     round_off));
    EXPECT_TRUE(near(analysis::von_mises(Eigen::Matrix<double, 1, 6>{1, 1, 1, 0, 0, 0}), 0.0, round_off));
}

}  // namespace
}  // namespace iga::test
