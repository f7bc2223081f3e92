#include "io/body_reader.hpp"

#include "io/amplitude_reader.hpp"
#include "io/gismo_xml.hpp"
#include "io/knot_checks.hpp"
#include "io/transform_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

namespace iga::io {

const std::pair<std::string, bool>* KnownNames::find_body(const std::string& name) const
{
    const auto it = std::find_if(bodies.begin(), bodies.end(), [&](const auto& b) { return b.first == name; });
    return it == bodies.end() ? nullptr : &*it;
}

const BodyParts* KnownNames::find_parts(const std::string& name) const
{
    const auto it = std::find_if(parts.begin(), parts.end(), [&](const auto& b) { return b.first == name; });
    return it == parts.end() ? nullptr : &it->second;
}

std::vector<std::string> KnownNames::body_names() const
{
    std::vector<std::string> names;
    for (const auto& b : bodies)
        names.push_back(b.first);
    return names;
}

bool NameRegistry::add(const std::string& name, const Cursor& at)
{
    for (const auto& [seen, where] : seen_) {
        if (seen != name)
            continue;
        std::string first;
        if (where.line > 0)
            first = " (first defined at line " + std::to_string(where.line) + ")";
        else if (where.file == command_line_file)
            first = " (first defined on the command line)";
        at.fail("duplicate " + what_ + " name" + first);
        return false;
    }
    seen_.emplace_back(name, at.location());
    return true;
}

std::optional<std::string> read_name(const Cursor& item)
{
    const auto name = item.read<std::string>("name");
    if (!name)
        return std::nullopt;
    if (name->empty() || name->find('.') != std::string::npos) {
        item.child("name").fail("must be a non-empty word without '.' (the separator in key paths and body.side)");
        return std::nullopt;
    }
    return name;
}

std::vector<std::string> side_names(int dim)
{
    std::vector<std::string> names;
    for (int i = 0; i < 2 * dim; ++i)
        names.emplace_back(side_name(static_cast<Side>(i)));
    return names;
}

std::optional<Side> side_from_text(const Cursor& at, const std::string& text, int dim)
{
    const auto side = parse_side(text);
    if (side && side_direction(*side) < dim)
        return side;
    at.fail("'" + text + "' is not a side of a " + std::to_string(dim) + "D patch (sides: " +
            join_names(side_names(dim)) + ")");
    return std::nullopt;
}

std::optional<SideReference> side_reference(const Cursor& at, const std::string& text, const std::string& body,
                                            const KnownNames& known)
{
    const BodyParts* parts = known.find_parts(body);
    if (!parts || parts->unknown)
        return std::nullopt;  // an unknown body is reported where it is named, an unread file where it is given
    if (std::find(parts->surfaces.begin(), parts->surfaces.end(), text) != parts->surfaces.end())
        return SideReference{"", Side::u0, text};
    const auto dot = text.find('.');
    if (!parts->multi_patch) {
        if (dot != std::string::npos) {
            at.fail("body '" + body + "' is a single patch: write a side (" + join_names(side_names(known.dim)) +
                    ")" + (parts->surfaces.empty() ? "" : " or a named surface (" + join_names(parts->surfaces) + ")"));
            return std::nullopt;
        }
        if (!parse_side(text) && !parts->surfaces.empty()) {
            at.fail("'" + text + "' is neither a side (" + join_names(side_names(known.dim)) +
                    ") nor a named surface of body '" + body + "'" + hint_or_list(text, parts->surfaces, "surfaces"));
            return std::nullopt;
        }
        const auto side = side_from_text(at, text, known.dim);
        return side ? std::optional(SideReference{"", *side, ""}) : std::nullopt;
    }
    if (dot == std::string::npos) {
        std::vector<std::string> choices = parts->surfaces;
        at.fail("'" + text + "' is not a named surface of the multi-patch body '" + body +
                "'; write a surface" + (choices.empty() ? "" : " (" + join_names(choices) + ")") +
                " or patch.side (e.g. " + parts->patches.front() + ".v0)");
        return std::nullopt;
    }
    const std::string patch = text.substr(0, dot);
    if (std::find(parts->patches.begin(), parts->patches.end(), patch) == parts->patches.end()) {
        at.fail("unknown patch '" + patch + "' of body '" + body + "'" + hint_or_list(patch, parts->patches, "patches"));
        return std::nullopt;
    }
    const auto side = side_from_text(at, text.substr(dot + 1), known.dim);
    return side ? std::optional(SideReference{patch, *side, ""}) : std::nullopt;
}

void read_geometry_file(const Cursor& at, const std::string& path, int dim, Body& body)
{
    try {
        for (ImportedPatch& imported : read_gismo_xml(path, dim))
            body.patches.push_back(PatchData{std::move(imported.name), std::move(imported.nurbs), {}});
    } catch (const DeckError& e) {
        // The file's own messages carry its path and line; the deck location says who asked for it.
        at.fail(std::string("cannot read the G+Smo XML geometry:\n") + e.what());
    }
}

namespace {

/// Degrees and knot vectors of a patch as the deck gives them: what `refine` is checked against.
struct Parametrization {
    std::vector<int> degrees;
    std::vector<std::vector<double>> knots;
};

/// The required value of `key`, or nullopt after recording that it is missing.
std::optional<Cursor> required(const Cursor& map, std::string_view key)
{
    const Cursor c = map.child(key);
    if (c.exists())
        return c;
    map.fail_missing(key);
    return std::nullopt;
}

/// Checks an open knot vector of degree p (io/knot_checks.hpp); records its problems at `c`.
bool check_knots(const Cursor& c, const std::vector<double>& u, int p)
{
    const auto problems = knot_vector_problems(u, p);
    for (const KnotProblem& problem : problems)
        (problem.knot ? c.item(*problem.knot) : c).fail(problem.reason);
    return problems.empty();
}

std::optional<NurbsData> read_nurbs(const Cursor& c, int dim, std::optional<Parametrization>& param)
{
    if (!c.check_keys())
        return std::nullopt;
    NurbsData nurbs;
    bool knots_ok = false;
    const auto degrees = c.read<std::vector<int>>("degrees", dim);
    const bool degrees_ok = degrees.has_value();
    nurbs.degrees = degrees.value_or(std::vector<int>{});
    if (const auto k = required(c, "knots")) {
        if (!k->is_list() || k->size() != static_cast<std::size_t>(dim)) {
            k->fail(fmt::format("expected a list of {} knot vectors (one per parametric direction)", dim));
        } else {
            knots_ok = degrees_ok;
            for (int dir = 0; dir < dim; ++dir) {
                const Cursor kc = k->item(dir);
                const auto u = kc.to_numbers();
                if (u)
                    nurbs.knots.push_back(*u);
                knots_ok = u && degrees_ok && check_knots(kc, *u, nurbs.degrees[dir]) && knots_ok;
            }
        }
    }
    if (const auto cps = required(c, "control_points"); cps && cps->expect_list()) {
        for (const Cursor& point : cps->items()) {
            const auto row = point.to_numbers(dim + 1);
            if (!row)
                continue;
            if (!(row->back() > 0))
                point.item(dim).fail("weight must be > 0");
            nurbs.control_points.push_back(*row);
        }
        if (knots_ok) {
            std::size_t expected = 1;
            std::string product;
            for (int dir = 0; dir < dim; ++dir) {
                const std::size_t n = nurbs.knots[dir].size() - nurbs.degrees[dir] - 1;
                expected *= n;
                product += (dir > 0 ? " x " : "") + std::to_string(n);
            }
            if (cps->size() != expected)
                cps->fail_here(fmt::format("expected {} control points ({} from the knots and degrees), got {}",
                                           expected, product, cps->size()));
        }
    }
    if (c.has("transform"))
        nurbs.transform = read_transform(c.child("transform"), dim);
    if (degrees_ok && knots_ok) {
        param = Parametrization{nurbs.degrees, nurbs.knots};  // `refine` is in the parameters as given
    }
    return nurbs;
}

/// The parametrization of a built-in shape, as nurbs/shapes.hpp builds it:
/// the degrees of io::shape_degrees, one span on [0, 1] per direction.
Parametrization shape_parametrization(const Shape& shape)
{
    Parametrization param;
    param.degrees = shape_degrees(shape);
    for (int p : param.degrees) {
        std::vector<double> u(2 * static_cast<std::size_t>(p) + 2, 0.0);
        std::fill(u.begin() + p + 1, u.end(), 1.0);
        param.knots.push_back(std::move(u));
    }
    return param;
}

std::optional<Shape> read_shape(const Cursor& c, int dim, std::optional<Parametrization>& param)
{
    if (!c.check_keys())
        return std::nullopt;
    const auto type = c.read<ShapeType>("type");
    if (!type)
        return std::nullopt;
    Shape s;
    s.type = *type;
    const std::string name(deck_name(s.type));
    const bool solid = is_solid_shape(s.type);
    if (solid && dim != 3) {
        c.child("type").fail("a 3D shape, but analysis.dimension is 2 (2D shapes: half_disc, quarter_disc, "
                             "rectangle)");
        return std::nullopt;
    }
    bool ok = true;
    if (c.has("extrude")) {
        const Cursor e = c.child("extrude");
        if (solid) {
            e.fail_here("does not apply to a " + name + " (a 3D shape; only 2D shapes are extruded)");
            ok = false;
        } else if (dim != 3) {
            e.fail_here("applies to 3D decks only (it sweeps a 2D shape along z)");
            ok = false;
        } else {
            s.extrude = c.read_required<double>("extrude");
            ok = s.extrude.has_value();
        }
    } else if (!solid && dim == 3) {
        c.fail_here("a 2D shape in a 3D deck needs 'extrude: L', its length along z (or use a 3D shape: "
                    "sphere_octant, box)");
        ok = false;
    }
    if (ok)
        param = shape_parametrization(s);
    const std::size_t n = solid ? 3 : 2;
    const bool round = s.type != ShapeType::rectangle && s.type != ShapeType::box;
    const std::string takes = round ? "center and radius" : "corner and size";
    for (const char* key : round ? std::vector{"corner", "size"} : std::vector{"center", "radius"})
        if (c.has(key))
            c.child(key).fail_here("does not apply to a " + name + " (it takes " + takes + ")");
    if (round) {
        s.center = c.read_required<std::vector<double>>("center", n).value_or(std::vector<double>{});
        s.radius = c.read_required<double>("radius").value_or(0.0);
    } else {
        s.corner = c.read_required<std::vector<double>>("corner", n).value_or(std::vector<double>{});
        s.size = c.read_required<std::vector<double>>("size", n).value_or(std::vector<double>{});
    }
    if (c.has("transform"))  // acts on the 3D solid after an extrusion: d = dim numbers either way
        s.transform = read_transform(c.child("transform"), dim);
    return s;
}

/// Checks one direction of `refine.insert` against the parameter interval and,
/// when the patch is known, against the degree after elevation: a value inserted
/// more often than the degree allows would break the patch apart.
void check_insert(const Cursor& c, const std::vector<double>& values, const std::vector<double>& knots, int degree,
                  int elevate, int spans)
{
    const double front = knots.front();
    const double back = knots.back();
    for (std::size_t k = 0; k < values.size(); ++k) {
        const double v = values[k];
        if (!(v > front && v < back)) {
            c.item(k).fail(fmt::format("must lie strictly inside the parameter interval ({}, {})", front, back));
            continue;
        }
        if (std::find(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), v) !=
            values.begin() + static_cast<std::ptrdiff_t>(k))
            continue;  // each value is checked once, at its first occurrence
        int multiplicity = static_cast<int>(std::count(knots.begin(), knots.end(), v));
        if (multiplicity > 0)
            multiplicity += elevate;  // elevation keeps the continuity, so interior knots repeat more
        else if (spans > 0) {
            // The grid values refine_uniform inserts, front + i (back - front) / spans for
            // 0 < i < spans: only the nearest few can be v (a loop over all of them took
            // minutes for spans: [1e8, 1e8]). A relative 1e-12 absorbs their round-off.
            const double nearest = std::round((v - front) / (back - front) * spans);
            for (double i = nearest - 1; i <= nearest + 1; ++i)
                if (i >= 1 && i < spans && std::abs(front + i * (back - front) / spans - v) <= 1e-12 * (back - front))
                    multiplicity = 1;
        }
        multiplicity += static_cast<int>(std::count(values.begin(), values.end(), v));
        if (multiplicity > degree + elevate)
            c.item(k).fail(fmt::format("the knot would appear {} times, more than the degree {}", multiplicity,
                                       degree + elevate));
    }
}

Refine read_refine(const Cursor& c, int dim, const std::optional<Parametrization>& param)
{
    Refine r;
    if (!c.check_keys())
        return r;
    r.elevate = c.read<std::vector<int>>("elevate", dim).value_or(r.elevate);
    r.spans = c.read<std::vector<int>>("spans", dim).value_or(r.spans);
    const Cursor insert = c.child("insert");
    if (!insert.exists())
        return r;
    if (!insert.is_list() || insert.size() != static_cast<std::size_t>(dim)) {
        insert.fail(fmt::format("expected a list of {} lists of knot values (one per parametric direction)", dim));
        return r;
    }
    for (int dir = 0; dir < dim; ++dir) {
        const Cursor values = insert.item(dir);
        const auto v = values.to_numbers();
        r.insert.push_back(v.value_or(std::vector<double>{}));
        if (v && param)
            check_insert(values, *v, param->knots[dir], param->degrees[dir],
                         r.elevate.empty() ? 0 : std::max(0, r.elevate[dir]),
                         r.spans.empty() ? 0 : r.spans[dir]);
    }
    return r;
}

std::optional<RigidPlane> read_plane(const Cursor& plane, int dim)
{
    if (!plane.check_keys())
        return std::nullopt;
    RigidPlane r;
    r.point = plane.read<std::vector<double>>("point", dim).value_or(std::vector<double>{});
    const auto n = plane.read<std::vector<double>>("normal", dim);
    if (!n)
        return r;
    const Cursor normal = plane.child("normal");
    double largest = 0.0;
    for (double x : *n)
        largest = std::max(largest, std::abs(x));
    if (!(largest > 0)) {
        normal.fail("must have non-zero length");
        return r;
    }
    double norm2 = 0.0;
    for (double x : *n)
        norm2 += x * x;
    // The sum of squares overflows beyond about 1e154 and underflows below 1e-154:
    // there, divide by the largest entry first (every finite non-zero normal is valid).
    const bool representable = std::isfinite(norm2) && norm2 >= std::numeric_limits<double>::min();
    double scale = 1.0;
    if (!representable) {
        scale = largest;
        norm2 = 0.0;
        for (double x : *n)
            norm2 += (x / scale) * (x / scale);
    }
    const double norm = std::sqrt(norm2);  // of n / scale
    r.normal = *n;
    // A normal of unit length up to round-off is kept as written, so that the
    // resolved deck reads back bit-identical (renormalizing may move the last bit).
    constexpr double unit_length_slack = 4 * std::numeric_limits<double>::epsilon();
    if (!representable || std::abs(norm - 1.0) > unit_length_slack)
        for (double& x : r.normal)
            x = x / scale / norm;
    return r;
}

std::optional<RigidSphere> read_sphere(const Cursor& sphere, int dim)
{
    if (!sphere.check_keys())
        return std::nullopt;
    RigidSphere r;
    r.center = sphere.read<std::vector<double>>("center", dim).value_or(std::vector<double>{});
    r.radius = sphere.read<double>("radius").value_or(0.0);
    return r;
}

/// `rigid:` of an obstacle: one of plane / circle (2D) / sphere (3D), and an optional motion
/// with an optional amplitude.
void read_rigid(const Cursor& c, int dim, Body& b)
{
    const char* round = dim == 3 ? "sphere" : "circle";
    const char* other_round = dim == 3 ? "circle" : "sphere";
    if (!c.check_keys())
        return;
    if (c.has(other_round)) {
        c.child(other_round).fail_here(fmt::format("a {}D analysis takes '{}', not '{}'", dim, round, other_round));
        return;
    }
    const bool plane = c.has("plane"), sphere = c.has(round);
    if (plane == sphere) {
        c.fail_here(plane ? fmt::format("takes 'plane' or '{}', not both", round)
                          : fmt::format("needs 'plane' or '{}'", round));
        return;
    }
    if (plane)
        b.plane = read_plane(c.child("plane"), dim);
    else
        b.sphere = read_sphere(c.child(round), dim);
    if (c.has("motion"))
        b.motion = c.read<std::vector<double>>("motion", dim).value_or(std::vector<double>{});
    if (c.has("amplitude")) {
        if (c.has("motion"))
            b.amplitude = read_amplitude(c.child("amplitude"));
        else
            c.child("amplitude").fail_here("scales the obstacle's 'motion'; this obstacle has none (it is fixed), "
                                           "so there is nothing to scale");
    }
}

/// `patches:` of a multi-patch body: a list of {name, nurbs, refine}.
std::vector<PatchData> read_patches(const Cursor& list, int dim, const Refine& body_refine)
{
    std::vector<PatchData> out;
    if (!list.expect_list())
        return out;
    if (list.size() == 0)
        list.fail_here("must list at least one patch");
    NameRegistry names("patch");
    for (const Cursor& c : list.items()) {
        if (!c.check_keys())
            continue;
        PatchData patch;
        if (const auto name = read_name(c)) {
            patch.name = *name;
            names.add(*name, c.child("name"));
        }
        std::optional<Parametrization> param;
        if (const auto nurbs = required(c, "nurbs"))
            if (auto data = read_nurbs(*nurbs, dim, param))
                patch.nurbs = std::move(*data);
        if (c.has("refine")) {
            // Inserted knots are checked against the patch as the body's refine leaves it.
            if (param)
                for (std::size_t dir = 0; dir < body_refine.elevate.size() && dir < param->degrees.size(); ++dir)
                    param->degrees[dir] += body_refine.elevate[dir];
            patch.refine = read_refine(c.child("refine"), dim, param);
        }
        out.push_back(std::move(patch));
    }
    return out;
}

/// `surfaces: {name: [patch.side, ...]}`: each side once per surface.
std::vector<NamedSurface> read_surfaces(const Cursor& map, const std::string& body, KnownNames& known)
{
    std::vector<NamedSurface> out;
    if (!map.expect_map())
        return out;
    BodyParts* parts = nullptr;
    for (auto& [name, p] : known.parts)
        if (name == body)
            parts = &p;
    for (const std::string& key : map.keys()) {
        const Cursor list = map.child(key);
        if (key.empty() || key.find('.') != std::string::npos || parse_side(key)) {
            list.fail_here("a surface name must be a non-empty word without '.' and not a side name (" +
                           join_names(side_names(known.dim)) + ")");
            continue;
        }
        if (parts && std::find(parts->patches.begin(), parts->patches.end(), key) != parts->patches.end()) {
            list.fail_here("'" + key + "' names a patch already; give the surface another name");
            continue;
        }
        NamedSurface surface{key, {}};
        if (!list.is_list() || list.size() == 0) {
            list.fail("expected a list of patch sides, e.g. [" +
                      (parts && parts->multi_patch ? parts->patches.front() + ".v0" : std::string("v0")) + "]");
            continue;
        }
        for (std::size_t i = 0; i < list.size(); ++i) {
            const Cursor item = list.item(i);
            const auto text = item.to_string();
            if (!text)
                continue;
            const auto ref = side_reference(item, *text, body, known);
            if (!ref)
                continue;
            if (!ref->surface.empty()) {
                item.fail("a surface lists patch sides, not other surfaces");
                continue;
            }
            const PatchSideRef side{ref->patch, ref->side};
            if (std::find(surface.sides.begin(), surface.sides.end(), side) != surface.sides.end()) {
                item.fail("names the side " + side_text(side.patch, side.side, "") + " twice");
                continue;
            }
            surface.sides.push_back(side);
        }
        out.push_back(std::move(surface));
    }
    if (parts)
        for (const auto& s : out)
            parts->surfaces.push_back(s.name);
    return out;
}

}  // namespace

Body read_body(const Cursor& c, KnownNames& known, NameRegistry& names)
{
    Body b;
    if (!c.check_keys())
        return b;
    b.rigid = c.has("rigid");
    if (const auto name = read_name(c)) {
        b.name = *name;
        if (names.add(*name, c.child("name")))
            known.bodies.emplace_back(*name, b.rigid);
    }
    if (b.rigid) {
        for (const std::string& key : map_keys(c.schema_path()))  // the keys of a deformable body
            if (key != "name" && key != "rigid" && c.has(key))
                c.child(key).fail_here("a rigid body takes no '" + key + "'");
        if (const Cursor rigid = c.child("rigid"); rigid.expect_map())
            read_rigid(rigid, known.dim, b);
        return b;
    }
    if (const auto material = c.read_required<std::string>("material")) {
        b.material = *material;
        if (std::find(known.materials.begin(), known.materials.end(), *material) == known.materials.end())
            c.child("material").fail("unknown material '" + *material + "'" +
                                     hint_or_list(*material, known.materials, "materials"));
    }
    const bool has_nurbs = c.has("nurbs");
    const bool has_shape = c.has("shape");
    const bool has_patches = c.has("patches");
    const bool has_file = c.has("geometry");
    const int n_given = has_nurbs + has_shape + has_patches + has_file;
    if (n_given > 1)
        c.fail_here("takes one of 'nurbs', 'shape', 'patches' or 'geometry', not several");
    else if (n_given == 0)
        c.fail_here("needs 'nurbs', 'shape', 'patches' or 'geometry' (or 'rigid' for an obstacle)");
    const bool alone = n_given == 1;
    std::optional<Parametrization> param;
    if (has_nurbs && alone)
        b.nurbs = read_nurbs(c.child("nurbs"), known.dim, param);
    if (has_shape && alone)
        b.shape = read_shape(c.child("shape"), known.dim, param);
    if (c.has("refine"))
        b.refine = read_refine(c.child("refine"), known.dim, param);  // multi-patch: checked per patch at build
    if (const Cursor q = c.child("quadrature"); q.exists() && q.check_keys()) {
        b.quadrature.element = q.read_or("element", 0);
        b.quadrature.side = q.read_or("side", 0);
    }
    if (has_patches && alone)
        b.patches = read_patches(c.child("patches"), known.dim, b.refine);
    if (has_file && alone) {
        const Cursor g = c.child("geometry");
        if (g.check_keys())
            if (const auto file = g.read<std::string>("file")) {
                b.geometry_file = *file;
                const std::filesystem::path p(*file);
                const std::string path = p.is_absolute() || known.deck_dir.empty()
                                             ? p.lexically_normal().string()
                                             : (std::filesystem::path(known.deck_dir) / p).lexically_normal().string();
                read_geometry_file(g.child("file"), path, known.dim, b);
                if (g.has("transform")) {
                    b.geometry_transform = read_transform(g.child("transform"), known.dim);
                    for (PatchData& patch : b.patches)
                        patch.nurbs.transform = b.geometry_transform;
                }
            }
    }
    BodyParts parts;
    parts.multi_patch = has_patches || has_file;
    parts.unknown = has_file && b.patches.empty();
    for (const PatchData& patch : b.patches)
        parts.patches.push_back(patch.name);
    if (parts.multi_patch && parts.patches.empty())
        parts.patches.push_back("p0");  // keeps later messages well-formed after an error here
    known.parts.emplace_back(b.name, std::move(parts));
    if (c.has("surfaces"))
        b.surfaces = read_surfaces(c.child("surfaces"), b.name, known);
    return b;
}

}  // namespace iga::io
