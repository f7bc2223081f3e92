#include "analysis/accuracy.hpp"

#include "analysis/contact_penalty.hpp"
#include "analysis/geometry.hpp"
#include "analysis/level_estimate.hpp"
#include "analysis/multipatch.hpp"
#include "analysis/scene.hpp"
#include "analysis/size_estimate.hpp"
#include "analysis/span_marking.hpp"
#include "analysis/zone_refinement.hpp"
#include "analysis/zone_symmetry.hpp"
#include "contact/contact_pair.hpp"
#include "core/error.hpp"
#include "io/deck_names.hpp"
#include "io/deck_writer.hpp"
#include "io/h5_file.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <set>

namespace iga::analysis {

namespace fs = std::filesystem;

namespace {

struct Level {
    int index = 0;
    long long dofs = 0;
    double wall_s = 0.0;
    double value = 0.0;
    std::optional<double> difference;  ///< d_k, the relative difference to the level before; empty at level 0
    std::optional<double> estimate;    ///< the estimated relative error; empty at level 0
    /// The estimate from the levels' differences alone (the next level's floor is it over
    /// largest_fall): the estimate without the penalty's part.
    std::optional<double> discretization;
    /// The penalty's part of the error, 1/kappa = E* / (eps a), where the penalty was held
    /// by the target at this level and the one before: then no difference sees it. The
    /// estimate adds it in quadrature, the bound adds it.
    double penalty_error = 0.0;
    /// Where the levels converge more slowly than the estimate assumes, the larger error
    /// their rate allows (level_estimate.hpp, slow_convergence); else the estimate.
    std::optional<double> bound;
    std::optional<double> reference_error;  ///< against the deck's analytic reference, where it has one
    std::vector<std::string> refined;       ///< what the refinement after this level halved
};

const io::ContactPairResult* pair_result(const RunOutcome& outcome, const std::string& pair)
{
    for (const io::ContactPairResult& p : outcome.contact)
        if (p.name == pair)
            return &p;
    return nullptr;
}

/// The pair's first side that carries Gauss points in a run's last increment.
const io::ContactSideResult* measured_side(const RunOutcome& outcome, const std::string& pair)
{
    const io::ContactPairResult* p = pair_result(outcome, pair);
    return p && !p->sides.empty() ? &p->sides.front() : nullptr;
}

/// One patch side of a contact surface, as analysed: its patch refined and glued.
struct SurfacePiece {
    std::string patch;  ///< the deck's patch name ("" for a single-patch body)
    Side side = Side::u0;  ///< as the deck names it
    nurbs::Patch side_patch;
    /// Its control points' numbers in the surface's numbering (contact::DeformableSide).
    std::vector<int> surface_index;
};

/// The patch sides of a body's contact surface (`side`, `patch.side`, or a named surface),
/// as analysed, in the surface's order.
std::vector<SurfacePiece> surface_pieces(const io::Deck& deck, const io::Body& body, const std::string& patch,
                                         std::optional<Side> side, const std::string& surface)
{
    const BodyPatches parts = build_body_patches(deck, body);
    const std::vector<BodySide> sides = resolve_sides(body, parts.names, patch, side.value_or(Side::u0), surface);
    std::vector<const nurbs::Patch*> parents;
    std::vector<Side> which;
    std::vector<std::vector<int>> nodes;
    for (const BodySide& at : sides) {
        parents.push_back(&parts.patches[static_cast<std::size_t>(at.patch)]);
        which.push_back(at.side);
        nodes.push_back(parts.topology.node[static_cast<std::size_t>(at.patch)]);
    }
    std::vector<int> surface_node;
    // Numbered as the contact module numbers it, so that the results' pressures read back.
    const contact::DeformableSide numbered = sides.size() == 1 ? contact::DeformableSide::make(*parents.front(), which.front())
                                                               : contact::DeformableSide::make(parents, which, nodes, surface_node);
    std::vector<SurfacePiece> out;
    for (std::size_t k = 0; k < sides.size(); ++k) {
        const contact::SidePiece& piece = numbered.pieces[k];
        out.push_back({parts.names[static_cast<std::size_t>(sides[k].patch)], sides[k].named, piece.side.patch,
                       piece.surface_index});
    }
    return out;
}

/// The body and surface of a results side name: "body.side", "body.patch.side" or
/// "body.surface".
struct SideLabel {
    const io::Body* body = nullptr;
    std::string patch;
    std::optional<Side> side;
    std::string surface;
};

SideLabel parse_label(const io::Deck& deck, const std::string& label)
{
    const std::size_t first = label.find('.'), last = label.rfind('.');
    SideLabel out{deck.find_body(label.substr(0, first)), "", parse_side(label.substr(last + 1)), ""};
    if (!out.side)
        out.surface = label.substr(first + 1);
    else if (last != first)
        out.patch = label.substr(first + 1, last - first - 1);
    return out;
}

std::vector<SurfacePiece> surface_pieces(const io::Deck& deck, const SideLabel& at)
{
    return surface_pieces(deck, *at.body, at.patch, at.side, at.surface);
}

/// The recovered pressure of a results side on the level's analysed patch sides.
SurfacePressure side_pressure(const io::Deck& deck, const io::ContactSideResult& result)
{
    const SideLabel at = parse_label(deck, result.side_name);
    IGA_CHECK(at.body != nullptr && (at.side || !at.surface.empty()),
              "accuracy: cannot find the contact side " + result.side_name);
    const Vector& p = result.postprocessed.control_point_pressure;
    SurfacePressure out;
    Index numbered = 0;
    for (SurfacePiece& piece : surface_pieces(deck, at)) {
        Vector values(static_cast<Index>(piece.surface_index.size()));
        for (std::size_t a = 0; a < piece.surface_index.size(); ++a) {
            const Index i = piece.surface_index[a];
            IGA_CHECK(i < p.size(), "accuracy: the recovered pressure of " + result.side_name + " does not match its side");
            values(static_cast<Index>(a)) = p(i);
            numbered = std::max(numbered, i + 1);
        }
        out.push_back(SidePressure{std::move(piece.side_patch), std::move(values)});
    }
    IGA_CHECK(numbered == p.size() && (result.patch_sides.empty() || result.patch_sides.size() == out.size()),
              "accuracy: the recovered pressure of " + result.side_name + " does not match its side");
    return out;
}

/// The recovered pressures of all sides of a pair that carry one, by side name.
std::map<std::string, SurfacePressure> side_pressures(const io::Deck& deck, const io::ContactPairResult& pair)
{
    std::map<std::string, SurfacePressure> out;
    for (const io::ContactSideResult& side : pair.sides)
        if (side.postprocessed.control_point_pressure.size() > 0)
            out.emplace(side.side_name, side_pressure(deck, side));
    return out;
}

/// The control points of a surface's patch sides, one block of rows per piece.
RowMatrix surface_points(const SurfacePressure& field)
{
    Index rows = 0;
    for (const SidePressure& piece : field)
        rows += piece.side.n_control_points();
    RowMatrix out(rows, field.front().side.dim());
    rows = 0;
    for (const SidePressure& piece : field) {
        out.middleRows(rows, piece.side.n_control_points()) = piece.side.control_points();
        rows += piece.side.n_control_points();
    }
    return out;
}

/// The Gauss points of piece `piece` of a surface (gauss_points/patch); all of them on
/// one patch side. What the stick zone's edge reads of them.
io::GaussPointData piece_points(const io::GaussPointData& g, int piece)
{
    if (g.patch.empty())
        return g;
    std::vector<Index> rows;
    for (std::size_t i = 0; i < g.patch.size(); ++i)
        if (g.patch[i] == piece)
            rows.push_back(static_cast<Index>(i));
    io::GaussPointData out;
    out.parameter = g.parameter(rows, Eigen::all);
    out.reference_coordinates = g.reference_coordinates(rows, Eigen::all);
    out.pressure = g.pressure(rows);
    if (g.weight.size() > 0)
        out.weight = g.weight(rows);
    for (const Index i : rows)
        out.status.push_back(g.status[static_cast<std::size_t>(i)]);
    return out;
}

/// The target pair's penalty on a level, and what it leaves.
struct LevelPenalty {
    double penalty = 0.0;
    double hertz_modulus = 0.0;  ///< E* of the pair
    bool by_target = false;      ///< kappa_target E* / (error a) gave it, not the mesh
};

/// `penalty: auto` on a level: the conditioning cap c_max E'/h of the level's own contact
/// sides, written into the level's deck as the number it is, so that the penalty's error
/// falls with h as the discretization's does and the levels' differences see it (an auto
/// penalty from the sides' size alone, kappa_side E*/l, stays the same on every level, and
/// its error, 0.5 % of the 2D Hertz L2 at 3 400 dofs, would end up above what the levels
/// estimate). For the target pair it is capped, once a level has measured the zone's
/// half-width a, at kappa_target E* / (error a): no stiffer than the target needs. A
/// penalty tied to the mesh alone grows as 1/h without end, and Newton's increments with
/// it (docs/accuracy_on_demand.md). The augmented Lagrangian's automatic gap tolerance is
/// already h p_max/E'. Adds the pairs' penalties to `log`; returns the target pair's.
LevelPenalty tie_penalty(io::Deck& deck, const io::Accuracy& a, std::optional<double> half_width,
                         std::vector<std::string>& log)
{
    LevelPenalty target;
    for (io::ContactPair& pair : deck.contact) {
        if (!pair.penalty_auto || pair.enforcement != io::Enforcement::penalty)
            continue;
        double h = std::numeric_limits<double>::infinity(), modulus = h, compliance = 0.0;
        int deformable = 0;
        for (const io::ContactSurface* s : {&pair.first, &pair.second}) {
            if (!s->deformable())
                continue;
            const io::Body& body = *deck.find_body(s->body);
            for (const SurfacePiece& piece : surface_pieces(deck, body, s->patch, s->side, s->surface))
                h = std::min(h, smallest_element_size(piece.side_patch));
            const double e = contact_modulus(to_material(*deck.find_material(body.material), deck.analysis));
            modulus = std::min(modulus, e);
            compliance += 1.0 / e;
            ++deformable;
        }
        pair.penalty = auto_penalty_cap * modulus / h;
        pair.penalty_auto = false;
        std::string origin = fmt::format("{:g} E'/h, h = {:.4g}", auto_penalty_cap, h);
        if (pair.name == a.pair) {
            target.hertz_modulus = deformable > 0 ? 1.0 / compliance : 0.0;
            if (half_width && *half_width > 0.0) {
                const double needed = kappa_target * target.hertz_modulus / (a.error * *half_width);
                if (needed < pair.penalty) {
                    pair.penalty = needed;
                    target.by_target = true;
                    origin = fmt::format("{:g} E* / (target a), E* = {:.4g}, a = {:.4g} (below {:g} E'/h, h = {:.4g})",
                                         kappa_target, target.hertz_modulus, *half_width, auto_penalty_cap, h);
                }
            }
            target.penalty = pair.penalty;
        }
        log.push_back(fmt::format("penalty of '{}' {:.4g} = {}", pair.name, pair.penalty, origin));
    }
    return target;
}

/// Half the largest extent of the pressed zone of a pair: its half-width (2D) or radius
/// (3D) where the model holds the whole zone, a quarter of the zone's width where a
/// symmetry plane halves it -- the smaller a, the stiffer (safer) the penalty above.
std::optional<double> zone_half_width(const io::ContactPairResult& pair)
{
    const std::optional<ZoneBox> zone = pressed_zone(pair);
    if (!zone)
        return std::nullopt;
    return 0.5 * (zone->upper - zone->lower).maxCoeff();
}

/// The error of the same quantity against the deck's analytic reference, if any: for the
/// pressure in the estimate's own norm (level_estimate.hpp, reference_pressure_error).
std::optional<double> reference_error(const io::Deck& deck, const io::Accuracy& a, const RunOutcome& outcome,
                                      const SurfacePressure& field)
{
    if (!deck.output.reference || deck.output.reference->pair != a.pair)
        return std::nullopt;
    if (a.quantity == io::AccuracyQuantity::pressure_l2) {
        for (const io::ReferenceData& r : outcome.references)
            if (r.pair == a.pair)
                return reference_pressure_error(r, field);
        return std::nullopt;
    }
    const char* radius = deck.analysis.dimension == 2 ? "half_width" : "contact_radius";
    const char* key = a.quantity == io::AccuracyQuantity::contact_radius ? radius : nullptr;
    if (!key)
        return std::nullopt;
    const auto it = outcome.errors.find(key);
    return it == outcome.errors.end() ? std::nullopt : std::optional(std::abs(it->second));
}

/// |q_k - q_{k-1}| / |q_k|; infinite while q_k is 0 (no point sticks yet on a coarse level).
double scalar_difference(double now, double before)
{
    return now != 0.0 ? std::abs(now - before) / std::abs(now) : std::numeric_limits<double>::infinity();
}

std::string percent(double x) { return fmt::format("{:.3g} %", 100.0 * x); }

/// The last completed level's results file, with /accuracy, into `final_path`
/// (a temporary name first, renamed when complete).
void write_results(const std::string& level_file, const std::string& final_path, const io::Accuracy& a,
                   const std::vector<Level>& levels, bool reached, const std::string& deck_text)
{
    const fs::path target(final_path);
    const fs::path temporary = target.parent_path() / ("." + target.filename().string() + ".accuracy.tmp");
    fs::copy_file(level_file, temporary, fs::copy_options::overwrite_existing);
    {
        io::h5::Handle file = io::h5::open_file_for_update(temporary.string());
        io::h5::Handle group = io::h5::create_group(file.id(), "accuracy");
        io::h5::write_attribute(group.id(), "pair", a.pair);
        io::h5::write_attribute(group.id(), "quantity", std::string(io::deck_name(a.quantity)));
        io::h5::write_attribute(group.id(), "target", a.error);
        io::h5::write_attribute(group.id(), "reached", reached ? 1 : 0);
        const Level& last = levels.back();
        io::h5::write_attribute(group.id(), "estimated_error",
                                last.bound.value_or(std::numeric_limits<double>::quiet_NaN()));
        // level, dofs, value, estimated_error (NaN at level 0), error_bound (the same, or the larger
        // error slow convergence allows), reference_error (NaN: none), difference (d_k, NaN at
        // level 0), penalty_error (the penalty's part of the estimate and the bound); the wall
        // times apart, as a timing (igacontact compare leaves them out)
        RowMatrix table(static_cast<Index>(levels.size()), 8);
        Vector wall(static_cast<Index>(levels.size()));
        std::vector<std::string> refined;
        const double none = std::numeric_limits<double>::quiet_NaN();
        for (std::size_t k = 0; k < levels.size(); ++k) {
            const Level& l = levels[k];
            table.row(static_cast<Index>(k)) << l.index, static_cast<double>(l.dofs), l.value,
                l.estimate.value_or(none), l.bound.value_or(none), l.reference_error.value_or(none),
                l.difference.value_or(none), l.penalty_error;
            wall(static_cast<Index>(k)) = l.wall_s;
            std::string line;
            for (const std::string& part : l.refined)
                line += (line.empty() ? "" : "; ") + part;
            refined.push_back(line);
        }
        io::h5::write_dataset(group.id(), "levels", table);
        io::h5::write_dataset(group.id(), "wall_s", wall);
        io::h5::write_string_dataset(group.id(), "refined", refined, {static_cast<hsize_t>(refined.size())});
        io::h5::write_string_dataset(group.id(), "refine", deck_text);
    }
    fs::rename(temporary, target);
}

/// The levels of one accuracy run, and their state between levels.
class AccuracyRun {
public:
    AccuracyRun(const io::Deck& input, const RunOptions& options, const RunContext& context)
        : input_(input), a_(*input.accuracy), options_(options), context_(context), deck_(input),
          start_(std::chrono::steady_clock::now())
    {
        const fs::path final_path(input.output.file);
        folder_ = final_path.parent_path() / (final_path.stem().string() + "_levels");
        fs::create_directories(folder_);
    }

    RunOutcome run()
    {
        for (int k = 0; k < a_.levels && stop_reason_.empty() && !reached_; ++k) {
            if (k > 0 && !budget_allows(k))
                break;
            const RunOutcome level_run = run_level(k);
            if (!measure(k, level_run) || reached_ || k + 1 == a_.levels)
                break;
            refine(k, level_run);
        }
        return finish();
    }

private:
    double elapsed() const
    {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }

    /// Whether level k fits the budget's dofs and seconds, and the machine's memory (else
    /// stop_reason_ says why not): a level that cannot be allocated is not started.
    bool budget_allows(int k)
    {
        const SizeEstimate size = estimate_size(deck_);
        const double dofs = size.dofs;
        const SizeLimits limits = machine_limits();
        if (a_.dofs > 0.0 && dofs > a_.dofs)
            stop_reason_ = fmt::format("level {} would have {:.3g} dofs, above the budget's {:.3g}", k, dofs, a_.dofs);
        else if (limits.memory_bytes > 0.0 && size.bytes > limits.memory_bytes)
            stop_reason_ = fmt::format("level {} would need about {:.3g} GB ({:.3g} dofs), more than {} {:.3g} GB", k,
                                       size.bytes / 1e9, dofs, limits.memory_name, limits.memory_bytes / 1e9);
        const double expected = elapsed() + levels_.back().wall_s * std::exp2(deck_.analysis.dimension);
        if (stop_reason_.empty() && a_.seconds > 0.0 && expected > a_.seconds)
            stop_reason_ = fmt::format("level {} would end at about {:.3g} s, beyond the budget's {:.3g} s", k,
                                       expected, a_.seconds);
        return stop_reason_.empty();
    }

    /// The deck as refined so far, run into level k's file.
    RunOutcome run_level(int k)
    {
        io::Deck level_deck = deck_;
        level_deck.output.file = (folder_ / fmt::format("level{}.h5", k)).string();
        level_deck.accuracy.reset();
        std::vector<std::string> penalties;
        penalties_.push_back(tie_penalty(level_deck, a_, half_width_, penalties));
        for (const std::string& line : penalties)
            context_.log(Verbosity::verbose, fmt::format("  level {}: {}", k, line));
        level_deck.resolved_yaml = io::write_resolved_yaml(level_deck);
        RunContext level_context = context_;
        // A coarse level's warnings (a zone a span or two across) are what the levels are
        // for: -v shows them; the final level's are given as a run's are, at the end.
        RunOptions level_options = options_;
        const RunContext& context = context_;
        level_options.warning = [&context, k](const std::string& line) {
            context.log(Verbosity::verbose, fmt::format("  level {} warning: {}", k, line));
        };
        return analysis::run(level_deck, level_options, level_context);
    }

    /// Level k's quantity, its estimate and whether it meets the target; false when the
    /// level failed (then stop_reason_ says so).
    bool measure(int k, const RunOutcome& level_run)
    {
        if (level_run.status != "completed") {
            stop_reason_ = fmt::format("level {} failed: {}", k, level_run.message);
            if (levels_.empty())  // nothing better to keep: the failed level's file is the results
                last_run_ = level_run;
            return false;
        }
        const io::ContactSideResult* side = measured_side(level_run, a_.pair);
        IGA_CHECK(side != nullptr, "accuracy: the results of level " + std::to_string(k) + " lack the pair " + a_.pair);
        std::map<std::string, SurfacePressure> fields = side_pressures(deck_, *pair_result(level_run, a_.pair));
        const SurfacePressure& field = fields.at(side->side_name);
        Level level;
        level.index = k;
        level.dofs = static_cast<long long>(level_run.numbers.at("dofs"));
        level.wall_s = level_run.wall_s;
        level.value = side_quantity(a_.quantity, *side, field, mirrors(*side, field));
        level.reference_error = reference_error(deck_, a_, level_run, field);
        if (const auto previous = fields_.find(side->side_name); previous != fields_.end()) {
            differences_.push_back(level_difference(previous->second, field, *side, level.value, levels_.back().value));
            level.difference = differences_.back();
            level.discretization = level_error(differences_.back(), levels_.back().discretization, largest_fall(a_.quantity));
            const std::optional<double> rate = slow_convergence(differences_);
            level.bound = rate ? std::max(*level.discretization, differences_.back() / (*rate - 1.0))
                               : *level.discretization;
            level.penalty_error = penalty_error(k, level_run);
            // Two errors of independent sources: the estimate adds them in quadrature, the
            // bound the target is judged by adds them.
            level.estimate = std::hypot(*level.discretization, level.penalty_error);
            *level.bound += level.penalty_error;
        }
        half_width_ = zone_half_width(*pair_result(level_run, a_.pair));
        previous_fields_ = std::move(fields_);
        fields_ = std::move(fields);
        last_run_ = level_run;
        reached_ = level.bound && safety_factor * *level.bound <= a_.error;
        log_level(level);
        levels_.push_back(level);
        return true;
    }

    /// How many symmetry planes of the measured side's body cut its zone (zone_symmetry.hpp).
    int mirrors(const io::ContactSideResult& side, const SurfacePressure& field) const
    {
        if (a_.quantity != io::AccuracyQuantity::contact_radius && a_.quantity != io::AccuracyQuantity::stick_zone)
            return 0;
        const io::Body& body = *parse_label(deck_, side.side_name).body;
        return zone_mirrors(symmetry_planes(deck_, body), surface_points(field), side.gauss_points,
                            zone_points(a_.quantity, side));
    }

    /// The penalty's part of level k's error, E* / (eps a) with a measured at level k, where
    /// the target held the pair's penalty at this level and the one before (else the change
    /// of the penalty is in the levels' difference); 0 otherwise.
    double penalty_error(int k, const RunOutcome& level_run) const
    {
        const auto at = [&](int j) { return penalties_[static_cast<std::size_t>(j)]; };
        if (k < 1 || !at(k).by_target || !at(k - 1).by_target)
            return 0.0;
        const std::optional<double> a = zone_half_width(*pair_result(level_run, a_.pair));
        return a && *a > 0.0 ? at(k).hertz_modulus / (at(k).penalty * *a) : 0.0;
    }

    /// d_k of the quantity. A zone (the contact zone, the stick zone), a sum of its Gauss
    /// points' weights, stays the same while no point at its edge changes state, however
    /// much the pressure moved (a coarse level's one or two pressed points): its difference
    /// is not taken below the resolution it is measured with (level_estimate.hpp,
    /// zone_resolution).
    double level_difference(const SurfacePressure& before, const SurfacePressure& now, const io::ContactSideResult& side,
                            double value, double value_before) const
    {
        switch (a_.quantity) {
        case io::AccuracyQuantity::pressure_l2: return pressure_difference(before, now).relative;
        case io::AccuracyQuantity::contact_radius:
        case io::AccuracyQuantity::stick_zone:
            return std::max(scalar_difference(value, value_before), zone_resolution(a_.quantity, side));
        case io::AccuracyQuantity::force: break;
        }
        return scalar_difference(value, value_before);
    }

    /// Why a level's estimate is above its difference: the floor (level_error).
    std::string floor_note(double estimate, double difference) const
    {
        const double fall = largest_fall(a_.quantity);
        return estimate * fall >= 1.0
                   ? fmt::format(" (100 % over {:g}: the level before had not resolved the {}; the difference is {})",
                                 fall, io::deck_name(a_.quantity), percent(difference))
                   : fmt::format(" (the last estimate over {:g}; the difference is {})", fall, percent(difference));
    }

    void log_level(const Level& level) const
    {
        const std::string slow = level.bound && *level.bound > *level.discretization + level.penalty_error
                                     ? fmt::format(" (up to {}: the levels converge slowly)", percent(*level.bound))
                                     : std::string();
        const std::string reference =
            level.reference_error ? ", against the reference " + percent(*level.reference_error) : std::string();
        context_.log(Verbosity::normal,
                     fmt::format("accuracy level {}: {} dofs, {:.3g} s, {} {:.6g}, estimated error {}{}{}{}{}", level.index,
                                 level.dofs, level.wall_s, io::deck_name(a_.quantity), level.value,
                                 level.estimate ? percent(*level.estimate) : std::string("- (level 0)"),
                                 level.difference && *level.difference < *level.discretization
                                     ? floor_note(*level.discretization, *level.difference)
                                     : std::string(),
                                 level.penalty_error > 0.0
                                     ? fmt::format(" (the penalty's part {})", percent(level.penalty_error))
                                     : std::string(),
                                 slow, reference));
    }

    /// Halves the spans where level k's pressure differs most from level k-1's (at level 0:
    /// around the pressed zone) on each deformable side of the pair (else stop_reason_ says
    /// why not).
    void refine(int k, const RunOutcome& level_run)
    {
        const io::ContactPairResult& pair = *pair_result(level_run, a_.pair);
        const std::optional<ZoneBox> zone = pressed_zone(pair);
        if (!zone) {
            stop_reason_ = fmt::format("no Gauss point of pair '{}' presses at level {}: there is no zone to refine "
                                       "toward",
                                       a_.pair, k);
            return;
        }
        double model_size = 0.0;  // the largest extent of a contact side
        for (const io::ContactPairResult& p : level_run.contact)
            for (const io::ContactSideResult& side : p.sides)
                if (const RowMatrix& x = side.gauss_points.reference_coordinates; x.rows() > 0)
                    model_size = std::max(model_size, (x.colwise().maxCoeff() - x.colwise().minCoeff()).norm());
        const io::ContactPair& deck_pair = *std::find_if(deck_.contact.begin(), deck_.contact.end(),
                                                         [&](const io::ContactPair& p) { return p.name == a_.pair; });
        // Marks first, for every surface, on the level's patches; then the knots.
        struct Marked {
            const io::ContactSurface* surface;
            std::vector<SurfacePiece> pieces;
            std::vector<SurfaceMarks> marks;  ///< one per piece
        };
        std::vector<Marked> surfaces;
        std::set<std::string> bodies;
        for (const io::ContactSurface* s : {&deck_pair.first, &deck_pair.second}) {
            if (!s->deformable() || !bodies.insert(s->body).second)  // a body refined once per level
                continue;
            Marked m{s, surface_pieces(deck_, *deck_.find_body(s->body), s->patch, s->side, s->surface), {}};
            const std::string name = s->body + "." + io::side_text(s->patch, s->side.value_or(Side::u0), s->surface);
            const auto now = fields_.find(name), before = previous_fields_.find(name);
            if (now != fields_.end() && before != previous_fields_.end()) {
                std::vector<const nurbs::Patch*> sides;
                for (const SidePressure& piece : now->second)
                    sides.push_back(&piece.side);
                m.marks = marks_from_indicators(sides, indicator(pair, name, before->second, now->second));
            }
            if (std::all_of(m.marks.begin(), m.marks.end(), [](const SurfaceMarks& x) { return x.empty(); })) {
                m.marks.clear();
                for (const SurfacePiece& piece : m.pieces)
                    m.marks.push_back(marks_from_zone(piece.side_patch, widened(*zone, model_size)));
            }
            surfaces.push_back(std::move(m));
        }
        for (const Marked& m : surfaces)
            for (std::size_t k = 0; k < m.pieces.size(); ++k) {
                if (m.marks[k].empty())
                    continue;
                // A piece refined before this one may have halved some of its spans (gluing).
                const SurfaceMarks marks =
                    k == 0 ? m.marks[k]
                           : remap_marks(m.marks[k], m.pieces[k].side_patch,
                                         surface_pieces(deck_, *deck_.find_body(m.surface->body), m.surface->patch,
                                                        m.surface->side, m.surface->surface)[k]
                                             .side_patch);
                for (const std::string& line :
                     refine_side(deck_, m.surface->body, m.pieces[k].patch, m.pieces[k].side, marks))
                    levels_.back().refined.push_back(line);
            }
        for (const std::string& line : levels_.back().refined)
            context_.log(Verbosity::verbose, "  refined " + line);
    }

    /// The squared indicator on each element (rows) and direction (columns) of each piece of
    /// surface `name`: where the pressure changed from the level before; for stick_zone, as
    /// much again where the stick zone's edge lies (span_marking.hpp), each part normalized
    /// to its total over the surface, so that the bulk takes the spans of both the contact
    /// zone's edge and the stick zone's.
    std::vector<RowMatrix> indicator(const io::ContactPairResult& pair, const std::string& name,
                                     const SurfacePressure& before, const SurfacePressure& now) const
    {
        std::vector<RowMatrix> eta2 = pressure_difference(before, now).element2;
        const auto side = std::find_if(pair.sides.begin(), pair.sides.end(),
                                       [&](const io::ContactSideResult& s) { return s.side_name == name; });
        if (a_.quantity != io::AccuracyQuantity::stick_zone || side == pair.sides.end())
            return eta2;
        std::vector<RowMatrix> edge;
        double p_total = 0.0, edge_total = 0.0;
        for (std::size_t k = 0; k < now.size(); ++k) {
            edge.push_back(stick_edge_indicator(now[k].side, piece_points(side->gauss_points, static_cast<int>(k)),
                                                stick_status));
            p_total += eta2[k].sum();
            edge_total += edge.back().sum();
        }
        for (std::size_t k = 0; k < now.size(); ++k) {
            if (p_total > 0.0)
                eta2[k] /= p_total;
            if (edge_total > 0.0)
                eta2[k] += edge[k] / edge_total;
        }
        return eta2;
    }

    /// The results file and the outcome: the last completed level's, with the verdict.
    RunOutcome finish()
    {
        if (stop_reason_.empty() && !reached_)
            stop_reason_ = fmt::format("the budget's {} levels are spent", a_.levels);
        if (reached_)
            context_.log(Verbosity::normal,
                         fmt::format("accuracy: {} of pair '{}' estimated at {} (target {}, with the safety factor "
                                     "{:g}) at level {}, {} dofs, {:.3g} s for all levels; the levels are in {}",
                                     io::deck_name(a_.quantity), a_.pair, percent(*levels_.back().bound),
                                     percent(a_.error), safety_factor, levels_.back().index, levels_.back().dofs,
                                     elapsed(), folder_.string()));
        RunOutcome outcome = last_run_;
        outcome.accuracy = summary();
        if (options_.warning)
            for (const std::string& line : last_run_.warnings)
                options_.warning(line);
        if (!levels_.empty()) {
            if (options_.comm.root())  // rank 0 writes the results (run.hpp)
                write_results(last_run_.results_file, input_.output.file, a_, levels_, reached_,
                              refine_text(deck_, a_.pair));
            outcome.results_file = input_.output.file;
        }
        if (!reached_) {
            const Level* last = levels_.empty() ? nullptr : &levels_.back();
            outcome.status = "failed";
            outcome.message = fmt::format(
                "accuracy target {} on {} of pair '{}' not reached: {}; {}", percent(a_.error),
                io::deck_name(a_.quantity), a_.pair, stop_reason_,
                last && last->bound ? fmt::format("the estimate reached is {} at level {} ({} dofs)",
                                                  percent(*last->bound), last->index, last->dofs)
                                    : std::string("no level has an estimate (it needs two)"));
        }
        return outcome;
    }

    /// The levels as the summary reports them.
    AccuracySummary summary() const
    {
        const double none = std::numeric_limits<double>::quiet_NaN();
        AccuracySummary out{a_.pair, std::string(io::deck_name(a_.quantity)), a_.error, reached_,
                            levels_.empty() || !levels_.back().bound ? none : *levels_.back().bound, elapsed(), {}};
        for (const Level& l : levels_) {
            std::string refined;
            for (const std::string& part : l.refined)
                refined += (refined.empty() ? "" : "; ") + part;
            out.levels.push_back({l.index, static_cast<double>(l.dofs), l.wall_s, l.value, l.difference.value_or(none),
                                  l.estimate.value_or(none), l.bound.value_or(none), l.reference_error.value_or(none),
                                  refined});
        }
        return out;
    }

    const io::Deck& input_;
    const io::Accuracy& a_;
    const RunOptions& options_;
    const RunContext& context_;
    io::Deck deck_;  ///< refined level by level
    fs::path folder_;
    std::chrono::steady_clock::time_point start_;
    std::vector<Level> levels_;
    std::vector<double> differences_;  ///< d_1 .. d_k
    std::vector<LevelPenalty> penalties_;  ///< the target pair's penalty on each level run
    std::optional<double> half_width_;     ///< of the last level's pressed zone (zone_half_width)
    std::map<std::string, SurfacePressure> fields_;           ///< the last level's recovered pressures, by side
    std::map<std::string, SurfacePressure> previous_fields_;  ///< the level's before
    RunOutcome last_run_;  ///< of the last completed level (or of a failed level 0)
    std::string stop_reason_;
    bool reached_ = false;
};

}  // namespace

RunOutcome run_to_accuracy(const io::Deck& input, const RunOptions& options, const RunContext& context)
{
    IGA_CHECK(input.accuracy.has_value(), "run_to_accuracy needs a deck with accuracy:");
    return AccuracyRun(input, options, context).run();
}

}  // namespace iga::analysis
