// Augmented-Lagrangian contact through the whole solver (enforcement:
// augmented_lagrangian; docs/theory.md "Augmented Lagrangian"), and `penalty: auto`.
//
// Oracles:
//  - one spring: a block (H = 1, E = 1e6, nu = 0) on a rigid plane, its top driven
//    down by Delta: uniaxial, so the bottom is one spring of stiffness k = E/H per
//    unit area in series with the contact law p = lambda + eps g. A solve with
//    multiplier lambda gives g = (k Delta - lambda)/(k + eps); the Uzawa update
//    lambda <- lambda + eps g then gives lambda_n = k Delta (1 - rho^n),
//    rho = k/(k + eps), at every Gauss point (closed form);
//  - contact patch tests (2D and 3D, non-matching): the zero-gap pressure
//    E Delta / H at every Gauss point, whatever the penalty;
//  - Hertz (docs/theory.md "The Hertz benchmark"): with the constraint enforced, the errors of a
//    penalty so stiff that it no longer matters (eps = 1e8, hertz_test.cpp).

#include "analysis/uzawa.hpp"
#include "run_support.hpp"
#include "two_cylinders_auto.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>

namespace iga::test {
namespace {

constexpr double E = 1.0e6, Delta = 0.01, H = 1.0;
constexpr double zero_gap_pressure = E * Delta / H;  // 1e4

/// max_g |p_g / p - 1| (NaN if empty or not finite).
double max_relative_deviation(const std::vector<double>& values, double expected)
{
    if (values.empty())
        return std::nan("");
    double worst = 0.0;
    for (double v : values) {
        const double d = std::abs(v / expected - 1.0);
        if (!std::isfinite(d))
            return std::nan("");
        worst = std::max(worst, d);
    }
    return worst;
}

/// A number as YAML text, all digits (std::to_string would print 1e-12 as 0.000000).
std::string number(double x)
{
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", x);
    return text;
}

/// A one-block deck: [0,1] x [0,1] on a rigid floor y = 0, top driven down by Delta.
std::string one_spring_deck(double penalty, double gap_tolerance, int max_updates = 30)
{
    return "format: 1\n"
           "analysis: {dimension: 2, plane: strain, kinematics: small}\n"
           "materials: [{name: solid, model: linear_elastic, E: 1.0e6, nu: 0.0}]\n"
           "bodies:\n"
           "  - {name: block, material: solid, shape: {type: rectangle, corner: [0, 0], size: [1, 1]},\n"
           "     refine: {elevate: [1, 1], spans: [3, 2]}}\n"
           "  - {name: floor, rigid: {plane: {point: [0, 0], normal: [0, 1]}}}\n"
           "constraints:\n"
           "  - {body: block, side: u0, fix: [x]}\n"
           "  - {body: block, side: v1, displacement: [0.0, -0.01]}\n"
           "contact:\n"
           "  - {name: touch, between: [block.v0, floor], penalty: " +
           number(penalty) +
           ",\n"
           "     enforcement: augmented_lagrangian,\n"
           "     augmented_lagrangian: {gap_tolerance: " +
           number(gap_tolerance) + ", max_updates: " + std::to_string(max_updates) + "}}\n";
}

TEST(AugmentedLagrangian, MultipliersFollowTheOneSpringClosedForm)
{
    // eps = 4 k: rho = 1/5, below the stall ratio 0.25, so the penalty is never raised.
    constexpr double k = E / H, penalty = 4.0 * k, rho = k / (k + penalty);
    // g_n = k Delta rho^n / (k + eps) = 2e-3 / 5^n: 2e-3, 4e-4, 8e-5, 1.6e-5, 3.2e-6:
    // a tolerance of 1e-5 needs exactly four updates.
    constexpr int expected_updates = 4;
    constexpr double gap_tolerance = 1e-5;
    const auto dir = scratch_dir("al_one_spring");
    const auto deck = dir / "spring.yaml";
    std::ofstream(deck) << one_spring_deck(penalty, gap_tolerance);
    const auto file = dir / "spring.h5";
    const analysis::RunOutcome outcome = run_deck(deck.string(), {}, file);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    const Results r(file);

    EXPECT_EQ(r.number("results", "uzawa_updates"), expected_updates);
    EXPECT_EQ(r.reals("history/uzawa_updates"), std::vector<double>{expected_updates});
    const std::string pair = "results/contact/touch";
    EXPECT_EQ(r.text(pair, "enforcement"), "augmented_lagrangian");
    EXPECT_EQ(r.number(pair, "penalty"), penalty) << "not raised";
    EXPECT_EQ(r.number(pair, "gap_tolerance"), gap_tolerance);

    const double lambda = k * Delta * (1.0 - std::pow(rho, expected_updates));
    const double gap = k * Delta * std::pow(rho, expected_updates) / (k + penalty);
    // Newton's 1e-10 relative residual leaves ~1e-10 relative in the uniform state
    // (the contact patch test measures 2e-11); 1e-8 keeps a margin, while one
    // update more or less changes lambda by 1e-3 relative.
    constexpr double closed_form_tolerance = 1e-8;
    const std::string side = pair + "/block.v0/gauss_points/";
    const std::vector<double> multipliers = r.reals(side + "multiplier");
    EXPECT_GE(multipliers.size(), 12u);
    EXPECT_TRUE(at_most(max_relative_deviation(multipliers, lambda), closed_form_tolerance)) << "lambda_4";
    EXPECT_TRUE(at_most(max_relative_deviation(r.reals(side + "gap"), gap), 1e3 * closed_form_tolerance))
        << "g_4 (a difference of displacements ~1e-2 of size 3e-6: three digits fewer)";
    EXPECT_TRUE(at_most(max_relative_deviation(r.reals(side + "pressure"), lambda + penalty * gap),
                        closed_form_tolerance))
        << "p = lambda + eps g";
}

// The safeguard keeps the penalty while the updates are on course. eps = k: rho = 1/2,
// g_n = k Delta rho^n/(k + eps) = 5e-3/2^n, within 1e-5 first at n = 9, well inside 30
// updates. (The former safeguard raised eps tenfold at the second update, since
// rho > 1/4, trading Uzawa updates for a stiffer Newton problem.)
TEST(AugmentedLagrangian, SafeguardKeepsThePenaltyWhileUzawaConverges)
{
    constexpr double k = E / H, penalty = k, rho = k / (k + penalty);
    constexpr int expected_updates = 9;
    constexpr double gap_tolerance = 1e-5;
    const auto dir = scratch_dir("al_safeguard_keeps");
    const auto deck = dir / "spring.yaml";
    std::ofstream(deck) << one_spring_deck(penalty, gap_tolerance);
    const auto file = dir / "spring.h5";
    const analysis::RunOutcome outcome = run_deck(deck.string(), {}, file);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    const Results r(file);
    EXPECT_EQ(r.number("results/contact/touch", "penalty"), penalty) << "not raised";
    EXPECT_EQ(r.number("results", "uzawa_updates"), expected_updates);
    constexpr double closed_form_tolerance = 1e-8;  // as in MultipliersFollowTheOneSpringClosedForm
    const double lambda = k * Delta * (1.0 - std::pow(rho, expected_updates));
    EXPECT_TRUE(at_most(max_relative_deviation(r.reals("results/contact/touch/block.v0/gauss_points/multiplier"),
                                               lambda),
                        closed_form_tolerance));
}

// ... and raises it when they are not: with 5 updates allowed, rho = 1/2 leaves
// g_1 rho^4 = 1.6e-4 > 1e-5, so eps becomes 10 k at the second update (rho = 1/11);
// then lambda_2 = 7500, g = 2.3e-4, 2.1e-5, 1.9e-6: accepted after 4 updates, no cutback.
TEST(AugmentedLagrangian, SafeguardRaisesThePenaltyWhenTheUpdatesLeftCannotSuffice)
{
    constexpr double k = E / H;
    const auto dir = scratch_dir("al_safeguard_raises");
    const auto deck = dir / "spring.yaml";
    std::ofstream(deck) << one_spring_deck(k, 1e-5, 5);
    const auto file = dir / "spring.h5";
    const analysis::RunOutcome outcome = run_deck(deck.string(), {}, file);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    const Results r(file);
    EXPECT_EQ(r.number("results/contact/touch", "penalty"), 10.0 * k);
    EXPECT_EQ(r.number("results", "uzawa_updates"), 4);
    EXPECT_EQ(outcome.cutbacks, 0);
}

TEST(AugmentedLagrangian, StallsOnlyWhenTheRateCannotReachTheTolerance)
{
    using analysis::stalls;
    EXPECT_FALSE(stalls(0.5, 2.5e-3, 1e-5, 29)) << "2.5e-3 / 2^29 is far below";
    EXPECT_TRUE(stalls(0.5, 2.5e-3, 1e-5, 4)) << "2.5e-3 / 16 = 1.6e-4";
    EXPECT_FALSE(stalls(0.5, 2.5e-3, 1e-5, 8)) << "2.5e-3 / 256 = 9.8e-6";
    EXPECT_TRUE(stalls(1.0, 2.5e-3, 1e-5, 100)) << "no progress";
    EXPECT_TRUE(stalls(std::nan(""), 2.5e-3, 1e-5, 100)) << "NaN is a stall";
}

TEST(AugmentedLagrangian, HeldOpenFractionIsTheForceAcrossGapsOpenBeyondTheTolerance)
{
    // Three Gauss points: penetrating, open within the tolerance, open beyond it.
    contact::CarrierResult carrier;
    carrier.gap = (Vector(3) << 1e-3, -1e-6, -1e-2).finished();
    carrier.pressure = (Vector(3) << 2.0, 1.0, 1.0).finished();
    carrier.weight = (Vector(3) << 1.0, 1.0, 2.0).finished();
    contact::PairEvaluation state;
    state.carriers.push_back(carrier);
    // W p: 2 + 1 + 2 = 5, of which the third point's 2 across a gap wider than 1e-4.
    EXPECT_EQ(analysis::held_open_fraction(state, 1e-4), 0.4);
    EXPECT_EQ(analysis::held_open_fraction(contact::PairEvaluation{}, 1e-4), 0.0) << "no force, none held";
}

// Too few updates allowed: the attempt is rejected and cut back, and the multipliers
// return to the committed ones (zero) each time. With g_n(L) = k Delta L rho^n/(k + eps)
// at load factor L and one update, g_1 = 4e-4 L is within 5.05e-5 first at L = 1/8
// (three cutbacks: 1, 1/2, 1/4 rejected); the multipliers there are the closed form
// from ZERO, k Delta L (1 - rho) = 1000. Multipliers left over from the rejected
// attempts (2000 at L = 1/4) would instead open the contact (g < 0), be accepted
// without an update and keep lambda = 2000. (One update: the safeguard, which needs
// two penetrations for a rate, cannot rescue the attempt by a raise.)
TEST(AugmentedLagrangian, RejectedAttemptsAreCutBackWithTheirMultipliersRolledBack)
{
    constexpr double k = E / H, penalty = 4.0 * k, rho = k / (k + penalty);
    constexpr int max_updates = 1, expected_cutbacks = 3;
    constexpr double first_load_factor = 0.125;
    const auto dir = scratch_dir("al_rollback");
    const auto deck = dir / "spring.yaml";
    std::ofstream(deck) << one_spring_deck(penalty, 5.05e-5, max_updates);
    const auto file = dir / "spring.h5";
    const analysis::RunOutcome outcome = run_deck(deck.string(), {}, file);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    const Results r(file);
    const std::string step = "steps/0001";
    EXPECT_EQ(r.number(step, "cutbacks"), expected_cutbacks);
    EXPECT_EQ(r.number(step, "load_factor"), first_load_factor);
    EXPECT_EQ(r.number(step, "uzawa_updates"), max_updates);
    const double lambda = k * Delta * first_load_factor * (1.0 - rho);
    constexpr double closed_form_tolerance = 1e-8;  // as in MultipliersFollowTheOneSpringClosedForm
    EXPECT_TRUE(at_most(max_relative_deviation(r.reals(step + "/contact/touch/block.v0/gauss_points/multiplier"),
                                               lambda),
                        closed_form_tolerance));
    EXPECT_GT(outcome.cutbacks, expected_cutbacks) << "later increments are cut back too";
}

// When cutbacks run out the run fails, naming the pair, the penetration and the tolerance.
TEST(AugmentedLagrangian, UpdatesThatNeverSufficeEndTheRunWithAClearMessage)
{
    const auto dir = scratch_dir("al_max_updates");
    const auto deck = dir / "spring.yaml";
    std::ofstream(deck) << one_spring_deck(4.0 * E / H, 1.0e-12, 1) << "steps: {max_cutbacks: 1}\n";
    const analysis::RunOutcome outcome = run_deck(deck.string(), {}, dir / "spring.h5");
    EXPECT_EQ(outcome.status, "failed");
    for (const char* part : {"the outer loop rejected the solution after 1 cutbacks", "contact pair 'touch'",
                             "above gap_tolerance 1e-12 after 1 Uzawa updates", "allow more updates"})
        EXPECT_NE(outcome.message.find(part), std::string::npos) << part << " in: " << outcome.message;
    EXPECT_EQ(outcome.message.find("round-off"), std::string::npos) << "no penalty hint for an outer-loop failure";
}

/// The 2D contact patch test deck with the augmented Lagrangian at `penalty`.
std::filesystem::path run_patch_2d(const std::string& name, const std::string& penalty, const std::string& formulation)
{
    const auto file = scratch_dir(name) / "patch.h5";
    const analysis::RunOutcome outcome =
        run_deck(source_path("inputs/contact_patch_test_2d.yaml"),
                 {"contact.interface.penalty=" + penalty, "contact.interface.formulation=" + formulation,
                  "contact.interface.enforcement=augmented_lagrangian",
                  "contact.interface.augmented_lagrangian.gap_tolerance=1e-10"},
                 file);
    EXPECT_EQ(outcome.status, "completed") << outcome.message;
    return file;
}

// The issue's bound. A gap of 1e-10 changes the pressure by 1e-10 E/H = 1e-8 relative.
constexpr double zero_gap_tolerance = 1e-6;

TEST(AugmentedLagrangian, ContactPatchTestGivesTheZeroGapPressureAtAnyPenalty)
{
    for (const std::string penalty : {"1.0e4", "1.0e6"}) {
        SCOPED_TRACE("penalty " + penalty);
        const Results r(run_patch_2d("al_patch_" + penalty, penalty, "two_half_pass"));
        ASSERT_EQ(r.text("/", "status"), "completed");
        for (const std::string side : {"upper.v0", "lower.v1"}) {
            const std::string group = "results/contact/interface/" + side;
            const double deviation = max_relative_deviation(r.reals(group + "/gauss_points/pressure"),
                                                            zero_gap_pressure);
            RecordProperty(side + "_deviation_" + penalty, std::to_string(deviation));
            EXPECT_TRUE(at_most(deviation, zero_gap_tolerance)) << side;
            EXPECT_TRUE(near_rel(r.number(group, "normal_force"), zero_gap_pressure, zero_gap_tolerance)) << side;
            EXPECT_TRUE(at_most(r.number(group, "max_penetration"), 1e-10)) << side;
        }
        EXPECT_GT(r.number("results", "uzawa_updates"), 0);
    }
}

// Single pass is not exact pointwise on this mesh (contact_patch_test.cpp), but the
// resultant is the zero-gap force once the constraint holds.
TEST(AugmentedLagrangian, SinglePassPatchTestReachesTheZeroGapResultant)
{
    const Results r(run_patch_2d("al_patch_single", "1.0e6", "single_pass"));
    ASSERT_EQ(r.text("/", "status"), "completed");
    const std::string group = "results/contact/interface/upper.v0";
    EXPECT_TRUE(near_rel(r.number(group, "normal_force"), zero_gap_pressure, zero_gap_tolerance));
    EXPECT_TRUE(at_most(r.number(group, "max_penetration"), 1e-10));
}

TEST(AugmentedLagrangian, ContactPatchTest3dGivesTheZeroGapPressure)
{
    const auto dir = scratch_dir("al_patch_3d");
    const auto deck = dir / "patch3d.yaml";
    std::ofstream(deck) << R"(format: 1
analysis: {dimension: 3, kinematics: small}
materials: [{name: solid, model: linear_elastic, E: 1.0e6, nu: 0.0}]
bodies:
  - {name: lower, material: solid, shape: {type: box, corner: [0, 0, 0], size: [1, 1, 0.5]},
     refine: {elevate: [1, 1, 1], spans: [3, 2, 2]}}
  - {name: upper, material: solid, shape: {type: box, corner: [0, 0, 0.5], size: [1, 1, 0.5]},
     refine: {elevate: [1, 1, 1], spans: [4, 3, 2]}}
constraints:
  - {body: lower, side: w0, fix: [z]}
  - {body: lower, side: u0, fix: [x]}
  - {body: lower, side: v0, fix: [y]}
  - {body: upper, side: u0, fix: [x]}
  - {body: upper, side: v0, fix: [y]}
  - {body: upper, side: w1, displacement: [~, ~, -0.01]}
contact:
  - {name: interface, between: [upper.w0, lower.w1], penalty: 1.0e5, enforcement: augmented_lagrangian,
     augmented_lagrangian: {gap_tolerance: 1.0e-10}}
)";
    const auto file = dir / "patch3d.h5";
    const analysis::RunOutcome outcome = run_deck(deck.string(), {}, file);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    const Results r(file);
    for (const char* side : {"upper.w0", "lower.w1"}) {
        const std::string g = std::string("results/contact/interface/") + side + "/gauss_points/";
        const double deviation = max_relative_deviation(r.reals(g + "pressure"), zero_gap_pressure);
        EXPECT_TRUE(at_most(deviation, zero_gap_tolerance)) << side << ": max relative deviation " << deviation;
    }
}

// ---- Hertz ---------------------------------------------------------------

const std::string hertz_reference = "reference/cyl_floor";

struct HertzErrors {
    double peak, half_width, l2;
};

/// inputs/hertz.yaml with the overrides; the post-processed errors against Hertz.
HertzErrors run_hertz(const std::string& name, const std::vector<std::string>& overrides)
{
    const auto file = scratch_dir(name) / "hertz.h5";
    const analysis::RunOutcome outcome = run_deck(source_path("inputs/hertz.yaml"), overrides, file);
    EXPECT_EQ(outcome.status, "completed") << outcome.message;
    const Results r(file);
    const HertzErrors e{r.number(hertz_reference, "peak"), r.number(hertz_reference, "half_width"),
                        r.number(hertz_reference, "l2")};
    return e;
}

// The issue's bounds: what penalty reaches only at eps = 1e8 (hertz_test.cpp
// measures peak -0.30 %, half-width +1.15 %, L2 0.82 % there; eps = 1e6 fails them
// with -0.62 %, +2.2 %, 1.75 %).
constexpr double peak_tolerance = 0.008;
constexpr double half_width_tolerance = 0.02;
constexpr double l2_tolerance = 0.012;

void expect_within_bounds(const HertzErrors& e)
{
    EXPECT_TRUE(near(e.peak, 0.0, peak_tolerance)) << "peak " << e.peak;
    EXPECT_TRUE(near(e.half_width, 0.0, half_width_tolerance)) << "half-width " << e.half_width;
    EXPECT_TRUE(at_most(e.l2, l2_tolerance)) << "L2 " << e.l2;
}

const std::vector<std::string> augmented{"contact.cyl_floor.enforcement=augmented_lagrangian",
                                         "contact.cyl_floor.penalty=1.0e4"};

TEST(AugmentedLagrangian, HertzAtPenalty1e4ReachesThePenalty1e8Accuracy)
{
    const HertzErrors e = run_hertz("al_hertz_1e4", augmented);
    RecordProperty("peak", std::to_string(e.peak));
    RecordProperty("half_width", std::to_string(e.half_width));
    RecordProperty("l2", std::to_string(e.l2));
    expect_within_bounds(e);
}

// A second mesh: finer graded knots (scripts/hertz_mesh.py 0.003 0.0007, the "fine"
// row of docs/performance.md "What accuracy costs (Hertz)"), where the penalty at 1e8 measures L2 0.64 %.
const std::string fine_graded_mesh =
    "bodies.cylinder.refine.insert=[[0.003,0.006,0.009,0.012,0.015,0.018,0.021,0.024,0.027,0.03,0.033,0.0"
    "36,0.039,0.042,0.045,0.048,0.051,0.054,0.0547,0.0554,0.0561,0.0568,0.0575,0.0582,0.0589,0.0596,0.060"
    "3,0.061,0.0617,0.0624,0.0631,0.0638,0.0645,0.0652,0.0659,0.0666,0.0673,0.068,0.0687,0.0694,0.0701,0."
    "0708,0.0715,0.0722,0.0729,0.0736,0.0743,0.075,0.0757,0.0764,0.0771,0.0778,0.0785,0.0792,0.0799,0.080"
    "6,0.0813,0.082,0.0827,0.0834,0.0841,0.0848,0.0855,0.0862,0.0869,0.0876,0.0883,0.089,0.0897,0.0904,0."
    "0911,0.0918,0.0925,0.0932,0.0939,0.0946,0.0953,0.096,0.0967,0.0974,0.1004,0.1034,0.1064,0.1094,0.112"
    "4,0.1154,0.1184,0.12545,0.130918,0.138299,0.148263,0.161715,0.179876,0.204392,0.237489,0.28217,0.342"
    "49,0.423922,0.533854,0.682263,0.882615],[0.003,0.0069,0.01197,0.018561,0.027129,0.038268,0.052749,0."
    "071573,0.096045,0.127858,0.169216,0.222981,0.292875,0.383738,0.501859,0.655417,0.855042]]";

TEST(AugmentedLagrangian, FineGradedHertzAtPenalty1e4MatchesPenalty1e8)
{
    std::vector<std::string> overrides = augmented;
    overrides.push_back(fine_graded_mesh);
    const HertzErrors al = run_hertz("al_hertz_fine_al", overrides);
    const HertzErrors stiff = run_hertz("al_hertz_fine_1e8", {fine_graded_mesh, "contact.cyl_floor.penalty=1.0e8"});
    RecordProperty("al_l2", std::to_string(al.l2));
    RecordProperty("penalty_1e8_l2", std::to_string(stiff.l2));
    expect_within_bounds(al);
    expect_within_bounds(stiff);
    // Both enforce the constraint to far below the mesh error: the same curve to
    // 0.1 % of p0 in L2 (a penalty of 1e6 differs from them by 1 %).
    constexpr double same_curve = 1e-3;
    EXPECT_TRUE(near(al.l2, stiff.l2, same_curve)) << al.l2 << " vs " << stiff.l2;
}

// The half cylinder of two patches glued at x = 0 (inputs/hertz_two_patches.yaml): a
// C0 patch corner right under the peak, the contact surface spanning both patches
// (one set of multipliers over both pieces). Penalty 1e8 measures peak -0.10 %,
// half-width +1.08 %, L2 0.71 % there.
TEST(AugmentedLagrangian, TwoPatchHertzAtPenalty1e4ReachesThePenalty1e8Accuracy)
{
    const auto file = scratch_dir("al_hertz_two_patches") / "hertz.h5";
    const analysis::RunOutcome outcome =
        run_deck(source_path("inputs/hertz_two_patches.yaml"),
                 {"contact.cyl_floor.enforcement=augmented_lagrangian", "contact.cyl_floor.penalty=1.0e4"}, file);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    const Results r(file);
    expect_within_bounds({r.number(hertz_reference, "peak"), r.number(hertz_reference, "half_width"),
                          r.number(hertz_reference, "l2")});
    EXPECT_GT(r.number("results", "uzawa_updates"), 0);
    EXPECT_FALSE(r.reals("results/contact/cyl_floor/cylinder.arc/gauss_points/multiplier").empty());
}

// ---- penalty: auto ----------------------------------------------------------

TEST(PenaltyAuto, HertzReportsTheRuleAndMeetsTheBounds)
{
    const auto file = scratch_dir("hertz_penalty_auto") / "hertz.h5";
    const analysis::RunOutcome outcome =
        run_deck(source_path("inputs/hertz.yaml"), {"contact.cyl_floor.penalty=auto"}, file);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    const Results r(file);
    const std::string pair = "results/contact/cyl_floor";
    EXPECT_EQ(r.text(pair, "penalty_rule"), "auto");
    // The rule, recomputed from the stored Gauss weights: 4 points per element
    // (degree 2 + 2), each element's reference length the sum of its weights, the
    // side's length l the sum of them all. Against a rigid plane E* = E'.
    const std::vector<double> W = r.reals(pair + "/cylinder.v0/gauss_points/weight");
    ASSERT_EQ(W.size() % 4, 0u);
    double h = std::numeric_limits<double>::infinity(), l = 0.0;
    for (std::size_t e = 0; e < W.size(); e += 4) {
        h = std::min(h, W[e] + W[e + 1] + W[e + 2] + W[e + 3]);
        l += W[e] + W[e + 1] + W[e + 2] + W[e + 3];
    }
    const double E_contact = 1000.0 / (1.0 - 0.3 * 0.3);
    constexpr double kappa_side = 1.0e4, cap = 100.0;  // docs/deck.md
    // The same Gauss rule computes h and l in the solver: round-off of sums of up to 400 terms.
    constexpr double rule_tolerance = 1e-12;
    const double expected = std::min(kappa_side * E_contact / l, cap * E_contact / h);
    EXPECT_TRUE(near_rel(r.number(pair, "penalty"), expected, rule_tolerance))
        << "eps = " << r.number(pair, "penalty") << ", h = " << h << ", l = " << l;
    EXPECT_TRUE(near_rel(r.number(pair, "penalty_side_size"), l, rule_tolerance));
    EXPECT_TRUE(near_rel(r.number(pair, "penalty_hertz_modulus"), E_contact, rule_tolerance));
    EXPECT_EQ(r.number(pair, "penalty"), r.number(pair, "penalty_initial"));
    expect_within_bounds({r.number(hertz_reference, "peak"), r.number(hertz_reference, "half_width"),
                          r.number(hertz_reference, "l2")});
}

TEST(PenaltyAuto, AugmentedLagrangianWithAutoPenaltyMeetsTheBounds)
{
    const HertzErrors e = run_hertz("hertz_penalty_auto_al", {"contact.cyl_floor.penalty=auto",
                                                             "contact.cyl_floor.enforcement=augmented_lagrangian"});
    expect_within_bounds(e);
}

// ---- penalty: auto under refinement (two_cylinders_auto.hpp) ------------------

TEST(PenaltyAuto, TwoCylindersRefinedOnceTakeOneIncrementAtTheFormerAccuracy)
{
    expect_one_increment_and_former_accuracy(run_two_cylinders_auto("two_cyl_auto_l1", "penalty", 1));
}

TEST(PenaltyAuto, TwoCylindersRefinedOnceWithAugmentedLagrangianTakeOneIncrement)
{
    expect_one_increment_and_former_accuracy(run_two_cylinders_auto("two_cyl_auto_al_l1", "augmented_lagrangian", 1));
}

}  // namespace
}  // namespace iga::test
