#pragma once
// What a run holds from its set-up to its end (analysis/run.hpp): the scene and its
// system of terms, the linear solver, the results file (rank 0's), the tessellations
// that ParaView and the stress fields are written on, and the warnings so far.
//
// Set-up order: the scene (every deck key is read here: nothing after reads the deck,
// only scene.settings), the system, K0 under small
// kinematics, the linear solver, then the results file: a backend that starts MPI
// (PETSc in a plain run starts a one-rank world, whose helper process inherits open
// files) must not hold the results file open after the run.

#include "analysis/free_modes.hpp"
#include "analysis/run.hpp"
#include "analysis/scene.hpp"
#include "analysis/system.hpp"
#include "analysis/tessellation.hpp"
#include "core/petsc_options.hpp"
#include "io/results_writer.hpp"
#include "solver/linear.hpp"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace iga::analysis {

/// PETSc options refused or rejected (core/petsc_options.hpp) as bad input, located
/// where they were given: the deck's solver.options, or the environment variable.
DeckError petsc_options_error(const RunSettings& settings, const PetscOptionsError& e);

class RunModel {
public:
    /// Builds everything a solve needs; bad input throws DeckError before the results
    /// file exists.
    RunModel(const io::Deck& deck, const RunOptions& options, RunContext& context);
    RunModel(const RunModel&) = delete;
    RunModel& operator=(const RunModel&) = delete;

    /// Names the free rigid-body modes, and holds them with weak springs; returns the
    /// reason the run cannot start when a load drives one of them.
    std::optional<std::string> hold_free_modes();
    /// Keeps warning lines and passes each to RunOptions::warning at once.
    void warn(const std::vector<std::string>& lines);

    const RunOptions& options;
    RunContext& context;
    StopRequest stop;  ///< the run's stop request (under MPI polled by all ranks together)
    Scene scene;
    const RunSettings& settings;  ///< scene.settings: all the run reads of the deck
    SceneSystem system;
    solver::NonlinearSystem nonlinear;
    std::unique_ptr<solver::LinearSolver> linear;
    std::optional<io::ResultsWriter> writer;      ///< rank 0's
    std::vector<TessellatedBody> tessellations;  ///< when output.paraview or output.fields
    std::vector<FreeModeGroup> free_modes;
    std::vector<std::string> warnings;

private:
    void open_results();
    void write_geometry();
    void log_pairs() const;
};

}  // namespace iga::analysis
