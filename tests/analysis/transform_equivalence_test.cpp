// Geometry you can place (docs/deck.md, "Placing geometry"): a 3D contact deck of
// two crossed half-cylinders built from built-in shapes with `transform:` (rotations,
// a mirror, translations) gives the same results file as the same geometry written
// as raw NURBS (tests/analysis/decks/crossed_cylinders_{shapes,nurbs}_3d.yaml; the
// raw control points were computed by hand from the shape's documented
// parametrization, with the mirrored body's u reversed).

#include "io/results_compare.hpp"
#include "run_support.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

namespace iga::test {

namespace {

// Quarter turns about coordinate axes and integer translations are exact, so both
// decks give bit-identical patches and the runs the same arithmetic (they compare
// equal with zero tolerance today); the bounds only allow for a summation order
// changed by anything else. A wrong placement, or the lower body placed without
// the mirror's u reversal (same geometry, other parametrization), changes the
// coordinates and displacements by O(1) relative.
constexpr double same_rtol = 1e-9;
// Absolute floor: displacements are O(1e-2), Newton's final residuals O(1e-11).
constexpr double same_atol = 1e-12;

}  // namespace

TEST(TransformEquivalence, CrossedCylindersFromShapesEqualTheRawNurbsDeck)
{
    const auto dir = scratch_dir("transform_equivalence");
    const auto shapes = run_deck(source_path("tests/analysis/decks/crossed_cylinders_shapes_3d.yaml"), {},
                                 dir / "shapes.h5");
    const auto raw = run_deck(source_path("tests/analysis/decks/crossed_cylinders_nurbs_3d.yaml"), {}, dir / "raw.h5");
    ASSERT_EQ(shapes.status, "completed") << shapes.message;
    ASSERT_EQ(raw.status, "completed") << raw.message;

    // The whole file, as `igacontact compare` with --rtol and --atol compares it: the raw
    // deck is the reference, since the shapes' file has /bodies/*/side_names in addition
    // (items only in NEW are not differences); /deck, whose text differs, is not compared.
    io::CompareOptions options;
    options.rtol = same_rtol;
    options.atol = same_atol;
    const io::CompareReport report = io::compare_results((dir / "raw.h5").string(), (dir / "shapes.h5").string(),
                                                         options);
    EXPECT_TRUE(report.same()) << io::format_report(report, false);
    EXPECT_GT(report.n_compared, 150);  // every step's displacements, contact data, reactions, ...

    // The contact is real: both half passes carry about the same force.
    const Results r(dir / "shapes.h5");
    const double f_lower = r.number("results/contact/crossing/lower.v0", "normal_force");
    const double f_upper = r.number("results/contact/crossing/upper.v0", "normal_force");
    EXPECT_GT(f_lower, 0.0);
    constexpr double half_pass_agreement = 0.05;  // coarse mesh: the two passes differ by per cents
    EXPECT_TRUE(near_rel(f_upper, f_lower, half_pass_agreement));
}

TEST(TransformEquivalence, AMirroredShapeKeepsItsSideNamesAndRefinementParameters)
{
    // A rectangle [0, 2] x [0, 1] mirrored in x lies in [-2, 0] x [0, 1]. As built, u0 is
    // its face x = 0 and the knot u = 0.1 lies 0.2 from it; a transform places the body
    // and renames nothing (issue 32): u0 is still the face at x = 0 (its own mirror
    // image), the knot lies at x = -0.2, and the face u1 at x = -2 carries the load.
    const auto dir = scratch_dir("transform_as_built");
    const auto deck = dir / "mirrored.yaml";
    std::ofstream(deck) << R"(format: 1
analysis: {dimension: 2, plane: strain, kinematics: small}
materials:
  - {name: m, model: linear_elastic, E: 1000.0, nu: 0.0}
bodies:
  - name: bar
    material: m
    shape: {type: rectangle, corner: [0, 0], size: [2, 1], transform: [{mirror: {normal: [1, 0]}}]}
    refine: {insert: [[0.1], []]}
constraints:
  - {body: bar, side: u0, fix: [x]}
  - {body: bar, side: v0, fix: [y]}
loads:
  - {body: bar, side: u1, traction: [-1.0, 0.0]}
steps: {count: 1}
)";
    const auto outcome = run_deck(deck.string(), {}, dir / "mirrored.h5");
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    const Results r(dir / "mirrored.h5");
    const RowMatrix points = r.matrix("/bodies/bar/control_points");
    std::vector<double> xs;
    for (Index a = 0; a < points.rows(); ++a)
        xs.push_back(points(a, 0));
    // Degree 1: the inserted knot is a control point column; exact arithmetic (0.1 * 2).
    constexpr double knot_tolerance = 1e-12;
    auto has_x = [&](double x) {
        return std::any_of(xs.begin(), xs.end(), [&](double v) { return std::abs(v - x) < knot_tolerance; });
    };
    EXPECT_TRUE(has_x(-0.2)) << "the knot u = 0.1 is 0.2 from the face u0 as built";
    EXPECT_FALSE(has_x(-1.8)) << "the refinement was applied in the placed (reversed) parameters";
    // The face held in x is u0 as built, at x = 0: the load pulls the bar (nu = 0) to
    // u_x = -strain * 2 = -2e-3 at x = -2, with the held face fixed.
    const RowMatrix u = r.matrix("/results/displacement/bar");
    ASSERT_EQ(u.rows(), points.rows());
    double u_min = 0.0, u_at_zero = 1.0;
    for (Index a = 0; a < points.rows(); ++a) {
        u_min = std::min(u_min, u(a, 0));
        if (std::abs(xs[static_cast<std::size_t>(a)]) < knot_tolerance)
            u_at_zero = std::abs(u(a, 0));
    }
    constexpr double solve_tolerance = 1e-9;  // a linear solve of a well-posed bar
    EXPECT_NEAR(u_at_zero, 0.0, solve_tolerance);
    EXPECT_NEAR(u_min, -2e-3, solve_tolerance);
}

}  // namespace iga::test
