#include "analysis/describe.hpp"
#include "io/deck_names.hpp"

#include "analysis/geometry.hpp"
#include "io/locate.hpp"
#include "nurbs/shapes.hpp"
#include "nurbs/side_patch.hpp"

#include <fmt/format.h>

namespace iga::analysis {

namespace {

std::string generic_side_meaning(Side s)
{
    static const char* directions = "uvw";
    return fmt::format("{} = {}", directions[side_direction(s)], side_at_end(s) ? "max" : "min");
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
    }
    return out;
}

}  // namespace iga::analysis
