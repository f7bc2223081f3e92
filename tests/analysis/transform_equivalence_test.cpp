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

TEST(TransformEquivalence, TheMirroredShapesSideNamesFollowTheReversal)
{
    const auto dir = scratch_dir("transform_side_names");
    const auto outcome = run_deck(source_path("tests/analysis/decks/crossed_cylinders_shapes_3d.yaml"),
                                  {"steps.count=1"}, dir / "shapes.h5");
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    const Results r(dir / "shapes.h5");
    const io::h5::Array names = io::h5::read_dataset(r.id(), "/bodies/lower/side_names");
    ASSERT_EQ(names.strings.size(), 12u);  // six sides of the extruded shape, (side, meaning) each
    // half_disc: u0 is the left end of the diameter as built; the mirror reversed u,
    // so that side is now called u1.
    for (std::size_t k = 0; k < names.strings.size(); k += 2)
        if (names.strings[k] == "u1")
            EXPECT_NE(names.strings[k + 1].find("left end"), std::string::npos) << names.strings[k + 1];
}

}  // namespace iga::test
