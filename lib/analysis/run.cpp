#include "analysis/run.hpp"

#include "analysis/contact_penalty.hpp"
#include "analysis/failure_advice.hpp"
#include "analysis/fields.hpp"
#include "analysis/free_modes.hpp"
#include "analysis/output.hpp"
#include "analysis/scene.hpp"
#include "analysis/solver_choice.hpp"
#include "analysis/system.hpp"
#include "analysis/tessellation.hpp"
#include "analysis/uzawa.hpp"
#include "analysis/warnings.hpp"
#include "assembly/threads.hpp"
#include "core/blas_kernels.hpp"
#include "io/locate.hpp"
#include "io/output_paths.hpp"
#include "io/results_writer.hpp"
#include "io/xdmf_writer.hpp"
#include "solver/failure_cause.hpp"
#include "solver/linear.hpp"
#include "solver/load_stepping.hpp"
#include "version.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <optional>

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

/// One /history row: the reactions and each contact side's force and penetration.
io::HistoryRow history_row(const io::StepData& step)
{
    io::HistoryRow row;
    row.load_factor = step.load_factor;
    row.uzawa_updates = step.uzawa_updates;
    row.reactions = step.reactions;
    for (const io::ContactPairResult& pair : step.contact)
        for (const io::ContactSideResult& side : pair.sides) {
            const auto penetration = side.attributes.find("max_penetration");
            const auto area = side.attributes.find("contact_area");
            const int d = side.gauss_points.coordinates.cols();
            row.contact.push_back({pair.name, side.side_name, side.normal_force,
                                   penetration == side.attributes.end() ? 0.0 : penetration->second,
                                   side.friction_force.empty() ? std::vector<double>(static_cast<std::size_t>(d), 0.0)
                                                               : side.friction_force,
                                   area == side.attributes.end() ? 0.0 : area->second});
        }
    return row;
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

/// Every deformable body's n_nodes x d displacements (body node numbering, which
/// the tessellations use; a multi-patch body's interface nodes once) at a state.
std::vector<RowMatrix> node_displacements(const Scene& scene, const SceneSystem& system, const Vector& u_free,
                                          double load_factor)
{
    const Vector u_full = scene.dofs->expand(u_free, load_factor);
    std::vector<RowMatrix> out;
    for (std::size_t b = 0; b < scene.bodies.size(); ++b)
        out.push_back(system.body_displacement(u_full, static_cast<int>(b)));
    return out;
}

/// output.fields of every body at converged increment `index` (`u`: node_displacements);
/// points that could not be evaluated hold zeros and are named in `warnings`.
std::vector<io::BodyFields> stress_fields(const Scene& scene, const std::vector<TessellatedBody>& tessellations,
                                          const std::vector<RowMatrix>& u, int index,
                                          std::vector<std::string>& warnings)
{
    std::vector<io::BodyFields> out;
    for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
        FieldsResult r = body_fields(scene.bodies[b], tessellations[b], scene.kinematics, u[b]);
        if (r.n_unevaluated > 0)
            warnings.push_back(fmt::format("increment {}: body '{}': stress not evaluable at {} tessellation "
                                           "point(s) (det F <= 0 there); stored as 0",
                                           index, scene.bodies[b].name, r.n_unevaluated));
        out.push_back(std::move(r.fields));
    }
    return out;
}

/// " (loads.0 and loads.2 act on it)": the deck's load items on the bodies of a group.
std::string load_items_text(const io::Deck& deck, const Scene& scene, const FreeModeGroup& group)
{
    std::vector<std::string> items;
    for (std::size_t k = 0; k < deck.loads.size(); ++k)
        for (int b : group.bodies)
            if (deck.loads[k].body == scene.bodies[static_cast<std::size_t>(b)].name)
                items.push_back(fmt::format("loads.{}", k));
    std::string out;
    for (std::size_t k = 0; k < items.size(); ++k)
        out += (k == 0 ? "" : k + 1 == items.size() ? " and " : ", ") + items[k];
    return items.empty() ? std::string() : fmt::format(" ({} act{} on it)", out, items.size() == 1 ? "s" : "");
}

}  // namespace

RunOutcome run(const io::Deck& deck, const RunOptions& options, RunContext& context)
{
    ScopedTimer total(nullptr, "total");
    const Communicator& comm = options.comm;
    // On several ranks a stop is taken by all ranks together, inside the residual
    // sum (analysis/system.hpp): a rank-local poll would leave one rank alone.
    const StopRequest stop = context.stop();
    if (comm.parallel())
        context.set_stop(StopRequest{});
    Scene scene = [&] {
        ScopedTimer t(&context, "setup");
        Scene built = build_scene(deck, options.refine_levels, context.stop(), comm);
        context.log(Verbosity::verbose, fmt::format("  set-up (patches, gluing and checks, element geometry, "
                                                    "pattern): {:.3g} s", t.elapsed()));
        return built;
    }();
    assembly::limit_library_threads();  // CHOLMOD's OpenMP loops inline: nothing spins
    SceneSystem system(scene, context, options.threads, comm);
    system.set_collective_stop(stop);
    // The factorizations' BLAS gets the assembly's cores; under MPI the ranks hold them.
    assembly::set_blas_threads(comm.parallel() ? 1 : system.library_threads());
    if (scene.kinematics == mechanics::Kinematics::small) {
        // K0 is all the element quadrature data serve under small kinematics: assembled
        // now, then freed.
        system.assemble_constant_stiffness(context.stop());
        release_element_geometry(scene, [](int) { return false; });
    }
    // The linear solver before the results file: a backend that starts MPI (PETSc in a
    // plain run starts a one-rank world, whose helper process inherits open files)
    // must not hold the results file open after the run.
    const solver::NonlinearSystem nonlinear = system.nonlinear_system();
    if (deck.solver.backend == io::SolverBackend::petsc && !solver::petsc_available())
        throw DeckError(io::located_issue(deck.source_file, "solver.backend", "petsc",
                                          "this igacontact was built without PETSc (scripts/setup.sh installs it, "
                                          "then rebuild); the suitesparse backend needs nothing else"));
    const std::unique_ptr<solver::LinearSolver> linear = [&] {
        try {
            return solver::make_linear_solver(linear_solver_policy(deck, scene, nonlinear, comm), comm);
        } catch (const Error& e) {
            // PETSc reads its options when the solver is made: a value it rejects
            // (-ksp_rtol abc) is bad input, named where the user gave it.
            const char* env = deck.solver.backend == io::SolverBackend::petsc ? std::getenv("PETSC_OPTIONS") : nullptr;
            const std::string reason = std::string("PETSc could not set up the solver with these options: ") + e.what();
            if (deck.solver.backend == io::SolverBackend::petsc && !deck.solver.options.empty())
                throw DeckError(io::located_issue(deck.source_file, "solver.options", deck.solver.options, reason));
            if (env && *env) {
                DeckIssue issue;
                issue.where.file = "environment";
                issue.path = "PETSC_OPTIONS";
                issue.value = env;
                issue.reason = reason;
                throw DeckError(std::move(issue));
            }
            throw;
        }
    }();
    context.log(Verbosity::verbose, "  linear solver: " + linear->describe());
    if (const std::string kernels = blas_kernels(); !kernels.empty()) {
        const char* forced = std::getenv("OPENBLAS_CORETYPE");
        context.log(Verbosity::verbose, "  BLAS: OpenBLAS, " + kernels + " kernels" +
                                            (forced ? std::string(" (OPENBLAS_CORETYPE=") + forced + ")" : ""));
    }

    std::optional<io::ResultsWriter> writer;  // rank 0's
    std::string open_error;
    if (comm.root()) {
        try {
            writer.emplace(deck.output.file, program_version, deck.resolved_yaml);
        } catch (const Error& e) {
            open_error = e.what();
        }
    }
    open_error = comm.first_message(open_error);  // every rank leaves with rank 0's error
    if (!open_error.empty())
        throw DeckError(io::located_issue(deck.source_file, "output.file", deck.output.file, open_error));
    // ParaView: tessellated bodies (4 cells per span and direction) and an XDMF index.
    constexpr int tessellation_cells_per_span = 4;
    std::vector<TessellatedBody> tessellations;
    std::vector<io::XdmfStep> xdmf_steps;
    {
        ScopedTimer t(&context, "output");
        if (writer)
            writer->write_bodies(body_geometry(deck, scene));
        if (deck.output.paraview || deck.output.fields)  // fields live on the tessellation points
            for (const BodyModel& body : scene.bodies)
                tessellations.push_back(tessellate(body, tessellation_cells_per_span));
        if (deck.output.paraview) {
            std::vector<io::Tessellation> meshes;
            for (const TessellatedBody& t : tessellations)
                meshes.push_back(t.mesh);
            if (writer)
                writer->write_tessellation(meshes);
        }
    }
    auto xdmf_step = [&](const io::StepData& step) {
        io::XdmfStep x;
        x.index = step.index;
        x.load_factor = step.load_factor;
        for (const io::ContactPairResult& pair : step.contact)
            for (const io::ContactSideResult& side : pair.sides)
                x.sides.push_back({"/steps/" + io::step_group_name(step.index) + "/contact/" + pair.name + "/" +
                                       side.side_name,
                                   pair.name + " " + side.side_name, side.gauss_points.coordinates.rows(),
                                   side.postprocessed.coordinates.rows(), scene.dim, side.postprocessed.grid[1],
                                   side.postprocessed.grid[0], side.postprocessed.patch_grids, side.patch_sides,
                                   side.gauss_points.tangential_traction_vector.size() > 0});
        return x;
    };

    Vector u = Vector::Zero(scene.dofs->n_free());

    std::vector<std::string> warnings;
    auto warn = [&](const std::vector<std::string>& lines) {
        for (const std::string& line : lines) {
            warnings.push_back(line);
            if (options.warning)
                options.warning(line);
        }
    };
    warn(duplicate_pair_warnings(scene));
    // An initial overlap is pushed out by the first increment; should that need a
    // cutback, the overlap is released gradually over the first planned increment.
    warn(release_initial_overclosure(scene, system, scene.path.end / std::max(deck.steps.count, 1)));

    // Free rigid-body modes (analysis/free_modes.hpp): named in a warning; loads
    // along one stop the run before any increment, else weak springs hold them.
    const std::vector<FreeModeGroup> free_modes = find_free_modes(scene);
    for (const FreeModeGroup& group : free_modes)
        warn({fmt::format("{}: no constraint or contact holds it; weak springs (stiffness {:.3g} per node, "
                          "{:g} of E L^(d-2) in all) fix its rigid position",
                          free_mode_text(group), group.spring_stiffness, weak_spring_factor)});
    // Loads are linear in t between breakpoints: checking t = 0 and each breakpoint covers the path.
    std::optional<std::string> driven_mode = driven_free_mode(scene, free_modes, reference_loads(scene, 0.0));
    for (std::size_t k = 0; k < scene.path.breakpoints.size() && !driven_mode; ++k)
        driven_mode = driven_free_mode(scene, free_modes, reference_loads(scene, scene.path.breakpoints[k]));
    if (driven_mode) {
        for (const FreeModeGroup& group : free_modes)
            if (driven_mode->find(group.label + " can") != std::string::npos) {
                *driven_mode += load_items_text(deck, scene, group);
                break;
            }
    } else {
        std::vector<NodeSpring> springs;
        for (const FreeModeGroup& group : free_modes)
            for (NodeSpring& spring : weak_springs(scene, group))
                springs.push_back(std::move(spring));
        system.set_weak_springs(std::move(springs));
    }
    // A body that only contact holds: its first-touch tangents are shifted at once (solver/newton.hpp).
    system.set_singular_without_contact(singular_without_contact(scene, free_modes));

    for (const PairModel& p : scene.pairs)
        if (p.penalty_auto)
            context.log(Verbosity::normal, "contact pair '" + p.name + "': penalty auto = " + describe(p.rule));
    for (const PairModel& p : scene.pairs)
        if (const contact::FrictionLaw& law = p.pair.settings().friction; law.active())
            context.log(Verbosity::verbose, fmt::format("  contact pair '{}': Coulomb friction, mu = {:g}, tangential "
                                                        "penalty {:g}{}",
                                                        p.name, law.coefficient, law.tangential_penalty,
                                                        p.augmented ? ", with tangential multipliers" : ""));

    std::optional<io::StepData> last_step;
    std::vector<std::array<double, 4>> convergence;
    UzawaLoop uzawa(scene, system, context);
    long long total_uzawa_updates = 0;  // of the converged increments
    solver::SteppingCallbacks callbacks;
    bool committed_any = false, releasing = false;
    callbacks.commit = [&] {
        committed_any = true;
        for (PairModel& p : scene.pairs)
            p.pair.commit();
        uzawa.begin_attempt();
    };
    callbacks.rollback = [&] {
        for (PairModel& p : scene.pairs)
            p.pair.rollback();
        uzawa.begin_attempt();
        // The first increment failed against a full initial overlap, which a cutback
        // alone would not shrink: from now on the overlap is released gradually.
        if (!committed_any && !releasing)
            for (PairModel& p : scene.pairs)
                if (p.pair.has_initial_overlap()) {
                    p.pair.release_overlap();
                    releasing = true;
                    warn({fmt::format("contact pair '{}': the first increment did not converge against the full "
                                      "initial overlap; the overlap is now released gradually over the first "
                                      "increment",
                                      p.name)});
                }
    };
    if (uzawa.active())
        callbacks.outer = [&](const Vector& state, double load_factor) {
            return uzawa.after_solve(state, load_factor);
        };
    // Between increments, too, the ranks stop together.
    if (options.stop_requested)
        callbacks.stop_requested = [&] { return comm.any(options.stop_requested()); };
    callbacks.converged = [&](const solver::IncrementRecord& record, const Vector& state) {
        ScopedTimer t(&context, "output");
        io::StepData step = step_data(scene, system, state, record.load_factor, deck.output.samples_per_span);
        step.index = record.index;
        step.newton_iterations = record.report.iterations;
        step.residual_norm = record.report.residual_norm;
        step.cutbacks = record.cutbacks;
        step.wall_s = record.wall_s;
        if (scene.has_contact())
            step.uzawa_updates = record.outer_updates;
        total_uzawa_updates += record.outer_updates;
        for (std::size_t k = 0; k < record.report.residual_history.size(); ++k)
            convergence.push_back({static_cast<double>(record.index), static_cast<double>(k),
                                   record.report.residual_history[k], record.load_factor});
        if (writer)
            writer->append_history(history_row(step));
        // Tessellation and fields work in body nodes: step.displacement lists only
        // the single-patch bodies (multi-patch ones are stored per patch).
        const std::vector<RowMatrix> u_nodes =
            deck.output.paraview || deck.output.fields ? node_displacements(scene, system, state, record.load_factor)
                                                       : std::vector<RowMatrix>{};
        if (deck.output.paraview)
            for (std::size_t b = 0; b < tessellations.size(); ++b)
                step.tessellation_displacement.emplace_back(scene.bodies[b].name,
                                                            tessellation_displacement(tessellations[b], u_nodes[b]));
        if (deck.output.fields) {
            std::vector<std::string> field_warnings;
            step.fields = stress_fields(scene, tessellations, u_nodes, record.index, field_warnings);
            warn(field_warnings);
        }
        if (deck.output.every_step && writer) {
            writer->write_step(step);
            if (deck.output.paraview)
                xdmf_steps.push_back(xdmf_step(step));
        }
        if (scene.has_contact())
            context.log(Verbosity::verbose, fmt::format("  active Gauss points: {}", system.last_active()));
        if (options.progress) {
            std::string line = fmt::format("increment {}/{}: load factor {:.4g}, {} Newton iteration(s)", record.index,
                                           std::max(deck.steps.count, record.index), record.load_factor,
                                           record.report.iterations);
            if (record.cutbacks > 0)
                line += fmt::format(", {} cutback(s)", record.cutbacks);
            if (record.outer_updates > 0)
                line += fmt::format(", {} Uzawa update(s)", record.outer_updates);
            if (scene.has_contact())
                line += fmt::format(", {} active Gauss points", system.last_active());
            options.progress(line);
        }
        last_step = std::move(step);
    };

    solver::SteppingResult result;
    if (driven_mode)
        result.message = *driven_mode;  // not completed, no increment
    else
        result = solver::run_load_steps(nonlinear, u, stepping_settings(deck.steps, scene.path),
                                        newton_settings(deck.newton), *linear, callbacks, &context);

    const solver::LinearStatistics linear_statistics = linear->statistics();
    context.add_count("symbolic_factorizations", linear_statistics.symbolic);
    context.add_count("numeric_factorizations", linear_statistics.numeric);
    if (scene.kinematics == mechanics::Kinematics::small && scene.has_contact() &&
        deck.solver.backend == io::SolverBackend::suitesparse && !comm.parallel())
        context.add_count("woodbury_updates", linear_statistics.updates);
    if (linear_statistics.iterations > 0)
        context.add_count("linear_iterations", linear_statistics.iterations);

    if (!deck.output.every_step && last_step) {
        ScopedTimer t(&context, "output");
        if (writer)
            writer->write_step(*last_step);
        if (deck.output.paraview)
            xdmf_steps.push_back(xdmf_step(*last_step));
    }

    warn(uzawa.notes());
    RunOutcome outcome;
    if (last_step && !free_modes.empty()) {  // the springs' energy at the last converged state
        const double spring = system.spring_energy(u, last_step->load_factor);
        const double strain = system.strain_energy(u, last_step->load_factor);
        const bool negligible = spring <= negligible_spring_energy * strain;
        warn({fmt::format("weak springs on free modes: energy {:.3g}, {} the strain energy {:.3g} ({})", spring,
                          strain > 0.0 ? fmt::format("{:.3g} of", spring / strain) : std::string("against"), strain,
                          negligible ? "negligible"
                                     : fmt::format("NOT negligible, above {:g}: the springs carry load and the "
                                                   "result depends on them",
                                                   negligible_spring_energy))});
    }
    if (last_step) {
        warn(contact_warnings(deck, scene, *last_step));
        outcome.reactions = last_step->reactions;
        for (const io::ContactPairResult& pair : last_step->contact)
            if (!pair.obstacle_force.empty())
                outcome.obstacle_forces.emplace_back(pair.name, pair.obstacle_force);
    }
    outcome.warnings = warnings;
    outcome.status = result.completed ? "completed" : "failed";
    outcome.message = result.message;
    // Name the cause of a Newton failure, read from its history, and what to change.
    if (!result.completed && !result.stopped && result.last_failure.status != solver::NewtonStatus::converged)
        outcome.message += failure_advice(solver::failure_cause(result.last_failure), failure_context(scene));
    outcome.results_file = deck.output.file;
    outcome.increments = static_cast<int>(result.increments.size());
    outcome.newton_iterations = result.total_iterations;
    outcome.cutbacks = result.total_cutbacks;

    io::RunSummary summary;
    summary.status = outcome.status;
    summary.message = outcome.message;
    for (const std::string& line : warnings)
        summary.warnings += (summary.warnings.empty() ? "" : "\n") + line;
    summary.references = references(deck, scene, last_step ? &*last_step : nullptr);
    for (const io::ReferenceData& r : summary.references)
        for (const auto& [key, value] : r.errors)
            outcome.errors[key] = value;
    summary.convergence.resize(static_cast<Index>(convergence.size()), 4);
    for (std::size_t k = 0; k < convergence.size(); ++k)
        for (int j = 0; j < 4; ++j)
            summary.convergence(static_cast<Index>(k), j) = convergence[k][static_cast<std::size_t>(j)];

    // Timings: the solver times all of evaluate() as "assembly"; contact is reported apart.
    const double contact_time = context.time("contact");
    summary.timings["assembly"] = std::max(0.0, context.time("assembly") - contact_time);
    summary.timings["elements"] = context.time("elements");
    summary.timings["contact"] = contact_time;
    summary.timings["contact_search"] = context.time("contact_search");
    summary.timings["projection"] = context.time("projection");
    summary.timings["linear_solve"] = context.time("linear_solve");
    summary.timings["output"] = context.time("output");
    summary.timings["total"] = total.elapsed();
    for (const auto& [name, count] : context.counters())
        summary.counters[name] = count;
    summary.counters["dofs"] = scene.dofs->n_full();
    summary.counters["free_dofs"] = scene.dofs->n_free();
    summary.counters["increments"] = outcome.increments;
    summary.counters["cutbacks"] = outcome.cutbacks;
    summary.counters["total_newton_iterations"] = outcome.newton_iterations;
    if (uzawa.active())
        summary.counters["uzawa_updates"] = total_uzawa_updates;
    long long gauss_points = 0;
    for (const PairModel& p : scene.pairs)
        for (int c = 0; c < p.pair.n_carriers(); ++c)
            gauss_points += p.pair.n_gauss_points(c);
    summary.counters["contact_gauss_points"] = gauss_points;

    summary.ranks = comm.size();
    if (comm.parallel()) {
        summary.parallel["elements_per_rank"] = system.elements_per_rank();
        summary.parallel["couplings_per_rank"] = system.couplings_per_rank();
    }
    summary.linear_solver = linear->describe();
    if (writer)
        writer->finish(summary);
    if (deck.output.paraview && writer) {
        std::vector<io::XdmfMesh> meshes;
        for (const TessellatedBody& t : tessellations)
            meshes.push_back({t.mesh.body, t.mesh.points.rows(),
                              static_cast<long long>(t.mesh.cells.size()) / t.mesh.nodes_per_cell, t.mesh.nodes_per_cell,
                              deck.output.fields});
        const std::string& file = deck.output.file;
        const std::size_t slash = file.find_last_of('/');
        const std::string name = slash == std::string::npos ? file : file.substr(slash + 1);
        io::write_xdmf(io::xdmf_path(file), io::xdmf_text(name, meshes, xdmf_steps));
        outcome.numbers["paraview"] = 1;
    }
    outcome.wall_s = total.elapsed();
    outcome.numbers["dofs"] = scene.dofs->n_full();
    outcome.numbers["threads"] = system.n_threads();
    outcome.numbers["ranks"] = comm.size();
    outcome.numbers["contact_gauss_points"] = static_cast<double>(gauss_points);
    if (uzawa.active())
        outcome.numbers["uzawa_updates"] = static_cast<double>(total_uzawa_updates);
    return outcome;
}

}  // namespace iga::analysis
