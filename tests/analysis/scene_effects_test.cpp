// Only the effects a scene calls for (issue 5): no contact pairs -> no contact
// work at all; bodies that never come near each other -> no projections; and the
// ParaView index (output.paraview) references only datasets that exist, with
// the shapes it announces.

#include "run_support.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

namespace iga::test {

namespace {

double counter_or_zero(const Results& r, const std::string& name)
{
    const io::h5::Handle group = io::h5::open_object(r.id(), "counters");
    for (const std::string& n : io::h5::attribute_names(group.id()))
        if (n == name)
            return r.number("counters", name);
    return 0.0;
}

}  // namespace

TEST(SceneEffects, NoContactPairsMeansNoContactWork)
{
    const auto dir = scratch_dir("no_contact_work");
    const auto out = dir / "lame.h5";
    const auto outcome = run_deck(source_path("inputs/lame_cylinder_2d.yaml"), {}, out);
    ASSERT_EQ(outcome.status, "completed");
    const Results r(out);
    // Exactly zero: no timer runs and no counter moves when the deck has no pairs.
    for (const char* timer : {"contact", "contact_search", "projection"})
        EXPECT_EQ(r.number("timings", timer), 0.0) << timer;
    for (const char* counter : {"projections", "contact_candidates", "projection_iterations", "contact_gauss_points"})
        EXPECT_EQ(counter_or_zero(r, counter), 0.0) << counter;
}

TEST(SceneEffects, DistantBodiesCostNoProjections)
{
    const auto dir = scratch_dir("distant_bodies");
    const auto deck = dir / "distant.yaml";
    std::ofstream(deck) << R"(format: 1
analysis: {dimension: 2, kinematics: small}
materials: [{name: m, model: linear_elastic, E: 1000.0, nu: 0.3}]
bodies:
  - {name: low, material: m, shape: {type: rectangle, corner: [0, 0], size: [1, 1]}, refine: {elevate: [1, 1], spans: [4, 4]}}
  - {name: high, material: m, shape: {type: rectangle, corner: [0, 5], size: [1, 1]}, refine: {elevate: [1, 1], spans: [4, 4]}}
constraints:
  - {body: low, side: v0, fix: [x, y]}
  - {body: high, side: v1, fix: [x, y]}
loads:
  - {body: low, side: v1, traction: [0, 1.0]}
contact:
  - {name: gap, between: [low.v1, high.v0], penalty: 1.0e6}
steps: {count: 2}
)";
    const auto out = dir / "distant.h5";
    const auto outcome = run_deck(deck.string(), {}, out);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    const Results r(out);
    EXPECT_GT(counter_or_zero(r, "contact_gauss_points"), 0.0);  // the pair exists and carries Gauss points
    EXPECT_EQ(counter_or_zero(r, "projections"), 0.0);           // ... but the global search prunes them all
    EXPECT_EQ(counter_or_zero(r, "contact_candidates"), 0.0);
    EXPECT_EQ(counter_or_zero(r, "projection_iterations"), 0.0);
}

/// Runs the Hertz deck with output.paraview (two increments) and checks that every
/// dataset the XDMF file names exists with the announced shape; returns the number
/// of referenced datasets (-1 after a fatal failure).
int check_paraview_index(const std::string& name, const std::vector<std::string>& extra_sets)
{
    const auto dir = scratch_dir(name);
    const auto out = dir / "hertz.h5";
    std::vector<std::string> sets = {"output.paraview=true", "steps.count=2", "steps.adaptive=false",
                                     "bodies.cylinder.refine.insert=[[0.02,0.04,0.06,0.08,0.1],[0.05,0.2]]"};
    sets.insert(sets.end(), extra_sets.begin(), extra_sets.end());
    const auto outcome = run_deck(source_path("inputs/hertz.yaml"), sets, out);
    EXPECT_EQ(outcome.status, "completed") << outcome.message;
    std::ifstream in(dir / "hertz.xdmf");
    EXPECT_TRUE(in.good()) << "no XDMF file beside the results";
    if (outcome.status != "completed" || !in.good())
        return -1;
    std::stringstream text;
    text << in.rdbuf();
    const std::string xdmf = text.str();
    EXPECT_EQ(xdmf.find("nan"), std::string::npos);

    const Results r(out);
    const std::regex item(R"re(<DataItem Dimensions="([0-9 ]+)"[^>]*>([^:<]+):([^<]+)</DataItem>)re");
    int n_items = 0;
    for (auto it = std::sregex_iterator(xdmf.begin(), xdmf.end(), item); it != std::sregex_iterator(); ++it) {
        ++n_items;
        const std::string dims = (*it)[1], file = (*it)[2], path = (*it)[3];
        EXPECT_EQ(file, "hertz.h5");
        if (!r.exists(path)) {
            ADD_FAILURE() << path << " is referenced but missing";
            continue;
        }
        const io::h5::Array a = io::h5::read_dataset(r.id(), path);
        std::string actual;
        for (std::size_t k = 0; k < a.dims.size(); ++k) {
            if (k > 0)
                actual += ' ';
            actual += std::to_string(a.dims[k]);  // (not " " + ...: GCC 12 -Wrestrict false positive)
        }
        EXPECT_EQ(actual, dims) << path;
    }
    EXPECT_EQ(r.steps().size(), 2u);
    // The tessellation moves with the solution: the lowest point of the arc goes down.
    const RowMatrix u = r.matrix("steps/0002/paraview/cylinder/displacement");
    EXPECT_TRUE(at_most(u.col(1).minCoeff(), 0.0));
    return n_items;
}

TEST(SceneEffects, ParaviewIndexReferencesExistingDatasetsWithTheirShapes)
{
    // Per increment: cells, points, displacement, 3 Gauss-point items, 2 post-processed items.
    EXPECT_EQ(check_paraview_index("paraview", {"output.fields=false"}), 2 * 8);
}

TEST(SceneEffects, ParaviewIndexReferencesStoredStressFields)
{
    // The results writer stores the fields of every increment: a run without them is a
    // regression, not a reason to skip.
    {
        const auto dir = scratch_dir("paraview_fields_probe");
        const auto out = dir / "probe.h5";
        const auto outcome = run_deck(source_path("inputs/lame_cylinder_2d.yaml"), {"output.fields=true"}, out);
        ASSERT_EQ(outcome.status, "completed") << outcome.message;
        const Results r(out);
        for (const char* field : {"stress", "von_mises", "displacement", "reference_coordinates"})
            EXPECT_TRUE(r.exists(std::string("/steps/0001/fields/tube/") + field))
                << "output.fields = true stored no /steps/0001/fields/tube/" << field;
    }
    // ... plus, with output.fields (on with paraview), six stress columns and von_mises.
    EXPECT_EQ(check_paraview_index("paraview_fields", {}), 2 * (8 + 7));
}

}  // namespace iga::test
