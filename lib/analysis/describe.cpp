#include "analysis/describe.hpp"

#include "nurbs/coincidence.hpp"
#include "core/text.hpp"
#include "io/deck_names.hpp"

#include "analysis/geometry.hpp"
#include "io/locate.hpp"
#include "nurbs/shapes.hpp"
#include "analysis/multipatch.hpp"
#include "nurbs/side_patch.hpp"

#include <fmt/format.h>

namespace iga::analysis {

namespace {

std::string generic_side_meaning(Side s)
{
    static const char* directions = "uvw";
    return fmt::format("{} = {}", directions[side_direction(s)], side_at_end(s) ? "max" : "min");
}

/// Control points of a patch coincide when closer than this (nurbs/coincidence.hpp).
double coincidence_tolerance(const nurbs::Patch& patch)
{
    return nurbs::coincidence_tolerance(patch.control_points());
}

/// The corners of a side (open knot vectors interpolate them): 2 in 2D, 4 in 3D,
/// in the side's own parameter order (first direction fastest).
std::string side_corners(const nurbs::SidePatch& sp)
{
    const RowMatrix& P = sp.patch.control_points();
    const int n0 = sp.patch.n_basis(0), n1 = sp.patch.n_par() > 1 ? sp.patch.n_basis(1) : 1;
    const std::vector<int> rows = n1 == 1 ? std::vector<int>{0, n0 - 1}
                                          : std::vector<int>{0, n0 - 1, n0 * (n1 - 1), n0 * n1 - 1};
    std::string out;
    for (int r : rows) {
        if (!out.empty())
            out += ' ';
        out += point_text(P, static_cast<Index>(r));
    }
    return out;
}

/// " (collapsed to a point)" when all control points of the side coincide, " (collapsed
/// to a line)" when a face's control points coincide along one of its directions (the
/// axis of a revolved solid, an extruded corner), "" for a side of positive measure.
std::string collapse_note(const nurbs::SidePatch& sp, double tolerance)
{
    if (nurbs::is_collapsed(sp, tolerance))
        return " (collapsed to a point)";
    return nurbs::is_collapsed_to_line(sp, tolerance) ? " (collapsed to a line)" : "";
}

/// "#     <label>: <meaning>; corners ... (collapsed ...)"
std::string side_line(const std::string& label, const std::string& meaning, const nurbs::SidePatch& sp,
                      double tolerance)
{
    return fmt::format("#     {}: {}; corners {}{}\n", label, meaning, side_corners(sp), collapse_note(sp, tolerance));
}

/// The line that says a mirror left the patch running backwards in u, and that side
/// names still refer to the patch as built.
std::string reversal_line(const std::string& what, const std::string& built)
{
    return fmt::format("#     {}mirrored: the analysed patch runs backwards in u (to stay right-handed); side names "
                       "are those of the {} as built, and `refine` is in its parameters\n",
                       what, built);
}

std::string degrees_and_spans(const nurbs::Patch& patch)
{
    std::string degrees, spans;
    for (int dir = 0; dir < patch.n_par(); ++dir) {
        degrees += fmt::format("{}{}", dir ? ", " : "", patch.degree(dir));
        spans += fmt::format("{}{}", dir ? ", " : "", patch.knots(dir).n_spans());
    }
    return fmt::format("degrees [{}], spans [{}], {} control points", degrees, spans, patch.n_control_points());
}

/// Patches, interfaces, every patch side with its corners, named surfaces.
std::string describe_multi_patch(const io::Deck& deck, const io::Body& body)
{
    const BodyPatches built = build_body_patches(deck, body);
    std::string out = fmt::format("#   {}: {} patches, {} interfaces, {} distinct control points\n", body.name,
                                  built.patches.size(), built.topology.interfaces.size(), built.topology.n_nodes);
    for (std::size_t p = 0; p < built.patches.size(); ++p) {
        out += fmt::format("#     patch {}: {}\n", built.names[p], degrees_and_spans(built.patches[p]));
        if (p < body.patches.size() && u_reversed(body, static_cast<int>(p)))
            out += reversal_line("patch " + built.names[p] + ": ", "patch");
    }
    auto named = [&](int patch, Side side) { return side_name(named_side(side, u_reversed(body, patch))); };
    for (const nurbs::Interface& i : built.topology.interfaces)
        out += fmt::format("#     interface {}.{} = {}.{}\n", built.names[static_cast<std::size_t>(i.patch_a)],
                           named(i.patch_a, i.side_a), built.names[static_cast<std::size_t>(i.patch_b)],
                           named(i.patch_b, i.side_b));
    for (std::size_t p = 0; p < built.patches.size(); ++p) {
        const nurbs::Patch& patch = built.patches[p];
        for (int k = 0; k < 2 * patch.n_par(); ++k) {
            const Side as_named = static_cast<Side>(k);
            const Side side = named_side(as_named, u_reversed(body, static_cast<int>(p)));
            std::string meaning = generic_side_meaning(as_named);
            if (built.topology.is_interface(static_cast<int>(p), side))
                meaning += " (interface)";
            out += side_line(fmt::format("{}.{}.{}", body.name, built.names[p], side_name(as_named)), meaning,
                             nurbs::extract_side(patch, side), coincidence_tolerance(patch));
        }
    }
    for (const io::NamedSurface& surface : body.surfaces) {
        std::string sides;
        for (const io::PatchSideRef& ref : surface.sides)
            sides += (sides.empty() ? "" : ", ") + io::side_text(ref.patch, ref.side, "");
        out += fmt::format("#     {}.{}: named surface [{}]\n", body.name, surface.name, sides);
    }
    return out;
}

}  // namespace

std::string describe_bodies(const io::Deck& deck)
{
    std::string out = "# bodies and their sides (corners of the analysed patch, after any transform):\n";
    const int d = deck.analysis.dimension;
    for (const io::Body& body : deck.bodies) {
        if (body.rigid) {
            const char* kind = body.plane ? "plane" : (d == 3 ? "sphere" : "circle");
            out += fmt::format("#   {}: rigid {}{} (no sides; name it directly in a contact pair)\n", body.name, kind,
                               body.moves() ? ", moving" : "");
            continue;
        }
        if (body.multi_patch()) {
            out += describe_multi_patch(deck, body);
            continue;
        }
        nurbs::Patch patch = [&] {
            try {
                return build_patch(body, d);
            } catch (const TransformOutOfRange& e) {
                throw transform_error(deck, body, "", e);
            } catch (const Error& e) {
                throw DeckError(io::located_issue(deck.source_file, "bodies." + body.name, "",
                                                  std::string("cannot build the patch: ") + e.what()));
            }
        }();
        out += fmt::format("#   {}: {}\n", body.name, degrees_and_spans(patch));
        const bool reversed = u_reversed(body, 0);
        if (reversed)
            out += reversal_line("", body.shape ? "shape" : "patch");
        const std::vector<std::pair<std::string, std::string>> meanings = side_meanings(body);
        for (int k = 0; k < 2 * patch.n_par(); ++k) {
            const Side as_named = static_cast<Side>(k);
            std::string meaning = generic_side_meaning(as_named);
            for (const auto& [name, text] : meanings)
                if (name == side_name(as_named))
                    meaning = text;
            out += side_line(body.name + "." + std::string(side_name(as_named)), meaning,
                             nurbs::extract_side(patch, named_side(as_named, reversed)), coincidence_tolerance(patch));
        }
        for (const io::NamedSurface& surface : body.surfaces) {
            std::string sides;
            for (const io::PatchSideRef& ref : surface.sides)
                sides += (sides.empty() ? "" : ", ") + std::string(side_name(ref.side));
            out += fmt::format("#     {}.{}: named surface [{}]\n", body.name, surface.name, sides);
        }
    }
    return out;
}

}  // namespace iga::analysis
