#include "analysis/increment_steps.hpp"

#include "analysis/fields.hpp"
#include "analysis/output.hpp"
#include "io/results_writer.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace iga::analysis {

namespace {

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

}  // namespace

IncrementSteps::IncrementSteps(RunModel& model) : m_(model), uzawa_(model.scene, model.system, model.context) {}

solver::SteppingCallbacks IncrementSteps::callbacks()
{
    solver::SteppingCallbacks callbacks;
    callbacks.commit = [this] { commit(); };
    callbacks.rollback = [this] { rollback(); };
    if (uzawa_.active())
        callbacks.outer = [this](const Vector& state, double load_factor) {
            return uzawa_.after_solve(state, load_factor);
        };
    // Between increments, too, the ranks stop together.
    if (m_.options.stop_requested)
        callbacks.stop_requested = [this] { return m_.options.comm.any(m_.options.stop_requested()); };
    callbacks.converged = [this](const solver::IncrementRecord& record, const Vector& state) {
        converged(record, state);
    };
    return callbacks;
}

void IncrementSteps::commit()
{
    committed_any_ = true;
    m_.system.commit();
    uzawa_.begin_attempt();
}

void IncrementSteps::rollback()
{
    m_.system.rollback();
    uzawa_.begin_attempt();
    // The first increment failed against a full initial overlap, which a cutback
    // alone would not shrink: from now on the overlap is released gradually.
    if (committed_any_ || releasing_)
        return;
    for (PairModel& p : m_.scene.pairs)
        if (p.pair.has_initial_overlap()) {
            p.pair.release_overlap();
            releasing_ = true;
            m_.warn({fmt::format("contact pair '{}': the first increment did not converge against the full initial "
                                 "overlap; the overlap is now released gradually over the first increment",
                                 p.name)});
        }
}

void IncrementSteps::converged(const solver::IncrementRecord& record, const Vector& state)
{
    ScopedTimer t(&m_.context, "output");
    io::StepData step = make_step(record, state);
    uzawa_updates_ += record.outer_updates;
    for (std::size_t k = 0; k < record.report.residual_history.size(); ++k)
        convergence_.push_back({static_cast<double>(record.index), static_cast<double>(k),
                                record.report.residual_history[k], record.load_factor});
    if (m_.writer)
        m_.writer->append_history(history_row(step));
    if (m_.settings.output.every_step && m_.writer) {
        m_.writer->write_step(step);
        if (m_.settings.output.paraview)
            xdmf_steps_.push_back(xdmf_step(step));
    }
    if (m_.scene.has_contact())
        m_.context.log(Verbosity::verbose, fmt::format("  active Gauss points: {}", m_.system.last_active()));
    report_progress(record);
    last_step_ = std::move(step);
}

io::StepData IncrementSteps::make_step(const solver::IncrementRecord& record, const Vector& state)
{
    const io::Output& output = m_.settings.output;
    io::StepData step = step_data(m_.scene, m_.system, state, record.load_factor, output.samples_per_span);
    step.index = record.index;
    step.newton_iterations = record.report.iterations;
    step.residual_norm = record.report.residual_norm;
    step.cutbacks = record.cutbacks;
    step.wall_s = record.wall_s;
    if (m_.scene.has_contact())
        step.uzawa_updates = record.outer_updates;
    // Tessellation and fields work in body nodes: step.displacement lists only
    // the single-patch bodies (multi-patch ones are stored per patch).
    const std::vector<RowMatrix> u_nodes = output.paraview || output.fields
                                               ? node_displacements(m_.scene, m_.system, state, record.load_factor)
                                               : std::vector<RowMatrix>{};
    if (output.paraview)
        for (std::size_t b = 0; b < m_.tessellations.size(); ++b)
            step.tessellation_displacement.emplace_back(m_.scene.bodies[b].name,
                                                        tessellation_displacement(m_.tessellations[b], u_nodes[b]));
    if (output.fields) {
        std::vector<std::string> field_warnings;
        step.fields = stress_fields(m_.scene, m_.tessellations, u_nodes, record.index, field_warnings);
        m_.warn(field_warnings);
    }
    return step;
}

void IncrementSteps::report_progress(const solver::IncrementRecord& record) const
{
    if (!m_.options.progress)
        return;
    std::string line = fmt::format("increment {}/{}: load factor {:.4g}, {} Newton iteration(s)", record.index,
                                   std::max(m_.settings.steps.count, record.index), record.load_factor,
                                   record.report.iterations);
    if (record.cutbacks > 0)
        line += fmt::format(", {} cutback(s)", record.cutbacks);
    if (record.outer_updates > 0)
        line += fmt::format(", {} Uzawa update(s)", record.outer_updates);
    if (m_.scene.has_contact())
        line += fmt::format(", {} active Gauss points", m_.system.last_active());
    m_.options.progress(line);
}

void IncrementSteps::write_last_step()
{
    if (m_.settings.output.every_step || !last_step_)
        return;
    ScopedTimer t(&m_.context, "output");
    if (m_.writer)
        m_.writer->write_step(*last_step_);
    if (m_.settings.output.paraview)
        xdmf_steps_.push_back(xdmf_step(*last_step_));
}

io::XdmfStep IncrementSteps::xdmf_step(const io::StepData& step) const
{
    io::XdmfStep x;
    x.index = step.index;
    x.load_factor = step.load_factor;
    for (const io::ContactPairResult& pair : step.contact)
        for (const io::ContactSideResult& side : pair.sides)
            x.sides.push_back({"/steps/" + io::step_group_name(step.index) + "/contact/" + pair.name + "/" +
                                   side.side_name,
                               pair.name + " " + side.side_name, side.gauss_points.coordinates.rows(),
                               side.postprocessed.coordinates.rows(), m_.scene.dim, side.postprocessed.grid[1],
                               side.postprocessed.grid[0], side.postprocessed.patch_grids, side.patch_sides,
                               side.gauss_points.tangential_traction_vector.size() > 0});
    return x;
}

}  // namespace iga::analysis
