#include "analysis/constraints.hpp"
#include "core/text.hpp"

#include "io/locate.hpp"
#include "nurbs/coincidence.hpp"
#include "nurbs/side_patch.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>

namespace iga::analysis {

namespace {

constexpr const char* component_names[] = {"x", "y", "z"};

std::string item_label(const io::Constraint& c, std::size_t index)
{
    return fmt::format("constraints.{} ({}.{})", index, c.body, io::side_text(c.patch, c.side, c.surface));
}

/// Side s of constraint item k: an interface side is bad input; a side collapsed to a
/// point or a line is a warning (it holds that point or line only).
nurbs::SidePatch checked_side(const io::Deck& deck, const BodyModel& body, const io::Constraint& c, std::size_t k,
                              const BodySide& s, std::vector<std::string>& warnings)
{
    for (const nurbs::Interface& i : body.interfaces)
        if ((i.patch_a == s.patch && i.side_a == s.side) || (i.patch_b == s.patch && i.side_b == s.side))
            throw DeckError(io::located_issue(deck.source_file, fmt::format("constraints.{}.side", k), "",
                                              fmt::format("the side {} of body '{}' is an interface between two "
                                                          "patches (inside the body), not a boundary side",
                                                          body_side_text(body.patch_names(), s), c.body)));
    const nurbs::Patch& patch = body.patches[static_cast<std::size_t>(s.patch)].patch;
    nurbs::SidePatch sp = nurbs::extract_side(patch, s.side);
    const double tolerance = nurbs::coincidence_tolerance(patch.control_points());
    const bool point = nurbs::is_collapsed(sp, tolerance);
    if (point || nurbs::is_collapsed_to_line(sp, tolerance))
        warnings.push_back(fmt::format(
            "constraints.{}.side: the side {} of body '{}' is collapsed to a {} {}: the constraint holds that {}, not "
            "a face; for a symmetry condition name the face (`check` lists every side with its corners)",
            k, body_side_text(body.patch_names(), s), c.body, point ? "point at" : "line through",
            point_text(sp.patch.control_points(), Index{0}), point ? "single point (a pin)" : "line only"));
    return sp;
}

}  // namespace

DirichletData dirichlet_data(const io::Deck& deck, const std::vector<BodyModel>& bodies,
                             const std::vector<int>& body_of_deck, const std::vector<int>& node_offset)
{
    const int d = deck.analysis.dimension;
    struct Owner {
        std::size_t item;
        double value;
    };
    std::map<int, Owner> owner;  // full dof -> first item prescribing it
    DirichletData out;
    std::map<std::string, std::size_t> group_of;  // "body.side" -> reactions index
    std::vector<ReactionGroup> totals;            // "total/<body>", deck order of first appearance
    std::vector<ReactionGroup> items(deck.constraints.size());  // "items/<k>": the dofs item k owns

    for (std::size_t k = 0; k < deck.constraints.size(); ++k) {
        const io::Constraint& c = deck.constraints[k];
        int b = -1;
        for (std::size_t i = 0; i < deck.bodies.size(); ++i)
            if (deck.bodies[i].name == c.body)
                b = body_of_deck[i];
        IGA_CHECK(b >= 0, "the deck reader let a constraint on a rigid or unknown body through");
        const BodyModel& body = bodies[static_cast<std::size_t>(b)];
        const io::Body* deck_body = deck.find_body(c.body);
        const std::vector<BodySide> sides = resolve_sides(*deck_body, body.patch_names(), c.patch, c.side, c.surface);
        std::vector<int> side_nodes;  // each once, in side order
        for (const BodySide& s : sides) {
            const nurbs::SidePatch sp = checked_side(deck, body, c, k, s, out.warnings);
            const PatchModel& patch = body.patches[static_cast<std::size_t>(s.patch)];
            for (const int a : sp.parent_index) {
                const int node = patch.node[static_cast<std::size_t>(a)];
                if (std::find(side_nodes.begin(), side_nodes.end(), node) == side_nodes.end())
                    side_nodes.push_back(node);
            }
        }

        const std::string name = c.body + "." + io::side_text(c.patch, c.side, c.surface);
        auto [group, added] = group_of.try_emplace(name, out.reactions.size());
        if (added)
            out.reactions.push_back({name, {}});
        std::vector<int>& group_dofs = out.reactions[group->second].dofs;
        items[k].name = fmt::format("items/{}", k);
        const std::string total_name = "total/" + c.body;
        auto total = std::find_if(totals.begin(), totals.end(), [&](const ReactionGroup& g) { return g.name == total_name; });
        if (total == totals.end())
            total = totals.insert(totals.end(), ReactionGroup{total_name, {}});

        for (int p : side_nodes)
            for (int i = 0; i < d; ++i) {
                if (!c.fixed[static_cast<std::size_t>(i)])
                    continue;
                const int dof = (node_offset[static_cast<std::size_t>(b)] + p) * d + i;
                const double value = c.value[static_cast<std::size_t>(i)];
                if (std::find(group_dofs.begin(), group_dofs.end(), dof) == group_dofs.end())
                    group_dofs.push_back(dof);
                const auto [it, fresh] = owner.try_emplace(dof, Owner{k, value});
                if (fresh) {  // the first item to prescribe a dof owns it (items/<k>, total/<body>)
                    out.prescribed.push_back({dof, value, c.amplitude.value_or(Amplitude())});
                    items[k].dofs.push_back(dof);
                    total->dofs.push_back(dof);
                    continue;
                }
                const io::Constraint& first = deck.constraints[it->second.item];
                // A zero value is zero under any amplitude.
                const bool same_path = value == 0.0 || first.amplitude.value_or(Amplitude()) ==
                                                           c.amplitude.value_or(Amplitude());
                if (it->second.value == value && same_path)
                    continue;
                // The same value under another amplitude, or another value.
                const bool same_value = it->second.value == value;
                const std::string values =
                    same_value ? fmt::format("(the same value {:.6g}) but with different amplitudes", value)
                               : fmt::format("({} = {:.6g} here, {:.6g} there)", component_names[i], value,
                                             it->second.value);
                const std::string advice = same_value ? "Give both the same amplitude, or leave that component "
                                                        "free in one of them (~ in 'displacement')"
                                                      : "Leave that component free in one of them (~ in "
                                                        "'displacement', or drop it from 'fix')";
                const std::string first_side = first.body + "." + io::side_text(first.patch, first.side, first.surface);
                const std::string this_side = c.body + "." + io::side_text(c.patch, c.side, c.surface);
                const std::string where = first_side == this_side
                                              ? fmt::format("both items are on the side {}", this_side)
                                              : fmt::format("the sides {} and {} meet there", first_side, this_side);
                throw DeckError(io::located_issue(
                    deck.source_file, fmt::format("constraints.{}", k), "",
                    fmt::format("conflicts with {}: both prescribe the {}-displacement of the control point at {} "
                                "of body '{}' {}; {}. {}",
                                item_label(first, it->second.item), component_names[i],
                                point_text(body.node_points, static_cast<Index>(p)), c.body, values, where, advice)));
            }
    }
    out.reactions.insert(out.reactions.end(), totals.begin(), totals.end());
    out.reactions.insert(out.reactions.end(), items.begin(), items.end());
    return out;
}

}  // namespace iga::analysis
