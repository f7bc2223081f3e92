#include "analysis/side_facing.hpp"

#include "contact/projection.hpp"
#include "core/text.hpp"
#include "io/locate.hpp"
#include "nurbs/side_patch.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

namespace iga::analysis {

namespace {

/// A point of a contact side with its outward normal.
struct Sample {
    VecN x;
    VecN normal;
};

/// Where a side meets its partner first, and how well it faces it there.
struct Facing {
    double best = -std::numeric_limits<double>::infinity();  ///< max facing over the nearest samples
    double nearest = std::numeric_limits<double>::infinity(); ///< distance of the nearest sample
    bool behind = false;  ///< at every nearest sample the partner lies behind the side, outside itself
    Sample at;            ///< the nearest sample
    VecN partner_normal;  ///< the partner's normal there
    bool judged() const { return std::isfinite(best); }
    bool faces() const { return !behind && best >= facing_away; }
};

/// Samples per element and direction, at these fractions of the span.
constexpr double fractions[] = {1.0 / 6.0, 0.5, 5.0 / 6.0};
/// At most this many samples per side (every k-th beyond): the test reads normals.
constexpr std::size_t max_samples = 4000;
/// The samples that count lie within this fraction of the smaller side's size of the nearest.
constexpr double nearest_band = 0.1;
/// Off a tangent plane by more than this fraction of the smaller side's size: in front of
/// it or behind it (two curved sides that touch sit within h^2/R of each other's planes).
constexpr double behind_band = 0.01;

std::vector<Sample> samples(const contact::DeformableSide& side)
{
    std::vector<Sample> out;
    for (const contact::SidePiece& piece : side.pieces) {
        const nurbs::Patch& patch = piece.side.patch;
        const int q = patch.n_par();
        for (const nurbs::Element& e : patch.elements())
            for (double f0 : fractions)
                for (double f1 : fractions) {
                    if (q == 1 && f1 != fractions[0])
                        continue;
                    const double f[2] = {f0, f1};
                    VecN xi(q);
                    std::array<bool, 2> near_lower{true, true};
                    for (int j = 0; j < q; ++j) {
                        xi(j) = e.lower[static_cast<std::size_t>(j)] +
                                f[j] * (e.upper[static_cast<std::size_t>(j)] - e.lower[static_cast<std::size_t>(j)]);
                        near_lower[static_cast<std::size_t>(j)] = f[j] < 0.5;
                    }
                    const nurbs::PointDerivatives p = nurbs::evaluate(patch, xi, 2);
                    const VecN n = contact::side_normal(p.dx, p.d2x, piece.outward_sign, near_lower);
                    if (n.norm() > 0.5)  // no normal on a collapsed spot
                        out.push_back({p.x, n});
                }
    }
    if (out.size() <= max_samples)
        return out;
    std::vector<Sample> thinned;
    const std::size_t stride = (out.size() + max_samples - 1) / max_samples;
    for (std::size_t k = 0; k < out.size(); k += stride)
        thinned.push_back(out[k]);
    return thinned;
}

double size_of(const std::vector<Sample>& points)
{
    if (points.empty())
        return 0.0;
    VecN lo = points.front().x, hi = points.front().x;
    for (const Sample& s : points) {
        lo = lo.cwiseMin(s.x);
        hi = hi.cwiseMax(s.x);
    }
    return (hi - lo).norm();
}

/// The partner of a side: a rigid obstacle, or the samples of a deformable side.
struct Partner {
    const contact::RigidObstacle* obstacle = nullptr;
    std::vector<Sample> points;

    /// The partner's point nearest to x, with its normal (nullopt: no normal there).
    std::optional<Sample> nearest(const VecN& x) const
    {
        if (obstacle) {
            const contact::ObstacleFoot foot = obstacle->foot(x, 0.0);
            if (!foot.ok)
                return std::nullopt;
            return Sample{x + foot.gap * foot.normal, foot.normal};  // gap > 0 in penetration
        }
        const Sample* best = nullptr;
        double d2 = std::numeric_limits<double>::infinity();
        for (const Sample& s : points)
            if (const double e = (s.x - x).squaredNorm(); e < d2) {
                d2 = e;
                best = &s;
            }
        return best ? std::optional(*best) : std::nullopt;
    }
};

Facing facing(const std::vector<Sample>& side, const Partner& partner)
{
    std::vector<std::optional<Sample>> foot(side.size());
    std::vector<double> distance(side.size(), std::numeric_limits<double>::infinity());
    Facing out;
    for (std::size_t k = 0; k < side.size(); ++k) {
        foot[k] = partner.nearest(side[k].x);
        if (!foot[k])
            continue;
        distance[k] = (foot[k]->x - side[k].x).norm();
        if (distance[k] < out.nearest) {
            out.nearest = distance[k];
            out.at = side[k];
            out.partner_normal = foot[k]->normal;
        }
    }
    if (!std::isfinite(out.nearest))
        return out;
    const double own = size_of(side);
    const double size = partner.obstacle ? own : std::min(own, size_of(partner.points));
    // Behind: the partner lies behind the side's tangent plane, and the side in front of
    // the partner's (not an overlap of two sides that do face each other).
    const double off_plane = behind_band * size;
    out.behind = true;
    for (std::size_t k = 0; k < side.size(); ++k) {
        if (!(distance[k] <= out.nearest + nearest_band * size))
            continue;
        const Sample& s = side[k];
        const Sample& p = *foot[k];
        out.best = std::max(out.best, -s.normal.dot(p.normal));
        const bool partner_behind = s.normal.dot(p.x - s.x) < -off_plane;
        const bool side_outside = p.normal.dot(s.x - p.x) > -off_plane;
        out.behind = out.behind && partner_behind && side_outside;
    }
    return out;
}

Partner partner_of(const PairModel& model, int k)
{
    Partner partner;
    const contact::Surface& surface = model.pair.surface(k);
    if (const auto* obstacle = std::get_if<contact::RigidObstacle>(&surface))
        partner.obstacle = obstacle;
    else
        partner.points = samples(std::get<contact::DeformableSide>(surface));
    return partner;
}

/// The sides of a single-patch body that face the partner, nearest first ("block.v0").
std::vector<std::string> facing_sides(const BodyModel& body, const Partner& partner)
{
    if (body.multi_patch || body.patches.size() != 1)
        return {};
    const nurbs::Patch& patch = body.patches.front().patch;
    std::vector<std::pair<double, std::string>> found;
    for (int s = 0; s < 2 * patch.n_par(); ++s) {
        const Side side = static_cast<Side>(s);
        std::optional<contact::DeformableSide> candidate;
        try {
            candidate = contact::DeformableSide::make(patch, side);
        } catch (const Error&) {
            continue;  // a collapsed side faces nothing
        }
        const Facing f = facing(samples(*candidate), partner);
        if (f.judged() && f.faces() && f.best > -facing_away)
            found.emplace_back(f.nearest, body.name + "." + std::string(side_name(side)));
    }
    std::sort(found.begin(), found.end());
    std::vector<std::string> out;
    for (const auto& [distance, name] : found)
        out.push_back(name);
    return out;
}

std::string vector_text(const VecN& v)
{
    std::string out = "(";
    for (Index i = 0; i < v.size(); ++i)
        out += fmt::format("{}{:.3g}", i ? ", " : "", std::abs(v(i)) < 1e-12 ? 0.0 : v(i));
    return out + ")";
}

}  // namespace

std::vector<std::string> check_sides_face(const io::Deck& deck, const Scene& scene, const io::ContactPair& pair,
                                          const PairModel& model)
{
    // Each surface as the other's partner (a deformable side sampled once).
    const std::array<Partner, 2> surface{partner_of(model, 0), partner_of(model, 1)};
    std::array<std::optional<Facing>, 2> found;
    for (int k = 0; k < 2; ++k)
        if (model.body[static_cast<std::size_t>(k)] >= 0) {
            const Facing f = facing(surface[static_cast<std::size_t>(k)].points,
                                    surface[static_cast<std::size_t>(1 - k)]);
            if (f.judged())
                found[static_cast<std::size_t>(k)] = f;
        }
    // A side with its partner behind it is the one named wrongly; its partner, facing the
    // wrong side's normal, would look turned away by the normals alone.
    const bool any_behind = (found[0] && found[0]->behind) || (found[1] && found[1]->behind);
    std::vector<int> edge_on;
    for (int k = 0; k < 2; ++k) {
        const auto& f = found[static_cast<std::size_t>(k)];
        if (!f || (any_behind && !f->behind))
            continue;
        const std::string& side = model.label[static_cast<std::size_t>(k)];
        const std::string& other = model.label[static_cast<std::size_t>(1 - k)];
        const std::string where = fmt::format("its outward normal {} at {}, the partner's {} there",
                                              vector_text(f->at.normal), vector_text(f->at.x),
                                              vector_text(f->partner_normal));
        if (f->faces()) {
            if (f->best < turned_across)
                edge_on.push_back(k);
            continue;
        }
        const int b = model.body[static_cast<std::size_t>(k)];
        const std::vector<std::string> better = facing_sides(scene.bodies[static_cast<std::size_t>(b)],
                                                             surface[static_cast<std::size_t>(1 - k)]);
        std::string hint;
        if (!better.empty()) {
            std::string list;
            for (std::size_t i = 0; i < better.size(); ++i)
                list += (i == 0 ? "" : i + 1 == better.size() ? " or " : ", ") + better[i];
            hint = fmt::format("; the side{} of '{}' facing {}: {} (`check` lists every side)",
                               better.size() == 1 ? "" : "s", scene.bodies[static_cast<std::size_t>(b)].name, other,
                               list);
        }
        throw DeckError(io::located_issue(
            deck.source_file, "contact." + pair.name + ".between", "",
            fmt::format("{} faces away from {} where they are nearest ({}{}): contact acts only on a side that "
                        "faces its partner, so the body would pass through {} unopposed{}",
                        side, other, where, f->behind ? "; " + other + " lies behind it" : "", other, hint)));
    }
    if (edge_on.empty())
        return {};
    // Two sides met edge-on show the same pair of normals: either may be the slip.
    const int k = edge_on.front();
    const Facing& f = *found[static_cast<std::size_t>(k)];
    const std::string& side = model.label[static_cast<std::size_t>(k)];
    const std::string& other = model.label[static_cast<std::size_t>(1 - k)];
    const std::string names = edge_on.size() == 2 ? side + " or " + other : side;
    return {fmt::format("contact pair '{}': {} meets {} edge-on where they are nearest (the outward normal {} at {}, "
                        "the partner's {} there): contact acts on sides that face each other; check that {} is the "
                        "side you mean",
                        pair.name, side, other, vector_text(f.at.normal), vector_text(f.at.x),
                        vector_text(f.partner_normal), names)};
}

}  // namespace iga::analysis
