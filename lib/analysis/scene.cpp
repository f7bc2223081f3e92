#include "analysis/scene.hpp"

#include "analysis/contact_penalty.hpp"
#include "analysis/size_estimate.hpp"

#include "analysis/constraints.hpp"
#include "boundary/patch_side.hpp"
#include "analysis/geometry.hpp"
#include "analysis/obstacles.hpp"
#include "analysis/side_facing.hpp"
#include "core/text.hpp"
#include "io/deck_names.hpp"
#include "io/locate.hpp"
#include "nurbs/side_patch.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace iga::analysis {

mechanics::Material to_material(const io::Material& m, const io::Analysis& analysis)
{
    mechanics::Material out;
    out.model = m.model;
    out.E = m.E;
    out.nu = m.nu;
    if (analysis.dimension == 3)
        out.plane = mechanics::PlaneMode::none;
    else
        out.plane = analysis.plane;
    return out;
}

namespace {

DeckIssue body_issue(const io::Deck& deck, const std::string& path, const std::string& reason)
{
    return io::located_issue(deck.source_file, path, "", reason);
}

/// Full dofs of a list of body control points (local dof a*d + i order).
std::vector<int> dofs_of(const assembly::DofMap& dofs, int body, const std::vector<int>& points)
{
    const int d = dofs.dimension();
    std::vector<int> out;
    out.reserve(points.size() * static_cast<std::size_t>(d));
    for (int p : points)
        for (int i = 0; i < d; ++i)
            out.push_back(dofs.dof(dofs.node_offset(body) + p, i));
    return out;
}

/// The side quadrature of a list of patch sides, element indices over body nodes;
/// n_per_direction <= 0: the default rule (max side degree + 1).
mechanics::SideQuadrature body_side_quadrature(const BodyModel& body, const std::vector<BodySide>& sides,
                                               int n_per_direction)
{
    mechanics::SideQuadrature out;
    for (const BodySide& side : sides) {
        const PatchModel& patch = body.patches[static_cast<std::size_t>(side.patch)];
        mechanics::SideQuadrature q = mechanics::side_quadrature(patch.patch, side.side, n_per_direction);
        out.side = q.side;
        out.dim = q.dim;
        for (mechanics::SideElement& element : q.elements) {
            for (int& a : element.indices)
                a = patch.node[static_cast<std::size_t>(a)];
            out.elements.push_back(std::move(element));
        }
    }
    return out;
}

/// A load or contact on an interface side is bad input (it lies inside the body).
void check_not_interface(const io::Deck& deck, const BodyModel& body, const std::vector<BodySide>& sides,
                         const std::string& path)
{
    for (const BodySide& side : sides)
        for (const nurbs::Interface& i : body.interfaces)
            if ((i.patch_a == side.patch && i.side_a == side.side) || (i.patch_b == side.patch && i.side_b == side.side))
                throw DeckError(body_issue(deck, path,
                                           fmt::format("the side {} of body '{}' is an interface between two patches "
                                                       "(inside the body), not a boundary side",
                                                       body_side_text(body.patch_names(), side), body.name)));
}

}  // namespace

std::vector<std::string> BodyModel::patch_names() const
{
    std::vector<std::string> names;
    for (const PatchModel& p : patches)
        names.push_back(p.name);
    return names;
}

std::vector<BodySide> sides_of(const io::Deck& deck, const Scene& scene, const std::string& body,
                               const std::string& patch, Side side, const std::string& surface)
{
    for (std::size_t k = 0; k < deck.bodies.size(); ++k)
        if (deck.bodies[k].name == body && scene.body_of_deck[k] >= 0)
            return resolve_sides(deck.bodies[k], scene.bodies[static_cast<std::size_t>(scene.body_of_deck[k])].patch_names(),
                                 patch, side, surface);
    IGA_CHECK(false, "sides_of: '" + body + "' is not a deformable body of the scene");
    return {};
}

std::vector<int> coupling_full_dofs(const PairModel& pair, const contact::Coupling& coupling)
{
    std::vector<int> full = pair.pair.coupling_dofs(coupling);
    for (int& dof : full)
        dof = pair.local_to_full[static_cast<std::size_t>(dof)];
    return full;
}

void release_element_geometry(Scene& scene, const std::function<bool(int block)>& keep)
{
    for (BodyModel& body : scene.bodies)
        for (std::size_t e = 0; e < body.elements.size(); ++e)
            if (!keep(body.first_block + static_cast<int>(e)))
                std::vector<mechanics::QuadraturePoint>().swap(body.elements[e].points);
}

Vector Scene::f_ext(double t) const
{
    Vector f = Vector::Zero(dofs->n_full());
    for (const DeadLoad& load : dead_loads)
        f += load.amplitude(t) * load.f;
    return f;
}

LoadPath deck_load_path(const io::Deck& deck)
{
    // The items with something to scale, each with its amplitude (the ramp when none is given).
    std::vector<Amplitude> amplitudes;
    for (const io::Load& load : deck.loads)
        amplitudes.push_back(load.amplitude.value_or(Amplitude()));
    for (const io::Constraint& c : deck.constraints)
        if (c.amplitude || std::any_of(c.value.begin(), c.value.end(), [](double v) { return v != 0.0; }))
            amplitudes.push_back(c.amplitude.value_or(Amplitude()));
    for (const io::Body& b : deck.bodies)
        if (b.rigid && !b.motion.empty())
            amplitudes.push_back(b.amplitude.value_or(Amplitude()));
    return load_path(amplitudes);
}

namespace {

/// The bounding box of the deformable bodies' control points, grown patch by patch.
struct BoundingBox {
    Eigen::VectorXd lo, hi;
    explicit BoundingBox(int d) : lo(Eigen::VectorXd::Constant(d, 1e300)), hi(Eigen::VectorXd::Constant(d, -1e300)) {}
    void add(const RowMatrix& points)
    {
        lo = lo.cwiseMin(points.colwise().minCoeff().transpose());
        hi = hi.cwiseMax(points.colwise().maxCoeff().transpose());
    }
};

/// One deformable body of the deck: its patches refined and glued, their element
/// geometry over body nodes, its material.
BodyModel body_model(const io::Deck& deck, const io::Body& body, int refine_levels, const StopRequest& stop,
                     BoundingBox& box)
{
    const int d = deck.analysis.dimension;
    BodyPatches built = build_body_patches(deck, body, refine_levels, stop);
    BodyModel model;
    model.name = body.name;
    model.multi_patch = body.multi_patch();
    model.interfaces = built.topology.interfaces;
    model.n_nodes = built.topology.n_nodes;
    model.node_points.resize(model.n_nodes, d);
    for (std::size_t p = 0; p < built.patches.size(); ++p) {
        nurbs::Patch& patch = built.patches[p];
        const std::vector<int>& node = built.topology.node[p];
        const std::string path = "bodies." + body.name + (body.multi_patch() ? ".patches." + built.names[p] : "");
        stop.check();
        std::vector<mechanics::ElementGeometry> elements;
        try {
            elements = mechanics::patch_geometry(patch, body.quadrature.element);
        } catch (const mechanics::NonPositiveJacobian& e) {
            throw DeckError(body_issue(
                deck, path,
                fmt::format("the parametrization is inverted or degenerate: det(dX/dxi) = {:.3g} at parameter {} "
                            "(X = {}); check the control point order (u index fastest) and that u, v(, w) "
                            "form a right-handed system",
                            e.det_J(), point_text(e.xi()), point_text(e.X()))));
        }
        for (int a = 0; a < patch.n_control_points(); ++a)
            model.node_points.row(node[static_cast<std::size_t>(a)]) = patch.control_points().row(a);
        PatchModel pm{built.names[p], patch, node, static_cast<int>(model.elements.size()),
                      static_cast<int>(elements.size()), u_reversed(body, static_cast<int>(p))};
        for (mechanics::ElementGeometry& element : elements) {
            for (int& a : element.indices)
                a = node[static_cast<std::size_t>(a)];
            model.elements.push_back(std::move(element));
        }
        box.add(patch.control_points());
        model.patches.push_back(std::move(pm));
    }
    const io::Material* material = deck.find_material(body.material);
    IGA_CHECK(material != nullptr, "the deck reader let an unknown material through");
    model.material = to_material(*material, deck.analysis);
    model.side_names = side_meanings(body);
    return model;
}

void add_bodies(const io::Deck& deck, int refine_levels, const StopRequest& stop, Scene& scene)
{
    BoundingBox box(scene.dim);
    for (const io::Body& body : deck.bodies) {
        if (body.rigid) {
            scene.body_of_deck.push_back(-1);
            continue;
        }
        scene.body_of_deck.push_back(static_cast<int>(scene.bodies.size()));
        scene.bodies.push_back(body_model(deck, body, refine_levels, stop, box));
    }
    if (!scene.bodies.empty())
        scene.model_size = std::max((box.hi - box.lo).norm(), 1e-300);
}

/// The deformable body index of a deck body name (-1: rigid or unknown).
int body_index(const io::Deck& deck, const Scene& scene, const std::string& name)
{
    for (std::size_t k = 0; k < deck.bodies.size(); ++k)
        if (deck.bodies[k].name == name)
            return scene.body_of_deck[k];
    return -1;
}

/// The dof map with the Dirichlet data and the reaction groups; the element blocks,
/// and this rank's range of them.
void add_dofs_and_elements(const io::Deck& deck, const Communicator& comm, Scene& scene,
                           std::vector<std::vector<int>>& blocks)
{
    std::vector<int> nodes_per_body;
    std::vector<int> node_offset;
    int n_nodes = 0;
    for (const BodyModel& b : scene.bodies) {
        node_offset.push_back(n_nodes);
        nodes_per_body.push_back(b.n_nodes);
        n_nodes += b.n_nodes;
    }
    DirichletData dirichlet = dirichlet_data(deck, scene.bodies, scene.body_of_deck, node_offset);
    scene.dofs = std::make_unique<assembly::DofMap>(scene.dim, nodes_per_body, dirichlet.prescribed);
    scene.reactions = std::move(dirichlet.reactions);
    scene.setup_warnings = std::move(dirichlet.warnings);
    for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
        BodyModel& body = scene.bodies[b];
        body.first_block = static_cast<int>(blocks.size());
        for (const auto& element : body.elements) {
            body.element_dofs.push_back(dofs_of(*scene.dofs, static_cast<int>(b), element.indices));
            blocks.push_back(body.element_dofs.back());
        }
    }
    scene.n_element_blocks = static_cast<int>(blocks.size());
    scene.partition.rank = comm.rank();
    scene.partition.size = comm.size();
    scene.partition.n_element_blocks = scene.n_element_blocks;
    const auto [first, last] = comm.block_range(scene.n_element_blocks);
    scene.partition.first_element = static_cast<int>(first);
    scene.partition.last_element = static_cast<int>(last);
}

/// Adds f (over the control points `indices` of body b) to the full vector f_ext.
void scatter_load(const assembly::DofMap& dofs, int body, const std::vector<int>& indices, const Vector& f,
                  Vector& f_ext)
{
    const std::vector<int> full = dofs_of(dofs, body, indices);
    for (std::size_t k = 0; k < full.size(); ++k)
        f_ext(full[k]) += f(static_cast<Index>(k));
}

/// The side quadrature a load item acts on (checked: not folded, not an interface).
mechanics::SideQuadrature load_side(const io::Deck& deck, const Scene& scene, const io::Load& load,
                                    std::size_t load_index)
{
    const BodyModel& body = scene.bodies[static_cast<std::size_t>(body_index(deck, scene, load.body))];
    const std::vector<BodySide> sides =
        sides_of(deck, scene, load.body, load.patch, load.side.value_or(Side::u0), load.surface);
    mechanics::SideQuadrature side;
    try {
        side = body_side_quadrature(body, sides, deck.find_body(load.body)->quadrature.side);
    } catch (const boundary::FoldedSide& e) {
        throw DeckError(body_issue(deck, fmt::format("loads.{}.side", load_index), e.what()));
    }
    check_not_interface(deck, body, sides, fmt::format("loads.{}.side", load_index));
    return side;
}

/// One load item: dead loads into f_ext (the vector of its amplitude), a follower
/// pressure under finite kinematics as its own blocks.
void add_load(const io::Deck& deck, std::size_t load_index, Scene& scene, Vector& f_ext,
              std::vector<std::vector<int>>& blocks)
{
    const io::Load& load = deck.loads[load_index];
    const assembly::DofMap& dofs = *scene.dofs;
    const int d = scene.dim;
    const int b = body_index(deck, scene, load.body);
    IGA_CHECK(b >= 0, "the deck reader let a load on a rigid or unknown body through");
    if (load.kind == io::LoadKind::gravity) {
        for (const auto& element : scene.bodies[static_cast<std::size_t>(b)].elements) {
            const mechanics::LocalForce f = mechanics::gravity(element, load.density, to_vec(load.vector));
            scatter_load(dofs, b, f.indices, f.f_ext, f_ext);
        }
        return;
    }
    mechanics::SideQuadrature side = load_side(deck, scene, load, load_index);
    // A side collapsed to a point (or a face to a line) has no length or area: a traction
    // or pressure on it adds nothing, a force cannot be spread over it.
    const double measure = mechanics::reference_measure(side);
    constexpr double collapsed_measure = 1e-12;  // of size^(d-1): round-off of coincident control points
    if (!(measure > collapsed_measure * std::pow(scene.bodies[static_cast<std::size_t>(b)].size(), d - 1)))
        throw DeckError(body_issue(deck, fmt::format("loads.{}.side", load_index),
                                   fmt::format("the side is collapsed to a {} (zero {}): a traction or pressure on it applies nothing, a force cannot be spread over it; "
                                               "`check` lists every side with its corners",
                                               d == 3 ? "point or a line" : "point", d == 3 ? "area" : "length")));
    if (load.kind == io::LoadKind::traction || load.kind == io::LoadKind::force) {
        VecN traction = to_vec(load.vector);
        if (load.kind == io::LoadKind::force)
            traction /= measure;
        for (const auto& element : side.elements) {
            const mechanics::LocalForce f = mechanics::dead_traction(element, d, traction);
            scatter_load(dofs, b, f.indices, f.f_ext, f_ext);
        }
    } else if (scene.kinematics == mechanics::Kinematics::small) {
        for (const auto& element : side.elements) {
            const Matrix none;
            const mechanics::LocalForceTangent f =
                mechanics::follower_pressure(element, d, load.pressure, scene.kinematics, none);
            scatter_load(dofs, b, f.indices, f.f_ext, f_ext);
        }
    } else {
        FollowerPressure follower{b, load.pressure, load.amplitude.value_or(Amplitude()), std::move(side), {},
                                  static_cast<int>(blocks.size())};
        for (const auto& element : follower.side.elements) {
            follower.element_dofs.push_back(dofs_of(dofs, b, element.indices));
            blocks.push_back(follower.element_dofs.back());
        }
        scene.followers.push_back(std::move(follower));
    }
}

/// Loads: dead ones summed at full value, one vector per amplitude.
void add_loads(const io::Deck& deck, Scene& scene, std::vector<std::vector<int>>& blocks)
{
    for (std::size_t load_index = 0; load_index < deck.loads.size(); ++load_index) {
        const Amplitude amplitude = deck.loads[load_index].amplitude.value_or(Amplitude());
        auto group = std::find_if(scene.dead_loads.begin(), scene.dead_loads.end(),
                                  [&](const DeadLoad& g) { return g.amplitude == amplitude; });
        if (group == scene.dead_loads.end())
            group = scene.dead_loads.insert(scene.dead_loads.end(),
                                            DeadLoad{amplitude, Vector::Zero(scene.dofs->n_full())});
        add_load(deck, load_index, scene, group->f, blocks);
    }
}

/// The two surfaces of a contact pair as they are being built.
struct PairSurfaces {
    std::array<int, 2> body{-1, -1};
    std::array<std::string, 2> label;
    std::array<std::vector<int>, 2> parent;
    std::array<std::vector<std::string>, 2> piece_label;
};

/// Surface k of a pair: a rigid obstacle, one patch side (the side's own numbering,
/// the single-patch layout) or the glued sides of a named surface.
contact::Surface contact_surface(const io::Deck& deck, const Scene& scene, const io::ContactPair& c,
                                 const io::ContactSurface& s, int k, PairSurfaces& out)
{
    const io::Body* deck_body = deck.find_body(s.body);
    IGA_CHECK(deck_body != nullptr, "the deck reader let an unknown contact body through");
    if (deck_body->rigid) {
        out.label[k] = s.body;
        return rigid_obstacle(*deck_body);
    }
    out.body[k] = body_index(deck, scene, s.body);
    out.label[k] = s.body + "." + io::side_text(s.patch, s.side.value_or(Side::u0), s.surface);
    const BodyModel& model = scene.bodies[static_cast<std::size_t>(out.body[k])];
    const std::vector<BodySide> sides = sides_of(deck, scene, s.body, s.patch, s.side.value_or(Side::u0), s.surface);
    check_not_interface(deck, model, sides, "contact." + c.name + ".between");
    for (const BodySide& bs : sides)
        out.piece_label[k].push_back(body_side_text(model.patch_names(), bs));
    if (sides.size() == 1) {
        const PatchModel& patch = model.patches[static_cast<std::size_t>(sides.front().patch)];
        contact::DeformableSide side = contact::DeformableSide::make(patch.patch, sides.front().side);
        out.parent[k].clear();
        for (const int a : side.pieces.front().side.parent_index)
            out.parent[k].push_back(patch.node[static_cast<std::size_t>(a)]);
        return side;
    }
    std::vector<const nurbs::Patch*> parents;
    std::vector<Side> which;
    std::vector<std::vector<int>> nodes;
    for (const BodySide& bs : sides) {
        const PatchModel& patch = model.patches[static_cast<std::size_t>(bs.patch)];
        parents.push_back(&patch.patch);
        which.push_back(bs.side);
        nodes.push_back(patch.node);
    }
    return contact::DeformableSide::make(parents, which, nodes, out.parent[k]);
}

/// The contact pair of deck item c, with the penalty (or its auto rule) and friction;
/// a pair the contact module cannot use is bad input, named at its `between`.
contact::ContactPair contact_pair(const io::Deck& deck, const Scene& scene, const io::ContactPair& c,
                                  contact::PairSettings& settings, AutoPenalty& rule, PairSurfaces& surfaces)
{
    try {
        contact::Surface first = contact_surface(deck, scene, c, c.first, 0, surfaces);
        contact::Surface second = contact_surface(deck, scene, c, c.second, 1, surfaces);
        std::vector<const contact::DeformableSide*> sides;
        std::vector<const mechanics::Material*> materials;
        for (int k = 0; k < 2; ++k)
            if (const auto* side = std::get_if<contact::DeformableSide>(k == 0 ? &first : &second)) {
                sides.push_back(side);
                materials.push_back(&scene.bodies[static_cast<std::size_t>(surfaces.body[k])].material);
            }
        rule = auto_penalty(sides, materials);
        if (c.penalty_auto)
            settings.law = contact::NormalLaw::penalty(rule.penalty);
        settings.friction.coefficient = c.friction.coefficient;
        settings.friction.tangential_penalty =
            c.friction.tangential_penalty_auto ? settings.law.stiffness() : c.friction.tangential_penalty;
        return contact::ContactPair(settings, std::move(first), std::move(second));
    } catch (const Error& e) {
        std::string reason = e.what();
        if (reason.rfind("contact: ", 0) == 0)
            reason = reason.substr(9);
        throw DeckError(body_issue(deck, "contact." + c.name + ".between", "cannot use this pair: " + reason));
    }
}

/// A penalty times h/E' beyond 1/machine epsilon: the contact stiffness swamps the
/// body's in double precision (the tangent cannot see the body any more), and the
/// products eps * gap overflow long before eps does (1e300 left inf in the slip).
/// `penalty: auto` is at most 1e3 E'/h.
constexpr double max_penalty_over_stiffness = 1e16;

/// A normal or tangential penalty out of that range is bad input, at its key.
void check_penalty_range(const io::Deck& deck, const io::ContactPair& c, const contact::PairSettings& settings,
                         const AutoPenalty& rule)
{
    if (!(rule.modulus > 0.0 && rule.element_size > 0.0))
        return;
    const double stiffness = rule.modulus / rule.element_size;
    auto check = [&](double penalty, const std::string& key) {
        if (penalty > max_penalty_over_stiffness * stiffness)
            throw DeckError(body_issue(
                deck, "contact." + c.name + "." + key,
                fmt::format("{:.3g} is {:.3g} times E'/h ({:.3g}): beyond {:g} the contact stiffness swamps the "
                            "bodies' in double precision; penalty: auto gives {:.3g}",
                            penalty, penalty / stiffness, stiffness, max_penalty_over_stiffness, rule.penalty)));
    };
    if (settings.law.as_penalty() && !c.penalty_auto)
        check(settings.law.stiffness(), "penalty");
    if (settings.friction.coefficient > 0.0 && !c.friction.tangential_penalty_auto)
        check(settings.friction.tangential_penalty, "friction.tangential_penalty");
}

/// Contact pair c of the deck, its dofs and its candidate couplings as pattern blocks.
PairModel pair_model(const io::Deck& deck, Scene& scene, const io::ContactPair& c,
                     std::vector<std::vector<int>>& blocks)
{
    contact::PairSettings settings;
    settings.formulation = c.formulation;
    settings.law = c.law.type == io::LawType::exponential ? contact::NormalLaw::exponential(c.law.clearance, c.law.pressure)
                                                          : contact::NormalLaw::penalty(c.penalty);
    settings.quadrature = c.quadrature;
    AutoPenalty rule;  // E', h and the auto penalty of the pair's deformable sides
    PairSurfaces s;
    contact::ContactPair pair = contact_pair(deck, scene, c, settings, rule, s);
    check_penalty_range(deck, c, settings, rule);
    PairModel model{c.name, std::move(pair), s.body, s.parent, s.label, s.piece_label, {}, {}, -1, settings.formulation};
    model.penalty_auto = c.penalty_auto;
    model.initial_penalty = settings.law.stiffness();
    model.augmented = c.enforcement == io::Enforcement::augmented_lagrangian;
    model.gap_tolerance = c.augmented_lagrangian.gap_tolerance;
    model.max_updates = c.augmented_lagrangian.max_updates;
    model.rule = rule;
    for (int k = 0; k < 2; ++k)
        if (s.body[k] < 0)
            model.obstacle = k;
    if (model.obstacle >= 0)
        check_obstacle_side(deck, scene, c, model);
    for (std::string& line : check_sides_face(deck, scene, c, model))
        scene.setup_warnings.push_back(std::move(line));
    for (int k = 0; k < 2; ++k)
        if (s.body[k] >= 0) {
            const std::vector<int> full = dofs_of(*scene.dofs, s.body[k], s.parent[k]);
            model.local_to_full.insert(model.local_to_full.end(), full.begin(), full.end());
        }
    IGA_CHECK(static_cast<int>(model.local_to_full.size()) == model.pair.n_local_dofs(),
              "contact pair local numbering does not match its sides");
    for (const contact::Coupling& coupling : model.pair.candidate_couplings()) {
        model.blocks.emplace(coupling, static_cast<int>(blocks.size()));
        blocks.push_back(coupling_full_dofs(model, coupling));
    }
    return model;
}

/// An analytic reference must fit its pair (checked now, not after the solve).
void check_reference(const io::Deck& deck, const Scene& scene)
{
    const auto& ref = deck.output.reference;
    if (!ref)
        return;
    for (const PairModel& p : scene.pairs) {
        if (p.name != ref->pair)
            continue;
        const int n_rigid = (p.body[0] < 0) + (p.body[1] < 0);
        // The reader matched the reference type to the dimension; here it must fit the pair.
        const bool round_obstacle = p.obstacle >= 0 && std::holds_alternative<contact::RigidSphere>(
            std::get<contact::RigidObstacle>(p.pair.surface(p.obstacle)).shape);
        const std::string type(io::deck_name(ref->type));
        const bool plane = io::is_against_plane(ref->type);
        const std::string other = ref->type == io::ReferenceType::hertz_cylinder_plane ? "hertz_two_cylinders"
                                  : ref->type == io::ReferenceType::hertz_two_cylinders ? "hertz_cylinder_plane"
                                  : ref->type == io::ReferenceType::hertz_sphere_plane  ? "hertz_two_spheres"
                                                                                        : "hertz_sphere_plane";
        if (plane && (n_rigid != 1 || round_obstacle))
            throw DeckError(body_issue(deck, "output.reference.type",
                                       type + " needs a pair of a deformable side and a rigid plane; use " + other +
                                           " for two deformable sides"));
        if (!plane && n_rigid != 0)
            throw DeckError(body_issue(deck, "output.reference.type",
                                       type + " needs two deformable sides; use " + other + " against a rigid plane"));
    }
}

/// The sparsity pattern of this rank's blocks.
void make_pattern(const Communicator& comm, Scene& scene, std::vector<std::vector<int>> blocks)
{
    // A block another rank assembles keeps its index but no entries here.
    for (std::size_t k = 0; k < blocks.size(); ++k)
        if (!scene.partition.owns(static_cast<int>(k)))
            blocks[k].clear();
    // Small kinematics assembles the element blocks once (the elastic term's constant
    // stiffness): their entry positions would outweigh the tangent in 3D. Contact
    // couplings: coupling_blocks_searched().
    std::vector<char> searched(blocks.size(), coupling_blocks_searched(scene.dim) ? 1 : 0);
    std::fill_n(searched.begin(), scene.n_element_blocks, scene.kinematics == mechanics::Kinematics::small ? 1 : 0);
    scene.pattern = std::make_unique<assembly::SparsePattern>(*scene.dofs, std::move(blocks), std::move(searched));
    if (comm.parallel())  // another rank evaluates those elements
        release_element_geometry(scene, [&](int block) { return scene.partition.owns(block); });
}

/// The run's settings: what the run needs of the deck beyond the model.
RunSettings run_settings(const io::Deck& deck)
{
    RunSettings s;
    s.source_file = deck.source_file;
    s.resolved_yaml = deck.resolved_yaml;
    s.output = deck.output;
    s.steps = deck.steps;
    s.newton = deck.newton;
    s.solver = deck.solver;
    for (const io::Load& load : deck.loads)
        s.load_body.push_back(load.body);
    auto norm = [](const std::vector<double>& v) {
        double sum = 0.0;
        for (double x : v)
            sum += x * x;
        return std::sqrt(sum);
    };
    for (const io::Constraint& c : deck.constraints)
        s.imposed_motions.emplace_back(norm(c.value), c.amplitude.value_or(Amplitude()));
    for (const io::Body& b : deck.bodies)
        if (b.rigid)
            s.imposed_motions.emplace_back(norm(b.motion), b.amplitude.value_or(Amplitude()));
    return s;
}

}  // namespace

Scene build_scene(const io::Deck& deck, int refine_levels, const StopRequest& stop, const Communicator& comm)
{
    check_size(deck);  // refuse an absurd model before allocating any of it
    Scene scene;
    scene.settings = run_settings(deck);
    scene.dim = deck.analysis.dimension;
    scene.kinematics = deck.analysis.kinematics;
    add_bodies(deck, refine_levels, stop, scene);
    std::vector<std::vector<int>> blocks;  // pattern blocks: elements, follower sides, contact couplings
    add_dofs_and_elements(deck, comm, scene, blocks);
    add_loads(deck, scene, blocks);
    for (const io::ContactPair& c : deck.contact)
        scene.pairs.push_back(pair_model(deck, scene, c, blocks));
    check_reference(deck, scene);
    make_pattern(comm, scene, std::move(blocks));
    scene.path = deck_load_path(deck);
    return scene;
}

}  // namespace iga::analysis
