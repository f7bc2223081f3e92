#include "analysis/zone_refinement.hpp"

#include "analysis/geometry.hpp"
#include "analysis/multipatch.hpp"
#include "core/error.hpp"
#include "io/yaml_cursor.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <set>

namespace iga::analysis {

namespace {

/// Neighbouring spans differ by at most this factor after a refinement (grading_knots).
constexpr double grading_ratio = 4.0;

/// Points per direction of the grid whose box stands for an element.
constexpr int points_per_direction = 5;

const io::ContactPair& find_pair(const io::Deck& deck, const std::string& pair)
{
    const auto it = std::find_if(deck.contact.begin(), deck.contact.end(),
                                 [&](const io::ContactPair& p) { return p.name == pair; });
    IGA_CHECK(it != deck.contact.end(), "accuracy: unknown contact pair '" + pair + "'");
    return *it;
}

/// The deformable bodies of a pair (one or two, each once).
std::vector<io::Body*> pair_bodies(io::Deck& deck, const io::ContactPair& pair)
{
    std::vector<io::Body*> out;
    for (const io::ContactSurface* s : {&pair.first, &pair.second})
        for (io::Body& body : deck.bodies)
            if (s->deformable() && body.name == s->body &&
                std::find(out.begin(), out.end(), &body) == out.end())
                out.push_back(&body);
    return out;
}

/// The bounding box of a grid of points on one element of `patch`.
ZoneBox element_box(const nurbs::Patch& patch, const nurbs::Element& element)
{
    const int n_par = patch.n_par();
    const int d = patch.dim();
    ZoneBox box{VecN::Constant(d, std::numeric_limits<double>::infinity()),
                VecN::Constant(d, -std::numeric_limits<double>::infinity())};
    int total = 1;
    for (int k = 0; k < n_par; ++k)
        total *= points_per_direction;
    VecN xi(n_par);
    for (int index = 0; index < total; ++index) {
        int rest = index;
        for (int k = 0; k < n_par; ++k) {
            const double t = static_cast<double>(rest % points_per_direction) / (points_per_direction - 1);
            rest /= points_per_direction;
            const auto kk = static_cast<std::size_t>(k);
            xi(k) = element.lower[kk] + t * (element.upper[kk] - element.lower[kk]);
        }
        const VecN x = nurbs::evaluate(patch, xi, 0).x;
        box.lower = box.lower.cwiseMin(x);
        box.upper = box.upper.cwiseMax(x);
    }
    return box;
}

/// Knots that keep neighbouring spans within a factor of two of each other (a 2:1 grading
/// out from the zone), given the breakpoints after the zone's halving: each span longer
/// than twice a neighbour is halved, until none is.
std::vector<double> grading_knots(std::vector<double> breaks)
{
    std::vector<double> added;
    for (bool changed = true; changed;) {
        changed = false;
        std::vector<double> next{breaks.front()};
        for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
            const double length = breaks[i + 1] - breaks[i];
            const double left = i > 0 ? breaks[i] - breaks[i - 1] : length;
            const double right = i + 2 < breaks.size() ? breaks[i + 2] - breaks[i + 1] : length;
            if (length > grading_ratio * std::min(left, right) * (1.0 + 1e-9)) {
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

bool overlaps(const ZoneBox& a, const ZoneBox& b)
{
    return (a.lower.array() <= b.upper.array()).all() && (b.lower.array() <= a.upper.array()).all();
}

}  // namespace

std::optional<ZoneBox> pressed_zone(const io::ContactPairResult& pair)
{
    std::optional<ZoneBox> box;
    for (const io::ContactSideResult& side : pair.sides) {
        const io::GaussPointData& g = side.gauss_points;
        for (Index k = 0; k < g.pressure.size(); ++k) {
            if (!(g.pressure(k) > 0.0))
                continue;
            const VecN x = g.reference_coordinates.row(k).transpose();
            if (!box)
                box = ZoneBox{x, x};
            box->lower = box->lower.cwiseMin(x);
            box->upper = box->upper.cwiseMax(x);
        }
    }
    return box;
}

std::vector<std::string> refine_toward_zone(io::Deck& deck, const std::string& pair_name, const ZoneBox& zone,
                                            double model_size)
{
    const io::ContactPair& pair = find_pair(deck, pair_name);
    const double margin = std::max(0.5 * (zone.upper - zone.lower).maxCoeff(), min_margin * model_size);
    const ZoneBox region{zone.lower.array() - margin, zone.upper.array() + margin};
    std::vector<std::string> lines;
    for (io::Body* body : pair_bodies(deck, pair)) {
        const nurbs::Patch patch = build_patch(*body, deck.analysis.dimension);
        const int n_par = patch.n_par();
        std::vector<std::set<int>> marked(static_cast<std::size_t>(n_par));  // span start knot index per direction
        for (const nurbs::Element& e : patch.elements())
            if (overlaps(element_box(patch, e), region))
                for (int k = 0; k < n_par; ++k)
                    marked[static_cast<std::size_t>(k)].insert(e.span[static_cast<std::size_t>(k)]);
        const bool reversed = u_reversed(*body, 0);
        io::Refine& refine = body->refine;
        refine.insert.resize(static_cast<std::size_t>(n_par));
        for (int k = 0; k < n_par; ++k) {
            const nurbs::KnotVector& kv = patch.knots(k);
            const auto& values = kv.knot_values();
            std::vector<double> knots;  // new knots, in the analysed patch's parameters
            double lo = kv.back(), hi = kv.front();
            for (const int i : marked[static_cast<std::size_t>(k)]) {
                const auto ii = static_cast<std::size_t>(i);
                knots.push_back(0.5 * (values[ii] + values[ii + 1]));
                lo = std::min(lo, values[ii]);
                hi = std::max(hi, values[ii + 1]);
            }
            if (knots.empty())
                continue;
            std::vector<double> breaks = kv.breakpoints();
            breaks.insert(breaks.end(), knots.begin(), knots.end());
            std::sort(breaks.begin(), breaks.end());
            const std::vector<double> graded = grading_knots(breaks);
            knots.insert(knots.end(), graded.begin(), graded.end());
            std::vector<double>& insert = refine.insert[static_cast<std::size_t>(k)];
            for (const double t : knots)  // the deck's u runs the other way in a mirrored body (geometry.hpp)
                insert.push_back(reversed && k == 0 ? kv.front() + kv.back() - t : t);
            std::sort(insert.begin(), insert.end());
            lines.push_back(fmt::format("{}: {} {} span(s) halved in [{:.4g}, {:.4g}], {} more to grade", body->name,
                                        "uvw"[k], marked[static_cast<std::size_t>(k)].size(), lo, hi,
                                        graded.size()));
        }
    }
    return lines;
}

std::string refine_text(const io::Deck& deck, const std::string& pair_name)
{
    io::Deck copy = deck;
    std::string text;
    for (const io::Body* body : pair_bodies(copy, find_pair(deck, pair_name))) {
        text += fmt::format("# bodies.{}.refine.insert\ninsert:\n", body->name);
        for (const std::vector<double>& knots : body->refine.insert) {
            std::vector<std::string> words;
            for (const double k : knots)
                words.push_back(io::format_number(k));
            text += fmt::format("  - [{}]\n", fmt::join(words, ", "));
        }
    }
    return text;
}

}  // namespace iga::analysis
