#include "analysis/describe.hpp"
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

std::string point_text(const VecN& x)
{
    std::string out = "(";
    for (Index i = 0; i < x.size(); ++i)
        out += fmt::format("{}{:.6g}", i ? ", " : "", x(i));
    return out + ")";
}

/// Patches, interfaces, boundary sides with their end points, named surfaces.
std::string describe_multi_patch(const io::Deck& deck, const io::Body& body)
{
    const BodyPatches built = build_body_patches(deck, body);
    std::string out = fmt::format("#   {}: {} patches, {} interfaces, {} distinct control points\n", body.name,
                                  built.patches.size(), built.topology.interfaces.size(), built.topology.n_nodes);
    for (std::size_t p = 0; p < built.patches.size(); ++p) {
        const nurbs::Patch& patch = built.patches[p];
        std::string degrees, spans;
        for (int dir = 0; dir < patch.n_par(); ++dir) {
            degrees += fmt::format("{}{}", dir ? ", " : "", patch.degree(dir));
            spans += fmt::format("{}{}", dir ? ", " : "", patch.knots(dir).n_spans());
        }
        out += fmt::format("#     patch {}: degrees [{}], spans [{}], {} control points\n", built.names[p], degrees,
                           spans, patch.n_control_points());
    }
    for (const nurbs::Interface& i : built.topology.interfaces)
        out += fmt::format("#     interface {}.{} = {}.{}\n", built.names[static_cast<std::size_t>(i.patch_a)],
                           side_name(i.side_a), built.names[static_cast<std::size_t>(i.patch_b)], side_name(i.side_b));
    for (std::size_t p = 0; p < built.patches.size(); ++p) {
        const nurbs::Patch& patch = built.patches[p];
        for (int k = 0; k < 2 * patch.n_par(); ++k) {
            const Side side = static_cast<Side>(k);
            if (built.topology.is_interface(static_cast<int>(p), side))
                continue;
            const nurbs::SidePatch sp = nurbs::extract_side(patch, side);
            const RowMatrix& P = sp.patch.control_points();
            // The corners of the side (open knot vectors interpolate them).
            std::string corners;
            const int n0 = sp.patch.n_basis(0), n1 = sp.patch.n_par() > 1 ? sp.patch.n_basis(1) : 1;
            const std::vector<int> corner_rows = n1 == 1 ? std::vector<int>{0, n0 - 1}
                                                         : std::vector<int>{0, n0 - 1, n0 * (n1 - 1), n0 * n1 - 1};
            for (int r : corner_rows)
                corners += (corners.empty() ? "" : " ") + point_text(P.row(r).transpose());
            const bool collapsed = nurbs::is_collapsed(sp, 1e-12 * (1.0 + P.cwiseAbs().maxCoeff()));
            out += fmt::format("#     {}.{}.{}: {} from {}{}\n", body.name, built.names[p], side_name(side),
                               generic_side_meaning(side), corners, collapsed ? " (collapsed)" : "");
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
    std::string out = "# bodies and their sides:\n";
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
            } catch (const Error& e) {
                throw DeckError(io::located_issue(deck.source_file, "bodies." + body.name, "",
                                                  std::string("cannot build the patch: ") + e.what()));
            }
        }();
        std::string degrees, spans;
        for (int dir = 0; dir < patch.n_par(); ++dir) {
            degrees += fmt::format("{}{}", dir ? ", " : "", patch.degree(dir));
            spans += fmt::format("{}{}", dir ? ", " : "", patch.knots(dir).n_spans());
        }
        out += fmt::format("#   {}: degrees [{}], spans [{}], {} control points\n", body.name, degrees, spans,
                           patch.n_control_points());
        const std::vector<std::pair<std::string, std::string>> meanings = side_meanings(body);
        for (int k = 0; k < 2 * patch.n_par(); ++k) {
            const Side side = static_cast<Side>(k);
            std::string meaning = generic_side_meaning(side);
            for (const auto& [name, text] : meanings)
                if (name == side_name(side))
                    meaning = text;
            const nurbs::SidePatch sp = nurbs::extract_side(patch, side);
            const bool collapsed = nurbs::is_collapsed(sp, 1e-12 * (1.0 + patch.control_points().cwiseAbs().maxCoeff()));
            out += fmt::format("#     {}.{}: {}{}\n", body.name, side_name(side), meaning,
                               collapsed && meaning.find("collapsed") == std::string::npos ? " (collapsed)" : "");
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
