#include "analysis/multipatch.hpp"

#include "analysis/geometry.hpp"
#include "io/locate.hpp"
#include "nurbs/refine.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace iga::analysis {
namespace {

/// Points of a patch inside another patch's parameter box by more than this
/// fraction of each range count as overlap: clear of the round-off with which a
/// point on a shared side inverts to the other patch's boundary.
constexpr double overlap_parameter_margin = 1e-6;

std::string patch_path(const io::Body& body, const std::string& patch)
{
    return "bodies." + body.name + (patch.empty() ? "" : ".patches." + patch);
}

DeckError body_error(const io::Deck& deck, const std::string& path, const std::string& reason)
{
    return DeckError(io::located_issue(deck.source_file, path, "", reason));
}

std::string point_text(const VecN& x)
{
    std::string out = "(";
    for (Index i = 0; i < x.size(); ++i)
        out += fmt::format("{}{:.6g}", i ? ", " : "", x(i));
    return out + ")";
}

/// The element centres of `a` that lie inside `b`: the first one, if any.
std::optional<VecN> point_inside(const nurbs::Patch& a, const nurbs::Patch& b)
{
    const RowMatrix& P = b.control_points();
    const VecN lo = P.colwise().minCoeff().transpose(), hi = P.colwise().maxCoeff().transpose();
    for (const nurbs::Element& e : a.elements()) {
        VecN xi(a.n_par());
        for (int k = 0; k < a.n_par(); ++k)
            xi(k) = 0.5 * (e.lower[static_cast<std::size_t>(k)] + e.upper[static_cast<std::size_t>(k)]);
        const VecN x = nurbs::evaluate(a, xi, 0).x;
        if ((x.array() < lo.array()).any() || (x.array() > hi.array()).any())
            continue;  // outside b's control hull box, so outside b
        if (nurbs::invert_point(b, x, overlap_parameter_margin))
            return x;
    }
    return std::nullopt;
}

}  // namespace

std::string body_side_text(const std::vector<std::string>& patch_names, const BodySide& side)
{
    const std::string& patch = patch_names[static_cast<std::size_t>(side.patch)];
    return patch.empty() ? std::string(side_name(side.side)) : patch + "." + std::string(side_name(side.side));
}

std::vector<BodySide> resolve_sides(const io::Body& body, const std::vector<std::string>& patch_names,
                                    const std::string& patch, Side side, const std::string& surface)
{
    auto index_of = [&](const std::string& name) {
        const auto it = std::find(patch_names.begin(), patch_names.end(), name);
        IGA_CHECK(it != patch_names.end(), "the deck reader let an unknown patch '" + name + "' through");
        return static_cast<int>(it - patch_names.begin());
    };
    if (surface.empty())
        return {BodySide{index_of(patch), side}};
    const io::NamedSurface* named = body.find_surface(surface);
    IGA_CHECK(named != nullptr, "the deck reader let an unknown surface '" + surface + "' through");
    std::vector<BodySide> out;
    for (const io::PatchSideRef& ref : named->sides)
        out.push_back(BodySide{index_of(ref.patch), ref.side});
    return out;
}

BodyPatches build_body_patches(const io::Deck& deck, const io::Body& body, int halvings)
{
    IGA_CHECK(!body.rigid, "build_body_patches called for the rigid body '" + body.name + "'");
    const int d = deck.analysis.dimension;
    BodyPatches out;
    if (!body.multi_patch()) {
        try {
            out.patches.push_back(build_patch(body, d, halvings));
        } catch (const Error& e) {
            throw body_error(deck, patch_path(body, ""), std::string("cannot build the patch: ") + e.what());
        }
        out.names.emplace_back();
    } else {
        for (const io::PatchData& data : body.patches) {
            try {
                out.patches.push_back(nurbs::halve_spans(refined(refined(raw_patch(data.nurbs, d), body.refine), data.refine), halvings));
            } catch (const Error& e) {
                throw body_error(deck, patch_path(body, data.name), std::string("cannot build the patch: ") + e.what());
            }
            out.names.push_back(data.name);
        }
    }
    for (std::size_t p = 0; p < out.patches.size(); ++p)
        if (out.patches[p].n_par() != d)
            throw body_error(deck, patch_path(body, out.names[p]),
                             fmt::format("a {}D analysis needs a patch with {} parametric directions", d, d));
    if (out.patches.size() == 1) {
        out.topology = nurbs::glue_patches(out.patches, 0.0);  // one patch: nodes = control points
        return out;
    }

    Eigen::VectorXd lo = Eigen::VectorXd::Constant(d, 1e300), hi = Eigen::VectorXd::Constant(d, -1e300);
    for (const nurbs::Patch& p : out.patches) {
        lo = lo.cwiseMin(p.control_points().colwise().minCoeff().transpose());
        hi = hi.cwiseMax(p.control_points().colwise().maxCoeff().transpose());
    }
    const double tolerance = glue_relative_tolerance * (hi - lo).norm();
    try {
        out.topology = nurbs::glue_patches(out.patches, tolerance);
    } catch (const nurbs::NonMatchingInterface& e) {
        throw body_error(deck, patch_path(body, out.names[static_cast<std::size_t>(e.patch_a)]),
                         fmt::format("non-matching interface: side {} of patch '{}' and side {} of patch '{}' share "
                                     "their corners, but {}",
                                     side_name(e.side_a), out.names[static_cast<std::size_t>(e.patch_a)],
                                     side_name(e.side_b), out.names[static_cast<std::size_t>(e.patch_b)], e.what()));
    } catch (const Error& e) {
        throw body_error(deck, patch_path(body, ""), std::string("cannot glue the patches: ") + e.what());
    }

    for (std::size_t a = 0; a < out.patches.size(); ++a)
        for (std::size_t b = 0; b < out.patches.size(); ++b) {
            if (a == b)
                continue;
            if (const auto x = point_inside(out.patches[a], out.patches[b]))
                throw body_error(deck, patch_path(body, out.names[a]),
                                 fmt::format("overlapping patches: patch '{}' has the point {} inside patch '{}' "
                                             "(patches of a body may share sides, not volume)",
                                             out.names[a], point_text(*x), out.names[b]));
        }

    // Connected through interfaces.
    std::vector<char> reached(out.patches.size(), 0);
    std::vector<int> queue{0};
    reached[0] = 1;
    while (!queue.empty()) {
        const int p = queue.back();
        queue.pop_back();
        for (const nurbs::Interface& i : out.topology.interfaces)
            for (const auto& [from, to] : {std::pair{i.patch_a, i.patch_b}, std::pair{i.patch_b, i.patch_a}})
                if (from == p && !reached[static_cast<std::size_t>(to)]) {
                    reached[static_cast<std::size_t>(to)] = 1;
                    queue.push_back(to);
                }
    }
    for (std::size_t p = 0; p < out.patches.size(); ++p)
        if (!reached[p])
            throw body_error(deck, patch_path(body, out.names[p]),
                             fmt::format("patch '{}' is not glued to patch '{}': the patches of a body must form one "
                                         "connected body, glued along whole sides (a side half shared with another "
                                         "patch, or patches that only touch at a point, are not glued)",
                                         out.names[p], out.names[0]));

    for (const io::NamedSurface& surface : body.surfaces)
        for (const BodySide& side : resolve_sides(body, out.names, "", Side::u0, surface.name))
            if (out.topology.is_interface(side.patch, side.side))
                throw body_error(deck, "bodies." + body.name + ".surfaces." + surface.name,
                                 fmt::format("the side {} is an interface between two patches (inside the body), "
                                             "not a boundary side",
                                             body_side_text(out.names, side)));
    return out;
}

}  // namespace iga::analysis
