// ContactPair: tangent = finite difference of the pair residual for two curved
// deformable sides (both formulations) and against a rigid plane; far-apart
// pairs do no work; two-half-pass is unbiased under swapping the surfaces.

#include "contact/contact_pair.hpp"

#include "fixtures.hpp"
#include "nurbs/refine.hpp"
#include "nurbs/shapes.hpp"
#include "support/finite_difference.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>
#include <random>

namespace iga::contact {
namespace {

using test::vec2;

// Central differences, h = 1e-7 on O(1) geometry with eps = 1e3: truncation
// ~h^2 and round-off ~eps_mach |r| / h stay near 1e-8 relative; 1e-6 still
// exposes a missing term (O(1e-2)) or a wrong sign (O(1)).
constexpr double fd_step = 1e-7;
constexpr double fd_tolerance = 1e-6;
// No Gauss point may sit closer than this to the kink of <g_N> (nor to a change
// of active set), or the FD quotient straddles it.
constexpr double min_gap_distance = 100 * fd_step;
// Sums and reorderings of O(100) terms of similar size: a few hundred ulps.
constexpr double round_off = 1e-12;
// Two-half-pass asymmetry is O(1) relative (different Gauss points per pass);
// anything above 1e-6 is far from round-off symmetry.
constexpr double min_asymmetry = 1e-6;
// Size of the random perturbation of control points: small against the 0.03-0.04
// overlap, large enough to make every Gauss point different.
constexpr double noise = 2e-3;

struct Scene {
    DeformableSide disc;   // arc of a half disc (centre (0, 1), R = 1), 8 spans
    DeformableSide block;  // curved rational top of a block
};

Scene make_scene()
{
    return {DeformableSide::make(test::refined_half_disc(8), Side::v0),
            DeformableSide::make(test::curved_block(), Side::v1)};
}

/// Disc pushed 0.04 into the block (and a little sideways), with noise.
std::pair<RowMatrix, RowMatrix> overlap_state(const ContactPair& pair, unsigned seed)
{
    std::mt19937 rng(seed);
    const RowMatrix u1 = test::shifted(pair.n_control_points(0), vec2(0.01, -0.04), noise, rng);
    const RowMatrix u2 = test::shifted(pair.n_control_points(1), vec2(0.0, 0.0), noise, rng);
    return {u1, u2};
}

double smallest_gap_magnitude(const PairEvaluation& ev)
{
    double smallest = std::numeric_limits<double>::infinity();
    for (const CarrierResult& c : ev.carriers)
        for (Index g = 0; g < c.gap.size(); ++g)
            if (c.state[g] == PointState::ok)
                smallest = std::min(smallest, std::abs(c.gap(g)));
    return smallest;
}

void expect_tangent_is_derivative(const ContactPair& pair, const RowMatrix& u1, const RowMatrix& u2,
                                  const std::string& what)
{
    const int n1 = pair.n_control_points(0), n2 = pair.n_control_points(1);
    const PairEvaluation ev = pair.evaluate(u1, u2, true);
    ASSERT_TRUE(ev.ok) << ev.message;
    ASSERT_GE(ev.n_active, 4) << what << ": the state must have several active Gauss points";
    ASSERT_TRUE(test::at_least(smallest_gap_magnitude(ev), min_gap_distance)) << what;
    const Matrix K = test::dense(ev.tangent, pair.n_local_dofs());
    auto residual = [&](const Vector& v) {
        const auto [a, b] = test::unstack(v, n1, n2);
        const PairEvaluation e = pair.evaluate(a, b, false);
        EXPECT_TRUE(e.ok) << e.message;
        EXPECT_EQ(e.n_active, ev.n_active) << what << ": active set changed under the FD step";
        return e.residual;
    };
    const Matrix K_fd = test::central_difference_jacobian(residual, test::stack(u1, u2), fd_step);
    const double err = (K - K_fd).norm() / K_fd.norm();
    EXPECT_TRUE(test::at_most(err, fd_tolerance)) << what;
}

TEST(ContactPair, TwoHalfPassTangentIsDerivative)
{
    const Scene s = make_scene();
    const ContactPair pair({.formulation = Formulation::two_half_pass, .law = NormalLaw::penalty(1e3)}, s.disc, s.block);
    EXPECT_EQ(pair.n_carriers(), 2);
    for (const unsigned seed : {1u, 2u}) {
        const auto [u1, u2] = overlap_state(pair, seed);
        expect_tangent_is_derivative(pair, u1, u2, "two_half_pass seed " + std::to_string(seed));
    }
}

TEST(ContactPair, SinglePassTangentIsSymmetricDerivative)
{
    const Scene s = make_scene();
    const ContactPair pair({.formulation = Formulation::single_pass, .law = NormalLaw::penalty(1e3)}, s.disc, s.block);
    EXPECT_EQ(pair.n_carriers(), 1);
    const auto [u1, u2] = overlap_state(pair, 3);
    expect_tangent_is_derivative(pair, u1, u2, "single_pass");
    const PairEvaluation ev = pair.evaluate(u1, u2, true);
    const Matrix K = test::dense(ev.tangent, pair.n_local_dofs());
    constexpr double symmetry_tolerance = 1e-10;  // Hessian of Pi_c: round-off only
    EXPECT_TRUE(test::at_most((K - K.transpose()).norm() / K.norm(), symmetry_tolerance));
    // Action = reaction: the single pass residual sums to zero per component.
    Vector sum = Vector::Zero(2);
    for (int a = 0; a < pair.n_local_dofs() / 2; ++a)
        sum += ev.residual.segment(2 * a, 2);
    EXPECT_TRUE(test::at_most(sum.norm(), round_off * ev.residual.norm()));
}

TEST(ContactPair, TwoHalfPassTangentIsNotSymmetric)
{
    // Not the Hessian of one potential (docs/theory.md "Contact formulation"): a symmetric solver would be wrong.
    const Scene s = make_scene();
    const ContactPair pair({.formulation = Formulation::two_half_pass, .law = NormalLaw::penalty(1e3)}, s.disc, s.block);
    const auto [u1, u2] = overlap_state(pair, 1);
    const PairEvaluation ev = pair.evaluate(u1, u2, true);
    const Matrix K = test::dense(ev.tangent, pair.n_local_dofs());
    EXPECT_TRUE(test::at_least((K - K.transpose()).norm() / K.norm(), min_asymmetry));
}

TEST(ContactPair, TwoHalfPassIsUnbiasedUnderSwap)
{
    const Scene s = make_scene();
    const PairSettings settings{.formulation = Formulation::two_half_pass, .law = NormalLaw::penalty(1e3)};
    const ContactPair ab(settings, s.disc, s.block);
    const ContactPair ba(settings, s.block, s.disc);
    const auto [u1, u2] = overlap_state(ab, 5);
    const PairEvaluation e_ab = ab.evaluate(u1, u2, true);
    const PairEvaluation e_ba = ba.evaluate(u2, u1, true);
    ASSERT_TRUE(e_ab.ok && e_ba.ok);
    const Index n1 = 2 * ab.n_control_points(0), n2 = 2 * ab.n_control_points(1);
    Vector swapped(n1 + n2);
    swapped << e_ba.residual.tail(n1), e_ba.residual.head(n2);
    // Same Gauss points, same projections (warm starts aside): round-off only.
    constexpr double swap_tolerance = round_off;
    EXPECT_TRUE(test::at_most((swapped - e_ab.residual).norm(), swap_tolerance * e_ab.residual.norm()));
    EXPECT_EQ(e_ab.n_active, e_ba.n_active);
}

TEST(ContactPair, RigidPlaneTangentIsDerivative)
{
    const DeformableSide disc = DeformableSide::make(test::refined_half_disc(8), Side::v0);
    const RigidPlane floor = RigidPlane::make(vec2(0.0, 0.0), vec2(0.05, 1.0));
    for (const Formulation f : {Formulation::two_half_pass, Formulation::single_pass}) {
        const ContactPair pair({.formulation = f, .law = NormalLaw::penalty(1e3)}, disc, floor);
        EXPECT_EQ(pair.n_local_dofs(), 2 * pair.n_control_points(0));
        std::mt19937 rng(7);
        const RowMatrix u1 = test::shifted(pair.n_control_points(0), vec2(0.0, -0.03), noise, rng);
        expect_tangent_is_derivative(pair, u1, RowMatrix(0, 2), "rigid plane");
        const PairEvaluation ev = pair.evaluate(u1, RowMatrix(0, 2), false);
        EXPECT_EQ(ev.projections, 0);
        // The plane pushes the disc up: the total force on the disc -sum r has a positive y.
        double fy = 0.0;
        for (int a = 0; a < pair.n_control_points(0); ++a)
            fy -= ev.residual(2 * a + 1);
        EXPECT_TRUE(test::at_least(fy, 0.0));
    }
    // The rigid obstacle may also be listed first.
    const ContactPair flipped({.law = NormalLaw::penalty(1e3)}, floor, disc);
    EXPECT_EQ(flipped.n_control_points(0), 0);
    std::mt19937 rng(7);
    const RowMatrix u = test::shifted(flipped.n_control_points(1), vec2(0.0, -0.03), noise, rng);
    expect_tangent_is_derivative(flipped, RowMatrix(0, 2), u, "rigid plane first");
}

TEST(ContactPair, FacesTouchingAtRestTakeThePressingBranchOfTheTangent)
{
    // A block resting flush on a wider one: every Gauss point at the kink of <eps g_N>,
    // nothing pressed. Newton's step from there must press the two together, so the
    // tangent is the one-sided derivative of pressing (a finite difference into the
    // press), while the residual stays zero.
    const nurbs::Patch top = nurbs::insert_knots(nurbs::rectangle(vec2(0.5, 1.0), vec2(1.0, 0.5)), 0, {0.25, 0.5, 0.75});
    const nurbs::Patch base = nurbs::insert_knots(nurbs::rectangle(vec2(0.0, 0.0), vec2(2.0, 1.0)), 0, {0.25, 0.5, 0.75});
    for (const Formulation f : {Formulation::two_half_pass, Formulation::single_pass}) {
        SCOPED_TRACE(f == Formulation::two_half_pass ? "two_half_pass" : "single_pass");
        const ContactPair pair({.formulation = f, .law = NormalLaw::penalty(1e3)}, DeformableSide::make(top, Side::v0),
                               DeformableSide::make(base, Side::v1));
        const int n1 = pair.n_control_points(0), n2 = pair.n_control_points(1);
        const RowMatrix rest1 = RowMatrix::Zero(n1, 2), rest2 = RowMatrix::Zero(n2, 2);
        const PairEvaluation ev = pair.evaluate(rest1, rest2, true);
        ASSERT_TRUE(ev.ok) << ev.message;
        EXPECT_EQ(ev.n_active, 0);
        EXPECT_EQ(ev.residual.norm(), 0.0);
        const Matrix K = test::dense(ev.tangent, pair.n_local_dofs());
        ASSERT_GT(K.norm(), 0.0) << "the touching faces' normal stiffness";
        // Pressing the top down by h: the gap is h where the faces overlap, r linear in it.
        RowMatrix press = RowMatrix::Zero(n1, 2);
        press.col(1).setConstant(-1.0);
        const Vector direction = test::stack(press, rest2);
        const double h = 1e-6;
        const auto [a, b] = test::unstack(h * direction, n1, n2);
        const PairEvaluation pressed = pair.evaluate(a, b, false);
        ASSERT_TRUE(pressed.ok) << pressed.message;
        ASSERT_GT(pressed.n_active, 0);
        const Vector slope = pressed.residual / h;
        EXPECT_TRUE(test::at_most((K * direction - slope).norm() / slope.norm(), 1e-6));
        // Lifting it: nothing presses, however the tangent reads the kink.
        const auto [c, e] = test::unstack(-h * direction, n1, n2);
        EXPECT_EQ(pair.evaluate(c, e, false).residual.norm(), 0.0);
    }
    // With friction the pressing branch sticks (the cone's limit as p -> 0+): a press with
    // a shear well inside the cone (0.1 of the press against mu = 0.3) is what the tangent
    // predicts, its tangential force included.
    const ContactPair rough({.law = NormalLaw::penalty(1e3), .friction = {.coefficient = 0.3, .tangential_penalty = 1e3}},
                            DeformableSide::make(top, Side::v0), DeformableSide::make(base, Side::v1));
    const int n1 = rough.n_control_points(0), n2 = rough.n_control_points(1);
    const PairEvaluation ev = rough.evaluate(RowMatrix::Zero(n1, 2), RowMatrix::Zero(n2, 2), true);
    ASSERT_TRUE(ev.ok) << ev.message;
    EXPECT_EQ(ev.residual.norm(), 0.0);
    RowMatrix move = RowMatrix::Zero(n1, 2);
    move.col(0).setConstant(0.1);
    move.col(1).setConstant(-1.0);
    const Vector direction = test::stack(move, RowMatrix::Zero(n2, 2));
    const double h = 1e-6;
    const auto [a, b] = test::unstack(h * direction, n1, n2);
    const PairEvaluation moved = rough.evaluate(a, b, false);
    ASSERT_TRUE(moved.ok) << moved.message;
    const Vector slope = moved.residual / h;
    Vector shear = Vector::Zero(slope.size());  // the x rows: the friction force's share
    for (Index k = 0; k < slope.size(); k += 2)
        shear(k) = slope(k);
    ASSERT_TRUE(test::at_least(shear.norm(), 0.05 * slope.norm())) << "the move must load the friction";
    const Matrix K = test::dense(ev.tangent, rough.n_local_dofs());
    EXPECT_TRUE(test::at_most((K * direction - slope).norm() / slope.norm(), 1e-6));
}

TEST(ContactPair, FarApartDoesNoWork)
{
    const Scene s = make_scene();
    for (const Formulation f : {Formulation::two_half_pass, Formulation::single_pass}) {
        const ContactPair pair({.formulation = f, .law = NormalLaw::penalty(1e3)}, s.disc, s.block);
        std::mt19937 rng(3);
        const RowMatrix u1 = test::shifted(pair.n_control_points(0), vec2(0.0, 10.0), noise, rng);
        const RowMatrix u2 = RowMatrix::Zero(pair.n_control_points(1), 2);
        RunContext ctx;
        const PairEvaluation ev = pair.evaluate(u1, u2, true, &ctx);
        ASSERT_TRUE(ev.ok);
        EXPECT_EQ(ev.projections, 0);
        EXPECT_EQ(ev.candidates, 0);
        EXPECT_EQ(ev.n_active, 0);
        EXPECT_EQ(ev.residual.size(), pair.n_local_dofs());
        EXPECT_EQ(ev.residual.norm(), 0.0);
        EXPECT_TRUE(ev.tangent.empty());
        EXPECT_EQ(ctx.count("projections"), 0);
        // Every Gauss point is reported, as far.
        ASSERT_EQ(static_cast<int>(ev.carriers.size()), pair.n_carriers());
        for (int c = 0; c < pair.n_carriers(); ++c) {
            EXPECT_EQ(static_cast<int>(ev.carriers[c].state.size()), pair.n_gauss_points(c));
            for (const PointState st : ev.carriers[c].state)
                EXPECT_EQ(st, PointState::far);
        }
    }
}

TEST(ContactPair, CountersAndCarriers)
{
    const Scene s = make_scene();
    ContactPair pair({.formulation = Formulation::two_half_pass, .law = NormalLaw::penalty(1e3), .quadrature = 3},
                     s.disc, s.block);
    // 8 spans x 3 points on the disc, 2 spans x 3 points on the block.
    EXPECT_EQ(pair.n_gauss_points(0), 24);
    EXPECT_EQ(pair.n_gauss_points(1), 6);
    const auto [u1, u2] = overlap_state(pair, 1);
    RunContext ctx;
    const PairEvaluation ev = pair.evaluate(u1, u2, false, &ctx);
    pair.adopt(ev.trial);  // the next evaluation warm-starts from this one's feet
    ASSERT_TRUE(ev.ok);
    EXPECT_GT(ev.projections, 0);
    EXPECT_EQ(ctx.count("projections"), ev.projections);
    EXPECT_EQ(ctx.count("contact_candidates"), ev.candidates);
    EXPECT_EQ(ctx.count("projection_iterations"), ev.projection_iterations);
    EXPECT_GE(ev.candidates, ev.projections);
    ASSERT_EQ(ev.carriers.size(), 2u);
    EXPECT_EQ(ev.carriers[0].surface, 0);
    EXPECT_EQ(ev.carriers[1].surface, 1);
    double max_gap = 0.0;
    for (const CarrierResult& c : ev.carriers)
        for (Index g = 0; g < c.gap.size(); ++g) {
            // Pressure is eps <g_N> exactly where the point was projected orthogonally.
            const double expected = c.state[g] == PointState::ok ? 1e3 * std::max(c.gap(g), 0.0) : 0.0;
            EXPECT_TRUE(test::near_rel(c.pressure(g), expected, round_off));
            if (c.state[g] == PointState::ok)
                max_gap = std::max(max_gap, c.gap(g));
            EXPECT_TRUE(test::at_least(c.weight(g), 0.0));
        }
    EXPECT_TRUE(test::near(ev.max_penetration, max_gap, 0.0));
    EXPECT_TRUE(test::at_least(ev.max_penetration, 0.03));  // pushed in by ~0.04

    // Warm starts: a repeated evaluation converges at once and gives the same
    // residual (both foot points are at round-off level).
    const PairEvaluation again = pair.evaluate(u1, u2, false);
    EXPECT_LT(again.projection_iterations, ev.projection_iterations);
    EXPECT_TRUE(test::at_most((again.residual - ev.residual).norm(), round_off * ev.residual.norm()));
}

TEST(ContactPair, NonFiniteDisplacementIsAFailureStatus)
{
    const Scene s = make_scene();
    const ContactPair pair({.law = NormalLaw::penalty(1e3)}, s.disc, s.block);
    RowMatrix u1 = RowMatrix::Zero(pair.n_control_points(0), 2);
    u1(3, 1) = std::numeric_limits<double>::quiet_NaN();
    const PairEvaluation ev = pair.evaluate(u1, RowMatrix::Zero(pair.n_control_points(1), 2), true);
    EXPECT_FALSE(ev.ok);
    EXPECT_FALSE(ev.message.empty());
}

TEST(ContactPair, UnsupportedInputsAreClearErrors)
{
    const Scene s = make_scene();
    const RigidPlane floor = RigidPlane::make(vec2(0, 0), vec2(0, 1));
    EXPECT_THROW(ContactPair({.law = NormalLaw::penalty(1e3)}, floor, floor), Error);
    EXPECT_THROW(ContactPair({.law = NormalLaw::penalty(0.0)}, s.disc, floor), Error);
    VecN p3(3), n3(3);
    p3 << 0, 0, 0;
    n3 << 0, 0, 1;
    EXPECT_THROW(ContactPair({.law = NormalLaw::penalty(1e3)}, s.disc, RigidPlane::make(p3, n3)), Error);
    // A collapsed side (the half disc's u0) cannot carry contact.
    SidePiece collapsed{nurbs::extract_side(test::refined_half_disc(2), Side::u0), 1, {}};
    for (int a = 0; a < collapsed.side.patch.n_control_points(); ++a)
        collapsed.surface_index.push_back(a);
    const int n_collapsed = collapsed.side.patch.n_control_points();
    EXPECT_THROW(ContactPair({.law = NormalLaw::penalty(1e3)}, DeformableSide{{collapsed}, n_collapsed}, floor), Error);
}

}  // namespace
}  // namespace iga::contact

namespace iga::contact {
namespace {

// The tangent comes as one small block per (first-surface element, second-surface
// element) coupling: each coupling once, its dofs those of the two elements, and
// in a state near the reference configuration every coupling met is one that the
// reference search admitted (so a pattern built from candidate_couplings() needs
// no extension at first touch).
TEST(ContactPair, TangentBlocksArePerCouplingAndCandidatesCoverThem)
{
    const Scene s = make_scene();
    for (const Formulation formulation : {Formulation::two_half_pass, Formulation::single_pass}) {
        const ContactPair pair({.formulation = formulation, .law = NormalLaw::penalty(1e3)}, s.disc, s.block);
        const auto [u1, u2] = overlap_state(pair, 7);
        const PairEvaluation ev = pair.evaluate(u1, u2, true);
        ASSERT_TRUE(ev.ok) << ev.message;
        ASSERT_FALSE(ev.tangent.empty());
        const std::vector<Coupling> candidates = pair.candidate_couplings();
        for (std::size_t k = 0; k < ev.tangent.size(); ++k) {
            const LocalBlock& block = ev.tangent[k];
            if (k > 0) {
                EXPECT_LT(ev.tangent[k - 1].element, block.element) << "sorted, each coupling once";
            }
            EXPECT_EQ(block.dofs, pair.coupling_dofs(block.element));
            constexpr int max_element_dofs = 4 * 2;  // sides of degree <= 3: 4 control points x d = 2
            EXPECT_LE(static_cast<int>(block.dofs.size()), 2 * max_element_dofs) << "two elements' dofs at most";
            EXPECT_LT(static_cast<int>(block.dofs.size()), pair.n_local_dofs()) << "never the whole pair";
            EXPECT_TRUE(std::binary_search(candidates.begin(), candidates.end(), block.element))
                << "coupling (" << block.element[0] << ", " << block.element[1] << ") not a reference candidate";
        }
    }
}

}  // namespace
}  // namespace iga::contact

namespace iga::contact {
namespace {

/// evaluate() followed by adopt() of its trial state, as the driver does after every
/// evaluation: the next one warm-starts from it, commit() keeps it.
PairEvaluation evaluate_adopting(ContactPair& pair, const RowMatrix& u1, const RowMatrix& u2, bool need_tangent)
{
    PairEvaluation ev = pair.evaluate(u1, u2, need_tangent);
    pair.adopt(ev.trial);
    return ev;
}

// The Uzawa step at a FIXED state is a closed form: with every point's gap g fixed,
// update k gives lambda_k = <lambda_{k-1} + eps g> = k eps g on the penetrating
// points (0 elsewhere), and the residual then carries p = (k + 1) eps g: exactly
// k + 1 times the penalty residual. Sums of a few O(p W) terms: round-off.
TEST(ContactPair, MultiplierUpdateAtAFixedStateIsExact)
{
    const Scene s = make_scene();
    for (const Formulation f : {Formulation::two_half_pass, Formulation::single_pass}) {
        SCOPED_TRACE(f == Formulation::two_half_pass ? "two_half_pass" : "single_pass");
        ContactPair pair({.formulation = f, .law = NormalLaw::penalty(1e3)}, s.disc, s.block);
        const auto [u1, u2] = overlap_state(pair, 11);
        const PairEvaluation penalty = evaluate_adopting(pair, u1, u2, false);
        ASSERT_TRUE(penalty.ok);
        ASSERT_GE(penalty.n_active, 4);
        for (int c = 0; c < pair.n_carriers(); ++c)
            EXPECT_EQ(pair.multipliers(c).norm(), 0.0) << "multipliers start at 0: the penalty law";

        PairEvaluation state = penalty;
        for (int k = 1; k <= 3; ++k) {
            pair.update_multipliers(state);
            for (int c = 0; c < pair.n_carriers(); ++c) {
                const CarrierResult& cr = penalty.carriers[static_cast<std::size_t>(c)];
                for (Index g = 0; g < cr.gap.size(); ++g) {
                    const double expected = cr.pressure(g) > 0.0 ? k * 1e3 * cr.gap(g) : 0.0;
                    EXPECT_TRUE(test::near(pair.multipliers(c)(g), expected, round_off * (1.0 + expected)))
                        << "update " << k << ", carrier " << c << ", point " << g;
                }
            }
            state = evaluate_adopting(pair, u1, u2, false);
            ASSERT_TRUE(state.ok);
            EXPECT_EQ(state.n_active, penalty.n_active);
            EXPECT_TRUE(test::at_most((state.residual - (k + 1.0) * penalty.residual).norm(),
                                      round_off * (k + 1.0) * penalty.residual.norm()))
                << "update " << k;
        }
    }
}

// Multipliers are state like the warm-start foot points: rollback() returns to
// those of the last commit(), so a cut-back increment restarts from them.
TEST(ContactPair, RollbackRestoresTheCommittedMultipliers)
{
    const Scene s = make_scene();
    ContactPair pair({.formulation = Formulation::two_half_pass, .law = NormalLaw::penalty(1e3)}, s.disc, s.block);
    const auto [u1, u2] = overlap_state(pair, 12);
    pair.update_multipliers(evaluate_adopting(pair, u1, u2, false));
    pair.commit();
    std::vector<Vector> committed;
    for (int c = 0; c < pair.n_carriers(); ++c)
        committed.push_back(pair.multipliers(c));
    const Vector committed_residual = evaluate_adopting(pair, u1, u2, false).residual;

    pair.update_multipliers(evaluate_adopting(pair, u1, u2, false));  // an attempt's updates...
    pair.update_multipliers(evaluate_adopting(pair, u1, u2, false));
    EXPECT_GT((pair.multipliers(0) - committed[0]).norm(), 0.0);
    pair.rollback();  // ...undone by a cutback
    for (int c = 0; c < pair.n_carriers(); ++c)
        EXPECT_EQ((pair.multipliers(c) - committed[static_cast<std::size_t>(c)]).norm(), 0.0) << "carrier " << c;
    EXPECT_EQ((evaluate_adopting(pair, u1, u2, false).residual - committed_residual).norm(), 0.0);
}

// The tangential multipliers (frictional augmented Lagrangian) are state too: after a
// commit with multipliers taken from a sliding state, an attempt's further updates
// are undone by rollback(), which gives back the committed multipliers and with them
// the committed residual bit for bit; and a point open at a commit carries none
// forward. Against a rigid plane (the multiplier in space) and a deformable block (in
// the block's reference space); the disc is first pressed and committed so that every
// touching point has an anchor.
TEST(ContactPair, RollbackRestoresTheCommittedTangentialMultipliers)
{
    const Scene s = make_scene();
    const RigidPlane floor = RigidPlane::make(vec2(0.0, 0.0), vec2(0.0, 1.0));
    const FrictionLaw friction{0.3, 1e3};
    for (const bool rigid : {true, false}) {
        SCOPED_TRACE(rigid ? "rigid plane" : "deformable block");
        ContactPair pair = rigid ? ContactPair({.law = NormalLaw::penalty(1e3), .friction = friction}, s.disc, floor)
                                 : ContactPair({.law = NormalLaw::penalty(1e3), .friction = friction}, s.disc, s.block);
        const RowMatrix u2 = rigid ? RowMatrix(0, 2) : RowMatrix::Zero(pair.n_control_points(1), 2);
        auto disc_at = [&](double x, double y) {
            std::mt19937 rng(14);
            return test::shifted(pair.n_control_points(0), vec2(x, y), noise, rng);
        };
        evaluate_adopting(pair, disc_at(0.0, -0.03), u2, false);
        pair.commit();  // pressed: every pressing point anchored
        const RowMatrix slid = disc_at(0.004, -0.03);
        pair.update_multipliers(evaluate_adopting(pair, slid, u2, false));
        pair.commit();
        std::vector<RowMatrix> committed;
        for (int c = 0; c < pair.n_carriers(); ++c)
            committed.push_back(pair.tangential_multipliers(c));
        ASSERT_GT(committed[0].norm(), 0.0) << "the sliding state carries tangential tractions";
        const Vector committed_residual = evaluate_adopting(pair, slid, u2, false).residual;

        const RowMatrix further = disc_at(0.01, -0.031);
        pair.update_multipliers(evaluate_adopting(pair, further, u2, false));  // an attempt's updates...
        pair.update_multipliers(evaluate_adopting(pair, further, u2, false));
        EXPECT_GT((pair.tangential_multipliers(0) - committed[0]).norm(), 0.0);
        pair.rollback();  // ...undone by a cutback
        for (int c = 0; c < pair.n_carriers(); ++c)
            EXPECT_EQ((pair.tangential_multipliers(c) - committed[static_cast<std::size_t>(c)]).norm(), 0.0)
                << "carrier " << c;
        EXPECT_EQ((evaluate_adopting(pair, slid, u2, false).residual - committed_residual).norm(), 0.0);

        evaluate_adopting(pair, disc_at(0.004, 0.2), u2, false);  // lifted off: every point open
        pair.commit();
        for (int c = 0; c < pair.n_carriers(); ++c)
            EXPECT_EQ(pair.tangential_multipliers(c).norm(), 0.0) << "carrier " << c;
    }
}

// With multipliers from one state, evaluated at a state lifted a little (some
// points open but still active through lambda), the pair tangent is still the
// derivative of its residual; a raised penalty (set_penalty) keeps it so.
TEST(ContactPair, TangentWithMultipliersIsDerivative)
{
    const Scene s = make_scene();
    for (const Formulation f : {Formulation::two_half_pass, Formulation::single_pass}) {
        ContactPair pair({.formulation = f, .law = NormalLaw::penalty(1e3)}, s.disc, s.block);
        const auto [u1, u2] = overlap_state(pair, 13);
        pair.update_multipliers(evaluate_adopting(pair, u1, u2, false));
        RowMatrix lifted = u1;
        lifted.col(1).array() += 0.01;
        expect_tangent_is_derivative(pair, lifted, u2, "multipliers");
        pair.set_penalty(1e4);
        EXPECT_EQ(pair.settings().law.stiffness(), 1e4);
        expect_tangent_is_derivative(pair, lifted, u2, "multipliers, raised penalty");
    }
}

// A point held open (Newton asks for it where the point cycles: docs/solver.md, "A point
// held open") carries no force in either pass, with or without friction, against a
// deformable block and a rigid plane; the tangent stays the residual's derivative, and
// once released the pair gives the residual it gave before, bit for bit.
TEST(ContactPair, AHeldPointCarriesNoForceUntilReleased)
{
    const Scene s = make_scene();
    const RigidPlane floor = RigidPlane::make(vec2(0.0, 0.0), vec2(0.05, 1.0));
    for (const bool rigid : {true, false})
        for (const double mu : {0.0, 0.3}) {
            SCOPED_TRACE(std::string(rigid ? "rigid plane" : "deformable block") + ", mu " + std::to_string(mu));
            const PairSettings settings{.law = NormalLaw::penalty(1e3), .friction = FrictionLaw{mu, 1e3}};
            ContactPair pair = rigid ? ContactPair(settings, s.disc, floor) : ContactPair(settings, s.disc, s.block);
            RowMatrix u1, u2;
            if (rigid) {
                std::mt19937 rng(7);
                u1 = test::shifted(pair.n_control_points(0), vec2(0.0, -0.03), noise, rng);
                u2 = RowMatrix(0, 2);
            } else {
                std::tie(u1, u2) = overlap_state(pair, 5);
            }
            const PairEvaluation free = evaluate_adopting(pair, u1, u2, false);
            const CarrierResult& carrier = free.carriers[0];
            Index pressed = 0;
            while (pressed < carrier.pressure.size() && !(carrier.pressure(pressed) > 0.0))
                ++pressed;
            ASSERT_LT(pressed, carrier.pressure.size()) << "no point presses";
            EXPECT_TRUE(pair.hold_open(0, static_cast<int>(pressed)));
            EXPECT_FALSE(pair.hold_open(0, static_cast<int>(pressed))) << "held already";
            const PairEvaluation held = evaluate_adopting(pair, u1, u2, false);
            EXPECT_EQ(held.carriers[0].pressure(pressed), 0.0);
            EXPECT_EQ(held.n_active, free.n_active - 1);
            if (mu > 0.0) {
                EXPECT_EQ(held.carriers[0].friction.status[static_cast<std::size_t>(pressed)], StickSlip::open);
            }
            EXPECT_GT((held.residual - free.residual).norm(), 0.0);
            expect_tangent_is_derivative(pair, u1, u2, "with a held point");
            pair.release_holds();
            EXPECT_EQ((evaluate_adopting(pair, u1, u2, false).residual - free.residual).norm(), 0.0);
            pair.hold_open(0, static_cast<int>(pressed));
            pair.rollback();  // a cutback frees it too
            EXPECT_FALSE(pair.is_held(0, static_cast<int>(pressed)));
        }
}

}  // namespace
}  // namespace iga::contact
