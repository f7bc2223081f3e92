#pragma once
// Set-ups that run to the end but are grossly wrong, caught and worded for the
// user (stderr "warning: ..." and the results' root attribute `warnings`):
//  - initial overclosure: contact surfaces that overlap in the reference
//    configuration by more than overclosure_tolerance of the model size (the
//    overlap is released over the load path, contact::ContactPair::set_initial_overlap);
//  - a penetration large against the contact zone (its reference length, or the
//    square root of its area in 3D), against the body, or against the travel
//    imposed by displacements and obstacle motion: the penalty is too soft for
//    the answer to mean much;
//  - two-half-pass sides whose contact forces disagree by more than
//    half_pass_disagreement, or whose pressures differ point-wise by more than
//    half_pass_pressure_apart of the peak, with the cause the run shows: a penalty far stiffer than
//    `penalty: auto` or the augmented Lagrangian (both over-constrain the two half
//    passes), a contact zone held by few pressed Gauss points, or two sides that
//    sample it differently;
//  - two contact pairs that share a patch side on both surfaces (in either order;
//    a named surface counts as its sides, a rigid obstacle as itself): each adds its
//    own contact forces there, so the contact is enforced twice (twice as stiff).
//  - a contact zone only a few knot spans across (resolved_zone_spans);
//  - a body driven into its rigid obstacle by half its thickness or more (a penalty
//    far too soft, a load the contact cannot hold, a side that does not face it).
//  - a boundary side that no pair checks against a rigid obstacle inside that
//    obstacle: the pair names the wrong side, and the body passed into the obstacle.
// A body that starts entirely inside a rigid obstacle is an error, not a warning
// (analysis/obstacles.hpp).

#include "analysis/scene.hpp"
#include "analysis/system.hpp"
#include "io/deck.hpp"
#include "io/results_data.hpp"

#include <string>
#include <vector>

namespace iga::analysis {

/// Overlap at the start beyond this fraction of the model size: round-off of exact
/// geometry (a circle touching a plane) is ~1e-16, a modelling slip is far larger.
constexpr double overclosure_tolerance = 1e-6;
/// Max penetration over the contact zone's size: beyond 5 % the zone itself and
/// the pressure are penalty artefacts (Hertz at kappa = eps a / E* ~ 1 is ~1.5 %).
constexpr double penetration_to_zone = 0.05;
/// Max penetration over the body size: a per-cent of the body is visible overlap.
constexpr double penetration_to_body = 0.01;
/// Max penetration over the imposed travel: a tenth of the travel lost to the penalty.
constexpr double penetration_to_travel = 0.1;
/// Relative disagreement of the two half passes' normal forces (0.35 % on matched
/// two-cylinder meshes): a few per cent flags a real resolution mismatch.
constexpr double half_pass_disagreement = 0.03;
/// The two half passes' post-processed pressures apart at one point by more than this
/// fraction of the peak (results attribute half_pass_pressure_difference): the matched
/// Hertz cylinders are 0.4 % apart, the three-body squeeze 2.9 %; at a tenth a user
/// reading one side's pressure reads a different answer from the other's.
constexpr double half_pass_pressure_apart = 0.1;
/// A penalty above this multiple of `penalty: auto`'s is named as the cause of a
/// half-pass disagreement: on a steel half disc pressed into an aluminium block
/// (tests/analysis/decks/disc_into_block_2d.yaml at 160 spans), 1.7 % with auto's, 6.0 %
/// at 2 times, 9.5 % at 3, 28 % at 5; at 40 spans and 6500 times the disc's Gauss points
/// carried the whole force and the block's none (docs/theory.md, "Two-half-pass balance").
constexpr double stiff_half_pass_penalty = 3.0;
/// Pressed Gauss points per direction of the contact zone (a curve's count, a
/// surface's square root) below which the zone counts as barely resolved: the same
/// deck disagreed by 7.4 % with 2 pressed points a side, 1.7 % with 12 and 14, 0.5 %
/// with 26 and 34, and the two-cylinder Hertz deck (131 a side) by 0.003 %.
constexpr double resolved_zone_points = 20.0;
/// Knot spans across a contact zone (on a side that extends beyond it) below which the
/// zone is reported as under-resolved: a rigid sphere into a cube at a/h ~ 6 had
/// Gauss-point pressures 29 % high; two spheres at a/h ~ 3.5 peaks of 2.4 p0.
constexpr int resolved_zone_spans = 4;
/// A body whose control points reach into a rigid obstacle by more than this fraction
/// of its thickness along the obstacle's normal has been driven through, not stopped:
/// a sound run's penetration is a per-cent of the body at most (penetration_to_body).
constexpr double driven_through = 0.5;
/// A boundary side of a body that no pair checks against a rigid obstacle, inside that
/// obstacle by more than the larger of these (times the deepest penetration of the pairs
/// that do check the body against it, times the body size), has passed into it: a pair
/// that names the wrong side (a disc's side beside its lowest one, which touches the
/// floor only after the disc has sunk 0.29 into it). A side next to a contact side
/// reaches in only where the two meet, as deep as the contact side there.
constexpr double undeclared_depth_to_penetration = 4.0;
constexpr double undeclared_depth_to_body = 1e-3;
/// Contact forces below this fraction of E L^(d-1) (L the body size) are round-off
/// of grazing contact, not a resolved force: no disagreement is reported for them.
constexpr double negligible_contact_force = 1e-8;

/// Warnings about contact pairs that act where an earlier pair acts (see above).
std::vector<std::string> duplicate_pair_warnings(const Scene& scene);

/// The surfaces' overlap at load factor 0 (u = 0): every Gauss point deeper than
/// overclosure_tolerance of the model size gets it as its initial overlap, to be
/// released up to load factor `release_end` if the first increment has to be cut
/// back (ContactPair::release_overlap); one warning per pair that has one.
std::vector<std::string> release_initial_overclosure(Scene& scene, SceneSystem& system, double release_end);

/// What the converged state of one pair says is wrong (ContactTerm::warnings): a
/// penetration too deep for the penalty, two half passes that disagree.
std::vector<std::string> pair_warnings(const Scene& scene, const PairModel& model, const io::ContactPairResult& pair,
                                       double load_factor);

/// Contact zones held by fewer than resolved_zone_spans knot spans across, on a side
/// that extends beyond them, at the converged state of `pair`.
std::vector<std::string> resolution_warnings(const PairModel& model, const io::ContactPairResult& pair);

/// A body driven into its rigid obstacle by more than driven_through of its thickness
/// at the converged state `step` (see above); none for a pair of deformable sides.
std::vector<std::string> driven_through_warnings(const Scene& scene, const PairModel& model, const io::StepData& step);

/// A boundary side of the pair's body (not glued, not on any pair's surface against the
/// pair's rigid obstacle) that lies inside that obstacle at the converged state `step`
/// (see above); none for a pair of deformable sides.
std::vector<std::string> undeclared_contact_warnings(const Scene& scene, const PairModel& model,
                                                     const io::StepData& step);

}  // namespace iga::analysis
