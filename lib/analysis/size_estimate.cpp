#include "analysis/size_estimate.hpp"

#include "io/locate.hpp"

#include <fmt/format.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>

namespace iga::analysis {

namespace {

/// One parametric direction of a body while its refinement is applied.
struct Direction {
    double degree = 1;
    double interior_knots = 0;       ///< with multiplicity
    double interior_breakpoints = 0; ///< distinct
    double spans() const { return interior_breakpoints + 1; }
    double control_points() const { return degree + 1 + interior_knots; }
};

std::vector<Direction> base_directions(const io::Body& body)
{
    std::vector<Direction> out;
    // A multi-patch body is estimated from its first patch times the patch count
    // (multi_patch_factor): the estimate guards against absurd refinements only.
    const io::NurbsData* nurbs = body.nurbs ? &*body.nurbs : body.multi_patch() ? &body.patches.front().nurbs : nullptr;
    if (nurbs) {
        for (std::size_t i = 0; i < nurbs->degrees.size() && i < nurbs->knots.size(); ++i) {
            const std::vector<double>& knots = nurbs->knots[i];
            Direction dir;
            dir.degree = nurbs->degrees[i];
            dir.interior_knots = std::max(0.0, static_cast<double>(knots.size()) - 2.0 * (dir.degree + 1));
            for (std::size_t k = 1; k < knots.size(); ++k)
                if (knots[k] != knots[k - 1] && k + 1 < knots.size() && knots[k] < knots.back())
                    dir.interior_breakpoints += 1;
            out.push_back(dir);
        }
    } else if (body.shape) {
        // nurbs/shapes.hpp: one span per direction.
        for (int degree : io::shape_degrees(*body.shape))
            out.push_back(Direction{static_cast<double>(degree), 0, 0});
    }
    const io::Refine& r = body.refine;
    for (std::size_t i = 0; i < out.size(); ++i) {
        Direction& dir = out[i];
        if (i < r.elevate.size() && r.elevate[i] > 0) {
            dir.degree += r.elevate[i];
            dir.interior_knots += r.elevate[i] * dir.interior_breakpoints;
        }
        if (i < r.spans.size() && r.spans[i] > 1) {
            dir.interior_knots += r.spans[i] - 1.0;
            dir.interior_breakpoints += r.spans[i] - 1.0;
        }
        if (i < r.insert.size()) {
            dir.interior_knots += static_cast<double>(r.insert[i].size());
            dir.interior_breakpoints += static_cast<double>(r.insert[i].size());
        }
    }
    return out;
}

double product(const std::vector<Direction>& dirs, const std::function<double(const Direction&)>& f,
               int skip = -1)
{
    double p = 1.0;
    for (std::size_t i = 0; i < dirs.size(); ++i)
        if (static_cast<int>(i) != skip)
            p *= f(dirs[i]);
    return p;
}

/// A contact side of a deformable body: its directions and the fixed one.
struct SideSize {
    double spans = 0, control_points = 0, max_degree = 0;
};

std::optional<SideSize> side_size(const io::Deck& deck, const io::ContactSurface& surface)
{
    const io::Body* body = deck.find_body(surface.body);
    if (body == nullptr || body->rigid || !surface.side)
        return std::nullopt;
    const std::vector<Direction> dirs = base_directions(*body);
    const int fixed = side_direction(*surface.side);
    SideSize s;
    s.spans = product(dirs, [](const Direction& d) { return d.spans(); }, fixed);
    s.control_points = product(dirs, [](const Direction& d) { return d.control_points(); }, fixed);
    for (std::size_t i = 0; i < dirs.size(); ++i)
        if (static_cast<int>(i) != fixed)
            s.max_degree = std::max(s.max_degree, dirs[i].degree);
    return s;
}

std::string format_list(const std::vector<int>& values)
{
    return fmt::format("[{}]", fmt::join(values, ", "));
}

std::string format_bytes(double bytes)
{
    if (bytes >= 1e9)
        return fmt::format("{:.3g} GB", bytes / 1e9);
    return fmt::format("{:.3g} MB", bytes / 1e6);
}

[[noreturn]] void refuse(const io::Deck& deck, const std::string& path, const std::string& value,
                         const std::string& reason)
{
    throw DeckError(io::located_issue(deck.source_file, path, value, reason));
}

/// A key that can make the model big, and the deck without it (for the culprit search).
struct Candidate {
    std::string path, value;
    io::Deck without;
};

std::vector<Candidate> candidates(const io::Deck& deck)
{
    std::vector<Candidate> out;
    for (std::size_t b = 0; b < deck.bodies.size(); ++b) {
        const io::Body& body = deck.bodies[b];
        if (body.rigid)
            continue;
        const std::string prefix = "bodies." + body.name + ".refine.";
        auto add = [&](const std::string& key, const std::string& value, const std::function<void(io::Refine&)>& clear) {
            Candidate c{prefix + key, value, deck};
            clear(c.without.bodies[b].refine);
            out.push_back(std::move(c));
        };
        if (!body.refine.elevate.empty())
            add("elevate", format_list(body.refine.elevate), [](io::Refine& r) { r.elevate.clear(); });
        if (!body.refine.spans.empty())
            add("spans", format_list(body.refine.spans), [](io::Refine& r) { r.spans.clear(); });
        if (!body.refine.insert.empty()) {
            std::vector<int> counts;
            for (const auto& knots : body.refine.insert)
                counts.push_back(static_cast<int>(knots.size()));
            add("insert", fmt::format("{} knots", format_list(counts)), [](io::Refine& r) { r.insert.clear(); });
        }
    }
    for (std::size_t p = 0; p < deck.contact.size(); ++p)
        if (deck.contact[p].quadrature > 0) {
            Candidate c{"contact." + deck.contact[p].name + ".quadrature", std::to_string(deck.contact[p].quadrature), deck};
            c.without.contact[p].quadrature = 0;
            out.push_back(std::move(c));
        }
    const io::Output defaults;
    if (deck.output.samples_per_span > defaults.samples_per_span) {
        Candidate c{"output.samples_per_span", std::to_string(deck.output.samples_per_span), deck};
        c.without.output.samples_per_span = defaults.samples_per_span;
        out.push_back(std::move(c));
    }
    return out;
}

}  // namespace

double machine_memory_bytes()
{
    const long pages = ::sysconf(_SC_PHYS_PAGES);
    const long page_size = ::sysconf(_SC_PAGE_SIZE);
    return pages > 0 && page_size > 0 ? static_cast<double>(pages) * static_cast<double>(page_size) : 0.0;
}

SizeLimits machine_limits()
{
    SizeLimits limits;
    limits.memory_bytes = machine_memory_bytes();
    return limits;
}

SizeEstimate estimate_size(const io::Deck& deck)
{
    SizeEstimate e;
    const double d = deck.analysis.dimension;
    for (const io::Body& body : deck.bodies) {
        if (body.rigid)
            continue;
        const std::vector<Direction> dirs = base_directions(body);
        BodySize b;
        b.name = body.name;
        for (const Direction& dir : dirs) {
            b.degrees.push_back(dir.degree);
            b.spans.push_back(dir.spans());
            b.control_points.push_back(dir.control_points());
        }
        const double n_local = product(dirs, [](const Direction& x) { return x.degree + 1; });
        const double gauss_per_element = n_local;  // (p+1) points per direction
        const double multi_patch_factor = body.multi_patch() ? static_cast<double>(body.patches.size()) : 1.0;
        b.elements = multi_patch_factor * product(dirs, [](const Direction& x) { return x.spans(); });
        b.dofs = multi_patch_factor * d * product(dirs, [](const Direction& x) { return x.control_points(); });
        b.nonzeros = b.dofs * d * product(dirs, [](const Direction& x) { return 2 * x.degree + 1; });
        e.dofs += b.dofs;
        e.nonzeros += b.nonzeros;
        e.element_gauss_points += b.elements * gauss_per_element;
        e.bytes += b.elements * gauss_per_element * (n_local * (d + 1) + 1) * 8;  // element geometry
        e.bytes += b.elements * 4 * (d * n_local) * (d * n_local);             // assembly positions
        e.bodies.push_back(std::move(b));
    }
    e.bytes += 2 * 12 * e.nonzeros;  // tangent and (at least as large) factor
    for (const io::ContactPair& pair : deck.contact) {
        double pair_dofs = 0;
        for (const io::ContactSurface* surface : {&pair.first, &pair.second}) {
            const std::optional<SideSize> side = side_size(deck, *surface);
            if (!side)
                continue;
            const double per_span = pair.quadrature > 0 ? pair.quadrature : side->max_degree + 2;
            const double gauss = std::pow(per_span, d - 1) * side->spans;
            const double samples = std::pow(static_cast<double>(deck.output.samples_per_span), d - 1) * side->spans;
            e.contact_gauss_points += gauss;
            e.samples += samples;
            e.bytes += gauss * 64 * d + samples * (2 * d + 1) * 8 * 4;
            pair_dofs += side->control_points * d;
        }
        e.bytes += pair_dofs * pair_dofs * 16;  // the pair's dense connectivity block
    }
    return e;
}

void check_size(const io::Deck& deck, const SizeLimits& limits)
{
    // Hard limits first: they name their key exactly.
    for (const io::Body& body : deck.bodies) {
        if (body.rigid)
            continue;
        const std::vector<Direction> dirs = base_directions(body);
        for (std::size_t i = 0; i < dirs.size(); ++i)
            if (dirs[i].degree > limits.max_degree) {
                const bool elevated = i < body.refine.elevate.size() && body.refine.elevate[i] > 0;
                const std::string path = "bodies." + body.name + (elevated ? ".refine.elevate" : ".nurbs.degrees");
                const std::string value =
                    elevated ? format_list(body.refine.elevate) : (body.nurbs ? format_list(body.nurbs->degrees) : "");
                refuse(deck, path, value,
                       fmt::format("gives degree {} in direction {}, above the limit of {} (docs/deck.md)",
                                   dirs[i].degree, "uvw"[i], limits.max_degree));
            }
    }
    for (const io::ContactPair& pair : deck.contact)
        if (pair.quadrature > limits.max_quadrature)
            refuse(deck, "contact." + pair.name + ".quadrature", std::to_string(pair.quadrature),
                   fmt::format("more than {} Gauss points per knot span (the limit; docs/deck.md)", limits.max_quadrature));
    if (deck.output.samples_per_span > limits.max_samples_per_span)
        refuse(deck, "output.samples_per_span", std::to_string(deck.output.samples_per_span),
               fmt::format("more than {} sample points per knot span (the limit; docs/deck.md)",
                           limits.max_samples_per_span));

    if (limits.memory_bytes <= 0)
        return;
    const SizeEstimate e = estimate_size(deck);
    if (e.bytes <= limits.memory_bytes)
        return;
    // The culprit: the key whose removal shrinks the estimate most.
    const std::vector<Candidate> keys = candidates(deck);
    const Candidate* culprit = nullptr;
    double best = e.bytes;
    for (const Candidate& c : keys) {
        const double bytes = estimate_size(c.without).bytes;
        if (bytes < best) {
            best = bytes;
            culprit = &c;
        }
    }
    const std::string reason = fmt::format(
        "the model would need at least {} of memory ({:.3g} dofs, {:.3g} stiffness nonzeros, {:.3g} element Gauss "
        "points, {:.3g} contact Gauss points, {:.3g} pressure samples), more than this machine's {}",
        format_bytes(e.bytes), e.dofs, e.nonzeros, e.element_gauss_points, e.contact_gauss_points, e.samples,
        format_bytes(limits.memory_bytes));
    if (culprit != nullptr)
        refuse(deck, culprit->path, culprit->value, reason);
    const auto biggest = std::max_element(e.bodies.begin(), e.bodies.end(),
                                          [](const BodySize& a, const BodySize& b) { return a.dofs < b.dofs; });
    refuse(deck, biggest == e.bodies.end() ? "bodies" : "bodies." + biggest->name, "", reason);
}

}  // namespace iga::analysis
