#include "analysis/multipatch.hpp"
#include "core/text.hpp"

#include "analysis/geometry.hpp"
#include "contact/search.hpp"
#include "io/locate.hpp"
#include "nurbs/refine.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <optional>

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

}  // namespace

DeckError transform_error(const io::Deck& deck, const io::Body& body, const std::string& patch,
                          const TransformOutOfRange& e)
{
    return body_error(deck, fmt::format("{}.{}.{}", transform_path(body, patch), e.step(), e.kind()), e.what());
}

namespace {

/// A point of one patch inside another.
struct Overlap {
    std::size_t a, b;  ///< patch with the point, patch that holds it
    VecN x;
};

/// The first element centre (patch order, then element order) that lies inside
/// another patch, if any. Every element of every patch is boxed by its Bezier
/// control points (the convex hull holds the element), the boxes go into one
/// bounding-volume tree (contact/search.hpp), and a centre is inverted only into
/// the elements whose box holds it, Newton starting in that element: O(n log n)
/// for n elements, where testing every centre against every patch was O(n^2).
std::optional<Overlap> overlapping_point(const std::vector<nurbs::Patch>& patches, double tolerance,
                                         const StopRequest& stop)
{
    struct Owner {
        std::size_t patch;
        nurbs::Element element;
    };
    std::vector<Owner> owners;
    std::vector<contact::Box> boxes;
    for (std::size_t p = 0; p < patches.size(); ++p) {
        stop.check();
        const nurbs::Patch& patch = patches[p];
        std::array<std::vector<Eigen::MatrixXd>, 3> extraction;
        for (int k = 0; k < patch.n_par(); ++k)
            extraction[static_cast<std::size_t>(k)] = nurbs::bezier_extraction(patch.knots(k));
        for (const nurbs::Element& e : patch.elements()) {
            // Inflated by the coincidence tolerance: a centre on a box face (round-off) is still found.
            boxes.push_back(contact::bounding_box(nurbs::bezier_control_points(patch, e, extraction)).inflated(tolerance));
            owners.push_back({p, e});
        }
    }
    const contact::ElementSearch search(std::move(boxes));
    std::vector<int> hits;
    for (std::size_t p = 0; p < patches.size(); ++p) {
        const nurbs::Patch& a = patches[p];
        for (const nurbs::Element& e : a.elements()) {
            stop.check();
            VecN xi(a.n_par());
            for (int k = 0; k < a.n_par(); ++k)
                xi(k) = 0.5 * (e.lower[static_cast<std::size_t>(k)] + e.upper[static_cast<std::size_t>(k)]);
            const VecN x = nurbs::evaluate(a, xi, 0).x;
            search.candidates(x, hits);
            for (const int h : hits) {
                const Owner& o = owners[static_cast<std::size_t>(h)];
                if (o.patch != p && nurbs::invert_point(patches[o.patch], x, overlap_parameter_margin, o.element))
                    return Overlap{p, o.patch, x};
            }
        }
    }
    return std::nullopt;
}

/// The parametric direction in which a patch is thinner than `tolerance` (its two
/// sides across that direction coincide corner by corner), if any.
std::optional<int> thin_direction(const nurbs::Patch& patch, double tolerance)
{
    const int n = patch.n_par();
    for (int k = 0; k < n; ++k) {
        double gap = 0.0;
        for (int c = 0; c < (1 << n); ++c) {  // the corners with index 0 in direction k
            if ((c >> k) & 1)
                continue;
            std::array<int, 3> lo{0, 0, 0};
            for (int j = 0; j < n; ++j)
                lo[static_cast<std::size_t>(j)] = ((c >> j) & 1) ? patch.n_basis(j) - 1 : 0;
            std::array<int, 3> hi = lo;
            hi[static_cast<std::size_t>(k)] = patch.n_basis(k) - 1;
            gap = std::max(gap, (patch.control_points().row(patch.control_point_index(lo)) -
                                 patch.control_points().row(patch.control_point_index(hi)))
                                    .norm());
        }
        if (gap <= tolerance)
            return k;
    }
    return std::nullopt;
}

}  // namespace

std::string body_side_text(const std::vector<std::string>& patch_names, const BodySide& side)
{
    const std::string& patch = patch_names[static_cast<std::size_t>(side.patch)];
    return patch.empty() ? std::string(side_name(side.named)) : patch + "." + std::string(side_name(side.named));
}

bool u_reversed(const io::Body& body, int patch)
{
    if (body.multi_patch())
        return io::reverses_u(body.patches[static_cast<std::size_t>(patch)].nurbs.transform);
    return io::reverses_u(body.nurbs ? body.nurbs->transform : body.shape->transform);
}

std::vector<BodySide> resolve_sides(const io::Body& body, const std::vector<std::string>& patch_names,
                                    const std::string& patch, Side side, const std::string& surface)
{
    auto index_of = [&](const std::string& name) {
        const auto it = std::find(patch_names.begin(), patch_names.end(), name);
        IGA_CHECK(it != patch_names.end(), "the deck reader let an unknown patch '" + name + "' through");
        return static_cast<int>(it - patch_names.begin());
    };
    auto body_side = [&](const std::string& name, Side as_named) {
        const int p = index_of(name);
        return BodySide{p, named_side(as_named, u_reversed(body, p)), as_named};
    };
    if (surface.empty())
        return {body_side(patch, side)};
    const io::NamedSurface* named = body.find_surface(surface);
    IGA_CHECK(named != nullptr, "the deck reader let an unknown surface '" + surface + "' through");
    std::vector<BodySide> out;
    for (const io::PatchSideRef& ref : named->sides)
        out.push_back(body_side(ref.patch, ref.side));
    return out;
}

BodyPatches build_body_patches(const io::Deck& deck, const io::Body& body, int halvings, const StopRequest& stop)
{
    IGA_CHECK(!body.rigid, "build_body_patches called for the rigid body '" + body.name + "'");
    const int d = deck.analysis.dimension;
    BodyPatches out;
    if (!body.multi_patch()) {
        try {
            out.patches.push_back(build_patch(body, d, halvings));
        } catch (const TransformOutOfRange& e) {
            throw transform_error(deck, body, "", e);
        } catch (const Error& e) {
            throw body_error(deck, patch_path(body, ""), std::string("cannot build the patch: ") + e.what());
        }
        out.names.emplace_back();
    } else {
        for (const io::PatchData& data : body.patches) {
            stop.check();
            try {
                const nurbs::Patch built = refined(refined(raw_patch(data.nurbs, d), body.refine), data.refine);
                out.patches.push_back(nurbs::halve_spans(placed(built, data.nurbs.transform), halvings));
            } catch (const TransformOutOfRange& e) {
                throw transform_error(deck, body, data.name, e);
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
    // A patch thinner than the tolerance would be glued on both sides at once, its
    // neighbours also to each other: refuse it here, where it can be named.
    for (std::size_t p = 0; p < out.patches.size(); ++p)
        if (const std::optional<int> k = thin_direction(out.patches[p], tolerance))
            throw body_error(deck, patch_path(body, out.names[p]),
                             fmt::format("patch '{}' is thinner than the gluing tolerance ({:.3g} = {:g} x the body "
                                         "size) in direction {}: its two sides across it coincide, so it cannot be "
                                         "glued; remove the patch or make it thicker",
                                         out.names[p], tolerance, glue_relative_tolerance, "uvw"[*k]));
    try {
        out.topology = nurbs::glue_patches(out.patches, tolerance, stop);
    } catch (const nurbs::NonMatchingInterface& e) {
        throw body_error(deck, patch_path(body, out.names[static_cast<std::size_t>(e.patch_a)]),
                         fmt::format("non-matching interface: side {} of patch '{}' and side {} of patch '{}' share "
                                     "their corners, but {}",
                                     side_name(e.side_a), out.names[static_cast<std::size_t>(e.patch_a)],
                                     side_name(e.side_b), out.names[static_cast<std::size_t>(e.patch_b)], e.what()));
    } catch (const Error& e) {
        throw body_error(deck, patch_path(body, ""), std::string("cannot glue the patches: ") + e.what());
    }

    if (const auto overlap = overlapping_point(out.patches, tolerance, stop))
        throw body_error(deck, patch_path(body, out.names[overlap->a]),
                         fmt::format("overlapping patches: patch '{}' has the point {} inside patch '{}' "
                                     "(patches of a body may share sides, not volume)",
                                     out.names[overlap->a], point_text(overlap->x), out.names[overlap->b]));

    // Connected through interfaces.
    std::vector<std::vector<int>> neighbours(out.patches.size());
    for (const nurbs::Interface& i : out.topology.interfaces) {
        neighbours[static_cast<std::size_t>(i.patch_a)].push_back(i.patch_b);
        neighbours[static_cast<std::size_t>(i.patch_b)].push_back(i.patch_a);
    }
    std::vector<char> reached(out.patches.size(), 0);
    std::vector<int> queue{0};
    reached[0] = 1;
    while (!queue.empty()) {
        const int p = queue.back();
        queue.pop_back();
        for (const int to : neighbours[static_cast<std::size_t>(p)])
            if (!reached[static_cast<std::size_t>(to)]) {
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
