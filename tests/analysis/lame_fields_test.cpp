// Stress fields at the tessellation points (analysis/fields.hpp) for Lame's
// thick-walled cylinder (inputs/lame_cylinder_2d.yaml, plane strain, small
// kinematics): sigma_rr, sigma_tt and sigma_zz at every tessellation point,
// boundary points included, against the closed form (Timoshenko & Goodier §28):
//   sigma_rr = A (1 - b^2/r^2),  sigma_tt = A (1 + b^2/r^2),  A = p a^2 / (b^2 - a^2),
//   sigma_zz = nu (sigma_rr + sigma_tt) = 2 nu A  (plane strain),   sigma_rt = 0.
// The solve runs through analysis::run; the fields are computed from the stored
// control-point displacements on the same scene, at the struct level (the results
// writer stores them under /steps/<kkkk>/fields, tested with the writer).

#include "run_support.hpp"
#include "support/tolerance.hpp"

#include "analysis/fields.hpp"
#include "analysis/scene.hpp"
#include "analysis/tessellation.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace iga::test {
namespace {

constexpr double nu = 0.3, pressure = 1.0, r_inner = 1.0, r_outer = 2.0;

// Degree 3, 16 x 16 spans: the pointwise stress error is O(h^3); measured at most
// 1.3e-4 p (the largest error sits on the boundary, where the stress gradient is
// largest), so 1e-3 p leaves a factor ~8 while a wrong component order, a missing
// plane-strain sigma_zz or a sign error is off by O(p).
constexpr double stress_tolerance = 1e-3 * pressure;
constexpr int tessellation_cells_per_span = 4;  // as output.paraview writes

TEST(LameFields, StressAtTessellationPointsMatchesTheClosedForm)
{
    const std::vector<std::string> overrides = {"bodies.tube.refine.elevate=[2,1]", "bodies.tube.refine.spans=[16,16]"};
    const auto dir = scratch_dir("lame_fields");
    const auto file = dir / "lame.h5";
    const analysis::RunOutcome outcome = run_deck(source_path("inputs/lame_cylinder_2d.yaml"), overrides, file);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;

    const io::Deck deck = io::read_deck(source_path("inputs/lame_cylinder_2d.yaml"), overrides);
    const analysis::Scene scene = analysis::build_scene(deck);
    ASSERT_EQ(scene.bodies.size(), 1u);
    const analysis::BodyModel& body = scene.bodies[0];
    const RowMatrix u = Results(file).matrix("results/displacement/tube");
    ASSERT_EQ(u.rows(), body.n_nodes);

    const analysis::TessellatedBody tessellation = analysis::tessellate(body, tessellation_cells_per_span);
    const analysis::FieldsResult result = analysis::body_fields(body, tessellation, scene.kinematics, u);
    const io::BodyFields& f = result.fields;
    EXPECT_EQ(result.n_unevaluated, 0);
    const Index n = tessellation.mesh.points.rows();
    ASSERT_EQ(f.reference_coordinates.rows(), n);
    ASSERT_EQ(f.reference_coordinates.cols(), 2);
    ASSERT_EQ(f.displacement.rows(), n);
    ASSERT_EQ(f.stress.rows(), n);
    ASSERT_EQ(f.stress.cols(), 6);
    ASSERT_EQ(f.von_mises.size(), n);

    const double A = pressure * r_inner * r_inner / (r_outer * r_outer - r_inner * r_inner);
    double worst = 0.0;
    for (Index k = 0; k < n; ++k) {
        const Eigen::Vector2d X = f.reference_coordinates.row(k).transpose();
        const double r = X.norm();
        const Eigen::Vector2d e_r = X / r, e_t(-e_r.y(), e_r.x());
        Eigen::Matrix2d s;
        s << f.stress(k, 0), f.stress(k, 3), f.stress(k, 3), f.stress(k, 1);
        const double s_rr = e_r.dot(s * e_r), s_tt = e_t.dot(s * e_t), s_rt = e_r.dot(s * e_t);
        const double exact_rr = A * (1.0 - r_outer * r_outer / (r * r));
        const double exact_tt = A * (1.0 + r_outer * r_outer / (r * r));
        const double exact_zz = nu * (exact_rr + exact_tt);
        for (const auto& [value, exact, name] :
             {std::tuple{s_rr, exact_rr, "sigma_rr"}, std::tuple{s_tt, exact_tt, "sigma_tt"},
              std::tuple{f.stress(k, 2), exact_zz, "sigma_zz"}, std::tuple{s_rt, 0.0, "sigma_rt"}}) {
            EXPECT_TRUE(near(value, exact, stress_tolerance)) << name << " at r = " << r << ": " << value
                                                                 << " vs " << exact;
            worst = std::max(worst, std::abs(value - exact));
        }
        EXPECT_EQ(f.stress(k, 4), 0.0);  // 2D: yz = xz = 0
        EXPECT_EQ(f.stress(k, 5), 0.0);
        // von Mises of the principal stresses (s_rr, s_tt, s_zz) of the closed form.
        const double exact_vm = std::sqrt(0.5 * ((exact_rr - exact_tt) * (exact_rr - exact_tt) +
                                                 (exact_tt - exact_zz) * (exact_tt - exact_zz) +
                                                 (exact_zz - exact_rr) * (exact_zz - exact_rr)));
        EXPECT_TRUE(near(f.von_mises(k), exact_vm, 2.0 * stress_tolerance)) << "von Mises at r = " << r;
    }
    RecordProperty("max_stress_error", std::to_string(worst));
}

}  // namespace
}  // namespace iga::test
