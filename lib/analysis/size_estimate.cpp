#include "analysis/size_estimate.hpp"

#include "contact/contact_pair.hpp"
#include "io/locate.hpp"

#include <fmt/format.h>

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
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

/// `dirs` after one refine block (elevate, spans, insert, in this order).
void apply_refine(const io::Refine& r, std::vector<Direction>& out)
{
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
}

/// The directions of one patch as given (before any refinement).
std::vector<Direction> raw_directions(const io::NurbsData* nurbs, const io::Body& body)
{
    std::vector<Direction> out;
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
    return out;
}

/// The directions of every patch of a body after refinement: the body's refine,
/// then the patch's own (analysis/multipatch.hpp). A single-patch body is one patch.
std::vector<std::vector<Direction>> patch_directions(const io::Body& body)
{
    std::vector<std::vector<Direction>> out;
    if (!body.multi_patch()) {
        out.push_back(raw_directions(body.nurbs ? &*body.nurbs : nullptr, body));
        apply_refine(body.refine, out.back());
        return out;
    }
    for (const io::PatchData& patch : body.patches) {
        out.push_back(raw_directions(&patch.nurbs, body));
        apply_refine(body.refine, out.back());
        apply_refine(patch.refine, out.back());
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
    double element_points = 0;  ///< control points of one side element, prod (p_i + 1), the largest
};

/// Entries (i, j) of one direction's Gram pattern: basis functions i and j share a
/// span. With simple interior knots function i meets i - p .. i + p, so the count is
/// n (2p + 1) - p (p + 1) for n functions (the p (p + 1) pairs that would reach past
/// either end removed); repeated knots (elevation) only remove pairs.
double overlapping_pairs(const Direction& dir)
{
    const double n = dir.control_points(), p = dir.degree;
    return std::max(n, n * (2 * p + 1) - p * (p + 1));
}

/// A contact surface of a deformable body: its patch sides together (a named
/// surface, `patch.side` or a side), the largest degree along any of them.
std::optional<SideSize> side_size(const io::Deck& deck, const io::ContactSurface& surface)
{
    const io::Body* body = deck.find_body(surface.body);
    if (body == nullptr || body->rigid || !surface.deformable())
        return std::nullopt;
    const std::vector<std::vector<Direction>> patches = patch_directions(*body);
    auto patch_index = [&](const std::string& name) -> std::optional<std::size_t> {
        if (!body->multi_patch())
            return 0;
        for (std::size_t p = 0; p < body->patches.size(); ++p)
            if (body->patches[p].name == name)
                return p;
        return std::nullopt;
    };
    std::vector<io::PatchSideRef> sides;
    if (!surface.surface.empty()) {
        if (const io::NamedSurface* named = body->find_surface(surface.surface))
            sides = named->sides;
    } else {
        sides.push_back(io::PatchSideRef{surface.patch, *surface.side});
    }
    SideSize s;
    for (const io::PatchSideRef& side : sides) {
        const std::optional<std::size_t> p = patch_index(side.patch);
        if (!p)
            continue;
        const std::vector<Direction>& dirs = patches[*p];
        const int fixed = side_direction(side.side);
        s.spans += product(dirs, [](const Direction& d) { return d.spans(); }, fixed);
        s.control_points += product(dirs, [](const Direction& d) { return d.control_points(); }, fixed);
        s.element_points = std::max(s.element_points, product(dirs, [](const Direction& d) { return d.degree + 1; }, fixed));
        for (std::size_t i = 0; i < dirs.size(); ++i)
            if (static_cast<int>(i) != fixed)
                s.max_degree = std::max(s.max_degree, dirs[i].degree);
    }
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
        for (std::size_t p = 0; p < body.patches.size(); ++p) {
            const io::Refine& r = body.patches[p].refine;
            const std::string patch_prefix = "bodies." + body.name + ".patches." + body.patches[p].name + ".refine.";
            auto add_patch = [&](const std::string& key, const std::string& value,
                                 const std::function<void(io::Refine&)>& clear) {
                Candidate c{patch_prefix + key, value, deck};
                clear(c.without.bodies[b].patches[p].refine);
                out.push_back(std::move(c));
            };
            if (!r.elevate.empty())
                add_patch("elevate", format_list(r.elevate), [](io::Refine& x) { x.elevate.clear(); });
            if (!r.spans.empty())
                add_patch("spans", format_list(r.spans), [](io::Refine& x) { x.spans.clear(); });
            if (!r.insert.empty()) {
                std::vector<int> counts;
                for (const auto& knots : r.insert)
                    counts.push_back(static_cast<int>(knots.size()));
                add_patch("insert", fmt::format("{} knots", format_list(counts)), [](io::Refine& x) { x.insert.clear(); });
            }
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
    auto lower = [&](double bytes, const char* name) {
        if (bytes > 0 && (limits.memory_bytes <= 0 || bytes < limits.memory_bytes)) {
            limits.memory_bytes = bytes;
            limits.memory_name = name;
        }
    };
    if (rlimit r{}; ::getrlimit(RLIMIT_AS, &r) == 0 && r.rlim_cur != RLIM_INFINITY)
        lower(static_cast<double>(r.rlim_cur), "the address-space limit (ulimit -v) of");
    // cgroup v2: "max" or a number of bytes.
    if (std::ifstream in("/sys/fs/cgroup/memory.max"); in) {
        double bytes = 0;
        if (in >> bytes)
            lower(bytes, "the container's memory limit (cgroup memory.max) of");
    }
    return limits;
}

SizeEstimate estimate_size(const io::Deck& deck)
{
    SizeEstimate e;
    const double d = deck.analysis.dimension;
    double largest_element_matrix = 0;
    for (const io::Body& body : deck.bodies) {
        if (body.rigid)
            continue;
        BodySize b;
        b.name = body.name;
        const std::vector<std::vector<Direction>> patches = patch_directions(body);
        for (std::size_t p = 0; p < patches.size(); ++p) {
            const std::vector<Direction>& dirs = patches[p];
            PatchSize s;
            s.name = body.multi_patch() ? body.patches[p].name : "";
            for (const Direction& dir : dirs) {
                s.degrees.push_back(dir.degree);
                s.spans.push_back(dir.spans());
                s.control_points.push_back(dir.control_points());
            }
            const double n_local = product(dirs, [](const Direction& x) { return x.degree + 1; });
            const int n_gauss = body.quadrature.element;  // 0: (p+1) points per direction
            const double gauss_per_element =
                n_gauss > 0 ? std::pow(static_cast<double>(n_gauss), static_cast<double>(dirs.size())) : n_local;
            s.elements = product(dirs, [](const Direction& x) { return x.spans(); });
            s.dofs = d * product(dirs, [](const Direction& x) { return x.control_points(); });
            const double nonzeros = d * d * product(dirs, overlapping_pairs);
            b.dofs += s.dofs;
            b.elements += s.elements;
            b.nonzeros += nonzeros;
            e.element_gauss_points += s.elements * gauss_per_element;
            e.bytes += s.elements * gauss_per_element * (n_local * (d + 1) + 1) * 8;  // element geometry
            e.bytes += s.elements * 4 * (d * n_local) * (d * n_local);             // assembly positions
            largest_element_matrix = std::max(largest_element_matrix, 8 * (d * n_local) * (d * n_local));
            for (std::size_t i = 0; i < dirs.size(); ++i) {  // the largest over the patches
                if (b.degrees.size() <= i) {
                    b.degrees.push_back(0);
                    b.spans.push_back(0);
                    b.control_points.push_back(0);
                }
                b.degrees[i] = std::max(b.degrees[i], s.degrees[i]);
                b.spans[i] = std::max(b.spans[i], s.spans[i]);
                b.control_points[i] = std::max(b.control_points[i], s.control_points[i]);
            }
            b.patches.push_back(std::move(s));
        }
        e.dofs += b.dofs;
        e.nonzeros += b.nonzeros;
        e.bodies.push_back(std::move(b));
    }
    e.bytes += 2 * 12 * e.nonzeros;  // tangent and (at least as large) factor
    e.bytes += largest_element_matrix;  // one dense element matrix at a time (per thread: at least one)
    for (const io::ContactPair& pair : deck.contact) {
        const std::optional<SideSize> sides[2] = {side_size(deck, pair.first), side_size(deck, pair.second)};
        for (const std::optional<SideSize>& side : sides) {
            if (!side)
                continue;
            const double per_span = pair.quadrature > 0 ? pair.quadrature : side->max_degree + 2;
            const double gauss = std::pow(per_span, d - 1) * side->spans;
            const double samples = std::pow(static_cast<double>(deck.output.samples_per_span), d - 1) * side->spans;
            e.contact_gauss_points += gauss;
            e.samples += samples;
            e.bytes += gauss * 64 * d + samples * (2 * d + 1) * 8 * 4;
        }
        // Couplings (contact/contact_pair.hpp): one pattern block per (slave element,
        // master element) pair the search admits in the reference configuration.
        // Against a rigid obstacle, one per side element (its dofs already coupled by
        // the element). Between two deformable sides, assumed to face each other: each
        // slave element meets the master elements within the search margin (a tenth of
        // the larger side: contact_pair.hpp), w = 2 + 0.2 n per direction for n master
        // spans per direction, and each slave control point then w + p_m + p_s master
        // control points per direction; both half passes find the same blocks.
        double couplings = 0, block_dofs = 0, cross = 0;
        if (sides[0] && sides[1]) {
            const double q = d - 1;  // side directions
            auto pass = [&](const SideSize& slave, const SideSize& master, double& blocks, double& entries) {
                const double w = 2 + 2 * contact::auto_search_fraction * std::pow(master.spans, 1 / q);
                blocks = slave.spans * std::pow(w, q);
                entries = slave.control_points * std::pow(w + master.max_degree + slave.max_degree, q);
            };
            double blocks_12 = 0, entries_12 = 0, blocks_21 = 0, entries_21 = 0;
            pass(*sides[0], *sides[1], blocks_12, entries_12);
            pass(*sides[1], *sides[0], blocks_21, entries_21);
            const bool both = pair.formulation == io::Formulation::two_half_pass;
            couplings = both ? std::max(blocks_12, blocks_21) : blocks_12;
            block_dofs = d * (sides[0]->element_points + sides[1]->element_points);
            cross = 2 * d * d * (both ? std::max(entries_12, entries_21) : entries_12);
        } else if (const std::optional<SideSize>& side = sides[0] ? sides[0] : sides[1]) {
            couplings = side->spans;
            block_dofs = d * side->element_points;
        }
        e.contact_couplings += couplings;
        e.nonzeros += cross;
        e.bytes += couplings * 4 * block_dofs * block_dofs + 2 * 12 * cross;  // positions; tangent and factor
    }
    return e;
}

void check_size(const io::Deck& deck, const SizeLimits& limits)
{
    // Hard limits first: they name their key exactly.
    for (const io::Body& body : deck.bodies) {
        if (body.rigid)
            continue;
        for (const auto& [key, n] : {std::pair{"element", body.quadrature.element}, {"side", body.quadrature.side}})
            if (n > limits.max_quadrature)
                refuse(deck, "bodies." + body.name + ".quadrature." + key, std::to_string(n),
                       fmt::format("more than {} Gauss points per knot span (the limit; docs/deck.md)",
                                   limits.max_quadrature));
        const std::vector<std::vector<Direction>> patches = patch_directions(body);
        for (std::size_t p = 0; p < patches.size(); ++p) {
            const std::vector<Direction>& dirs = patches[p];
            const io::PatchData* patch = body.multi_patch() ? &body.patches[p] : nullptr;
            for (std::size_t i = 0; i < dirs.size(); ++i) {
                if (dirs[i].degree <= limits.max_degree)
                    continue;
                // The key to blame: the patch's elevate, the body's, or the degrees as given.
                auto elevates = [i](const io::Refine& r) { return i < r.elevate.size() && r.elevate[i] > 0; };
                const std::string body_path = "bodies." + body.name;
                const std::string patch_path = patch ? body_path + ".patches." + patch->name : body_path;
                std::string path, value;
                if (patch && elevates(patch->refine)) {
                    path = patch_path + ".refine.elevate";
                    value = format_list(patch->refine.elevate);
                } else if (elevates(body.refine)) {
                    path = body_path + ".refine.elevate";
                    value = format_list(body.refine.elevate);
                } else {
                    path = patch_path + ".nurbs.degrees";
                    const io::NurbsData* nurbs = patch ? &patch->nurbs : body.nurbs ? &*body.nurbs : nullptr;
                    value = nurbs ? format_list(nurbs->degrees) : "";
                }
                refuse(deck, path, value,
                       fmt::format("gives degree {} in direction {}, above the limit of {} (docs/deck.md)",
                                   dirs[i].degree, "uvw"[i], limits.max_degree));
            }
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
        "points, {:.3g} contact Gauss points, {:.3g} pressure samples), more than {} {}",
        format_bytes(e.bytes), e.dofs, e.nonzeros, e.element_gauss_points, e.contact_gauss_points, e.samples,
        limits.memory_name, format_bytes(limits.memory_bytes));
    if (culprit != nullptr)
        refuse(deck, culprit->path, culprit->value, reason);
    const auto biggest = std::max_element(e.bodies.begin(), e.bodies.end(),
                                          [](const BodySize& a, const BodySize& b) { return a.dofs < b.dofs; });
    refuse(deck, biggest == e.bodies.end() ? "bodies" : "bodies." + biggest->name, "", reason);
}

}  // namespace iga::analysis
