#pragma once
// What the driver does around each increment of the load stepping
// (solver::SteppingCallbacks): the model's terms commit their state after a
// converged increment and roll it back after a failed attempt; the Uzawa loop
// (analysis/uzawa.hpp) judges every converged solve of augmented pairs; and each
// converged increment becomes a step of the results (io::StepData): written at once
// with output.every_step, else only the last one, by write_last_step().
//
// Initial overlap: when the first increment fails against a full initial overlap,
// which a cutback alone would not shrink, the overlap is released gradually from
// then on (contact::ContactPair::release_overlap), with a warning.

#include "analysis/run_model.hpp"
#include "analysis/uzawa.hpp"
#include "io/xdmf_writer.hpp"
#include "solver/load_stepping.hpp"

#include <array>
#include <optional>
#include <vector>

namespace iga::analysis {

class IncrementSteps {
public:
    explicit IncrementSteps(RunModel& model);

    /// The hooks the load stepper calls (they capture this object).
    solver::SteppingCallbacks callbacks();
    /// Without output.every_step: writes the last converged increment.
    void write_last_step();

    const std::optional<io::StepData>& last_step() const { return last_step_; }
    /// (increment, iteration, relative residual, load factor) of every Newton iteration.
    const std::vector<std::array<double, 4>>& convergence() const { return convergence_; }
    const std::vector<io::XdmfStep>& xdmf_steps() const { return xdmf_steps_; }
    long long uzawa_updates() const { return uzawa_updates_; }
    const UzawaLoop& uzawa() const { return uzawa_; }

private:
    void commit();
    void rollback();
    void converged(const solver::IncrementRecord& record, const Vector& state);
    /// The converged state as a results step: contact, reactions, fields.
    io::StepData make_step(const solver::IncrementRecord& record, const Vector& state);
    void report_progress(const solver::IncrementRecord& record) const;
    io::XdmfStep xdmf_step(const io::StepData& step) const;

    RunModel& m_;
    UzawaLoop uzawa_;
    bool committed_any_ = false;
    bool releasing_ = false;
    std::optional<io::StepData> last_step_;
    std::vector<std::array<double, 4>> convergence_;
    std::vector<io::XdmfStep> xdmf_steps_;
    long long uzawa_updates_ = 0;  ///< of the converged increments
};

}  // namespace iga::analysis
