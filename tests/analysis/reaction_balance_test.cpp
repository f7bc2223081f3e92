// Reactions that balance (issue 17, item 2): where two constrained sides share an
// edge (3D) or a corner (2D) and both hold the same component, the per-side
// reactions count those dofs twice; reactions/total/<body> counts every
// constrained dof once, so that
//   total reaction + lambda (external loads) + contact force on the body = 0,
// and reactions/items/<k> split that total among the constraint items (a shared
// dof goes to the first item in deck order that prescribes it).
//
// Why it balances: sum over all dofs of a body of r = f_int - lambda f_ext + r_c
// has sum f_int = 0 (a rigid translation does no internal work), the free rows are
// Newton's residual and the constrained rows are the reactions R, so
// sum R - lambda F_ext + sum r_c = -(sum of the free residual); the contact force
// on the body is -r_c, and the obstacle feels +r_c (obstacle_force).

#include "run_support.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <fstream>

namespace iga::test {

namespace {

// Newton stops at ||r_free|| <= 1e-10 x force scale; the sum of a few hundred free
// entries is then below ~1e-8 of the force scale (sqrt(n) x 1e-10, n < 1e4); the
// shared dofs' reactions that the per-side sum counts twice are O(1e-2) of it here.
constexpr double balance_tolerance = 1e-8;
// Items partition the same dofs as the total: only the summation order differs.
constexpr double partition_tolerance = 1e-12;

std::vector<double> attribute_vector(const Results& r, const std::string& object, const std::string& name)
{
    const io::h5::Handle o = io::h5::open_object(r.id(), object);
    return io::h5::read_attribute(o.id(), name).reals;
}

/// A d-vector dataset (reactions/...).
VecN vector_at(const Results& r, const std::string& path)
{
    const std::vector<double> v = r.reals(path);
    return Eigen::Map<const VecN>(v.data(), static_cast<Index>(v.size()));
}

VecN vec(std::initializer_list<double> values)
{
    VecN v(static_cast<Index>(values.size()));
    Index k = 0;
    for (double x : values)
        v(k++) = x;
    return v;
}

/// A block held on two sides that both fix x (they meet on the line x = y = 0),
/// on its bottom in z, pulled by a traction on its right face, under gravity, and
/// pressed by a rigid platen that moves down onto its top.
std::string block_3d_deck()
{
    return R"(format: 1
analysis: {dimension: 3, kinematics: small}
materials: [{name: solid, model: linear_elastic, E: 1000.0, nu: 0.3}]
bodies:
  - {name: block, material: solid, shape: {type: box, corner: [0, 0, 0], size: [1, 1, 1]},
     refine: {elevate: [1, 1, 1], spans: [2, 2, 2]}}
  - {name: platen, rigid: {plane: {point: [0, 0, 1], normal: [0, 0, -1]}, motion: [0, 0, -0.01]}}
constraints:
  - {body: block, side: u0, fix: [x]}
  - {body: block, side: v0, fix: [x, y]}
  - {body: block, side: w0, fix: [z]}
loads:
  - {body: block, side: u1, traction: [2.0, 1.0, 0.5]}
  - {body: block, gravity: [0, 0, -9.81], density: 0.5}
contact:
  - {name: press, between: [block.w1, platen], penalty: 1.0e5}
steps: {count: 2}
)";
}
// Loads at load factor 1: the traction on the unit face u1 and rho g over the unit cube.
const VecN block_3d_load = vec({2.0, 1.0, 0.5 - 0.5 * 9.81});

/// A square held at its left side in x and displaced at its top in x and y (the
/// corner (0, 1) has x fixed by both), on a rigid floor, pulled sideways by a
/// traction on its right side.
std::string square_2d_deck()
{
    return R"(format: 1
analysis: {dimension: 2, plane: strain, kinematics: small}
materials: [{name: solid, model: linear_elastic, E: 1000.0, nu: 0.3}]
bodies:
  - {name: square, material: solid, shape: {type: rectangle, corner: [0, 0], size: [1, 1]},
     refine: {elevate: [1, 1], spans: [3, 3]}}
  - {name: floor, rigid: {plane: {point: [0, 0], normal: [0, 1]}}}
constraints:
  - {body: square, side: u0, fix: [x]}
  - {body: square, side: v1, displacement: [0, -0.01]}
loads:
  - {body: square, side: u1, traction: [3.0, 0.0]}
contact:
  - {name: ground, between: [square.v0, floor], penalty: 1.0e5}
steps: {count: 2}
)";
}
const VecN square_2d_load = vec({3.0, 0.0});

struct Case {
    const char* name;
    std::string deck;
    std::string body;
    std::vector<std::string> sides;  ///< the constrained sides, deck order
    int n_items;
    std::string pair;
    VecN load;  ///< external load at load factor 1
};

class ReactionBalance : public ::testing::TestWithParam<Case> {};

TEST_P(ReactionBalance, TotalReactionLoadsAndContactSumToZero)
{
    const Case& c = GetParam();
    const auto dir = scratch_dir(std::string("reaction_balance_") + c.name);
    const auto deck = dir / "deck.yaml";
    std::ofstream(deck) << c.deck;
    const auto file = dir / "run.h5";
    const analysis::RunOutcome outcome = run_deck(deck.string(), {}, file);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    const Results r(file);
    const std::vector<std::string> steps = r.steps();
    ASSERT_GE(steps.size(), 2u);  // every increment balances, not only the last
    for (const std::string& step : steps) {
        const std::string g = "steps/" + step;
        const double lambda = r.number(g, "load_factor");
        const VecN total = vector_at(r, g + "/reactions/total/" + c.body);
        const std::vector<double> on_obstacle = attribute_vector(r, g + "/contact/" + c.pair, "obstacle_force");
        ASSERT_EQ(on_obstacle.size(), static_cast<std::size_t>(c.load.size()));
        const VecN contact_on_body = -Eigen::Map<const VecN>(on_obstacle.data(), c.load.size());
        ASSERT_TRUE(at_least(contact_on_body.norm(), 1e-3)) << "no contact in " << step;

        const double scale = (lambda * c.load).norm() + contact_on_body.norm() + total.norm();
        const VecN imbalance = total + lambda * c.load + contact_on_body;
        EXPECT_TRUE(at_most(imbalance.norm(), balance_tolerance * scale))
            << step << ": |total + loads + contact| = " << imbalance.norm() << " of scale " << scale;

        // The old check: the per-side reactions count the shared dofs twice and do not balance.
        VecN side_sum = VecN::Zero(c.load.size());
        for (const std::string& side : c.sides)
            side_sum += vector_at(r, g + "/reactions/" + c.body + "." + side);
        const double side_imbalance = (side_sum + lambda * c.load + contact_on_body).norm();
        EXPECT_TRUE(at_least(side_imbalance, 1e3 * balance_tolerance * scale))
            << step << ": the shared dofs carry no reaction, the deck tests nothing";

        // The items split the total: each dof once, the first item in deck order owns it.
        VecN item_sum = VecN::Zero(c.load.size());
        for (int k = 0; k < c.n_items; ++k)
            item_sum += vector_at(r, g + "/reactions/items/" + std::to_string(k));
        EXPECT_TRUE(at_most((item_sum - total).norm(), partition_tolerance * scale)) << step;
        // The first item owns its whole side: its share is that side's reaction.
        EXPECT_TRUE(at_most((vector_at(r, g + "/reactions/items/0") -
                             vector_at(r, g + "/reactions/" + c.body + "." + c.sides.front()))
                                .norm(),
                            partition_tolerance * scale))
            << step;
    }
    // /results mirrors the last step; /history has one row per increment.
    const RowMatrix history = r.matrix("history/reactions/total/" + c.body);
    ASSERT_EQ(history.rows(), static_cast<Index>(steps.size()));
    const VecN last_row = history.row(history.rows() - 1).transpose();
    EXPECT_EQ(last_row, vector_at(r, "results/reactions/total/" + c.body));
    EXPECT_EQ(r.matrix("history/reactions/items/0").rows(), static_cast<Index>(steps.size()));
}

INSTANTIATE_TEST_SUITE_P(
    SharedDofs, ReactionBalance,
    ::testing::Values(Case{"edge_3d", block_3d_deck(), "block", {"u0", "v0", "w0"}, 3, "press", block_3d_load},
                      Case{"corner_2d", square_2d_deck(), "square", {"u0", "v1"}, 2, "ground", square_2d_load}),
    [](const ::testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace iga::test
