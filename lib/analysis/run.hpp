#pragma once
// The driver: deck -> scene -> load steps (Newton) -> results file.
//
//   build_scene -> open the results file (temporary name) -> write bodies ->
//   run_load_steps, writing each converged increment -> references and errors ->
//   finish (status, timings, counters, convergence) -> atomic rename.
//
// Bad input found here (geometry that cannot be built, an output path that
// cannot be written) throws DeckError before anything is written. A failed solve
// is not an exception: the file is written with status "failed" and the message.
// On several ranks every rank runs this same sequence (its collective sums in step),
// and only rank 0 opens and writes the results file.

#include "core/parallel.hpp"
#include "core/run_context.hpp"
#include "io/deck.hpp"
#include "io/output_paths.hpp"
#include "io/results_data.hpp"

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace iga::analysis {

struct RunOptions {
    std::function<bool()> stop_requested;  ///< polled between increments (SIGINT)
    /// Called after each converged increment with a one-line summary (k/N, load
    /// factor, iterations, active Gauss points); the app prints it on a terminal.
    std::function<void(const std::string&)> progress;
    /// Called with each warning (without the "warning: " prefix) as soon as it is found.
    std::function<void(const std::string&)> warning;
    /// Threads of the element assembly: >= 1 exactly that many, 0 automatic
    /// (serial below a work threshold; assembly/threads.hpp).
    int threads = 0;
    /// Uniform h-refinement on top of the deck's: every knot span of every patch is
    /// halved this many times after the deck's own refinement (`--refine-levels`,
    /// the levels of `igacontact study`). 0: the deck as written.
    int refine_levels = 0;
    /// The ranks of the run (core/parallel.hpp): each builds the same scene and
    /// assembles its part; rank 0 writes the results file. One process by default.
    Communicator comm;
    /// Where output.file came from: a results file that cannot be created is reported
    /// there (at the deck's key, "<command line>" for --set, naming -o for -o).
    io::OutputOrigin output_origin = io::OutputOrigin::deck;
};

/// One level of an `accuracy:` run, as the summary reports it (accuracy.hpp).
struct AccuracyLevel {
    int level = 0;
    double dofs = 0.0;
    double wall_s = 0.0;
    double value = 0.0;
    double difference = 0.0;       ///< NaN at level 0
    double estimated_error = 0.0;  ///< NaN at level 0
    double error_bound = 0.0;      ///< NaN at level 0
    double reference_error = 0.0;  ///< NaN without a matching reference
    std::string refined;           ///< what the refinement after it halved ("" for the last)
};

/// What an `accuracy:` run reached (the results' /accuracy, for --summary json).
struct AccuracySummary {
    std::string pair, quantity;
    double target = 0.0;
    bool reached = false;
    double estimated_error = 0.0;  ///< the last level's error bound
    double wall_s = 0.0;           ///< all levels together
    std::vector<AccuracyLevel> levels;
};

struct RunOutcome {
    std::string status;        ///< "completed" or "failed"
    std::string message;
    std::string results_file;
    int increments = 0;
    int newton_iterations = 0;
    int cutbacks = 0;
    double wall_s = 0.0;
    std::map<std::string, double> errors;   ///< against the reference, when the deck asks for one
    std::vector<io::ReferenceData> references;  ///< the references themselves (accuracy.hpp measures against them)
    std::map<std::string, double> numbers;  ///< dofs, gauss points, active points, ...
    std::vector<std::string> warnings;      ///< also in the results' root attribute `warnings`
    std::vector<io::Reaction> reactions;    ///< of the last converged increment
    /// (pair, d-vector) of the last converged increment: force on each rigid obstacle.
    std::vector<std::pair<std::string, std::vector<double>>> obstacle_forces;
    /// Every pair's contact results of the last converged increment (accuracy.hpp measures them).
    std::vector<io::ContactPairResult> contact;
    /// An `accuracy:` run's levels; empty for a plain run (then wall_s etc. are the run's,
    /// else the last level's).
    std::optional<AccuracySummary> accuracy;
};

RunOutcome run(const io::Deck& deck, const RunOptions& options, RunContext& context);

}  // namespace iga::analysis
