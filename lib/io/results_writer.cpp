#include "io/results_writer.hpp"

#include "core/error.hpp"
#include "io/h5_file.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <set>
#include <unistd.h>

namespace iga::io {

namespace {

/// /history, column by column (one entry per append_history call), written by finish().
struct HistoryColumns {
    std::size_t n_rows = 0;
    std::vector<double> load_factor;
    std::vector<int> uzawa_updates;              ///< empty unless the first row had them
    std::vector<std::string> reaction_names;
    std::size_t dimension = 0;                   ///< entries of each reaction vector
    std::vector<std::vector<double>> reactions;  ///< per name, n_rows x dimension, row-major
    std::vector<std::pair<std::string, std::string>> contact_sides;  ///< (pair, side)
    std::vector<std::vector<double>> normal_force;     ///< per contact side, n_rows
    std::vector<std::vector<double>> max_penetration;  ///< per contact side, n_rows
    std::size_t friction_dimension = 0;                ///< entries of each friction force (d)
    std::vector<std::vector<double>> friction_force;   ///< per contact side, n_rows x friction_dimension
    std::vector<std::vector<double>> contact_area;     ///< per contact side, n_rows
};

}  // namespace

struct ResultsWriter::State {
    h5::Handle file;
    HistoryColumns history;
};

namespace {

constexpr const char* format_name = "igacontact-results";
constexpr int format_version = 1;

// Why a file cannot be created at `path`, in words, if the folder is the cause; "" otherwise.
std::string folder_problem(const std::string& path)
{
    namespace fs = std::filesystem;
    fs::path folder = fs::path(path).parent_path();
    if (folder.empty())
        folder = ".";
    std::error_code error;
    if (!fs::exists(folder, error))
        return "folder '" + folder.string() + "' does not exist";
    if (!fs::is_directory(folder, error))
        return "'" + folder.string() + "' is not a folder";
    if (::access(folder.c_str(), W_OK) != 0)
        return "folder '" + folder.string() + "' is not writable";
    // Found here, not at the final rename: else a whole solve would be lost to it.
    if (fs::is_directory(path, error))
        return "'" + path + "' is a folder, not a file";
    // The final rename would replace a device, FIFO or socket by a regular file.
    if (fs::exists(path, error) && !fs::is_regular_file(path, error))
        return "'" + path + "' is a device, FIFO or socket, not a regular file";
    return {};
}

/// degrees, knots/u, knots/v(, knots/w), control_points of one patch into `group`.
void write_patch(hid_t group, const std::string& name, const std::vector<int>& degrees,
                 const std::vector<std::vector<double>>& knot_vectors, const RowMatrix& control_points)
{
    const std::size_t n_directions = degrees.size();
    IGA_CHECK(n_directions >= 1 && n_directions <= 3 && knot_vectors.size() == n_directions,
              "body " + name + ": need one knot vector per degree (1 to 3)");
    h5::write_dataset(group, "degrees", std::span<const int>(degrees));
    h5::Handle knots = h5::create_group(group, "knots");
    constexpr const char* direction_names[] = {"u", "v", "w"};
    for (std::size_t k = 0; k < n_directions; ++k)
        h5::write_dataset(knots.id(), direction_names[k], std::span<const double>(knot_vectors[k]),
                          {static_cast<hsize_t>(knot_vectors[k].size())});
    h5::write_dataset(group, "control_points", control_points);
}

void write_body(hid_t bodies, const BodyGeometry& body)
{
    IGA_CHECK(!body.name.empty(), "a body needs a name");
    h5::Handle group = h5::create_group(bodies, body.name);
    if (body.patches.empty()) {
        write_patch(group.id(), body.name, body.degrees, body.knots, body.control_points);
    } else {
        h5::Handle patches = h5::create_group(group.id(), "patches");
        for (const PatchGeometry& patch : body.patches) {
            h5::Handle patch_group = h5::create_group(patches.id(), patch.name);
            write_patch(patch_group.id(), body.name + "." + patch.name, patch.degrees, patch.knots,
                        patch.control_points);
        }
    }
    if (!body.side_names.empty()) {
        std::vector<std::string> table;
        for (const auto& [name, side] : body.side_names) {
            table.push_back(name);
            table.push_back(side);
        }
        h5::write_string_dataset(group.id(), "side_names", table, {static_cast<hsize_t>(body.side_names.size()), 2});
    }
}

void write_side(hid_t pair, const ContactSideResult& side)
{
    IGA_CHECK(!side.side_name.empty(), "a contact side needs a name (body.side)");
    h5::Handle group = h5::create_group(pair, side.side_name);
    h5::write_attribute(group.id(), "normal_force", side.normal_force);
    if (!side.friction_force.empty())
        h5::write_attribute(group.id(), "friction_force", std::span<const double>(side.friction_force));
    for (const auto& [name, value] : side.attributes)
        h5::write_attribute(group.id(), name, value);

    const GaussPointData& gp = side.gauss_points;
    h5::Handle gauss = h5::create_group(group.id(), "gauss_points");
    h5::write_dataset(gauss.id(), "coordinates", gp.coordinates);
    h5::write_dataset(gauss.id(), "reference_coordinates", gp.reference_coordinates);
    if (gp.parameter.cols() <= 1) {  // 2D: one parameter per point, stored 1-D as results.md says
        const Vector flat = gp.parameter.cols() == 1 ? Vector(gp.parameter.col(0)) : Vector(gp.parameter.rows());
        h5::write_dataset(gauss.id(), "parameter", flat);
    } else {
        h5::write_dataset(gauss.id(), "parameter", gp.parameter);
    }
    h5::write_dataset(gauss.id(), "gap", gp.gap);
    h5::write_dataset(gauss.id(), "pressure", gp.pressure);
    if (gp.weight.size() > 0)
        h5::write_dataset(gauss.id(), "weight", gp.weight);
    if (gp.multiplier.size() > 0)
        h5::write_dataset(gauss.id(), "multiplier", gp.multiplier);
    if (gp.tangential_traction_vector.size() > 0) {
        IGA_CHECK(gp.status.size() == static_cast<std::size_t>(gp.gap.size()),
                  "contact side " + side.side_name + ": one friction status per Gauss point");
        h5::write_dataset(gauss.id(), "tangential_traction", gp.tangential_traction);
        h5::write_dataset(gauss.id(), "tangential_traction_vector", gp.tangential_traction_vector);
        h5::write_dataset(gauss.id(), "status", std::span<const int>(gp.status));
        h5::write_dataset(gauss.id(), "slip_increment", gp.slip_increment);
        h5::write_dataset(gauss.id(), "slip", gp.slip);
        if (gp.elastic_slip.size() > 0)
            h5::write_dataset(gauss.id(), "elastic_slip", gp.elastic_slip);
    }
    if (!side.patch_sides.empty()) {
        IGA_CHECK(gp.patch.size() == static_cast<std::size_t>(gp.gap.size()),
                  "contact side " + side.side_name + ": one patch index per Gauss point");
        h5::write_string_dataset(group.id(), "patch_sides", side.patch_sides, {side.patch_sides.size()});
        h5::write_dataset(gauss.id(), "patch", std::span<const int>(gp.patch));
    }

    const PostProcessedData& pp = side.postprocessed;
    h5::Handle post = h5::create_group(group.id(), "postprocessed");
    h5::write_dataset(post.id(), "control_point_pressure", pp.control_point_pressure);
    h5::write_dataset(post.id(), "coordinates", pp.coordinates);
    h5::write_dataset(post.id(), "reference_coordinates", pp.reference_coordinates);
    h5::write_dataset(post.id(), "pressure", pp.pressure);
    if (pp.tangential_traction_vector.size() > 0) {
        h5::write_dataset(post.id(), "tangential_traction", pp.tangential_traction);
        h5::write_dataset(post.id(), "tangential_traction_vector", pp.tangential_traction_vector);
    }
    if (!pp.patch_grids.empty()) {
        IGA_CHECK(pp.patch_grids.size() == side.patch_sides.size(),
                  "contact side " + side.side_name + ": one sample grid per patch side");
        std::vector<int> shape;
        long long n_s = 0;
        for (const auto& grid : pp.patch_grids) {
            shape.push_back(static_cast<int>(grid[0]));
            shape.push_back(static_cast<int>(grid[1]));
            n_s += grid[0] * grid[1];
        }
        IGA_CHECK(n_s == pp.pressure.size(), "contact side " + side.side_name + ": the patch grids hold every sample");
        h5::write_dataset(post.id(), "patch_grid_shape", std::span<const int>(shape), {pp.patch_grids.size(), 2});
    } else if (pp.grid[0] > 0 && pp.grid[1] > 0) {
        const std::array<double, 2> shape{static_cast<double>(pp.grid[0]), static_cast<double>(pp.grid[1])};
        h5::write_attribute(post.id(), "grid_shape", std::span<const double>(shape));
    }
}

void write_fields(hid_t step, const std::vector<BodyFields>& fields)
{
    h5::Handle group = h5::create_group(step, "fields");
    for (const BodyFields& body : fields) {
        IGA_CHECK(!body.body.empty(), "stress fields need the body's name");
        const Index n = body.reference_coordinates.rows();
        IGA_CHECK(body.displacement.rows() == n && body.stress.rows() == n && body.von_mises.size() == n,
                  "fields of body " + body.body + ": every array needs one row per tessellation point");
        IGA_CHECK(body.stress.cols() == 6, "fields of body " + body.body + ": stress has 6 columns (xx, yy, zz, xy, yz, xz)");
        h5::Handle body_group = h5::create_group(group.id(), body.body);
        h5::write_dataset(body_group.id(), "reference_coordinates", body.reference_coordinates);
        h5::write_dataset(body_group.id(), "displacement", body.displacement);
        h5::write_dataset(body_group.id(), "stress", body.stress);
        h5::write_dataset(body_group.id(), "von_mises", body.von_mises);
    }
}

/// The group that holds the reaction `name` ("block.v0", or "total/block" below
/// the subgroup "total", created on first use), and the dataset's name in it.
std::pair<h5::Handle, std::string> reaction_location(hid_t reactions, const std::string& name)
{
    const std::size_t slash = name.find('/');
    if (slash == std::string::npos)
        return {h5::open_object(reactions, "."), name};
    const std::string subgroup = name.substr(0, slash);
    if (!h5::exists(reactions, subgroup))
        h5::create_group(reactions, subgroup);
    return {h5::open_object(reactions, subgroup), name.substr(slash + 1)};
}

void write_reactions(hid_t step, const std::vector<Reaction>& reactions)
{
    h5::Handle group = h5::create_group(step, "reactions");
    for (const Reaction& reaction : reactions) {
        IGA_CHECK(!reaction.name.empty(), "a reaction needs the name of its side (body.side)");
        const auto [parent, name] = reaction_location(group.id(), reaction.name);
        h5::write_dataset(parent.id(), name, std::span<const double>(reaction.force),
                          {static_cast<hsize_t>(reaction.force.size())});
    }
}

void write_reference(hid_t references, const ReferenceData& reference)
{
    IGA_CHECK(!reference.pair.empty(), "a reference curve needs its pair name");
    h5::Handle group = h5::create_group(references, reference.pair);
    h5::write_dataset(group.id(), "coordinates", reference.coordinates);
    h5::write_dataset(group.id(), "x", reference.x);
    h5::write_dataset(group.id(), "pressure", reference.pressure);

    // inputs and errors share the attribute namespace of the group with the fixed names.
    std::set<std::string> used{"type", "a", "p0", "center", "tangent", "normal"};
    auto write_unique = [&](const std::string& name, double value) {
        IGA_CHECK(used.insert(name).second, "reference " + reference.pair + ": attribute '" + name + "' given twice");
        h5::write_attribute(group.id(), name, value);
    };
    h5::write_attribute(group.id(), "type", reference.type);
    h5::write_attribute(group.id(), "a", reference.a);
    h5::write_attribute(group.id(), "p0", reference.p0);
    for (const auto& [name, value] : reference.inputs)
        write_unique(name, value);
    for (const auto& [name, value] : reference.errors)
        write_unique(name, value);
    if (!reference.center.empty())
        h5::write_attribute(group.id(), "center", std::span<const double>(reference.center));
    if (!reference.tangent.empty())
        h5::write_attribute(group.id(), "tangent", std::span<const double>(reference.tangent));
    if (!reference.normal.empty())
        h5::write_attribute(group.id(), "normal", std::span<const double>(reference.normal));
}

// /history from the columns gathered by append_history (load_factor only, of length 0, without rows).
void write_history(hid_t file, const HistoryColumns& h)
{
    const auto n = static_cast<hsize_t>(h.n_rows);
    h5::Handle group = h5::create_group(file, "history");
    h5::write_dataset(group.id(), "load_factor", std::span<const double>(h.load_factor), {n});
    if (h.uzawa_updates.size() == h.n_rows && h.n_rows > 0)
        h5::write_dataset(group.id(), "uzawa_updates", std::span<const int>(h.uzawa_updates), {n});
    if (!h.reaction_names.empty()) {
        h5::Handle reactions = h5::create_group(group.id(), "reactions");
        for (std::size_t k = 0; k < h.reaction_names.size(); ++k) {
            const auto [parent, name] = reaction_location(reactions.id(), h.reaction_names[k]);
            h5::write_dataset(parent.id(), name, std::span<const double>(h.reactions[k]),
                              {n, static_cast<hsize_t>(h.dimension)});
        }
    }
    if (!h.contact_sides.empty()) {
        h5::Handle contact = h5::create_group(group.id(), "contact");
        for (std::size_t k = 0; k < h.contact_sides.size(); ++k) {
            const auto& [pair, side] = h.contact_sides[k];
            if (!h5::exists(contact.id(), pair))
                h5::create_group(contact.id(), pair);
            h5::Handle pair_group = h5::open_object(contact.id(), pair);
            h5::Handle side_group = h5::create_group(pair_group.id(), side);
            h5::write_dataset(side_group.id(), "normal_force", std::span<const double>(h.normal_force[k]), {n});
            h5::write_dataset(side_group.id(), "max_penetration", std::span<const double>(h.max_penetration[k]), {n});
            h5::write_dataset(side_group.id(), "friction_force", std::span<const double>(h.friction_force[k]),
                              {n, static_cast<hsize_t>(h.friction_dimension)});
            h5::write_dataset(side_group.id(), "contact_area", std::span<const double>(h.contact_area[k]), {n});
        }
    }
}

void flush(hid_t file, const std::string& path)
{
    if (H5Fflush(file, H5F_SCOPE_GLOBAL) < 0)
        h5::throw_error("cannot flush results file " + path);
}

}  // namespace

std::string step_group_name(int index)
{
    IGA_CHECK(index >= 1, "step indices start at 1");
    return fmt::format("{:04d}", index);
}

ResultsWriter::ResultsWriter(std::string final_path, const std::string& program_version,
                             const std::string& resolved_deck)
    : final_path_(std::move(final_path)), temp_path_(final_path_ + ".tmp-" + std::to_string(::getpid()))
{
    h5::ErrorSilencer silence;
    const std::string problem = folder_problem(final_path_);
    if (!problem.empty())
        throw Error("cannot create results file " + final_path_ + ": " + problem);
    auto state = std::make_unique<State>();
    try {
        state->file = h5::create_file(temp_path_);
    } catch (const Error& error) {
        throw Error("cannot create results file " + final_path_ + ": " + error.what());
    }
    state_ = std::move(state);
    try {
        const hid_t file = state_->file.id();
        h5::write_attribute(file, "format", std::string(format_name));
        h5::write_attribute(file, "format_version", format_version);
        h5::write_attribute(file, "program_version", program_version);
        h5::write_attribute(file, "status", std::string("running"));
        h5::write_attribute(file, "message", std::string());
        h5::write_attribute(file, "warnings", std::string());
        h5::write_string_dataset(file, "deck", resolved_deck);
        h5::create_group(file, "steps");
        flush(file, temp_path_);
    } catch (...) {
        abandon();
        throw;
    }
}

ResultsWriter::~ResultsWriter() { abandon(); }

ResultsWriter::ResultsWriter(ResultsWriter&&) noexcept = default;

ResultsWriter& ResultsWriter::operator=(ResultsWriter&& other) noexcept
{
    if (this != &other) {
        abandon();
        final_path_ = std::move(other.final_path_);
        temp_path_ = std::move(other.temp_path_);
        state_ = std::move(other.state_);
    }
    return *this;
}

bool ResultsWriter::is_open() const { return state_ != nullptr; }

void ResultsWriter::write_bodies(const std::vector<BodyGeometry>& bodies)
{
    IGA_CHECK(is_open(), "results file " + final_path_ + " is already closed");
    h5::ErrorSilencer silence;
    const hid_t file = state_->file.id();
    IGA_CHECK(!h5::exists(file, "bodies"), "write_bodies may be called only once");
    h5::Handle group = h5::create_group(file, "bodies");
    for (const BodyGeometry& body : bodies)
        write_body(group.id(), body);
    flush(file, temp_path_);
}

void ResultsWriter::write_tessellation(const std::vector<Tessellation>& bodies)
{
    IGA_CHECK(is_open(), "results file " + final_path_ + " is already closed");
    h5::ErrorSilencer silence;
    const hid_t file = state_->file.id();
    h5::Handle group = h5::create_group(file, "paraview");
    for (const Tessellation& t : bodies) {
        IGA_CHECK(t.nodes_per_cell > 0 && t.cells.size() % static_cast<std::size_t>(t.nodes_per_cell) == 0,
                  "tessellation cells do not match nodes_per_cell");
        h5::Handle body = h5::create_group(group.id(), t.body);
        h5::write_dataset(body.id(), "points", t.points);
        h5::write_dataset(body.id(), "cells", std::span<const int>(t.cells),
                          {static_cast<hsize_t>(t.cells.size() / static_cast<std::size_t>(t.nodes_per_cell)),
                           static_cast<hsize_t>(t.nodes_per_cell)});
    }
    flush(file, temp_path_);
}

void ResultsWriter::write_step(const StepData& step)
{
    IGA_CHECK(is_open(), "results file " + final_path_ + " is already closed");
    h5::ErrorSilencer silence;
    const hid_t file = state_->file.id();
    const std::string name = step_group_name(step.index);
    IGA_CHECK(!h5::exists(file, "steps/" + name), "step " + name + " written twice");
    {
        // Built unlinked and flushed before it is linked into /steps: HDF5 is not
        // crash-safe, and a run killed while writing a linked group left a /steps
        // entry pointing past the end of the file. Now a kill leaves at most an
        // unreachable group, and /steps lists complete increments only.
        h5::Handle group(H5Gcreate_anon(file, H5P_DEFAULT, H5P_DEFAULT), H5Gclose, "cannot create steps/" + name);
        h5::write_attribute(group.id(), "load_factor", step.load_factor);
        h5::write_attribute(group.id(), "newton_iterations", step.newton_iterations);
        h5::write_attribute(group.id(), "residual_norm", step.residual_norm);
        h5::write_attribute(group.id(), "cutbacks", step.cutbacks);
        h5::write_attribute(group.id(), "wall_s", step.wall_s);
        if (step.uzawa_updates >= 0)
            h5::write_attribute(group.id(), "uzawa_updates", step.uzawa_updates);

        h5::Handle displacement = h5::create_group(group.id(), "displacement");
        for (const auto& [body, values] : step.displacement)
            h5::write_dataset(displacement.id(), body, values);
        for (const auto& [body, patches] : step.patch_displacement) {
            h5::Handle body_group = h5::create_group(displacement.id(), body);
            for (const auto& [patch, values] : patches)
                h5::write_dataset(body_group.id(), patch, values);
        }

        h5::Handle contact = h5::create_group(group.id(), "contact");
        for (const ContactPairResult& pair : step.contact) {
            h5::Handle pair_group = h5::create_group(contact.id(), pair.name);
            for (const auto& [attribute, value] : pair.attributes)
                h5::write_attribute(pair_group.id(), attribute, value);
            for (const auto& [attribute, text] : pair.text_attributes)
                h5::write_attribute(pair_group.id(), attribute, text);
            if (!pair.obstacle_force.empty())
                h5::write_attribute(pair_group.id(), "obstacle_force", std::span<const double>(pair.obstacle_force));
            for (const ContactSideResult& side : pair.sides)
                write_side(pair_group.id(), side);
        }
        if (!step.tessellation_displacement.empty()) {
            h5::Handle paraview = h5::create_group(group.id(), "paraview");
            for (const auto& [body, values] : step.tessellation_displacement) {
                h5::Handle body_group = h5::create_group(paraview.id(), body);
                h5::write_dataset(body_group.id(), "displacement", values);
            }
        }
        if (!step.reactions.empty())
            write_reactions(group.id(), step.reactions);
        if (!step.fields.empty())
            write_fields(group.id(), step.fields);
        flush(file, temp_path_);
        if (H5Olink(group.id(), file, ("steps/" + name).c_str(), H5P_DEFAULT, H5P_DEFAULT) < 0)
            h5::throw_error("cannot link steps/" + name + " in results file " + temp_path_);
    }
    h5::replace_hard_link(file, "steps/" + name, "results");
    flush(file, temp_path_);
}

void ResultsWriter::append_history(const HistoryRow& row)
{
    IGA_CHECK(is_open(), "results file " + final_path_ + " is already closed");
    HistoryColumns& h = state_->history;
    if (h.n_rows == 0) {
        for (const Reaction& reaction : row.reactions) {
            IGA_CHECK(!reaction.name.empty(), "a history reaction needs the name of its side (body.side)");
            h.reaction_names.push_back(reaction.name);
        }
        h.dimension = row.reactions.empty() ? 0 : row.reactions.front().force.size();
        h.reactions.assign(row.reactions.size(), {});
        for (const HistoryRow::ContactSide& side : row.contact) {
            IGA_CHECK(!side.pair.empty() && !side.side.empty(), "a history contact side needs its pair and side");
            h.contact_sides.emplace_back(side.pair, side.side);
        }
        h.normal_force.assign(row.contact.size(), {});
        h.max_penetration.assign(row.contact.size(), {});
        h.friction_force.assign(row.contact.size(), {});
        h.contact_area.assign(row.contact.size(), {});
        h.friction_dimension = row.contact.empty() ? 0 : row.contact.front().friction_force.size();
    }
    IGA_CHECK(row.reactions.size() == h.reaction_names.size() && row.contact.size() == h.contact_sides.size(),
              "every /history row has the reactions and contact sides of the first");
    for (std::size_t k = 0; k < row.reactions.size(); ++k) {
        IGA_CHECK(row.reactions[k].name == h.reaction_names[k] && row.reactions[k].force.size() == h.dimension,
                  "history row " + std::to_string(h.n_rows + 1) + ": reaction '" + row.reactions[k].name +
                      "' does not match the first row's '" + h.reaction_names[k] + "'");
        h.reactions[k].insert(h.reactions[k].end(), row.reactions[k].force.begin(), row.reactions[k].force.end());
    }
    for (std::size_t k = 0; k < row.contact.size(); ++k) {
        IGA_CHECK(row.contact[k].pair == h.contact_sides[k].first && row.contact[k].side == h.contact_sides[k].second,
                  "history row " + std::to_string(h.n_rows + 1) + ": contact side '" + row.contact[k].pair + "/" +
                      row.contact[k].side + "' does not match the first row's");
        h.normal_force[k].push_back(row.contact[k].normal_force);
        h.max_penetration[k].push_back(row.contact[k].max_penetration);
        IGA_CHECK(row.contact[k].friction_force.size() == h.friction_dimension,
                  "history row " + std::to_string(h.n_rows + 1) + ": a friction force needs d components");
        h.friction_force[k].insert(h.friction_force[k].end(), row.contact[k].friction_force.begin(),
                                   row.contact[k].friction_force.end());
        h.contact_area[k].push_back(row.contact[k].contact_area);
    }
    IGA_CHECK((row.uzawa_updates >= 0) == (h.n_rows == 0 ? row.uzawa_updates >= 0 : !h.uzawa_updates.empty()),
              "every /history row has uzawa_updates, or none has");
    if (row.uzawa_updates >= 0)
        h.uzawa_updates.push_back(row.uzawa_updates);
    h.load_factor.push_back(row.load_factor);
    ++h.n_rows;
}

std::string ResultsWriter::finish(const RunSummary& summary, const std::function<bool()>& interrupted,
                                  const std::string& interrupted_message)
{
    IGA_CHECK(is_open(), "results file " + final_path_ + " is already closed");
    IGA_CHECK(summary.status == "completed" || summary.status == "failed" || summary.status == "running",
              "status must be completed, failed or running, not '" + summary.status + "'");
    IGA_CHECK(summary.convergence.rows() == 0 || summary.convergence.cols() == 4,
              "the convergence table has 4 columns: increment, iteration, residual_norm, load_factor");
    h5::ErrorSilencer silence;
    const hid_t file = state_->file.id();
    h5::write_attribute(file, "status", summary.status);
    h5::write_attribute(file, "message", summary.message);
    h5::write_attribute(file, "warnings", summary.warnings);
    h5::write_attribute(file, "ranks", summary.ranks);
    h5::write_attribute(file, "linear_solver", summary.linear_solver);
    write_history(file, state_->history);

    h5::Handle timings = h5::create_group(file, "timings");
    for (const auto& [name, seconds] : summary.timings)
        h5::write_attribute(timings.id(), name, seconds);
    h5::Handle counters = h5::create_group(file, "counters");
    for (const auto& [name, count] : summary.counters)
        h5::write_attribute(counters.id(), name, count);

    const RowMatrix& table = summary.convergence;
    h5::write_dataset(file, "convergence",
                      std::span<const double>(table.data(), static_cast<std::size_t>(table.size())),
                      {static_cast<hsize_t>(table.rows()), 4});

    if (!summary.parallel.empty()) {
        h5::Handle parallel = h5::create_group(file, "parallel");
        for (const auto& [name, values] : summary.parallel)
            h5::write_dataset(parallel.id(), name, std::span<const double>(values.data(), values.size()),
                              {static_cast<hsize_t>(values.size())});
    }

    if (!summary.references.empty()) {
        h5::Handle references = h5::create_group(file, "reference");
        for (const ReferenceData& reference : summary.references)
            write_reference(references.id(), reference);
    }
    timings.reset();
    counters.reset();

    std::string status = summary.status;
    auto stopped_now = [&] { return status == "completed" && interrupted && interrupted(); };
    auto mark_failed = [&](hid_t f) {
        h5::write_attribute(f, "status", std::string("failed"));
        h5::write_attribute(f, "message", interrupted_message);
        status = "failed";
    };
    if (stopped_now())
        mark_failed(file);
    h5::Handle closing = std::move(state_->file);
    state_.reset();
    try {
        closing.close();
        if (stopped_now()) {  // during the close (which writes the file's metadata): opened once more
            h5::Handle again(H5Fopen(temp_path_.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose,
                             "cannot open " + temp_path_);
            mark_failed(again.id());
            again.close();
        }
    } catch (const StorageError& error) {
        std::remove(temp_path_.c_str());
        throw StorageError("cannot complete results file " + final_path_ + ": " + error.what() +
                           "; it was not written, and a file already there is untouched");
    } catch (const Error& error) {
        std::remove(temp_path_.c_str());
        throw Error("cannot complete results file " + final_path_ + ": " + error.what());
    }
    if (std::rename(temp_path_.c_str(), final_path_.c_str()) != 0) {
        // The file system's refusal, not ours (a folder removed or made read-only under the run).
        const std::string reason = std::strerror(errno);
        std::error_code ignored;
        throw StorageError("cannot rename " + temp_path_ + " to results file " + final_path_ + ": " + reason +
                           (std::filesystem::exists(temp_path_, ignored)
                                ? " (the results are in the temporary file)"
                                : " (the temporary file is no longer there either)"));
    }
    return status;
}

void ResultsWriter::abandon() noexcept
{
    if (!state_)
        return;
    {
        h5::ErrorSilencer silence;
        state_->file.reset();
    }
    state_.reset();
    std::remove(temp_path_.c_str());
}

}  // namespace iga::io
