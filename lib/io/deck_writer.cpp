#include "io/deck_writer.hpp"

#include "io/deck_names.hpp"
#include "io/yaml_cursor.hpp"

#include <algorithm>
#include <variant>

namespace iga::io {
namespace {

// Numbers and words go to the emitter as pre-formatted text: yaml-cpp writes a
// string plain when it is a valid plain scalar, and quotes it otherwise.

const char* word(bool value)
{
    return value ? "true" : "false";
}

template <class E>
std::string word(E value)
{
    return std::string(deck_name(value));
}

/// Starts a block list of items, or writes `[]` when there are none (a block
/// emitter would put the empty list on a line of its own).
template <class T>
bool begin_items(YAML::Emitter& out, const std::vector<T>& items)
{
    if (items.empty()) {
        out << YAML::Flow << YAML::BeginSeq << YAML::EndSeq;
        return false;
    }
    out << YAML::BeginSeq;
    return true;
}

void numbers(YAML::Emitter& out, const std::vector<double>& values)
{
    out << YAML::Flow << YAML::BeginSeq;
    for (double v : values)
        out << format_number(v);
    out << YAML::EndSeq;
}

void integers(YAML::Emitter& out, const std::vector<int>& values)
{
    out << YAML::Flow << YAML::BeginSeq;
    for (int v : values)
        out << std::to_string(v);
    out << YAML::EndSeq;
}

/// `amplitude: [[t0, a0], [t1, a1], ...]` when the item has one (none: the default ramp, left out).
void write_amplitude(YAML::Emitter& out, const std::optional<Amplitude>& amplitude)
{
    if (!amplitude)
        return;
    out << YAML::Key << "amplitude" << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (const AmplitudePoint& p : amplitude->points())
        numbers(out, {p.time, p.value});
    out << YAML::EndSeq;
}

std::string surface(const ContactSurface& s)
{
    return s.deformable() ? s.body + "." + side_text(s.patch, s.side.value_or(Side::u0), s.surface) : s.body;
}

/// `transform: [...]` in flow style, each step a one-key map; nothing when there are no steps.
void write_transform(YAML::Emitter& out, const std::vector<TransformStep>& steps)
{
    if (steps.empty())
        return;
    out << YAML::Key << "transform" << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (const TransformStep& step : steps) {
        out << YAML::BeginMap << YAML::Key << std::string(transform_step_keys[step.index()]) << YAML::Value;
        if (const auto* t = std::get_if<Translate>(&step)) {
            numbers(out, t->offset);
        } else if (const auto* r = std::get_if<Rotate>(&step)) {
            out << YAML::BeginMap;
            if (!r->axis.empty()) {  // 2D: about z, no axis
                out << YAML::Key << "axis" << YAML::Value;
                numbers(out, r->axis);
            }
            out << YAML::Key << "angle_deg" << YAML::Value << format_number(r->angle_deg);
            out << YAML::Key << "about" << YAML::Value;
            numbers(out, r->about);
            out << YAML::EndMap;
        } else if (const auto* m = std::get_if<Mirror>(&step)) {
            out << YAML::BeginMap << YAML::Key << "normal" << YAML::Value;
            numbers(out, m->normal);
            out << YAML::Key << "point" << YAML::Value;
            numbers(out, m->point);
            out << YAML::EndMap;
        } else {
            out << format_number(std::get<Scale>(step).factor);
        }
        out << YAML::EndMap;
    }
    out << YAML::EndSeq;
}

void write_nurbs(YAML::Emitter& out, const NurbsData& nurbs)
{
    out << YAML::BeginMap;
    out << YAML::Key << "degrees" << YAML::Value;
    integers(out, nurbs.degrees);
    out << YAML::Key << "knots" << YAML::Value << YAML::BeginSeq;
    for (const auto& u : nurbs.knots)
        numbers(out, u);
    out << YAML::EndSeq;
    out << YAML::Key << "control_points" << YAML::Value << YAML::BeginSeq;
    for (const auto& p : nurbs.control_points)
        numbers(out, p);
    out << YAML::EndSeq;
    write_transform(out, nurbs.transform);
    out << YAML::EndMap;
}

void write_refine(YAML::Emitter& out, const Refine& r)
{
    if (r.elevate.empty() && r.spans.empty() && r.insert.empty())
        return;
    out << YAML::Key << "refine" << YAML::Value << YAML::BeginMap;
    if (!r.elevate.empty()) {
        out << YAML::Key << "elevate" << YAML::Value;
        integers(out, r.elevate);
    }
    if (!r.spans.empty()) {
        out << YAML::Key << "spans" << YAML::Value;
        integers(out, r.spans);
    }
    if (!r.insert.empty()) {
        out << YAML::Key << "insert" << YAML::Value << YAML::Flow << YAML::BeginSeq;
        for (const auto& values : r.insert)
            numbers(out, values);
        out << YAML::EndSeq;
    }
    out << YAML::EndMap;
}

void write_body(YAML::Emitter& out, const Body& b)
{
    out << YAML::BeginMap << YAML::Key << "name" << YAML::Value << b.name;
    if (b.rigid) {
        out << YAML::Key << "rigid" << YAML::Value << YAML::Flow << YAML::BeginMap;
        if (b.plane) {
            out << YAML::Key << "plane" << YAML::Value << YAML::BeginMap;
            out << YAML::Key << "point" << YAML::Value;
            numbers(out, b.plane->point);
            out << YAML::Key << "normal" << YAML::Value;
            numbers(out, b.plane->normal);
            out << YAML::EndMap;
        }
        if (b.sphere) {
            out << YAML::Key << (b.sphere->center.size() == 3 ? "sphere" : "circle") << YAML::Value
                << YAML::BeginMap;
            out << YAML::Key << "center" << YAML::Value;
            numbers(out, b.sphere->center);
            out << YAML::Key << "radius" << YAML::Value << format_number(b.sphere->radius);
            out << YAML::EndMap;
        }
        if (!b.motion.empty()) {
            out << YAML::Key << "motion" << YAML::Value;
            numbers(out, b.motion);
            write_amplitude(out, b.amplitude);
        }
        out << YAML::EndMap << YAML::EndMap;
        return;
    }
    out << YAML::Key << "material" << YAML::Value << b.material;
    if (b.nurbs) {
        out << YAML::Key << "nurbs" << YAML::Value;
        write_nurbs(out, *b.nurbs);
    }
    // A geometry file's patches take no refine of their own: once one has (accuracy:
    // levels refine a patch), the body is written as inline patches.
    const bool own_refine = std::any_of(b.patches.begin(), b.patches.end(),
                                        [](const PatchData& p) { return p.refine != Refine{}; });
    if (!b.geometry_file.empty() && !own_refine) {
        out << YAML::Key << "geometry" << YAML::Value << YAML::Flow << YAML::BeginMap;
        out << YAML::Key << "file" << YAML::Value << b.geometry_file;
        write_transform(out, b.geometry_transform);
        out << YAML::EndMap;
    } else if (b.multi_patch()) {
        out << YAML::Key << "patches" << YAML::Value << YAML::BeginSeq;
        for (const PatchData& patch : b.patches) {
            out << YAML::BeginMap << YAML::Key << "name" << YAML::Value << patch.name;
            out << YAML::Key << "nurbs" << YAML::Value;
            write_nurbs(out, patch.nurbs);
            write_refine(out, patch.refine);
            out << YAML::EndMap;
        }
        out << YAML::EndSeq;
    }
    if (b.shape) {
        const Shape& s = *b.shape;
        out << YAML::Key << "shape" << YAML::Value << YAML::Flow << YAML::BeginMap;
        out << YAML::Key << "type" << YAML::Value << word(s.type);
        if (s.type == ShapeType::rectangle || s.type == ShapeType::box) {
            out << YAML::Key << "corner" << YAML::Value;
            numbers(out, s.corner);
            out << YAML::Key << "size" << YAML::Value;
            numbers(out, s.size);
        } else {
            out << YAML::Key << "center" << YAML::Value;
            numbers(out, s.center);
            out << YAML::Key << "radius" << YAML::Value << format_number(s.radius);
        }
        if (s.extrude)
            out << YAML::Key << "extrude" << YAML::Value << format_number(*s.extrude);
        write_transform(out, s.transform);
        out << YAML::EndMap;
    }
    write_refine(out, b.refine);
    if (b.quadrature.element > 0 || b.quadrature.side > 0) {  // 0: the default rule, left out
        out << YAML::Key << "quadrature" << YAML::Value << YAML::Flow << YAML::BeginMap;
        if (b.quadrature.element > 0)
            out << YAML::Key << "element" << YAML::Value << std::to_string(b.quadrature.element);
        if (b.quadrature.side > 0)
            out << YAML::Key << "side" << YAML::Value << std::to_string(b.quadrature.side);
        out << YAML::EndMap;
    }
    if (!b.surfaces.empty()) {
        out << YAML::Key << "surfaces" << YAML::Value << YAML::BeginMap;
        for (const NamedSurface& surface : b.surfaces) {
            out << YAML::Key << surface.name << YAML::Value << YAML::Flow << YAML::BeginSeq;
            for (const PatchSideRef& side : surface.sides)
                out << side_text(side.patch, side.side, "");
            out << YAML::EndSeq;
        }
        out << YAML::EndMap;
    }
    out << YAML::EndMap;
}

void write_constraint(YAML::Emitter& out, const Constraint& k, int dim)
{
    out << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "body" << YAML::Value << k.body;
    out << YAML::Key << "side" << YAML::Value << side_text(k.patch, k.side, k.surface);
    // Zero values are written as `fix`, the others as `displacement` with ~ for
    // the components it leaves to `fix` or free: reads back to the same constraint.
    // With an amplitude every prescribed component goes to `displacement` (zeros
    // as 0.0): an amplitude needs a `displacement` to scale.
    constexpr const char* components[] = {"x", "y", "z"};
    const int n = std::min(dim, static_cast<int>(k.fixed.size()));
    const bool scaled = k.amplitude.has_value();
    bool any_fixed = false, any_value = false;
    for (int i = 0; i < n; ++i) {
        any_fixed = any_fixed || (k.fixed[i] && k.value[i] == 0.0 && !scaled);
        any_value = any_value || (k.fixed[i] && (k.value[i] != 0.0 || scaled));
    }
    if (any_fixed || !any_value) {
        out << YAML::Key << "fix" << YAML::Value << YAML::Flow << YAML::BeginSeq;
        for (int i = 0; i < n; ++i)
            if (k.fixed[i] && k.value[i] == 0.0)
                out << components[i];
        out << YAML::EndSeq;
    }
    if (any_value) {
        out << YAML::Key << "displacement" << YAML::Value << YAML::Flow << YAML::BeginSeq;
        for (int i = 0; i < n; ++i) {
            if (k.fixed[i] && (k.value[i] != 0.0 || scaled))
                out << format_number(k.value[i]);
            else
                out << YAML::Null;
        }
        out << YAML::EndSeq;
    }
    write_amplitude(out, k.amplitude);
    out << YAML::EndMap;
}

void write_load(YAML::Emitter& out, const Load& l)
{
    out << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "body" << YAML::Value << l.body;
    if (l.side || !l.surface.empty())
        out << YAML::Key << "side" << YAML::Value << side_text(l.patch, l.side.value_or(Side::u0), l.surface);
    out << YAML::Key << word(l.kind) << YAML::Value;  // the kind is the key of the load's value
    if (l.kind == LoadKind::pressure)
        out << format_number(l.pressure);
    else
        numbers(out, l.vector);
    if (l.kind == LoadKind::gravity)
        out << YAML::Key << "density" << YAML::Value << format_number(l.density);
    write_amplitude(out, l.amplitude);
    out << YAML::EndMap;
}

void write_contact(YAML::Emitter& out, const ContactPair& p)
{
    out << YAML::BeginMap;
    out << YAML::Key << "name" << YAML::Value << p.name;
    out << YAML::Key << "between" << YAML::Value << YAML::Flow << YAML::BeginSeq << surface(p.first)
        << surface(p.second) << YAML::EndSeq;
    out << YAML::Key << "formulation" << YAML::Value << word(p.formulation);
    out << YAML::Key << "enforcement" << YAML::Value << word(p.enforcement);
    if (p.law.type == LawType::exponential) {
        out << YAML::Key << "law" << YAML::Value << YAML::Flow << YAML::BeginMap;
        out << YAML::Key << "type" << YAML::Value << word(p.law.type);
        out << YAML::Key << "clearance" << YAML::Value << format_number(p.law.clearance);
        out << YAML::Key << "pressure" << YAML::Value << format_number(p.law.pressure);
        out << YAML::EndMap;
    } else if (p.penalty_auto) {
        out << YAML::Key << "penalty" << YAML::Value << "auto";
    } else {
        out << YAML::Key << "penalty" << YAML::Value << format_number(p.penalty);
    }
    if (p.enforcement == Enforcement::augmented_lagrangian) {
        out << YAML::Key << "augmented_lagrangian" << YAML::Value << YAML::Flow << YAML::BeginMap;
        if (p.augmented_lagrangian.gap_tolerance > 0.0)  // 0: automatic, left out as quadrature 0 is
            out << YAML::Key << "gap_tolerance" << YAML::Value << format_number(p.augmented_lagrangian.gap_tolerance);
        out << YAML::Key << "max_updates" << YAML::Value << std::to_string(p.augmented_lagrangian.max_updates);
        out << YAML::EndMap;
    }
    if (p.friction.coefficient > 0.0) {
        out << YAML::Key << "friction" << YAML::Value << YAML::Flow << YAML::BeginMap;
        out << YAML::Key << "coefficient" << YAML::Value << format_number(p.friction.coefficient);
        out << YAML::Key << "tangential_penalty" << YAML::Value
            << (p.friction.tangential_penalty_auto ? std::string("auto") : format_number(p.friction.tangential_penalty));
        out << YAML::EndMap;
    }
    if (p.quadrature > 0)
        out << YAML::Key << "quadrature" << YAML::Value << std::to_string(p.quadrature);
    out << YAML::EndMap;
}

void write_output(YAML::Emitter& out, const Output& o)
{
    out << YAML::BeginMap;
    out << YAML::Key << "file" << YAML::Value << o.file;
    out << YAML::Key << "every_step" << YAML::Value << word(o.every_step);
    out << YAML::Key << "samples_per_span" << YAML::Value << std::to_string(o.samples_per_span);
    if (o.reference) {
        const Reference& r = *o.reference;
        out << YAML::Key << "reference" << YAML::Value << YAML::Flow << YAML::BeginMap;
        out << YAML::Key << "pair" << YAML::Value << r.pair;
        out << YAML::Key << "type" << YAML::Value << word(r.type);
        if (is_against_plane(r.type)) {
            out << YAML::Key << "radius" << YAML::Value << format_number(r.radius);
        } else {
            out << YAML::Key << "radii" << YAML::Value;
            numbers(out, r.radii);
        }
        out << YAML::Key << "force" << YAML::Value << format_number(r.force);
        out << YAML::EndMap;
    }
    out << YAML::Key << "paraview" << YAML::Value << word(o.paraview);
    out << YAML::Key << "fields" << YAML::Value << word(o.fields);
    out << YAML::EndMap;
}

void write_accuracy(YAML::Emitter& out, const Accuracy& a)
{
    out << YAML::BeginMap;
    out << YAML::Key << "target" << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "pair" << YAML::Value << a.pair;
    out << YAML::Key << "quantity" << YAML::Value << word(a.quantity);
    out << YAML::Key << "error" << YAML::Value << format_number(a.error);
    out << YAML::EndMap;
    out << YAML::Key << "budget" << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "levels" << YAML::Value << std::to_string(a.levels);
    if (a.dofs > 0.0)
        out << YAML::Key << "dofs" << YAML::Value << format_number(a.dofs);
    if (a.seconds > 0.0)
        out << YAML::Key << "seconds" << YAML::Value << format_number(a.seconds);
    out << YAML::EndMap;
    out << YAML::EndMap;
}

}  // namespace

std::string write_resolved_yaml(const Deck& deck)
{
    YAML::Emitter out;
    out.SetIndent(2);
    out << YAML::BeginMap;
    out << YAML::Key << "format" << YAML::Value << std::to_string(deck.format);
    out << YAML::Key << "title" << YAML::Value << deck.title;

    out << YAML::Key << "analysis" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "dimension" << YAML::Value << std::to_string(deck.analysis.dimension);
    if (deck.analysis.dimension == 2)
        out << YAML::Key << "plane" << YAML::Value << word(deck.analysis.plane);
    out << YAML::Key << "kinematics" << YAML::Value << word(deck.analysis.kinematics);
    out << YAML::EndMap;

    out << YAML::Key << "materials" << YAML::Value << YAML::BeginSeq;
    for (const Material& m : deck.materials) {
        out << YAML::BeginMap << YAML::Key << "name" << YAML::Value << m.name;
        out << YAML::Key << "model" << YAML::Value << word(m.model);
        out << YAML::Key << "E" << YAML::Value << format_number(m.E);
        out << YAML::Key << "nu" << YAML::Value << format_number(m.nu);
        out << YAML::EndMap;
    }
    out << YAML::EndSeq;

    out << YAML::Key << "bodies" << YAML::Value << YAML::BeginSeq;
    for (const Body& b : deck.bodies)
        write_body(out, b);
    out << YAML::EndSeq;

    out << YAML::Key << "constraints" << YAML::Value;
    if (begin_items(out, deck.constraints)) {
        for (const Constraint& k : deck.constraints)
            write_constraint(out, k, deck.analysis.dimension);
        out << YAML::EndSeq;
    }

    out << YAML::Key << "loads" << YAML::Value;
    if (begin_items(out, deck.loads)) {
        for (const Load& l : deck.loads)
            write_load(out, l);
        out << YAML::EndSeq;
    }

    out << YAML::Key << "contact" << YAML::Value;
    if (begin_items(out, deck.contact)) {
        for (const ContactPair& p : deck.contact)
            write_contact(out, p);
        out << YAML::EndSeq;
    }

    out << YAML::Key << "steps" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "count" << YAML::Value << std::to_string(deck.steps.count);
    out << YAML::Key << "adaptive" << YAML::Value << word(deck.steps.adaptive);
    out << YAML::Key << "max_cutbacks" << YAML::Value << std::to_string(deck.steps.max_cutbacks);
    out << YAML::EndMap;

    out << YAML::Key << "newton" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "tolerance" << YAML::Value << format_number(deck.newton.tolerance);
    out << YAML::Key << "max_iterations" << YAML::Value << std::to_string(deck.newton.max_iterations);
    out << YAML::Key << "line_search" << YAML::Value << word(deck.newton.line_search);
    out << YAML::EndMap;

    out << YAML::Key << "solver" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "backend" << YAML::Value << word(deck.solver.backend);
    out << YAML::Key << "type" << YAML::Value << word(deck.solver.type);
    if (!deck.solver.options.empty())
        out << YAML::Key << "options" << YAML::Value << deck.solver.options;
    out << YAML::EndMap;

    out << YAML::Key << "output" << YAML::Value;
    write_output(out, deck.output);
    if (deck.accuracy) {
        out << YAML::Key << "accuracy" << YAML::Value;
        write_accuracy(out, *deck.accuracy);
    }
    out << YAML::EndMap;
    return std::string(out.c_str()) + "\n";
}

}  // namespace iga::io
