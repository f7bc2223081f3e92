#include "analysis/run.hpp"

#include "analysis/contact_penalty.hpp"
#include "analysis/fields.hpp"
#include "analysis/output.hpp"
#include "analysis/scene.hpp"
#include "analysis/system.hpp"
#include "analysis/tessellation.hpp"
#include "analysis/uzawa.hpp"
#include "analysis/warnings.hpp"
#include "assembly/threads.hpp"
#include "io/locate.hpp"
#include "io/output_paths.hpp"
#include "io/results_writer.hpp"
#include "io/xdmf_writer.hpp"
#include "solver/linear.hpp"
#include "solver/load_stepping.hpp"
#include "version.hpp"

#include <fmt/format.h>

#include <algorithm>
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
            row.contact.push_back({pair.name, side.side_name, side.normal_force,
                                   penetration == side.attributes.end() ? 0.0 : penetration->second});
        }
    return row;
}

solver::SteppingSettings stepping_settings(const io::Steps& steps)
{
    solver::SteppingSettings s;
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

/// output.fields of every body at a converged state (`u`: node_displacements);
/// points that could not be evaluated are reported in the log (they hold zeros).
std::vector<io::BodyFields> stress_fields(const Scene& scene, const std::vector<TessellatedBody>& tessellations,
                                          const std::vector<RowMatrix>& u, RunContext& context)
{
    std::vector<io::BodyFields> out;
    for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
        FieldsResult r = body_fields(scene.bodies[b], tessellations[b], scene.kinematics, u[b]);
        if (r.n_unevaluated > 0)
            context.log(Verbosity::normal,
                        fmt::format("warning: body '{}': stress not evaluable at {} tessellation point(s) "
                                    "(det F <= 0 there); stored as 0",
                                    scene.bodies[b].name, r.n_unevaluated));
        out.push_back(std::move(r.fields));
    }
    return out;
}

}  // namespace

RunOutcome run(const io::Deck& deck, const RunOptions& options, RunContext& context)
{
    ScopedTimer total(nullptr, "total");
    Scene scene = build_scene(deck, options.refine_levels);
    assembly::limit_library_threads();  // CHOLMOD's OpenMP loops inline: nothing spins
    SceneSystem system(scene, context, options.threads);

    std::optional<io::ResultsWriter> writer;
    try {
        writer.emplace(deck.output.file, program_version, deck.resolved_yaml);
    } catch (const Error& e) {
        throw DeckError(io::located_issue(deck.source_file, "output.file", deck.output.file, e.what()));
    }
    // ParaView: tessellated bodies (4 cells per span and direction) and an XDMF index.
    constexpr int tessellation_cells_per_span = 4;
    std::vector<TessellatedBody> tessellations;
    std::vector<io::XdmfStep> xdmf_steps;
    {
        ScopedTimer t(&context, "output");
        writer->write_bodies(body_geometry(deck, scene));
        if (deck.output.paraview || deck.output.fields)  // fields live on the tessellation points
            for (const BodyModel& body : scene.bodies)
                tessellations.push_back(tessellate(body, tessellation_cells_per_span));
        if (deck.output.paraview) {
            std::vector<io::Tessellation> meshes;
            for (const TessellatedBody& t : tessellations)
                meshes.push_back(t.mesh);
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
                                   side.postprocessed.grid[0], side.postprocessed.patch_grids, side.patch_sides});
        return x;
    };

    const solver::NonlinearSystem nonlinear = system.nonlinear_system();
    solver::LinearSolver linear(nonlinear.symmetric ? solver::LinearSolver::Kind::cholesky
                                                    : solver::LinearSolver::Kind::lu);
    if (scene.dim == 3)
        linear.set_ordering(solver::LinearSolver::Ordering::nested_dissection);
    // Small-strain elasticity plus penalty contact against rigid planes (eps N N^T
    // (x) n n^T per Gauss point) is positive semi-definite: a tangent Cholesky refuses
    // is singular (a body held by contact alone before it touches), and the LU that
    // would only find that out again (several Cholesky costs in 3D) is skipped.
    // Curved obstacles (the turning normal adds -p/r (I - n n)) and finite strain
    // can be indefinite and keep the LU fallback.
    const bool only_planes = std::all_of(scene.pairs.begin(), scene.pairs.end(), [](const PairModel& p) {
        if (p.obstacle < 0)
            return false;
        const auto& obstacle = std::get<contact::RigidObstacle>(p.pair.surface(p.obstacle));
        return std::holds_alternative<contact::RigidPlane>(obstacle.shape);
    });
    linear.set_semidefinite(nonlinear.symmetric && scene.kinematics == mechanics::Kinematics::small &&
                            scene.followers.empty() && only_planes);
    Vector u = Vector::Zero(scene.dofs->n_free());
    // Small kinematics with contact: the tangent is the constant elastic stiffness
    // plus the contact stiffness of the active Gauss points, so one factorization
    // serves the following iterations and increments as a reference, and each new
    // tangent is a Woodbury update on the active contact dofs (solver/woodbury.hpp)
    // as long as that costs fewer flops than a factorization (the solver decides).
    if (scene.kinematics == mechanics::Kinematics::small && scene.has_contact())
        linear.set_updates(true);

    std::vector<std::string> warnings;
    auto warn = [&](const std::vector<std::string>& lines) {
        for (const std::string& line : lines) {
            warnings.push_back(line);
            if (options.warning)
                options.warning(line);
        }
    };
    warn(overclosure_warnings(scene, system));

    for (const PairModel& p : scene.pairs)
        if (p.penalty_auto)
            context.log(Verbosity::normal, "contact pair '" + p.name + "': penalty auto = " + describe(p.rule));

    std::optional<io::StepData> last_step;
    std::vector<std::array<double, 4>> convergence;
    UzawaLoop uzawa(scene, system, context);
    long long total_uzawa_updates = 0;  // of the converged increments
    solver::SteppingCallbacks callbacks;
    callbacks.commit = [&] {
        for (PairModel& p : scene.pairs)
            p.pair.commit();
        uzawa.begin_attempt();
    };
    callbacks.rollback = [&] {
        for (PairModel& p : scene.pairs)
            p.pair.rollback();
        uzawa.begin_attempt();
    };
    if (uzawa.active())
        callbacks.outer = [&](const Vector& state, double load_factor) {
            return uzawa.after_solve(state, load_factor);
        };
    callbacks.stop_requested = options.stop_requested;
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
        if (deck.output.fields)
            step.fields = stress_fields(scene, tessellations, u_nodes, context);
        if (deck.output.every_step) {
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

    const solver::SteppingResult result =
        solver::run_load_steps(nonlinear, u, stepping_settings(deck.steps), newton_settings(deck.newton), linear,
                               callbacks, &context);

    context.add_count("symbolic_factorizations", linear.n_symbolic());
    context.add_count("numeric_factorizations", linear.n_numeric());
    if (scene.kinematics == mechanics::Kinematics::small && scene.has_contact())
        context.add_count("woodbury_updates", linear.n_updates());

    if (!deck.output.every_step && last_step) {
        ScopedTimer t(&context, "output");
        writer->write_step(*last_step);
        if (deck.output.paraview)
            xdmf_steps.push_back(xdmf_step(*last_step));
    }

    warn(uzawa.notes());
    RunOutcome outcome;
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
    // Name the cause of a failure with contact. A residual that alternates between two
    // levels is an active-set (or projection) flip-flop, whatever the penalty. Else the
    // usual cause of a stiff failure: a penalty so large against E that the residual's
    // round-off floor (about eps * penalty / E relative) exceeds the tolerance.
    if (!result.completed && scene.has_contact() &&
        result.last_failure.trend == solver::ResidualTrend::two_state_cycle) {
        outcome.message += ". The Newton residual cycles between two states: an active-set (or projection) "
                           "flip-flop, Gauss points entering and leaving contact (or switching the segment they "
                           "project onto) on alternate iterations. Use smaller increments (a larger steps.count) "
                           "or a smaller penalty (about 1e2-1e3 E/h is plenty)";
    } else if (!result.completed && scene.has_contact() &&
               result.last_failure.status != solver::NewtonStatus::converged) {  // not an outer-loop rejection
        double E_min = std::numeric_limits<double>::infinity(), penalty_max = 0.0;
        for (const BodyModel& b : scene.bodies)
            E_min = std::min(E_min, b.material.E);
        for (const PairModel& p : scene.pairs)
            penalty_max = std::max(penalty_max, p.pair.settings().penalty);
        const double floor = std::numeric_limits<double>::epsilon() * penalty_max / E_min;
        if (floor > 0.01 * deck.newton.tolerance)
            outcome.message += fmt::format(
                ". The penalty is {:.3g} times E: in double precision the round-off of the contact forces "
                "(about {:.1g} of the elastic stiffness) swamps the Newton tolerance {:.1g}. Use a smaller penalty "
                "(about 1e2-1e3 E/h is plenty) or a looser newton.tolerance",
                penalty_max / E_min, floor, deck.newton.tolerance);
    }
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

    writer->finish(summary);
    if (deck.output.paraview) {
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
    outcome.numbers["contact_gauss_points"] = static_cast<double>(gauss_points);
    if (uzawa.active())
        outcome.numbers["uzawa_updates"] = static_cast<double>(total_uzawa_updates);
    return outcome;
}

}  // namespace iga::analysis
