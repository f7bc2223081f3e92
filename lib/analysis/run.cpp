#include "analysis/run.hpp"

#include "analysis/failure_advice.hpp"
#include "analysis/increment_steps.hpp"
#include "analysis/output.hpp"
#include "analysis/run_model.hpp"
#include "analysis/warnings.hpp"
#include "io/output_paths.hpp"
#include "io/xdmf_writer.hpp"
#include "solver/failure_cause.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace iga::analysis {

namespace {

solver::NewtonSettings newton_settings(const io::Newton& n)
{
    solver::NewtonSettings s;
    s.tolerance = n.tolerance;
    s.max_iterations = n.max_iterations;
    s.line_search = n.line_search;
    return s;
}

solver::SteppingSettings stepping_settings(const io::Steps& steps, const LoadPath& path)
{
    solver::SteppingSettings s;
    s.path = path;
    s.count = steps.count;
    s.adaptive = steps.adaptive;
    s.max_cutbacks = steps.max_cutbacks;
    return s;
}

/// The linear solver's work, as counters of the run.
void count_linear_statistics(const RunModel& m)
{
    const solver::LinearStatistics statistics = m.linear->statistics();
    m.context.add_count("symbolic_factorizations", statistics.symbolic);
    m.context.add_count("numeric_factorizations", statistics.numeric);
    if (m.scene.kinematics == mechanics::Kinematics::small && m.scene.has_contact() &&
        m.settings.solver.backend == io::SolverBackend::suitesparse && !m.options.comm.parallel())
        m.context.add_count("woodbury_updates", statistics.updates);
    if (statistics.iterations > 0)
        m.context.add_count("linear_iterations", statistics.iterations);
}

/// The warnings only the end of a run can give: raised penalties, the weak springs'
/// share of the energy, and what the last state says of the contact.
void warn_at_end(RunModel& m, const IncrementSteps& steps, const Vector& u)
{
    m.warn(steps.uzawa().notes());
    m.warn(m.linear->warnings());
    const std::optional<io::StepData>& last = steps.last_step();
    if (!last)
        return;
    if (!m.free_modes.empty()) {  // the springs' energy at the last converged state
        const double spring = m.system.spring_energy(u, last->load_factor);
        const double strain = m.system.strain_energy(u, last->load_factor);
        const bool negligible = spring <= negligible_spring_energy * strain;
        m.warn({fmt::format("weak springs on free modes: energy {:.3g}, {} the strain energy {:.3g} ({})", spring,
                            strain > 0.0 ? fmt::format("{:.3g} of", spring / strain) : std::string("against"), strain,
                            negligible ? "negligible"
                                       : fmt::format("NOT negligible, above {:g}: the springs carry load and the "
                                                     "result depends on them",
                                                     negligible_spring_energy))});
    }
    m.warn(m.system.warnings(*last));
}

RunOutcome outcome_of(const RunModel& m, const IncrementSteps& steps, const solver::SteppingResult& result)
{
    RunOutcome outcome;
    if (const std::optional<io::StepData>& last = steps.last_step()) {
        outcome.reactions = last->reactions;
        outcome.contact = last->contact;
        for (const io::ContactPairResult& pair : last->contact)
            if (!pair.obstacle_force.empty())
                outcome.obstacle_forces.emplace_back(pair.name, pair.obstacle_force);
    }
    outcome.warnings = m.warnings;
    outcome.status = result.completed ? "completed" : "failed";
    outcome.message = result.message;
    // Name the cause of a Newton failure, read from its history, and what to change.
    if (!result.completed && !result.stopped && !result.out_of_memory && result.last_failure.status != solver::NewtonStatus::converged)
        outcome.message += failure_advice(solver::failure_cause(result.last_failure),
                                          failure_context(m.scene, steps.last_step() ? &*steps.last_step() : nullptr));
    outcome.results_file = m.settings.output.file;
    outcome.increments = static_cast<int>(result.increments.size());
    outcome.newton_iterations = result.total_iterations;
    outcome.cutbacks = result.total_cutbacks;
    return outcome;
}

long long contact_gauss_points(const Scene& scene)
{
    long long n = 0;
    for (const PairModel& p : scene.pairs)
        for (int c = 0; c < p.pair.n_carriers(); ++c)
            n += p.pair.n_gauss_points(c);
    return n;
}

/// Timings: the solver times all of evaluate() as "assembly"; contact is reported apart.
std::map<std::string, double> timings(const RunContext& context, double total)
{
    const double contact_time = context.time("contact");
    std::map<std::string, double> t;
    t["assembly"] = std::max(0.0, context.time("assembly") - contact_time);
    t["elements"] = context.time("elements");
    t["contact"] = contact_time;
    t["contact_search"] = context.time("contact_search");
    t["projection"] = context.time("projection");
    t["linear_solve"] = context.time("linear_solve");
    t["output"] = context.time("output");
    t["total"] = total;
    return t;
}

io::RunSummary summary_of(RunModel& m, const IncrementSteps& steps, RunOutcome& outcome, double total)
{
    io::RunSummary summary;
    summary.status = outcome.status;
    summary.message = outcome.message;
    for (const std::string& line : m.warnings)
        summary.warnings += (summary.warnings.empty() ? "" : "\n") + line;
    summary.references = references(m.scene, steps.last_step() ? &*steps.last_step() : nullptr);
    for (const io::ReferenceData& r : summary.references)
        for (const auto& [key, value] : r.errors)
            outcome.errors[key] = value;
    outcome.references = summary.references;
    const auto& convergence = steps.convergence();
    summary.convergence.resize(static_cast<Index>(convergence.size()), 4);
    for (std::size_t k = 0; k < convergence.size(); ++k)
        for (int j = 0; j < 4; ++j)
            summary.convergence(static_cast<Index>(k), j) = convergence[k][static_cast<std::size_t>(j)];
    summary.timings = timings(m.context, total);
    for (const auto& [name, count] : m.context.counters())
        summary.counters[name] = count;
    summary.counters["dofs"] = m.scene.dofs->n_full();
    summary.counters["free_dofs"] = m.scene.dofs->n_free();
    summary.counters["increments"] = outcome.increments;
    summary.counters["cutbacks"] = outcome.cutbacks;
    summary.counters["total_newton_iterations"] = outcome.newton_iterations;
    if (steps.uzawa().active())
        summary.counters["uzawa_updates"] = steps.uzawa_updates();
    summary.counters["contact_gauss_points"] = contact_gauss_points(m.scene);
    summary.ranks = m.options.comm.size();
    if (m.options.comm.parallel()) {
        summary.parallel["elements_per_rank"] = m.system.elements_per_rank();
        summary.parallel["couplings_per_rank"] = m.system.couplings_per_rank();
    }
    summary.linear_solver = m.linear->describe();
    return summary;
}

/// The XDMF index of a ParaView run, beside the results file.
void write_xdmf_index(const RunModel& m, const IncrementSteps& steps)
{
    std::vector<io::XdmfMesh> meshes;
    for (const TessellatedBody& t : m.tessellations)
        meshes.push_back({t.mesh.body, t.mesh.points.rows(),
                          static_cast<long long>(t.mesh.cells.size()) / t.mesh.nodes_per_cell, t.mesh.nodes_per_cell,
                          m.settings.output.fields});
    const std::string& file = m.settings.output.file;
    const std::size_t slash = file.find_last_of('/');
    const std::string name = slash == std::string::npos ? file : file.substr(slash + 1);
    io::write_xdmf(io::xdmf_path(file), io::xdmf_text(name, meshes, steps.xdmf_steps()));
}

/// The end of a run: counters, warnings, the results file finished, the outcome.
RunOutcome finish(RunModel& m, IncrementSteps& steps, const solver::SteppingResult& result, const Vector& u,
                  const ScopedTimer& total)
{
    count_linear_statistics(m);
    steps.write_last_step();
    warn_at_end(m, steps, u);
    RunOutcome outcome = outcome_of(m, steps, result);
    const io::RunSummary summary = summary_of(m, steps, outcome, total.elapsed());
    // A stop (SIGINT/SIGTERM) while the results are written: the run did not end as
    // it should, so the file says "failed" (with every increment) and the exit is 1.
    const std::string interrupted_message =
        fmt::format("interrupted (SIGINT/SIGTERM) while the results were written, after increment {} (load factor "
                    "{:.6g}); every converged increment is stored",
                    outcome.increments, steps.last_step() ? steps.last_step()->load_factor : 0.0);
    if (outcome.status == "completed" && m.stop.requested()) {
        outcome.status = "failed";
        outcome.message = interrupted_message;
    }
    if (m.writer) {
        io::RunSummary written = summary;
        written.status = outcome.status;
        written.message = outcome.message;
        if (m.writer->finish(written, [&m] { return m.stop.requested(); }, interrupted_message) != outcome.status) {
            outcome.status = "failed";
            outcome.message = interrupted_message;
        }
    }
    if (m.settings.output.paraview && m.writer) {
        write_xdmf_index(m, steps);
        outcome.numbers["paraview"] = 1;
    }
    outcome.wall_s = total.elapsed();
    outcome.numbers["dofs"] = m.scene.dofs->n_full();
    outcome.numbers["threads"] = m.system.n_threads();
    outcome.numbers["ranks"] = m.options.comm.size();
    outcome.numbers["contact_gauss_points"] = static_cast<double>(contact_gauss_points(m.scene));
    if (steps.uzawa().active())
        outcome.numbers["uzawa_updates"] = static_cast<double>(steps.uzawa_updates());
    return outcome;
}

}  // namespace

RunOutcome run(const io::Deck& deck, const RunOptions& options, RunContext& context)
{
    ScopedTimer total(nullptr, "total");
    RunModel model(deck, options, context);
    IncrementSteps steps(model);
    Vector u = Vector::Zero(model.scene.dofs->n_free());
    solver::SteppingResult result;
    if (const std::optional<std::string> driven_mode = model.hold_free_modes())
        result.message = *driven_mode;  // not completed, no increment
    else {
        solver::SteppingCallbacks callbacks = steps.callbacks();
        try {
            result = solver::run_load_steps(model.nonlinear, u,
                                            stepping_settings(model.settings.steps, model.scene.path),
                                            newton_settings(model.settings.newton), *model.linear, callbacks, &context);
        } catch (const PetscOptionsError& e) {
            // An option PETSc rejects only when it sets up or runs the solver: bad input,
            // as at the start (the results file is abandoned, never renamed).
            throw petsc_options_error(model.settings, e);
        }
    }
    return finish(model, steps, result, u, total);
}

}  // namespace iga::analysis
