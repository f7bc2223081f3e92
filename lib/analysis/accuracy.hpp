#pragma once
// `accuracy:` (docs/accuracy_on_demand.md): accuracy on demand. The deck's mesh is level 0; each
// level is a complete run of the deck (its whole load path, replayed from the start: a
// friction history or a load path needs no transfer between meshes), written to
// <results stem>_levels/level<k>.h5. After each level the target quantity is measured
// on the pair's first side that carries Gauss points, compared with the level before
// (level_estimate.hpp), and, while the estimate is above the target and the budget
// allows another level, the spans over and around the contact zone are halved
// (zone_refinement.hpp) and the deck runs again.
//
// The results file is the last completed level's, with /accuracy added: the target, the
// levels (dofs, time, value, estimate, observed order), what each refined, and the
// final `refine.insert` lists as deck text. It is written under a temporary name and
// renamed into place, so a results file that existed is replaced only by a complete one.
// A target that the budget cannot reach ends with status "failed" (exit 1) and the
// estimate reached; the results file then says reached = 0.
//
// The enforcement follows the mesh where the deck asks for `penalty: auto` (chosen from
// each level's element size); a fixed penalty stays, and with it its share of the error.

#include "analysis/run.hpp"

namespace iga::analysis {

/// Runs the levels of deck.accuracy (which must be set). context is copied for each level
/// before any timer runs, so each level's results file has its own timings and counters.
RunOutcome run_to_accuracy(const io::Deck& deck, const RunOptions& options, const RunContext& context);

}  // namespace iga::analysis
