// Initial overclosure (docs/theory.md "Initial overclosure"), on tests/analysis/decks/gross_overclosure_2d.yaml: a rigid plane
// 0.01 inside a half disc whose top is held and moved down 0.002, eps = 1e4 E.
//  (a) The run completes (the second release failed after 8 cutbacks) and names the
//      overlap in its warnings. (Should the first increment need a cutback, the
//      overlap is released gradually over it: ContactPair::release_overlap.)
//  (b) The end state does not depend on how the overlap came about: the same plane
//      placed at the disc's lowest point (y = 0, touching) and moved up 0.01 over the
//      load path gives the same reaction. Elastic and frictionless, both paths end in
//      the same equilibrium.

#include "run_support.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

namespace iga::test {
namespace {

std::string deck_path()
{
    return source_path("tests/analysis/decks/gross_overclosure_2d.yaml");
}

TEST(Overclosure, GrossOverlapIsReleasedAndEndsWhereAMovingPlaneEnds)
{
    const auto dir = scratch_dir("overclosure");
    const analysis::RunOutcome overlap = run_deck(deck_path(), {}, dir / "overlap.h5");
    ASSERT_EQ(overlap.status, "completed") << overlap.message;
    const Results a(dir / "overlap.h5");
    EXPECT_NE(a.text("/", "warnings").find("deep inside the other surface"), std::string::npos)
        << a.text("/", "warnings");

    const analysis::RunOutcome moved = run_deck(
        deck_path(),
        {"bodies.floor.rigid={plane: {point: [0.0, 0.0], normal: [0.0, 1.0]}, motion: [0.0, 0.01]}"},
        dir / "moved.h5");
    ASSERT_EQ(moved.status, "completed") << moved.message;
    const Results b(dir / "moved.h5");

    // Both end in the same linear problem with the same active set, solved to the
    // Newton tolerance (1e-10 of the force); 1e-6 leaves room for a different active
    // set at one Gauss point on the way, not for a lost or half-released overlap
    // (the reaction then changes by O(1)).
    constexpr double path_tolerance = 1e-6;
    const double ra = a.reals("results/reactions/drum.v1").at(1);
    const double rb = b.reals("results/reactions/drum.v1").at(1);
    RecordProperty("reaction", std::to_string(ra));
    EXPECT_TRUE(at_least(-ra, 1.0)) << "the plane pushes the disc up: " << ra;
    EXPECT_TRUE(near_rel(ra, rb, path_tolerance)) << ra << " vs " << rb;
}

}  // namespace
}  // namespace iga::test
