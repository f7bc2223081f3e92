// Sparse contact coupling (analysis/system.hpp, analysis/scene.hpp): the tangent
// assembled block by block into the per-coupling pattern blocks equals the dense
// assembly of the whole pair (elements + one n_local x n_local contact matrix per
// pair, the first release's way) on the 2D contact decks; a coupling met during
// a run (a block sliding along another) extends the pattern, and the run ends in
// the same state as one with every coupling registered up front.

#include "analysis/scene.hpp"
#include "analysis/system.hpp"
#include "io/deck_reader.hpp"
#include "solver/load_stepping.hpp"
#include "solver/suitesparse_solver.hpp"
#include "support/tolerance.hpp"

#include "run_support.hpp"

#include <gtest/gtest.h>

#include <random>

namespace iga::analysis {
namespace {

// Tangents summed in a different order (per coupling block, then into K, instead
// of per pair into one dense matrix): round-off of the largest entry only.
constexpr double assembly_order_tolerance = 1e-13;

/// Free-dof tangent at u of a scene built from the deck (contact included or not).
SparseMatrix tangent_at(Scene& scene, const Vector& u, double load_factor)
{
    RunContext context(nullptr, Verbosity::quiet);
    SceneSystem system(scene, context, 1);
    solver::Evaluation out;
    system.evaluate(u, load_factor, true, out);
    EXPECT_TRUE(out.ok) << out.message;
    return out.tangent;
}

/// A state with contact: the converged solution of the deck (a few increments).
Vector solved_state(Scene& scene)
{
    RunContext context(nullptr, Verbosity::quiet);
    SceneSystem system(scene, context, 1);
    solver::SuiteSparseSolver linear(solver::SuiteSparseSolver::Kind::lu);
    Vector u = Vector::Zero(scene.dofs->n_free());
    solver::SteppingCallbacks callbacks;
    callbacks.commit = [&] {
        for (PairModel& p : scene.pairs)
            p.pair.commit();
    };
    callbacks.rollback = [&] {
        for (PairModel& p : scene.pairs)
            p.pair.rollback();
    };
    const solver::SteppingResult result = solver::run_load_steps(
        system.nonlinear_system(), u, solver::SteppingSettings{}, solver::NewtonSettings{}, linear, callbacks, nullptr);
    EXPECT_TRUE(result.completed) << result.message;
    return u;
}

struct DeckCase {
    const char* name;
    const char* deck;
};

class SparseContactAssembly : public ::testing::TestWithParam<DeckCase> {};

TEST_P(SparseContactAssembly, EqualsTheDenseAssemblyOfEachPair)
{
    const io::Deck deck = io::read_deck(test::source_path(GetParam().deck));
    Scene scene = build_scene(deck);
    const Vector u = solved_state(scene);
    const SparseMatrix K = tangent_at(scene, u, 1.0);

    // The reference: the elements' tangent (the same deck without contact), plus
    // each pair's tangent densified over all of its dofs and scattered.
    io::Deck no_contact = deck;
    no_contact.contact.clear();
    Scene bare = build_scene(no_contact);
    ASSERT_EQ(bare.dofs->n_free(), scene.dofs->n_free());
    const SparseMatrix K_elements = tangent_at(bare, u, 1.0);
    std::vector<Triplet> contact_entries;
    const Vector u_full = scene.dofs->expand(u, 1.0);
    RunContext context(nullptr, Verbosity::quiet);
    SceneSystem system(scene, context, 1);
    int n_active = 0;
    for (std::size_t p = 0; p < scene.pairs.size(); ++p) {
        PairModel& pair = scene.pairs[p];
        contact::PairEvaluation c =
            pair.pair.evaluate(system.side_displacement(u_full, static_cast<int>(p), 0),
                               system.side_displacement(u_full, static_cast<int>(p), 1), true, nullptr, 1.0);
        pair.pair.adopt(std::move(c.trial));
        ASSERT_TRUE(c.ok) << c.message;
        n_active += c.n_active;
        const Index n = pair.pair.n_local_dofs();
        Matrix K_pair = Matrix::Zero(n, n);
        for (const contact::LocalBlock& block : c.tangent) {
            EXPECT_TRUE(pair.blocks.contains(block.element)) << "a coupling of the solved state is not registered";
            for (std::size_t j = 0; j < block.dofs.size(); ++j)
                for (std::size_t i = 0; i < block.dofs.size(); ++i)
                    K_pair(block.dofs[i], block.dofs[j]) += block.K(static_cast<Index>(i), static_cast<Index>(j));
        }
        for (Index j = 0; j < n; ++j)
            for (Index i = 0; i < n; ++i) {
                const int row = scene.dofs->free_index(pair.local_to_full[static_cast<std::size_t>(i)]);
                const int col = scene.dofs->free_index(pair.local_to_full[static_cast<std::size_t>(j)]);
                if (row >= 0 && col >= 0 && K_pair(i, j) != 0.0)
                    contact_entries.emplace_back(row, col, K_pair(i, j));
            }
    }
    ASSERT_GT(n_active, 0) << "the state must be in contact";
    SparseMatrix K_contact(K.rows(), K.cols());
    K_contact.setFromTriplets(contact_entries.begin(), contact_entries.end());
    const SparseMatrix reference = K_elements + K_contact;
    const double scale = reference.coeffs().cwiseAbs().maxCoeff();
    const SparseMatrix difference = K - reference;
    const double error = difference.coeffs().cwiseAbs().maxCoeff() / scale;
    EXPECT_TRUE(test::at_most(error, assembly_order_tolerance)) << GetParam().name;
    // Never more entries than the first release's pattern (one dense block over all
    // dofs of each pair's two sides).
    std::vector<std::vector<int>> dense_blocks;
    for (const BodyModel& body : scene.bodies)
        dense_blocks.insert(dense_blocks.end(), body.element_dofs.begin(), body.element_dofs.end());
    for (const PairModel& pair : scene.pairs)
        dense_blocks.push_back(pair.local_to_full);
    const assembly::SparsePattern dense_pattern(*scene.dofs, dense_blocks);
    EXPECT_LE(K.nonZeros(), dense_pattern.n_nonzeros());
}

INSTANTIATE_TEST_SUITE_P(Decks, SparseContactAssembly,
                         ::testing::Values(DeckCase{"hertz_displacement", "inputs/hertz_displacement_2d.yaml"},
                                           DeckCase{"two_cylinders", "inputs/hertz_two_cylinders_2d.yaml"},
                                           DeckCase{"patch_test", "inputs/contact_patch_test_2d.yaml"},
                                           DeckCase{"punch", "inputs/punch_cylinder_block_2d.yaml"}),
                         [](const auto& info) { return std::string(info.param.name); });

// A short block pressed onto a long base and dragged along it by its top face:
// its contact Gauss points slide over base elements far beyond the search margin
// of the reference configuration.
const char* const sliding_deck = R"(
format: 1
analysis: {dimension: 2, plane: strain, kinematics: small}
materials:
  - {name: m, model: linear_elastic, E: 1000.0, nu: 0.3}
bodies:
  - name: slider
    material: m
    shape: {type: rectangle, corner: [0.0, 0.0], size: [0.5, 0.25]}
    refine: {elevate: [1, 1], spans: [4, 2]}
  - name: base
    material: m
    shape: {type: rectangle, corner: [-0.5, -0.5], size: [4.0, 0.5]}
    refine: {elevate: [1, 1], spans: [32, 3]}
constraints:
  - {body: base, side: v0, fix: [x, y]}
  - {body: slider, side: v1, displacement: [2.0, -0.002]}
contact:
  - {name: slide, between: [slider.v0, base.v1], penalty: 1.0e5}
steps: {count: 8, adaptive: false}
)";

struct SlidingRun {
    Vector u;
    int blocks_before = 0;
    int blocks_after = 0;
    int symbolic = 0;
};

SlidingRun run_sliding(bool register_all_couplings)
{
    const io::Deck deck = io::read_deck_text(sliding_deck, "sliding.yaml", ".");
    Scene scene = build_scene(deck);
    if (register_all_couplings) {
        PairModel& pair = scene.pairs.front();
        std::vector<std::vector<int>> blocks;
        std::vector<contact::Coupling> couplings;
        for (int a = 0; a < pair.pair.n_elements(0); ++a)
            for (int b = 0; b < pair.pair.n_elements(1); ++b)
                if (!pair.blocks.contains({a, b})) {
                    couplings.push_back({a, b});
                    blocks.push_back(coupling_full_dofs(pair, {a, b}));
                }
        const int first = scene.pattern->extend(std::move(blocks));
        for (std::size_t k = 0; k < couplings.size(); ++k)
            pair.blocks.emplace(couplings[k], first + static_cast<int>(k));
    }
    SlidingRun run;
    run.blocks_before = scene.pattern->n_blocks();
    RunContext context(nullptr, Verbosity::quiet);
    SceneSystem system(scene, context, 1);
    solver::SuiteSparseSolver linear(solver::SuiteSparseSolver::Kind::lu);
    run.u = Vector::Zero(scene.dofs->n_free());
    solver::SteppingCallbacks callbacks;
    callbacks.commit = [&] { scene.pairs.front().pair.commit(); };
    callbacks.rollback = [&] { scene.pairs.front().pair.rollback(); };
    solver::SteppingSettings stepping;
    stepping.count = 8;
    stepping.adaptive = false;
    const solver::SteppingResult result =
        solver::run_load_steps(system.nonlinear_system(), run.u, stepping, solver::NewtonSettings{}, linear,
                               callbacks, nullptr);
    EXPECT_TRUE(result.completed) << result.message;
    EXPECT_GT(system.last_active(), 0) << "the slider must still press on the base";
    run.blocks_after = scene.pattern->n_blocks();
    run.symbolic = linear.n_symbolic();
    return run;
}

TEST(SparseContact, SlidingExtendsThePatternAndMatchesAllCouplingsRegistered)
{
    const SlidingRun extended = run_sliding(false);
    const SlidingRun registered = run_sliding(true);
    EXPECT_GT(extended.blocks_after, extended.blocks_before) << "sliding must meet couplings not registered";
    EXPECT_GT(extended.symbolic, 1) << "a grown pattern needs a new symbolic analysis";
    EXPECT_EQ(registered.blocks_after, registered.blocks_before) << "nothing left to register";
    ASSERT_EQ(extended.u.size(), registered.u.size());
    // Both runs solve the same equations to the Newton tolerance (1e-10 of the
    // forces); only the LU ordering differs. 1e-8 of the slide leaves room for that.
    constexpr double same_state_tolerance = 1e-8;
    const double difference = (extended.u - registered.u).lpNorm<Eigen::Infinity>() /
                              registered.u.lpNorm<Eigen::Infinity>();
    EXPECT_TRUE(test::at_most(difference, same_state_tolerance));
}

}  // namespace
}  // namespace iga::analysis
