#include "analysis/zone_refinement.hpp"

#include "analysis/geometry.hpp"
#include "analysis/multipatch.hpp"
#include "core/error.hpp"
#include "io/yaml_cursor.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <deque>
#include <limits>

namespace iga::analysis {

namespace {

/// Sub-segments per span of the chord sum that measures its length.
constexpr int segments_per_span = 4;

const io::ContactPair& find_pair(const io::Deck& deck, const std::string& pair)
{
    const auto it = std::find_if(deck.contact.begin(), deck.contact.end(),
                                 [&](const io::ContactPair& p) { return p.name == pair; });
    IGA_CHECK(it != deck.contact.end(), "accuracy: unknown contact pair '" + pair + "'");
    return *it;
}

/// The deformable bodies of a pair (one or two, each once).
std::vector<const io::Body*> pair_bodies(const io::Deck& deck, const io::ContactPair& pair)
{
    std::vector<const io::Body*> out;
    for (const io::ContactSurface* s : {&pair.first, &pair.second})
        for (const io::Body& body : deck.bodies)
            if (s->deformable() && body.name == s->body && std::find(out.begin(), out.end(), &body) == out.end())
                out.push_back(&body);
    return out;
}

/// The lengths in space of the spans between `breaks` along direction k of `patch`, on
/// the parametric line through xi.
std::vector<double> lengths_along(const nurbs::Patch& patch, int k, VecN xi, const std::vector<double>& breaks)
{
    std::vector<double> out;
    out.reserve(breaks.size());
    auto at = [&](double t) {
        xi(k) = t;
        return nurbs::evaluate(patch, xi, 0).x;
    };
    VecN previous = at(breaks.front());
    for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
        double length = 0.0;
        for (int m = 1; m <= segments_per_span; ++m) {
            const VecN x = at(breaks[i] + (breaks[i + 1] - breaks[i]) * m / segments_per_span);
            length += (x - previous).norm();
            previous = x;
        }
        out.push_back(length);
    }
    return out;
}

/// Adds knots of the analysed patch's direction k to the deck's insert list of that
/// direction: a mirrored body's u runs the other way in the analysed patch (geometry.hpp).
void add_to_insert(std::vector<double>& insert, const nurbs::Patch& patch, bool reversed, int k,
                   const std::vector<double>& knots)
{
    for (const double t : knots)
        insert.push_back(reversed && k == 0 ? patch.knots(0).front() + patch.knots(0).back() - t : t);
    std::sort(insert.begin(), insert.end());
}

/// The deck's refine that acts on patch p of `body` alone: a single-patch body's own, else
/// the patch's (applied after the body's, before gluing: glue_patches carries its knots
/// across the interfaces). The resolved deck writes a geometry file's patches inline once
/// one has a refine of its own (io/deck_writer.hpp).
io::Refine& deck_refine(io::Body& body, int p)
{
    return body.multi_patch() ? body.patches[static_cast<std::size_t>(p)].refine : body.refine;
}

std::vector<double> merged(std::vector<double> breaks, const std::vector<double>& knots)
{
    breaks.insert(breaks.end(), knots.begin(), knots.end());
    std::sort(breaks.begin(), breaks.end());
    return breaks;
}

/// The middle of side `side` of `patch` in its parameters (the side's own direction at its end).
VecN side_middle(const nurbs::Patch& patch, Side side)
{
    VecN xi(patch.n_par());
    for (int k = 0; k < patch.n_par(); ++k)
        xi(k) = 0.5 * (patch.knots(k).front() + patch.knots(k).back());
    const int k = side_direction(side);
    xi(k) = side_at_end(side) ? patch.knots(k).back() : patch.knots(k).front();
    return xi;
}

}  // namespace

std::vector<double> graded_knots(std::vector<double> breaks, const SpanLengths& lengths, GradingSource source)
{
    // Halving a span of a curved line does not halve its length exactly (a quarter circle's
    // rational speed varies by 40 %): without this slack a span a few per cent over twice its
    // halved neighbour would be halved, and its neighbour next, across the whole patch.
    constexpr double slack = 1.25;
    const double smallest_span = 1e-9 * (breaks.back() - breaks.front());  // parameters: no halving below
    std::vector<double> added;
    for (bool changed = true; changed;) {
        const std::vector<double> L = lengths(breaks);
        const std::size_t n = L.size();
        std::vector<double> s(n + 1, 0.0);  // position in space of each breakpoint
        for (std::size_t i = 0; i < n; ++i)
            s[i + 1] = s[i] + L[i];
        // A span of no length (a collapsed edge of the line) bounds nothing.
        const double negligible = 1e-9 * s[n];
        // limit_i = min over j != i of smooth_ratio L_j + growth gap(i, j), by a sweep each way
        std::vector<double> limit(n, std::numeric_limits<double>::infinity());
        double best = std::numeric_limits<double>::infinity();  // min over j < i of smooth_ratio L_j - growth s_{j+1}
        for (std::size_t i = 0; i < n; ++i) {
            limit[i] = std::min(limit[i], best + growth * s[i]);
            if (L[i] > negligible)
                best = std::min(best, smooth_ratio * L[i] - growth * s[i + 1]);
        }
        best = std::numeric_limits<double>::infinity();  // min over j > i of smooth_ratio L_j + growth s_j
        for (std::size_t i = n; i-- > 0;) {
            limit[i] = std::min(limit[i], best - growth * s[i + 1]);
            if (L[i] > negligible)
                best = std::min(best, smooth_ratio * L[i] + growth * s[i]);
        }
        if (source.h0 > 0.0)
            for (std::size_t i = 0; i < n; ++i)
                limit[i] = std::min(limit[i], source.h0 + growth * (source.at_end ? s[n] - s[i + 1] : s[i]));
        changed = false;
        std::vector<double> next{breaks.front()};
        for (std::size_t i = 0; i < n; ++i) {
            if (L[i] > limit[i] * slack && breaks[i + 1] - breaks[i] > smallest_span) {
                const double mid = 0.5 * (breaks[i] + breaks[i + 1]);
                next.push_back(mid);
                added.push_back(mid);
                changed = true;
            }
            next.push_back(breaks[i + 1]);
        }
        breaks = std::move(next);
    }
    return added;
}

std::vector<std::string> grade_neighbours(io::Deck& deck, io::Body& body, int refined)
{
    std::vector<std::string> lines;
    std::vector<bool> graded;
    std::deque<int> queue{refined};
    while (!queue.empty()) {
        const int p = queue.front();
        queue.pop_front();
        const BodyPatches parts = build_body_patches(deck, body);  // with the knots written so far
        graded.resize(parts.patches.size(), false);
        graded[static_cast<std::size_t>(refined)] = true;
        for (const nurbs::Interface& i : parts.topology.interfaces) {
            const bool from_a = i.patch_a == p;
            if (!from_a && i.patch_b != p)
                continue;
            const int q = from_a ? i.patch_b : i.patch_a;
            if (graded[static_cast<std::size_t>(q)])
                continue;
            graded[static_cast<std::size_t>(q)] = true;
            queue.push_back(q);
            const Side side_p = from_a ? i.side_a : i.side_b, side_q = from_a ? i.side_b : i.side_a;
            const nurbs::Patch& from = parts.patches[static_cast<std::size_t>(p)];
            const nurbs::Patch& to = parts.patches[static_cast<std::size_t>(q)];
            const int kp = side_direction(side_p), kq = side_direction(side_q);
            // p's span at the interface, measured across it, is where q's spans start.
            const std::vector<double> across =
                lengths_along(from, kp, side_middle(from, side_p), from.knots(kp).breakpoints());
            const double h0 = side_at_end(side_p) ? across.back() : across.front();
            const std::vector<double> added = graded_knots(
                to.knots(kq).breakpoints(),
                [&](const std::vector<double>& b) { return lengths_along(to, kq, side_middle(to, side_q), b); },
                GradingSource{side_at_end(side_q), h0});
            if (added.empty())
                continue;
            io::Refine& refine = deck_refine(body, q);
            refine.insert.resize(static_cast<std::size_t>(to.n_par()));
            add_to_insert(refine.insert[static_cast<std::size_t>(kq)], to, u_reversed(body, q), kq, added);
            lines.push_back(fmt::format("{}.{}: {} {} span(s) halved from its interface with {}", body.name,
                                        parts.names[static_cast<std::size_t>(q)], "uvw"[kq], added.size(),
                                        parts.names[static_cast<std::size_t>(p)]));
        }
    }
    return lines;
}

std::vector<std::string> refine_side(io::Deck& deck, const std::string& body_name, const std::string& patch_name,
                                     Side side, const SurfaceMarks& marks)
{
    const auto found = std::find_if(deck.bodies.begin(), deck.bodies.end(),
                                    [&](const io::Body& b) { return b.name == body_name; });
    io::Body* body = found == deck.bodies.end() ? nullptr : &*found;
    IGA_CHECK(body != nullptr && !body->rigid, "accuracy: '" + body_name + "' is not a deformable body");
    // The patch as analysed: refined, and glued, so that its spans include the knots its
    // neighbours carried over.
    const BodyPatches parts = build_body_patches(deck, *body);
    const BodySide at = resolve_sides(*body, parts.names, patch_name, side, "").front();
    const nurbs::Patch& patch = parts.patches[static_cast<std::size_t>(at.patch)];
    io::Refine& refine = deck_refine(*body, at.patch);
    const std::string label = body->name + (patch_name.empty() ? "" : "." + patch_name);
    const int n_par = patch.n_par();
    const bool reversed = u_reversed(*body, at.patch);
    const Side analysed = at.side;
    const int normal = side_direction(analysed);
    IGA_CHECK(static_cast<int>(marks.spans.size()) == n_par - 1,
              "accuracy: the marks of " + label + " do not match its side");
    // The zone's point in the body's parameters: the side's directions skip the normal one.
    VecN xi(n_par);
    for (int j = 0, k = 0; k < n_par; ++k) {
        if (k == normal)
            xi(k) = side_at_end(analysed) ? patch.knots(k).back() : patch.knots(k).front();
        else
            xi(k) = marks.center(j++);
    }
    std::vector<std::vector<double>> knots(static_cast<std::size_t>(n_par));  // new knots, analysed parameters
    std::vector<std::string> lines;
    // Along the side: the marked spans halved; the shortest of them sets the depth's first span.
    double shortest = std::numeric_limits<double>::infinity();
    std::vector<std::size_t> marked_count(static_cast<std::size_t>(n_par), 0);
    for (int j = 0, k = 0; k < n_par; ++k) {
        if (k == normal)
            continue;
        const std::vector<double>& values = patch.knots(k).knot_values();
        std::vector<double> children;  // the breakpoints of the halved spans, for their lengths
        for (const int i : marks.spans[static_cast<std::size_t>(j)]) {
            const auto ii = static_cast<std::size_t>(i);
            const double mid = 0.5 * (values[ii] + values[ii + 1]);
            knots[static_cast<std::size_t>(k)].push_back(mid);
            for (const double t : {values[ii], mid, values[ii + 1]})
                children.push_back(t);
        }
        marked_count[static_cast<std::size_t>(k)] = marks.spans[static_cast<std::size_t>(j)].size();
        for (std::size_t c = 0; c + 2 < children.size(); c += 3)
            for (const double length : lengths_along(patch, k, xi, {children[c], children[c + 1], children[c + 2]}))
                if (length > 0.0)
                    shortest = std::min(shortest, length);
        ++j;
    }
    for (int k = 0; k < n_par; ++k) {
        const auto kk = static_cast<std::size_t>(k);
        GradingSource source;
        if (k == normal && std::isfinite(shortest))
            source = GradingSource{side_at_end(analysed), depth_aspect * shortest};
        const std::vector<double> graded =
            graded_knots(merged(patch.knots(k).breakpoints(), knots[kk]),
                         [&](const std::vector<double>& b) { return lengths_along(patch, k, xi, b); }, source);
        knots[kk].insert(knots[kk].end(), graded.begin(), graded.end());
        if (knots[kk].empty())
            continue;
        refine.insert.resize(static_cast<std::size_t>(n_par));
        add_to_insert(refine.insert[kk], patch, reversed, k, knots[kk]);
        lines.push_back(k == normal ? fmt::format("{}: {} {} span(s) halved below {}", label, "uvw"[k],
                                                  graded.size(), side_name(side))
                                    : fmt::format("{}: {} {} span(s) halved at the zone, {} more to grade", label,
                                                  "uvw"[k], marked_count[kk], graded.size()));
    }
    if (body->multi_patch())
        for (std::string& line : grade_neighbours(deck, *body, at.patch))
            lines.push_back(std::move(line));
    return lines;
}

void fold_halvings(io::Deck& deck, int halvings)
{
    for (io::Body& body : deck.bodies) {
        if (body.rigid)
            continue;
        // Each patch's glued spans: the midpoints on the two sides of an interface match.
        const BodyPatches parts = build_body_patches(deck, body);
        for (std::size_t p = 0; p < parts.patches.size(); ++p) {
            const nurbs::Patch& patch = parts.patches[p];
            const bool reversed = u_reversed(body, static_cast<int>(p));
            io::Refine& refine = deck_refine(body, static_cast<int>(p));
            refine.insert.resize(static_cast<std::size_t>(patch.n_par()));
            for (int k = 0; k < patch.n_par(); ++k) {
                std::vector<double> breaks = patch.knots(k).breakpoints();
                std::vector<double>& insert = refine.insert[static_cast<std::size_t>(k)];
                for (int h = 0; h < halvings; ++h) {
                    std::vector<double> mids;
                    for (std::size_t i = 0; i + 1 < breaks.size(); ++i)
                        mids.push_back(0.5 * (breaks[i] + breaks[i + 1]));
                    add_to_insert(insert, patch, reversed, k, mids);
                    breaks = merged(std::move(breaks), mids);
                }
            }
        }
    }
}

std::string refine_text(const io::Deck& deck, const std::string& pair_name)
{
    std::string text;
    const auto lists = [&](const std::string& path, const io::Refine& refine) {
        text += fmt::format("# {}.refine.insert\ninsert:\n", path);
        for (const std::vector<double>& knots : refine.insert) {
            std::vector<std::string> words;
            for (const double k : knots)
                words.push_back(io::format_number(k));
            text += fmt::format("  - [{}]\n", fmt::join(words, ", "));
        }
    };
    for (const io::Body* body : pair_bodies(deck, find_pair(deck, pair_name))) {
        if (!body->geometry_file.empty())
            text += fmt::format("# {}'s patches come from {}, whose patches take no refine of their own: paste the "
                                "body's inline `patches:` from the last level's /deck, or these lists into them\n",
                                body->name, body->geometry_file);
        if (!body->multi_patch())
            lists("bodies." + body->name, body->refine);
        for (const io::PatchData& patch : body->patches)
            if (!patch.refine.insert.empty())  // a patch that only gluing refined keeps its deck text
                lists(fmt::format("bodies.{}.patches.{}", body->name, patch.name), patch.refine);
    }
    return text;
}

}  // namespace iga::analysis
