#include "analysis/warnings.hpp"
#include "analysis/geometry.hpp"
#include "nurbs/side_patch.hpp"
#include "core/text.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <algorithm>
#include <limits>
#include <optional>
#include <set>

namespace iga::analysis {

namespace {

/// The largest imposed travel at pseudo-time t: prescribed displacements and
/// obstacle motions, each scaled by its amplitude.
double imposed_travel(const RunSettings& settings, double t)
{
    double travel = 0.0;
    for (const auto& [magnitude, amplitude] : settings.imposed_motions)
        travel = std::max(travel, std::abs(amplitude(t)) * magnitude);
    return travel;
}

double attribute(const io::ContactSideResult& side, const std::string& name)
{
    const auto it = side.attributes.find(name);
    return it == side.attributes.end() ? 0.0 : it->second;
}

/// The pieces a contact surface covers: "body.patch_side" per side of a deformable
/// surface (a named surface counts as its sides), the body's name for a rigid one.
std::set<std::string> surface_pieces(const Scene& scene, const PairModel& pair, int k)
{
    const int body = pair.body[static_cast<std::size_t>(k)];
    if (body < 0)
        return {pair.label[static_cast<std::size_t>(k)]};
    std::set<std::string> out;
    for (const std::string& piece : pair.piece_label[static_cast<std::size_t>(k)])
        out.insert(scene.bodies[static_cast<std::size_t>(body)].name + "." + piece);
    return out;
}

/// A piece both sets hold, or "" if none.
std::string common_piece(const std::set<std::string>& a, const std::set<std::string>& b)
{
    for (const std::string& x : a)
        if (b.count(x))
            return x;
    return {};
}

}  // namespace

std::vector<std::string> duplicate_pair_warnings(const Scene& scene)
{
    std::vector<std::string> out;
    const auto& pairs = scene.pairs;
    std::vector<std::array<std::set<std::string>, 2>> pieces;
    for (const PairModel& p : pairs)
        pieces.push_back({surface_pieces(scene, p, 0), surface_pieces(scene, p, 1)});
    for (std::size_t j = 1; j < pairs.size(); ++j)
        for (std::size_t i = 0; i < j; ++i) {
            const auto& a = pieces[i];
            const auto& b = pieces[j];
            // The same two pieces in either order: both pairs act there.
            std::string first = common_piece(a[0], b[0]), second = common_piece(a[1], b[1]);
            if (first.empty() || second.empty()) {
                first = common_piece(a[0], b[1]);
                second = common_piece(a[1], b[0]);
            }
            if (first.empty() || second.empty())
                continue;
            out.push_back(fmt::format("contact pairs '{}' and '{}' both act between {} and {}: each adds its own "
                                      "contact forces, so this contact is enforced twice (remove one of them)",
                                      pairs[i].name, pairs[j].name, first, second));
            break;  // one warning per repeating pair
        }
    return out;
}

std::vector<std::string> release_initial_overclosure(Scene& scene, SceneSystem& system, double release_end)
{
    std::vector<std::string> out;
    if (!scene.has_contact())
        return out;
    const Vector u0 = Vector::Zero(scene.dofs->n_free());
    const std::vector<contact::PairEvaluation> states = system.contact_state(u0, 0.0);
    const double tolerance = overclosure_tolerance * scene.model_size;
    for (std::size_t p = 0; p < scene.pairs.size(); ++p) {
        PairModel& model = scene.pairs[p];
        std::vector<Vector> overlap;
        std::string line;
        for (const contact::CarrierResult& carrier : states[p].carriers) {
            Vector g0 = Vector::Zero(carrier.gap.size());
            Index deepest = -1;
            for (Index g = 0; g < carrier.gap.size(); ++g) {
                if (carrier.state[static_cast<std::size_t>(g)] != contact::PointState::ok || !(carrier.gap(g) > tolerance))
                    continue;
                g0(g) = carrier.gap(g);
                if (deepest < 0 || carrier.gap(g) > carrier.gap(deepest))
                    deepest = g;
            }
            if (deepest >= 0 && line.empty())  // one line per pair: the other half pass sees the same overlap
                line = fmt::format(
                    "contact pair '{}': {} starts {:.3g} deep inside the other surface (at {}); the overlap is "
                    "pushed out by the first increment; should that need a cutback, the overlap is released "
                    "gradually up to load factor {:.4g}. If it is not intended, move the bodies apart",
                    model.name, model.label[static_cast<std::size_t>(carrier.surface)], carrier.gap(deepest),
                    point_text(carrier.reference_coordinates, deepest, 4), release_end);
            overlap.push_back(std::move(g0));
        }
        if (line.empty())
            continue;
        model.pair.set_initial_overlap(std::move(overlap), release_end);
        out.push_back(std::move(line));
    }
    return out;
}

namespace {

/// "1 pressed Gauss point", "3 pressed Gauss points".
std::string pressed_points(double n)
{
    return fmt::format("{:.0f} pressed Gauss point{}", n, n == 1.0 ? "" : "s");
}

/// Why the two half passes of a pair disagree, from what the run shows (docs/theory.md,
/// "Two-half-pass balance"): a penalty far stiffer than `penalty: auto`, or the
/// augmented Lagrangian, over-constrains the contact (each side's Gauss points hold
/// the other surface off by themselves); otherwise the zone is sampled by too few
/// pressed Gauss points, or differently on the two sides.
std::string half_pass_cause(const PairModel& model, const io::ContactPairResult& pair, int d)
{
    const std::string& a = pair.sides[0].side_name;
    const std::string& b = pair.sides[1].side_name;
    const double n_a = attribute(pair.sides[0], "n_active"), n_b = attribute(pair.sides[1], "n_active");
    // Pressed points per direction of the zone: a curve's count, a surface's square root.
    auto across = [d](double n) { return d == 3 ? std::sqrt(n) : n; };
    const auto it = pair.attributes.find("penalty");
    const double penalty = it == pair.attributes.end() ? model.initial_penalty : it->second;
    const std::string single = "formulation: single_pass, which balances the two bodies exactly";
    if (model.augmented)
        return fmt::format("with enforcement: augmented_lagrangian both half passes drive the gap to zero at their "
                           "own Gauss points ({:.0f} pressed on {}, {:.0f} on {}), more conditions than the two "
                           "surfaces can meet at once, so the force splits unevenly between the sides: use "
                           "enforcement: penalty with penalty: auto, or {}",
                           n_a, a, n_b, b, single);
    if (model.pair.settings().law.as_penalty() && model.rule.penalty > 0.0 &&
        penalty > stiff_half_pass_penalty * model.rule.penalty)
        return fmt::format("the penalty {:.3g} is {:.0f} times what penalty: auto gives ({:.3g}); so stiff a penalty "
                           "lets the Gauss points of one side hold the other surface off by themselves ({:.0f} pressed "
                           "on {}, {:.0f} on {}), so the force splits unevenly between the sides: use contact.{}."
                           "penalty: auto, or {}",
                           penalty, penalty / model.rule.penalty, model.rule.penalty, n_a, a, n_b, b, pair.name, single);
    if (std::min(across(n_a), across(n_b)) < resolved_zone_points) {
        if (std::max(n_a, n_b) >= 2.0 * std::min(n_a, n_b)) {
            const bool a_coarse = n_a < n_b;
            return fmt::format("the contact zone holds only {} of {} against {:.0f} of {}: "
                               "refine {} where it touches (more knot spans there) or raise contact.{}.quadrature",
                               pressed_points(std::min(n_a, n_b)), a_coarse ? a : b, std::max(n_a, n_b), a_coarse ? b : a,
                               a_coarse ? a : b, pair.name);
        }
        return fmt::format("the contact zone holds only {} of {} and {:.0f} of {}, too few "
                           "for the two integrals to agree: refine both sides where they touch (more knot spans "
                           "across the zone)",
                           pressed_points(n_a), a, n_b, b);
    }
    return fmt::format("the two sides sample the contact zone differently ({:.0f} pressed Gauss points on {}, {:.0f} on "
                       "{}): refine the coarser side or raise contact.{}.quadrature",
                       n_a, a, n_b, b, pair.name);
}

/// The control points of deformable body b in the configuration of `step` (n x d).
RowMatrix current_control_points(const BodyModel& body, const io::StepData& step)
{
    std::vector<RowMatrix> blocks;
    for (const auto& [name, u] : step.displacement)
        if (name == body.name && body.patches.size() == 1)
            blocks.push_back(body.patches.front().patch.control_points() + u);
    for (const auto& [name, patches] : step.patch_displacement)
        if (name == body.name)
            for (const auto& [patch, u] : patches)
                for (const PatchModel& model : body.patches)
                    if (model.name == patch && model.patch.control_points().rows() == u.rows())
                        blocks.push_back(model.patch.control_points() + u);
    Index rows = 0;
    for (const RowMatrix& b : blocks)
        rows += b.rows();
    RowMatrix out(rows, body.node_points.cols());
    Index at = 0;
    for (const RowMatrix& b : blocks) {
        out.middleRows(at, b.rows()) = b;
        at += b.rows();
    }
    return out;
}

/// The displacement of patch p of `body` in `step` (n_cp x d), or nullptr.
const RowMatrix* patch_displacement(const BodyModel& body, std::size_t p, const io::StepData& step)
{
    if (body.patches.size() == 1)
        for (const auto& [name, u] : step.displacement)
            if (name == body.name)
                return &u;
    for (const auto& [name, patches] : step.patch_displacement)
        if (name == body.name)
            for (const auto& [patch, u] : patches)
                if (patch == body.patches[p].name)
                    return &u;
    return nullptr;
}

/// The deepest point of a (deformed) side inside a rigid obstacle, sampled at 3 points
/// per element and direction inside the elements; 0 when none is inside.
double deepest_point(const nurbs::Patch& side, const contact::RigidObstacle& obstacle, double load_factor)
{
    constexpr std::array<double, 3> at{1.0 / 6.0, 0.5, 5.0 / 6.0};
    const int n = side.n_par();
    double depth = 0.0;
    for (const nurbs::Element& e : side.elements())
        for (int c = 0; c < (n == 1 ? 3 : 9); ++c) {
            VecN xi(n);
            for (int j = 0; j < n; ++j) {
                const auto jj = static_cast<std::size_t>(j);
                xi(j) = e.lower[jj] + at[static_cast<std::size_t>(j == 0 ? c % 3 : c / 3)] * (e.upper[jj] - e.lower[jj]);
            }
            const contact::ObstacleFoot foot = obstacle.foot(nurbs::evaluate(side, xi, 0).x, load_factor);
            if (foot.ok)
                depth = std::max(depth, foot.gap);
        }
    return depth;
}

/// Knot spans the pressed Gauss points of a deformable side occupy, per parameter
/// direction of the side (pieces of a named surface add up), and the side's spans.
struct ZoneSpans {
    std::vector<int> pressed;  ///< per direction
    std::vector<int> total;    ///< per direction
};

ZoneSpans zone_spans(const contact::DeformableSide& side, const io::GaussPointData& gp)
{
    const int q = side.pieces.front().side.patch.n_par();
    ZoneSpans out{std::vector<int>(static_cast<std::size_t>(q), 0), std::vector<int>(static_cast<std::size_t>(q), 0)};
    for (std::size_t k = 0; k < side.pieces.size(); ++k) {
        const nurbs::Patch& patch = side.pieces[k].side.patch;
        for (int j = 0; j < q; ++j) {
            std::set<int> spans;
            for (Index g = 0; g < gp.pressure.size(); ++g) {
                const bool on_piece = gp.patch.empty() ? k == 0 : gp.patch[static_cast<std::size_t>(g)] == static_cast<int>(k);
                if (on_piece && gp.pressure(g) > 0.0 && g < gp.parameter.rows())
                    spans.insert(patch.knots(j).find_span(gp.parameter(g, j)));
            }
            out.pressed[static_cast<std::size_t>(j)] += static_cast<int>(spans.size());
            out.total[static_cast<std::size_t>(j)] += patch.knots(j).n_spans();
        }
    }
    return out;
}

}  // namespace

std::vector<std::string> resolution_warnings(const PairModel& model, const io::ContactPairResult& pair)
{
    std::vector<std::string> out;
    for (int k = 0; k < 2; ++k) {
        const auto* side = std::get_if<contact::DeformableSide>(&model.pair.surface(k));
        const auto result = std::find_if(pair.sides.begin(), pair.sides.end(), [&](const io::ContactSideResult& r) {
            return r.side_name == model.label[static_cast<std::size_t>(k)];
        });
        if (!side || side->pieces.empty() || result == pair.sides.end())
            continue;
        const ZoneSpans spans = zone_spans(*side, result->gauss_points);
        // The narrowest direction of the zone that the side's extent does not bound: a zone
        // as wide as the side (a flat punch, a patch test) is not under-resolved.
        int fewest = std::numeric_limits<int>::max();
        for (std::size_t j = 0; j < spans.pressed.size(); ++j)
            if (spans.pressed[j] > 0 && spans.pressed[j] < spans.total[j])
                fewest = std::min(fewest, spans.pressed[j]);
        if (fewest >= resolved_zone_spans)
            continue;
        out.push_back(fmt::format(
            "contact pair '{}': the contact zone on {} spans only {} knot span{} across{}: too few to resolve the "
            "pressure (Gauss-point pressures and the contact {} can be off by tens of per cent); refine {} where it "
            "touches (refine.insert), {} or more spans across the zone",
            model.name, result->side_name, fewest, fewest == 1 ? "" : "s",
            spans.pressed.size() > 1 ? " in its narrower direction" : "", spans.pressed.size() > 1 ? "radius" : "width",
            result->side_name, 2 * resolved_zone_spans));
    }
    return out;
}

namespace {

/// A pair of a deformable body and a rigid obstacle, as the warnings below read it.
struct ObstaclePair {
    int k = -1;  ///< the obstacle's surface in the pair
    int b = -1;  ///< the body's index in the scene
    const BodyModel* body = nullptr;
    const contact::RigidObstacle* obstacle = nullptr;
};

std::optional<ObstaclePair> obstacle_pair(const Scene& scene, const PairModel& model)
{
    const int k = model.obstacle;
    if (k < 0)
        return std::nullopt;
    const int b = model.body[static_cast<std::size_t>(1 - k)];
    return ObstaclePair{k, b, &scene.bodies[static_cast<std::size_t>(b)],
                        &std::get<contact::RigidObstacle>(model.pair.surface(k))};
}

}  // namespace

std::vector<std::string> driven_through_warnings(const Scene& scene, const PairModel& model, const io::StepData& step)
{
    const std::optional<ObstaclePair> at = obstacle_pair(scene, model);
    if (!at)
        return {};
    const int k = at->k;
    const BodyModel& body = *at->body;
    const contact::RigidObstacle& obstacle = *at->obstacle;
    const RowMatrix points = current_control_points(body, step);
    // The deepest control point inside the obstacle, and the body's thickness along the
    // obstacle's normal there (by the convex-hull property, the body lies within them).
    double depth = 0.0;
    VecN normal;
    for (Index a = 0; a < points.rows(); ++a) {
        const contact::ObstacleFoot foot = obstacle.foot(points.row(a).transpose(), step.load_factor);
        if (foot.ok && foot.gap > depth) {
            depth = foot.gap;
            normal = foot.normal;
        }
    }
    if (!(depth > 0.0))
        return {};
    const Vector along = points * normal;
    const double thickness = along.maxCoeff() - along.minCoeff();
    if (!(depth > driven_through * thickness))
        return {};
    return {fmt::format("contact pair '{}': at load factor {:.4g} the body '{}' reaches {:.3g} into the obstacle "
                        "'{}', {:.0f} % of its thickness {:.3g} along the obstacle's normal: it has been driven "
                        "through, not stopped (a penalty far too soft for the load, a load beyond what the contact "
                        "can hold, or a contact side that does not face the obstacle)",
                        model.name, step.load_factor, body.name, depth, model.label[static_cast<std::size_t>(k)],
                        100.0 * std::min(depth / thickness, 1.0), thickness)};
}

std::vector<std::string> undeclared_contact_warnings(const Scene& scene, const PairModel& model,
                                                     const io::StepData& step)
{
    const std::optional<ObstaclePair> at = obstacle_pair(scene, model);
    if (!at)
        return {};
    const int k = at->k, b = at->b;
    const BodyModel& body = *at->body;
    const contact::RigidObstacle& obstacle = *at->obstacle;
    const std::string& obstacle_name = model.label[static_cast<std::size_t>(k)];
    // The body's nodes on a surface that some pair checks against this obstacle, and the
    // deepest penetration those pairs leave.
    std::set<int> checked;
    double penetration = 0.0;
    for (const PairModel& other : scene.pairs) {
        const int j = other.obstacle;
        if (j < 0 || other.label[static_cast<std::size_t>(j)] != obstacle_name ||
            other.body[static_cast<std::size_t>(1 - j)] != b)
            continue;
        const std::vector<int>& nodes = other.parent_index[static_cast<std::size_t>(1 - j)];
        checked.insert(nodes.begin(), nodes.end());
        for (const io::ContactPairResult& result : step.contact)
            if (result.name == other.name)
                for (const io::ContactSideResult& side : result.sides)
                    penetration = std::max(penetration, attribute(side, "max_penetration"));
    }
    const double allowed = std::max(undeclared_depth_to_penetration * penetration, undeclared_depth_to_body * body.size());
    double worst = 0.0;
    std::string where;
    for (std::size_t p = 0; p < body.patches.size(); ++p) {
        const PatchModel& patch = body.patches[p];
        const RowMatrix* u = patch_displacement(body, p, step);
        if (u == nullptr || u->rows() != patch.patch.n_control_points())
            continue;
        const nurbs::Patch current = patch.patch.with_control_points(patch.patch.control_points() + *u);
        for (int s = 0; s < 2 * patch.patch.n_par(); ++s) {
            const auto side = static_cast<Side>(s);
            const bool glued = std::any_of(body.interfaces.begin(), body.interfaces.end(), [&](const nurbs::Interface& i) {
                return (i.patch_a == static_cast<int>(p) && i.side_a == side) ||
                       (i.patch_b == static_cast<int>(p) && i.side_b == side);
            });
            const nurbs::SidePatch reference = nurbs::extract_side(patch.patch, side);
            const bool in_pair = std::all_of(reference.parent_index.begin(), reference.parent_index.end(), [&](int a) {
                return checked.count(patch.node[static_cast<std::size_t>(a)]) > 0;
            });
            if (glued || in_pair || nurbs::is_collapsed(reference, 1e-12 * body.size()))
                continue;
            const double depth = deepest_point(nurbs::extract_side(current, side).patch, obstacle, step.load_factor);
            if (depth > worst) {
                worst = depth;
                const std::string named(side_name(named_side(side, patch.u_reversed)));
                where = patch.name.empty() ? named : patch.name + "." + named;
            }
        }
    }
    if (!(worst > allowed))
        return {};
    return {fmt::format("contact pair '{}': at load factor {:.4g} the side {}.{} lies {:.3g} inside the obstacle "
                        "'{}', and no contact pair checks it against '{}' (this pair's side is {}, which penetrates "
                        "{:.3g}): the body has passed into the obstacle where the deck declares no contact, so the "
                        "results are not those of a body the obstacle stops. Name the side that meets the obstacle "
                        "in the pair (several patch sides: a named surface, `surfaces:`)",
                        model.name, step.load_factor, body.name, where, worst, obstacle_name, obstacle_name,
                        model.label[static_cast<std::size_t>(1 - k)], penetration)};
}

std::vector<std::string> pair_warnings(const Scene& scene, const PairModel& model, const io::ContactPairResult& pair,
                                       double load_factor)
{
    std::vector<std::string> out;
    const double travel = imposed_travel(scene.settings, load_factor);
    const int d = scene.dim;
    for (const io::ContactSideResult& side : pair.sides) {
        const double penetration = attribute(side, "max_penetration");
        if (!(penetration > 0.0))
            continue;
        const double measure = attribute(side, "contact_measure");
        const double zone = d == 3 ? std::sqrt(measure) : measure;
        int b = -1;
        for (int k = 0; k < 2; ++k)
            if (model.label[static_cast<std::size_t>(k)] == side.side_name)
                b = model.body[static_cast<std::size_t>(k)];
        const double size = b >= 0 ? scene.bodies[static_cast<std::size_t>(b)].size() : 0.0;
        std::string against;
        if (zone > 0.0 && penetration > penetration_to_zone * zone)
            against = fmt::format("{:.0f} % of the contact zone ({:.3g})", 100.0 * penetration / zone, zone);
        else if (size > 0.0 && penetration > penetration_to_body * size)
            against = fmt::format("{:.1f} % of the body size ({:.3g})", 100.0 * penetration / size, size);
        else if (travel > 0.0 && penetration > penetration_to_travel * travel)
            against = fmt::format("{:.0f} % of the imposed travel ({:.3g})", 100.0 * penetration / travel, travel);
        if (!against.empty() && model.pair.settings().law.as_penalty())  // softened contact: overclosure by design
            out.push_back(fmt::format(
                "contact pair '{}': {} penetrates {:.3g} at load factor {:.3g}, {}: the penalty is too soft "
                "for this load; raise contact.{}.penalty (the penetration falls in proportion)",
                pair.name, side.side_name, penetration, load_factor, against, pair.name));
    }
    if (model.formulation == contact::Formulation::two_half_pass && pair.sides.size() == 2) {
        const double f1 = pair.sides[0].normal_force, f2 = pair.sides[1].normal_force;
        const double scale = std::max(std::abs(f1), std::abs(f2));
        // Grazing contact leaves forces at round-off level, whose ratio means nothing.
        const BodyModel& body = scene.bodies[static_cast<std::size_t>(model.body[0])];
        const double material_force = body.material.E * std::pow(body.size(), d - 1);
        const auto pointwise = pair.attributes.find("half_pass_pressure_difference");
        const double apart = pointwise == pair.attributes.end() ? 0.0 : pointwise->second;
        if (scale > negligible_contact_force * material_force && std::abs(f1 - f2) > half_pass_disagreement * scale)
            out.push_back(fmt::format("contact pair '{}': the two half passes disagree in normal force by {:.1f} % "
                                      "({}: {:.6g}, {}: {:.6g}; their pressures point-wise by up to {:.0f} % of the "
                                      "peak); {}",
                                      pair.name, 100.0 * std::abs(f1 - f2) / scale, pair.sides[0].side_name, f1,
                                      pair.sides[1].side_name, f2, 100.0 * apart, half_pass_cause(model, pair, d)));
        else if (scale > negligible_contact_force * material_force && apart > half_pass_pressure_apart)
            out.push_back(fmt::format("contact pair '{}': the two half passes' pressures differ point-wise by up to "
                                      "{:.0f} % of the peak ({} and {}, post-processed), though their forces agree: "
                                      "the pressure of either side is uncertain by that much; {}",
                                      pair.name, 100.0 * apart, pair.sides[0].side_name, pair.sides[1].side_name,
                                      half_pass_cause(model, pair, d)));
    }
    return out;
}

}  // namespace iga::analysis
