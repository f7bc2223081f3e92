#include "analysis/span_marking.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <numeric>

namespace iga::analysis {

namespace {

/// Points per direction of the grid whose box stands for an element.
constexpr int points_per_direction = 5;

bool overlaps(const ZoneBox& a, const ZoneBox& b)
{
    return (a.lower.array() <= b.upper.array()).all() && (b.lower.array() <= a.upper.array()).all();
}

VecN element_center(const nurbs::Element& e, int n_par)
{
    VecN xi(n_par);
    for (int k = 0; k < n_par; ++k)
        xi(k) = 0.5 * (e.lower[static_cast<std::size_t>(k)] + e.upper[static_cast<std::size_t>(k)]);
    return xi;
}

}  // namespace

bool SurfaceMarks::empty() const
{
    return std::all_of(spans.begin(), spans.end(), [](const std::set<int>& s) { return s.empty(); });
}

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

ZoneBox widened(const ZoneBox& zone, double model_size)
{
    const double margin = std::max(0.5 * (zone.upper - zone.lower).maxCoeff(), min_margin * model_size);
    return ZoneBox{zone.lower.array() - margin, zone.upper.array() + margin};
}

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

SurfaceMarks marks_from_indicators(const nurbs::Patch& side, const RowMatrix& eta2, double fraction)
{
    const std::vector<nurbs::Element> elements = side.elements();
    const int n_par = side.n_par();
    IGA_CHECK(eta2.rows() == static_cast<Index>(elements.size()) && eta2.cols() == n_par,
              "accuracy: one indicator per element and direction of the side is needed");
    SurfaceMarks marks{std::vector<std::set<int>>(static_cast<std::size_t>(n_par)), VecN::Zero(n_par)};
    Index largest = 0;
    if (eta2.size() == 0 || !(eta2.rowwise().sum().maxCoeff(&largest) > 0.0))
        return marks;
    marks.center = element_center(elements[static_cast<std::size_t>(largest)], n_par);
    // A slab is one span of one direction; all directions' slabs compete for the bulk.
    std::map<std::pair<int, int>, double> slab;  // (direction, span) -> its elements' indicators along it
    for (std::size_t e = 0; e < elements.size(); ++e)
        for (int k = 0; k < n_par; ++k)
            slab[{k, elements[e].span[static_cast<std::size_t>(k)]}] += eta2(static_cast<Index>(e), k);
    std::vector<std::pair<double, std::pair<int, int>>> order;
    double total = 0.0;
    for (const auto& [key, value] : slab) {
        order.emplace_back(value, key);
        total += value;
    }
    std::sort(order.begin(), order.end(), std::greater<>());
    double taken = 0.0;
    for (const auto& [value, key] : order) {
        if (taken >= fraction * total)
            break;
        marks.spans[static_cast<std::size_t>(key.first)].insert(key.second);
        taken += value;
    }
    return marks;
}

SurfaceMarks marks_from_zone(const nurbs::Patch& side, const ZoneBox& region)
{
    const int n_par = side.n_par();
    SurfaceMarks marks{std::vector<std::set<int>>(static_cast<std::size_t>(n_par)), VecN::Zero(n_par)};
    VecN lower = VecN::Constant(n_par, std::numeric_limits<double>::infinity());
    VecN upper = -lower;
    for (const nurbs::Element& e : side.elements()) {
        if (!overlaps(element_box(side, e), region))
            continue;
        for (int k = 0; k < n_par; ++k) {
            const auto kk = static_cast<std::size_t>(k);
            marks.spans[kk].insert(e.span[kk]);
            lower(k) = std::min(lower(k), e.lower[kk]);
            upper(k) = std::max(upper(k), e.upper[kk]);
        }
    }
    if (!marks.empty())
        marks.center = 0.5 * (lower + upper);
    return marks;
}

}  // namespace iga::analysis
