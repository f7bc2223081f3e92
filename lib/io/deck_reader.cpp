#include "io/deck_reader.hpp"

#include "core/petsc_options.hpp"
#include "io/amplitude_reader.hpp"
#include "io/body_reader.hpp"
#include "io/deck_writer.hpp"
#include "io/overrides.hpp"
#include "io/yaml_cursor.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

namespace iga::io {
namespace {

namespace fs = std::filesystem;

Analysis read_analysis(const Cursor& root, KnownNames& known)
{
    Analysis a;
    const Cursor c = root.child("analysis");
    if (!c.exists()) {
        root.fail_missing("analysis");
        return a;
    }
    if (!c.check_keys())
        return a;
    if (const auto d = c.read<int>("dimension")) {
        if (*d == 2 || *d == 3)
            a.dimension = known.dim = *d;
        else
            c.child("dimension").fail("must be 2 or 3");
    }
    a.kinematics = c.read_or("kinematics", a.kinematics);
    if (c.has("plane")) {
        if (known.dim == 3)
            c.child("plane").fail("applies to 2D only (analysis.dimension is 3)");
        else
            a.plane = c.read_or("plane", a.plane);
    }
    return a;
}

std::vector<Material> read_materials(const Cursor& root, KnownNames& known)
{
    std::vector<Material> out;
    const Cursor list = root.child("materials");
    if (!list.exists()) {
        root.fail_missing("materials");
        return out;
    }
    if (!list.expect_list())
        return out;
    if (list.size() == 0)
        list.fail_here("must list at least one material");
    NameRegistry names("material");
    for (const Cursor& c : list.items()) {
        if (!c.check_keys())
            continue;
        Material m;
        if (const auto name = read_name(c)) {
            m.name = *name;
            if (names.add(*name, c.child("name")))
                known.materials.push_back(*name);
        }
        m.model = c.read_or("model", m.model);
        m.E = c.read<double>("E").value_or(m.E);
        m.nu = c.read<double>("nu").value_or(m.nu);
        out.push_back(m);
    }
    return out;
}

std::vector<Body> read_bodies(const Cursor& root, KnownNames& known)
{
    std::vector<Body> out;
    const Cursor list = root.child("bodies");
    if (!list.exists()) {
        root.fail_missing("bodies");
        return out;
    }
    if (!list.expect_list())
        return out;
    NameRegistry names("body");
    for (const Cursor& c : list.items())
        out.push_back(read_body(c, known, names));
    if (std::none_of(out.begin(), out.end(), [](const Body& b) { return !b.rigid; }))
        list.fail_here("needs at least one deformable body (one with 'nurbs' or 'shape')");
    return out;
}

/// The name under `key` of a body that may carry constraints or loads (a deformable one).
std::optional<std::string> deformable_body(const Cursor& map, const KnownNames& known, const std::string& what)
{
    const auto name = map.read<std::string>("body");
    if (!name)
        return std::nullopt;
    const Cursor c = map.child("body");
    const auto* body = known.find_body(*name);
    if (!body) {
        c.fail("unknown body '" + *name + "'" + hint_or_list(*name, known.body_names(), "bodies"));
        return std::nullopt;
    }
    if (body->second) {
        c.fail("rigid body '" + *name + "' takes no " + what + ": rigid obstacles are fixed");
        return std::nullopt;
    }
    return name;
}

/// The required `side` of a constraint or load on deformable body `body` (a side,
/// patch.side or a named surface; body "" when the body is unknown or rigid).
std::optional<SideReference> required_side(const Cursor& map, const std::string& body, const KnownNames& known)
{
    const Cursor c = map.child("side");
    if (!c.exists()) {
        map.fail_missing("side");
        return std::nullopt;
    }
    const auto text = c.to_string();
    if (!text)
        return std::nullopt;
    if (body.empty())  // the body was reported; still check the word where it can only be a side
        return parse_side(*text) ? std::optional(SideReference{"", *parse_side(*text), ""}) : std::nullopt;
    return side_reference(c, *text, body, known);
}

std::vector<Constraint> read_constraints(const Cursor& root, const KnownNames& known)
{
    std::vector<Constraint> out;
    const Cursor list = root.child("constraints");
    if (!list.exists() || !list.expect_list())
        return out;
    const int dim = known.dim;
    const std::vector<std::string> components = dim == 2 ? std::vector<std::string>{"x", "y"}
                                                          : std::vector<std::string>{"x", "y", "z"};
    for (const Cursor& c : list.items()) {
        if (!c.check_keys())
            continue;
        Constraint k;
        k.body = deformable_body(c, known, "constraints").value_or("");
        if (const auto ref = required_side(c, k.body, known)) {
            k.side = ref->side;
            k.patch = ref->patch;
            k.surface = ref->surface;
        }
        const bool fix = c.has("fix");
        const bool displacement = c.has("displacement");
        k.fixed.assign(dim, false);
        k.value.assign(dim, 0.0);
        if (!fix && !displacement)
            c.fail_here("needs 'fix' (components held at zero) and/or 'displacement' (prescribed values, ~ for "
                        "a free component)");
        if (fix) {
            const Cursor f = c.child("fix");
            if (!f.is_list() || f.size() == 0)
                f.fail("expected a list of components, e.g. [" + join_names(components) + "]");
            for (const Cursor& item : f.items()) {
                const auto name = item.to_string();
                const auto at = name ? std::find(components.begin(), components.end(), *name) : components.end();
                if (at != components.end())
                    k.fixed[static_cast<std::size_t>(at - components.begin())] = true;
                else if (name)
                    item.fail("expected a component: " + join_names(components));
            }
        }
        if (displacement) {
            const Cursor v = c.child("displacement");
            if (!v.is_list() || v.size() != static_cast<std::size_t>(dim)) {
                v.fail(fmt::format("expected a list of {} values (~ leaves a component free), e.g. [~, -0.01]", dim));
            } else {
                bool any = false;
                for (int i = 0; i < dim; ++i) {
                    const Cursor item = v.item(static_cast<std::size_t>(i));
                    if (!item.exists())  // ~ (null): this component is free
                        continue;
                    const auto value = item.to_number();
                    if (!value)
                        continue;
                    any = true;
                    if (k.fixed[static_cast<std::size_t>(i)] && *value != 0.0) {
                        item.fail(fmt::format("component {} is also in 'fix' (held at zero); write ~ here or drop "
                                              "it from 'fix'",
                                              components[static_cast<std::size_t>(i)]));
                        continue;
                    }
                    k.fixed[static_cast<std::size_t>(i)] = true;
                    k.value[static_cast<std::size_t>(i)] = *value;
                }
                if (!any && !fix)
                    v.fail("prescribes no component (every entry is ~)");
            }
        }
        if (c.has("amplitude")) {
            if (displacement)
                k.amplitude = read_amplitude(c.child("amplitude"));
            else
                c.child("amplitude").fail_here("scales a 'displacement'; this constraint has only 'fix' (held at "
                                               "zero), so there is nothing to scale");
        }
        out.push_back(k);
    }
    return out;
}

std::vector<Load> read_loads(const Cursor& root, const KnownNames& known)
{
    std::vector<Load> out;
    const Cursor list = root.child("loads");
    if (!list.exists() || !list.expect_list())
        return out;
    const int dim = known.dim;
    std::vector<std::string> kinds;  // the load kinds are keys of a load: traction, force, ...
    for (const auto& entry : DeckNames<LoadKind>::all)
        kinds.emplace_back(entry.name);
    for (const Cursor& c : list.items()) {
        if (!c.check_keys())
            continue;
        Load l;
        l.body = deformable_body(c, known, "loads").value_or("");
        std::vector<std::string> given;
        for (const auto& entry : DeckNames<LoadKind>::all)
            if (c.has(entry.name)) {
                given.emplace_back(entry.name);
                l.kind = entry.value;
            }
        if (given.size() != 1) {
            c.fail_here(given.empty() ? "needs one of " + join_names(kinds)
                                      : "takes exactly one of " + join_names(kinds) + " (got " + join_names(given) +
                                            ")");
            out.push_back(l);
            continue;
        }
        const std::string& key = given.front();
        if (l.kind == LoadKind::gravity) {
            if (c.has("side"))
                c.child("side").fail("gravity acts on the whole body: no side");
            l.density = c.read_required<double>("density").value_or(l.density);
        } else {
            if (c.has("density"))
                c.child("density").fail("applies to gravity loads only");
            if (const auto ref = required_side(c, l.body, known)) {
                if (ref->surface.empty())
                    l.side = ref->side;
                l.patch = ref->patch;
                l.surface = ref->surface;
            }
        }
        if (l.kind == LoadKind::pressure)
            l.pressure = c.read<double>(key).value_or(0.0);
        else
            l.vector = c.read<std::vector<double>>(key, dim).value_or(std::vector<double>{});
        if (c.has("amplitude"))
            l.amplitude = read_amplitude(c.child("amplitude"));
        out.push_back(l);
    }
    return out;
}

/// One entry of `between`: "body.side", "body.patch.side" or "body.surface" of a
/// deformable body, or a rigid body's name.
std::optional<ContactSurface> read_surface(const Cursor& c, const KnownNames& known)
{
    const auto text = c.to_string();
    if (!text)
        return std::nullopt;
    const std::string sides = "(sides: " + join_names(side_names(known.dim)) + ")";
    if (const auto* body = known.find_body(*text)) {
        if (body->second)
            return ContactSurface{*text, std::nullopt, {}, {}};
        c.fail("a deformable body's surface needs a side, e.g. '" + *text + ".v0' " + sides);
        return std::nullopt;
    }
    const auto dot = text->find('.');
    const std::string name = text->substr(0, dot);
    const auto* body = known.find_body(name);
    if (!body) {
        c.fail("unknown body '" + name + "'" + hint_or_list(name, known.body_names(), "bodies"));
        return std::nullopt;
    }
    if (body->second) {
        c.fail("'" + name + "' is a rigid body: it has no sides, write just '" + name + "'");
        return std::nullopt;
    }
    if (dot == std::string::npos)
        return std::nullopt;  // unreachable: a body name alone was handled above
    const auto ref = side_reference(c, text->substr(dot + 1), name, known);
    if (!ref)
        return std::nullopt;
    ContactSurface s{name, std::nullopt, ref->patch, ref->surface};
    if (ref->surface.empty())
        s.side = ref->side;
    return s;
}

/// The value of `key`, a number in the schema's range or the word `auto`: {true, nullopt}
/// for auto, {false, value} for a valid number, {false, nullopt} when absent or after
/// recording the issue. `auto_note` says what auto means (" (the pair's normal
/// penalty)"), or nothing.
std::pair<bool, std::optional<double>> number_or_auto(const Cursor& map, std::string_view key,
                                                      const std::string& auto_note = "")
{
    const Cursor value = map.child(key);
    if (!value.exists())
        return {false, std::nullopt};
    const DeckKey* entry = find_deck_key(value.schema_path());
    IGA_CHECK(entry && entry->type == ValueType::number_or_auto, "'" + value.schema_path() + "' is no number or auto");
    const Range& range = entry->range;
    // A scalar that is not a number: `auto`, or a word we reject here with the choices.
    if (!value.is_list() && !value.is_map() && !parse_number(value.value_text())) {
        if (value.value_text() == "auto")
            return {true, std::nullopt};
        value.fail("expected a number " + range.text() + " or auto" + auto_note);
        return {false, std::nullopt};
    }
    if (const auto number = value.to<double>()) {  // (to<> rejects NaN and infinities)
        if (range.admits(*number))
            return {false, number};
        value.fail(range.failure() + (auto_note.empty() ? std::string() : ", or auto" + auto_note));
    }
    return {false, std::nullopt};
}

/// contact.<pair>.law: {type, clearance, pressure}; clearance and pressure with type
/// exponential only, and required there. False when a `law` is given whose type could
/// not be read (the issue is recorded; what else the pair needs then is unknown).
bool read_law(const Cursor& c, ContactPair& p)
{
    const Cursor law = c.child("law");
    if (!law.exists())
        return true;
    if (!law.check_keys())
        return false;
    const auto type = law.read<LawType>("type");
    if (!type)
        return false;
    p.law.type = *type;
    const bool exponential = p.law.type == LawType::exponential;
    for (const char* key : {"clearance", "pressure"})
        if (!exponential && law.has(key))
            law.child(key).fail_here("applies with type: exponential only");
    if (exponential) {
        p.law.clearance = law.read_required<double>("clearance").value_or(0.0);
        p.law.pressure = law.read_required<double>("pressure").value_or(0.0);
    }
    return true;
}

void read_penalty(const Cursor& c, ContactPair& p)
{
    if (p.law.type == LawType::exponential) {
        // The exponential law's stiffness comes from its clearance and pressure.
        if (c.has("penalty"))
            c.child("penalty").fail_here("does not apply with law: exponential (its stiffness is set by the "
                                         "law's clearance and pressure)");
        if (p.enforcement == Enforcement::augmented_lagrangian)
            c.child("enforcement").fail("the exponential law has no multipliers; use enforcement: penalty or "
                                        "leave it out with law: exponential");
        return;
    }
    if (!c.has("penalty")) {
        c.fail_missing("penalty");
        return;
    }
    const auto [is_auto, value] = number_or_auto(c, "penalty");
    p.penalty_auto = is_auto;
    if (value)
        p.penalty = *value;
}

/// contact.<pair>.augmented_lagrangian: {gap_tolerance, max_updates}, with enforcement
/// augmented_lagrangian only.
void read_augmented_lagrangian(const Cursor& c, ContactPair& p)
{
    const Cursor al = c.child("augmented_lagrangian");
    if (!al.exists())
        return;
    if (p.enforcement != Enforcement::augmented_lagrangian) {
        al.fail_here("applies with enforcement: augmented_lagrangian only (the pair's enforcement is " +
                     std::string(deck_name(p.enforcement)) + ")");
        return;
    }
    if (!al.check_keys())
        return;
    p.augmented_lagrangian.gap_tolerance = al.read_or("gap_tolerance", p.augmented_lagrangian.gap_tolerance);
    p.augmented_lagrangian.max_updates = al.read_or("max_updates", p.augmented_lagrangian.max_updates);
}

/// contact.<pair>.friction: {coefficient, tangential_penalty: <value | auto>}.
void read_friction(const Cursor& c, ContactPair& p)
{
    const Cursor f = c.child("friction");
    if (!f.exists() || !f.check_keys())
        return;
    p.friction.coefficient = f.read<double>("coefficient").value_or(p.friction.coefficient);
    if (f.has("tangential_penalty")) {
        const auto [is_auto, value] = number_or_auto(f, "tangential_penalty", " (the pair's normal penalty)");
        p.friction.tangential_penalty_auto = is_auto;
        if (value)
            p.friction.tangential_penalty = *value;
    }
}

std::vector<ContactPair> read_contact(const Cursor& root, KnownNames& known)
{
    std::vector<ContactPair> out;
    const Cursor list = root.child("contact");
    if (!list.exists() || !list.expect_list())
        return out;
    NameRegistry names("contact pair");
    for (const Cursor& c : list.items()) {
        if (!c.check_keys())
            continue;
        ContactPair p;
        if (const auto name = read_name(c)) {
            p.name = *name;
            if (names.add(*name, c.child("name")))
                known.pairs.push_back(*name);
        }
        const Cursor between = c.child("between");
        if (!between.exists()) {
            c.fail_missing("between");
        } else if (!between.is_list() || between.size() != 2) {
            between.fail("expected a list of two surfaces: [body.side, body.side or rigid body]");
        } else {
            const auto first = read_surface(between.item(0), known);
            const auto second = read_surface(between.item(1), known);
            if (first && second) {
                if (!first->deformable() && !second->deformable())
                    between.fail("at least one surface must be the side of a deformable body");
                else if (*first == *second)
                    between.fail("the two surfaces are the same side");
                p.first = *first;
                p.second = *second;
            }
        }
        p.formulation = c.read_or("formulation", p.formulation);
        p.enforcement = c.read_or("enforcement", p.enforcement);
        if (read_law(c, p))
            read_penalty(c, p);
        read_augmented_lagrangian(c, p);
        read_friction(c, p);
        p.quadrature = c.read_or("quadrature", p.quadrature);
        out.push_back(p);
    }
    return out;
}

Steps read_steps(const Cursor& root)
{
    Steps s;
    const Cursor c = root.child("steps");
    if (!c.exists() || !c.check_keys())
        return s;
    s.count = c.read_or("count", s.count);
    s.adaptive = c.read_or("adaptive", s.adaptive);
    s.max_cutbacks = c.read_or("max_cutbacks", s.max_cutbacks);
    return s;
}

Newton read_newton(const Cursor& root)
{
    Newton n;
    const Cursor c = root.child("newton");
    if (!c.exists() || !c.check_keys())
        return n;
    n.tolerance = c.read_or("tolerance", n.tolerance);
    n.max_iterations = c.read_or("max_iterations", n.max_iterations);
    n.line_search = c.read_or("line_search", n.line_search);
    return n;
}

Solver read_solver(const Cursor& root)
{
    Solver s;
    const Cursor c = root.child("solver");
    if (!c.exists() || !c.check_keys())
        return s;
    s.backend = c.read_or("backend", s.backend);
    s.type = c.read_or("type", s.type);
    s.options = c.read_or("options", s.options);
    // Only PETSc has iterative methods and options: without a backend they choose it
    // (as mpirun -np N > 1 does); a suitesparse backend said outright contradicts them.
    if (!c.child("backend").exists() && (s.type == SolverType::iterative || !s.options.empty()))
        s.backend = SolverBackend::petsc;
    if (s.type == SolverType::iterative && s.backend == SolverBackend::suitesparse)
        c.child("type").fail("type iterative needs backend petsc (the suitesparse backend is direct only)");
    if (!s.options.empty() && s.backend != SolverBackend::petsc)
        c.child("options").fail("options are PETSc options: they need backend petsc");
    else if (const PetscOptionsCheck options = check_petsc_options(s.options, PetscOptionsSource::deck); !options.ok())
        c.child("options").fail(options.message());  // before PETSc sees them (core/petsc_options.hpp)
    return s;
}

std::optional<Reference> read_reference(const Cursor& c, const KnownNames& known)
{
    if (!c.check_keys())
        return std::nullopt;
    Reference r;
    if (const auto pair = c.read<std::string>("pair")) {
        r.pair = *pair;
        if (std::find(known.pairs.begin(), known.pairs.end(), *pair) == known.pairs.end())
            c.child("pair").fail("unknown contact pair '" + *pair + "'" + hint_or_list(*pair, known.pairs, "pairs"));
    }
    const auto type = c.read<ReferenceType>("type");
    if (!type)
        return r;
    r.type = *type;
    if (is_point_contact(r.type) != (known.dim == 3)) {
        c.child("type").fail(known.dim == 3 ? "a 2D line-contact reference; a 3D deck takes hertz_sphere_plane or "
                                              "hertz_two_spheres"
                                            : "a 3D point-contact reference; a 2D deck takes hertz_cylinder_plane or "
                                              "hertz_two_cylinders");
        return r;
    }
    const bool plane = is_against_plane(r.type);
    const std::string takes = plane ? "radius" : "radii";
    const std::string other = plane ? "radii" : "radius";
    if (c.has(other))
        c.child(other).fail_here("does not apply to " + std::string(deck_name(r.type)) + " (it takes '" + takes +
                                 "')");
    if (plane)
        r.radius = c.read_required<double>("radius").value_or(0.0);
    else
        r.radii = c.read_required<std::vector<double>>("radii", 2).value_or(std::vector<double>{});
    r.force = c.read<double>("force").value_or(0.0);
    return r;
}

/// `file` relative to the deck's folder, unless absolute.
std::string resolve_path(const std::string& deck_dir, const std::string& file)
{
    const fs::path p(file);
    if (p.is_absolute() || deck_dir.empty())
        return p.lexically_normal().string();
    return (fs::path(deck_dir) / p).lexically_normal().string();
}

Output read_output(const Cursor& root, const std::string& file_label, const std::string& deck_dir,
                   const KnownNames& known)
{
    Output o;
    o.file = resolve_path(deck_dir, fs::path(file_label).filename().replace_extension(".h5").string());
    const Cursor c = root.child("output");
    if (!c.exists() || !c.check_keys())
        return o;
    if (c.has("file")) {
        const auto file = c.child("file").to_string();
        if (file && file->empty())
            c.child("file").fail("must not be empty");
        else if (file)
            o.file = resolve_path(deck_dir, *file);
    }
    o.every_step = c.read_or("every_step", o.every_step);
    o.samples_per_span = c.read_or("samples_per_span", o.samples_per_span);
    if (c.has("reference"))
        o.reference = read_reference(c.child("reference"), known);
    o.paraview = c.read_or("paraview", o.paraview);
    o.fields = c.read_or("fields", o.paraview);  // on with paraview unless said otherwise
    return o;
}

std::optional<Accuracy> read_accuracy(const Cursor& root, const Deck& deck, const KnownNames& known)
{
    const Cursor c = root.child("accuracy");
    if (!c.exists() || !c.check_keys())
        return std::nullopt;
    Accuracy a;
    const Cursor target = c.child("target");
    if (!target.exists())
        c.fail_here("needs a target: {pair, quantity, error}");
    else if (target.check_keys()) {
        if (const auto pair = target.read_required<std::string>("pair")) {
            a.pair = *pair;
            if (std::find(known.pairs.begin(), known.pairs.end(), *pair) == known.pairs.end())
                target.child("pair").fail("unknown contact pair '" + *pair + "'" +
                                          hint_or_list(*pair, known.pairs, "pairs"));
        }
        a.quantity = target.read_or("quantity", a.quantity);
        if (a.quantity == AccuracyQuantity::stick_zone) {
            const auto pair = std::find_if(deck.contact.begin(), deck.contact.end(),
                                           [&](const ContactPair& p) { return p.name == a.pair; });
            if (pair != deck.contact.end() && !(pair->friction.coefficient > 0.0))
                target.child("quantity").fail("stick_zone needs friction on pair '" + a.pair +
                                              "' (contact." + a.pair + ".friction.coefficient > 0): without it no "
                                              "point sticks");
        }
        a.error = target.read_required<double>("error").value_or(0.0);
    }
    const Cursor budget = c.child("budget");
    if (budget.exists() && budget.check_keys()) {
        a.levels = budget.read_or("levels", a.levels);
        a.dofs = budget.read_or("dofs", a.dofs);
        a.seconds = budget.read_or("seconds", a.seconds);
    }
    return a;
}

Deck read_tree(const Cursor& root, const std::string& file_label, const std::string& deck_dir)
{
    Deck deck;
    if (!root.exists()) {
        root.fail_here("the deck is empty: it needs at least format, analysis, materials and bodies");
        return deck;
    }
    if (!root.check_keys())
        return deck;
    if (const auto format = root.read<int>("format"); format && *format != 1)
        root.child("format").fail("unsupported deck format: this program reads format 1");
    deck.title = root.read_or<std::string>("title", "");
    KnownNames known;
    known.deck_dir = deck_dir;
    deck.analysis = read_analysis(root, known);
    deck.materials = read_materials(root, known);
    if (known.dim == 0)
        return deck;  // every later section depends on the dimension
    deck.bodies = read_bodies(root, known);
    deck.constraints = read_constraints(root, known);
    deck.loads = read_loads(root, known);
    deck.contact = read_contact(root, known);
    deck.steps = read_steps(root);
    deck.newton = read_newton(root);
    deck.solver = read_solver(root);
    deck.output = read_output(root, file_label, deck_dir, known);
    deck.accuracy = read_accuracy(root, deck, known);
    return deck;
}

}  // namespace

Deck read_deck_text(const std::string& yaml_text, const std::string& file_label, const std::string& deck_dir,
                    const std::vector<std::string>& set_overrides)
{
    std::vector<YAML::Node> documents;
    try {
        documents = YAML::LoadAll(yaml_text);
    } catch (const YAML::Exception& e) {
        const bool located = e.mark.line >= 0;
        throw DeckError(DeckIssue{{file_label, located ? e.mark.line + 1 : 0, located ? e.mark.column + 1 : 0},
                                  "",
                                  "",
                                  "invalid YAML: " + e.msg});
    }
    if (documents.size() > 1) {  // a reader that kept the first would drop the rest without a word
        const YAML::Mark mark = documents[1].Mark();
        const bool located = mark.line >= 0;
        throw DeckError(DeckIssue{{file_label, located ? mark.line + 1 : 0, located ? mark.column + 1 : 0},
                                  "",
                                  "",
                                  "a second YAML document ('---'): a deck is one document"});
    }
    YAML::Node root = documents.empty() ? YAML::Node() : documents.front();
    DeckSource source(file_label);
    IssueList issues;
    apply_overrides(root, set_overrides, source, issues);
    const Cursor root_cursor(root, source, issues);
    root_cursor.check_duplicate_keys();  // anywhere, also inside --set values
    Deck deck = read_tree(root_cursor, file_label, deck_dir);
    issues.throw_if_any();
    deck.source_file = file_label;
    deck.resolved_yaml = write_resolved_yaml(deck);
    return deck;
}

Deck read_deck(const std::string& path, const std::vector<std::string>& set_overrides)
{
    const auto cannot = [&](const std::string& why) {
        DeckIssue issue;
        issue.where.file = path;
        issue.reason = why;
        return DeckError(std::move(issue));
    };
    std::error_code ec;
    if (!fs::exists(path, ec))
        throw cannot("no such deck file");
    if (fs::is_directory(path, ec))
        throw cannot("is a directory, not a deck file");
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw cannot("cannot open the deck file (" + std::generic_category().message(errno) + ")");
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad())
        throw cannot("cannot read the deck file");
    return read_deck_text(text.str(), path, fs::path(path).parent_path().string(), set_overrides);
}

}  // namespace iga::io
