#include "analysis/run_model.hpp"

#include "analysis/output.hpp"
#include "analysis/solver_choice.hpp"
#include "analysis/warnings.hpp"
#include "assembly/threads.hpp"
#include "core/blas_kernels.hpp"
#include "io/locate.hpp"
#include "version.hpp"

#include <fmt/format.h>

#include <cstdlib>

namespace iga::analysis {

namespace {

/// On several ranks a stop is taken by all ranks together, inside the residual sum
/// (analysis/system.hpp): a rank-local poll would leave one rank alone. Returns the
/// run's stop request and, under MPI, clears the context's own.
StopRequest collective_stop(RunContext& context, const Communicator& comm)
{
    const StopRequest stop = context.stop();
    if (comm.parallel())
        context.set_stop(StopRequest{});
    return stop;
}

Scene timed_scene(const io::Deck& deck, const RunOptions& options, RunContext& context)
{
    ScopedTimer t(&context, "setup");
    Scene built = build_scene(deck, options.refine_levels, context.stop(), options.comm);
    context.log(Verbosity::verbose,
                fmt::format("  set-up (patches, gluing and checks, element geometry, pattern): {:.3g} s", t.elapsed()));
    assembly::limit_library_threads();  // CHOLMOD's OpenMP loops inline: nothing spins
    return built;
}

/// The linear solver of the deck. The PETSc backend checks its options when it is
/// made (core/petsc_options.hpp) and PETSc reads them: a refused option, or a value
/// PETSc rejects (-pc_type bogus), is bad input, named where the user gave it.
std::unique_ptr<solver::LinearSolver> make_solver(const Scene& scene, const solver::NonlinearSystem& nonlinear,
                                                  const Communicator& comm)
{
    const RunSettings& settings = scene.settings;
    const bool petsc = settings.solver.backend == io::SolverBackend::petsc;
    if (petsc && !solver::petsc_available())
        throw DeckError(io::located_issue(settings.source_file, "solver.backend", "petsc",
                                          "this igacontact was built without PETSc (scripts/setup.sh installs it, "
                                          "then rebuild); the suitesparse backend needs nothing else"));
    try {
        return solver::make_linear_solver(linear_solver_policy(scene, nonlinear, comm), comm);
    } catch (const PetscOptionsError& e) {
        // Under mpirun the backend is petsc whatever the deck says: the error says
        // which options it was.
        throw petsc_options_error(settings, e);
    }
}

void log_solver(RunContext& context, const solver::LinearSolver& linear)
{
    context.log(Verbosity::verbose, "  linear solver: " + linear.describe());
    if (const std::string kernels = blas_kernels(); !kernels.empty()) {
        const char* forced = std::getenv("OPENBLAS_CORETYPE");
        context.log(Verbosity::verbose, "  BLAS: OpenBLAS, " + kernels + " kernels" +
                                            (forced ? std::string(" (OPENBLAS_CORETYPE=") + forced + ")" : ""));
    }
}

/// " (loads.0 and loads.2 act on it)": the deck's load items on the bodies of a group.
std::string load_items_text(const Scene& scene, const FreeModeGroup& group)
{
    std::vector<std::string> items;
    const std::vector<std::string>& load_body = scene.settings.load_body;
    for (std::size_t k = 0; k < load_body.size(); ++k)
        for (int b : group.bodies)
            if (load_body[k] == scene.bodies[static_cast<std::size_t>(b)].name)
                items.push_back(fmt::format("loads.{}", k));
    std::string out;
    for (std::size_t k = 0; k < items.size(); ++k)
        out += (k == 0 ? "" : k + 1 == items.size() ? " and " : ", ") + items[k];
    return items.empty() ? std::string() : fmt::format(" ({} act{} on it)", out, items.size() == 1 ? "s" : "");
}

}  // namespace

DeckError petsc_options_error(const RunSettings& settings, const PetscOptionsError& e)
{
    if (e.source() == PetscOptionsSource::deck)
        return DeckError(io::located_issue(settings.source_file, "solver.options", settings.solver.options, e.what()));
    return DeckError(e.environment_issue());
}

RunModel::RunModel(const io::Deck& deck, const RunOptions& options_, RunContext& context_)
    : options(options_), context(context_), stop(collective_stop(context_, options_.comm)),
      scene(timed_scene(deck, options_, context_)), settings(scene.settings),
      system(scene, context_, options_.threads, options_.comm)
{
    system.set_collective_stop(stop);
    // The factorizations' BLAS gets the assembly's cores; under MPI the ranks hold them.
    assembly::set_blas_threads(options.comm.parallel() ? 1 : system.library_threads());
    if (scene.kinematics == mechanics::Kinematics::small) {
        // K0 is all the element quadrature data serve under small kinematics: assembled now, then freed.
        system.assemble_constant_stiffness(context.stop());
        release_element_geometry(scene, [](int) { return false; });
    }
    nonlinear = system.nonlinear_system();
    linear = make_solver(scene, nonlinear, options.comm);
    log_solver(context, *linear);
    open_results();
    write_geometry();
    if (options.threads > assembly::hardware_threads())
        warn({fmt::format("--threads {}: this machine runs {} threads at once, and the run uses {} (more would only "
                          "cost memory)",
                          options.threads, assembly::hardware_threads(), assembly::hardware_threads())});
    warn(scene.setup_warnings);
    warn(duplicate_pair_warnings(scene));
    // An initial overlap is pushed out by the first increment; should that need a
    // cutback, the overlap is released gradually over the first planned increment.
    warn(release_initial_overclosure(scene, system, scene.path.end / std::max(settings.steps.count, 1)));
}

void RunModel::warn(const std::vector<std::string>& lines)
{
    for (const std::string& line : lines) {
        warnings.push_back(line);
        if (options.warning)
            options.warning(line);
    }
}

void RunModel::open_results()
{
    std::string open_error;
    if (options.comm.root()) {
        try {
            writer.emplace(settings.output.file, program_version, settings.resolved_yaml);
        } catch (const Error& e) {
            open_error = e.what();
        }
    }
    open_error = options.comm.first_message(open_error);  // every rank leaves with rank 0's error
    if (!open_error.empty())
        throw io::output_error(settings.source_file, settings.output.file, options.output_origin, open_error);
}

void RunModel::write_geometry()
{
    // ParaView: tessellated bodies (4 cells per span and direction) and an XDMF index.
    constexpr int tessellation_cells_per_span = 4;
    ScopedTimer t(&context, "output");
    if (writer)
        writer->write_bodies(body_geometry(scene));
    if (settings.output.paraview || settings.output.fields)  // fields live on the tessellation points
        for (const BodyModel& body : scene.bodies)
            tessellations.push_back(tessellate(body, tessellation_cells_per_span));
    if (settings.output.paraview && writer) {
        std::vector<io::Tessellation> meshes;
        for (const TessellatedBody& body : tessellations)
            meshes.push_back(body.mesh);
        writer->write_tessellation(meshes);
    }
}

std::optional<std::string> RunModel::hold_free_modes()
{
    // Free rigid-body modes (analysis/free_modes.hpp): named in a warning; loads
    // along one stop the run before any increment, else weak springs hold them.
    free_modes = find_free_modes(scene);
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
                *driven_mode += load_items_text(scene, group);
                break;
            }
    } else {
        std::vector<NodeSpring> springs;
        for (const FreeModeGroup& group : free_modes)
            for (NodeSpring& spring : weak_springs(scene, group))
                springs.push_back(std::move(spring));
        if (!springs.empty())
            system.set_weak_springs(std::move(springs));
    }
    // A body that only contact holds: its first-touch tangents are shifted at once (solver/newton.hpp).
    system.set_singular_without_contact(singular_without_contact(scene, free_modes));
    log_pairs();
    return driven_mode;
}

void RunModel::log_pairs() const
{
    for (const PairModel& p : scene.pairs)
        if (p.penalty_auto)
            context.log(Verbosity::normal, "contact pair '" + p.name + "': penalty auto = " + describe(p.rule));
    for (const PairModel& p : scene.pairs)
        if (const contact::FrictionLaw& law = p.pair.settings().friction; law.active())
            context.log(Verbosity::verbose, fmt::format("  contact pair '{}': Coulomb friction, mu = {:g}, tangential "
                                                        "penalty {:g}{}",
                                                        p.name, law.coefficient, law.tangential_penalty,
                                                        p.augmented ? ", with tangential multipliers" : ""));
}

}  // namespace iga::analysis
