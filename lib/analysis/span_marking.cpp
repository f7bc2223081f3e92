#include "analysis/span_marking.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <array>
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

std::vector<SurfaceMarks> marks_from_indicators(const std::vector<const nurbs::Patch*>& sides,
                                                const std::vector<RowMatrix>& eta2, double fraction)
{
    IGA_CHECK(sides.size() == eta2.size(), "accuracy: one indicator matrix per patch side is needed");
    std::vector<SurfaceMarks> marks;
    // A slab is one span of one direction of one piece; all compete for the bulk.
    std::map<std::array<int, 3>, double> slab;  // (piece, direction, span) -> its elements' indicators along it
    for (std::size_t piece = 0; piece < sides.size(); ++piece) {
        const std::vector<nurbs::Element> elements = sides[piece]->elements();
        const int n_par = sides[piece]->n_par();
        const RowMatrix& eta = eta2[piece];
        IGA_CHECK(eta.rows() == static_cast<Index>(elements.size()) && eta.cols() == n_par,
                  "accuracy: one indicator per element and direction of the side is needed");
        SurfaceMarks& m = marks.emplace_back(SurfaceMarks{std::vector<std::set<int>>(static_cast<std::size_t>(n_par)),
                                                          VecN::Zero(n_par)});
        const Vector per_element = eta.rowwise().sum();
        if (eta.size() == 0 || !(per_element.maxCoeff() > 0.0))
            continue;
        // The first element that ties with the largest: of two mirror elements, always the same one.
        Index largest = 0;
        while (per_element(largest) < per_element.maxCoeff() * (1.0 - tie_tolerance))
            ++largest;
        m.center = element_center(elements[static_cast<std::size_t>(largest)], n_par);
        for (std::size_t e = 0; e < elements.size(); ++e)
            for (int k = 0; k < n_par; ++k)
                slab[{static_cast<int>(piece), k, elements[e].span[static_cast<std::size_t>(k)]}] +=
                    eta(static_cast<Index>(e), k);
    }
    std::vector<std::pair<double, std::array<int, 3>>> order;
    double total = 0.0;
    for (const auto& [key, value] : slab) {
        order.emplace_back(value, key);
        total += value;
    }
    std::sort(order.begin(), order.end(), std::greater<>());
    std::size_t n_marked = 0;
    for (double taken = 0.0; n_marked < order.size() && taken < fraction * total; ++n_marked)
        taken += order[n_marked].first;
    // The slabs that tie with the last one marked are marked with it: a symmetric zone's
    // mirror spans are refined alike, and round-off (another rank count's sums) does not
    // choose between them.
    const double last = n_marked > 0 ? order[n_marked - 1].first : 0.0;
    while (n_marked < order.size() && order[n_marked].first >= last * (1.0 - tie_tolerance))
        ++n_marked;
    for (std::size_t i = 0; i < n_marked; ++i) {
        const auto [piece, k, span] = order[i].second;
        marks[static_cast<std::size_t>(piece)].spans[static_cast<std::size_t>(k)].insert(span);
    }
    return marks;
}

SurfaceMarks marks_from_indicators(const nurbs::Patch& side, const RowMatrix& eta2, double fraction)
{
    return marks_from_indicators(std::vector<const nurbs::Patch*>{&side}, std::vector<RowMatrix>{eta2}, fraction)
        .front();
}

SurfaceMarks remap_marks(const SurfaceMarks& marks, const nurbs::Patch& marked, const nurbs::Patch& now)
{
    SurfaceMarks out{std::vector<std::set<int>>(marks.spans.size()), marks.center};
    for (std::size_t k = 0; k < marks.spans.size(); ++k) {
        const std::vector<double>& before = marked.knots(static_cast<int>(k)).knot_values();
        const std::vector<double>& after = now.knots(static_cast<int>(k)).knot_values();
        for (const int i : marks.spans[k]) {
            const double a = before[static_cast<std::size_t>(i)], b = before[static_cast<std::size_t>(i) + 1];
            // The span of `now` that starts at a (the last knot equal to a) and still ends at b.
            const auto end = std::upper_bound(after.begin(), after.end(), a);
            if (end != after.begin() && end != after.end() && *(end - 1) == a && *end == b)
                out.spans[k].insert(static_cast<int>(end - after.begin()) - 1);
        }
    }
    return out;
}

RowMatrix stick_edge_indicator(const nurbs::Patch& side, const io::GaussPointData& points, int stick_status)
{
    const std::vector<nurbs::Element> elements = side.elements();
    const int n_par = side.n_par();
    const auto n_dir = static_cast<std::size_t>(n_par);
    IGA_CHECK(points.parameter.cols() == n_par && points.status.size() == static_cast<std::size_t>(points.pressure.size()),
              "accuracy: the stick zone's edge needs the side's Gauss point parameters and friction states");
    // The elements as a grid: each direction's distinct lower bounds, in order.
    std::vector<std::vector<double>> breaks(n_dir);
    for (const nurbs::Element& e : elements)
        for (std::size_t k = 0; k < n_dir; ++k)
            breaks[k].push_back(e.lower[k]);
    for (std::vector<double>& b : breaks) {
        std::sort(b.begin(), b.end());
        b.erase(std::unique(b.begin(), b.end()), b.end());
    }
    auto grid_index = [&](std::size_t k, double xi) {
        const auto it = std::upper_bound(breaks[k].begin(), breaks[k].end(), xi);
        return static_cast<int>(std::max<std::ptrdiff_t>(0, it - breaks[k].begin() - 1));
    };
    std::map<std::array<int, 3>, std::size_t> at;  // grid position -> element
    std::vector<std::array<int, 3>> cells(elements.size(), {0, 0, 0});
    for (std::size_t e = 0; e < elements.size(); ++e) {
        for (std::size_t k = 0; k < n_dir; ++k)
            cells[e][k] = grid_index(k, elements[e].lower[k]);
        at[cells[e]] = e;
    }
    // What each element holds: bit 1 a sticking point, bit 2 a point that does not stick.
    constexpr int sticks = 1, does_not = 2;
    std::vector<int> holds(elements.size(), 0);
    std::vector<double> measure(elements.size(), 0.0);
    for (Index i = 0; i < points.parameter.rows(); ++i) {
        std::array<int, 3> cell{0, 0, 0};
        for (std::size_t k = 0; k < n_dir; ++k)
            cell[k] = grid_index(k, points.parameter(i, static_cast<Index>(k)));
        const auto found = at.find(cell);
        if (found == at.end())
            continue;
        const std::size_t e = found->second;
        const bool stick = points.pressure(i) > 0.0 && points.status[static_cast<std::size_t>(i)] == stick_status;
        holds[e] |= stick ? sticks : does_not;
        measure[e] += points.weight.size() > 0 ? points.weight(i) : 0.0;
    }
    RowMatrix eta2 = RowMatrix::Zero(static_cast<Index>(elements.size()), n_par);
    for (std::size_t e = 0; e < elements.size(); ++e) {
        if (holds[e] == 0)
            continue;
        std::array<int, 3> across{0, 0, 0};  // differing neighbours per direction
        int total = 0;
        for (std::size_t k = 0; k < n_dir; ++k)
            for (const int step : {-1, 1}) {
                std::array<int, 3> cell = cells[e];
                cell[k] += step;
                const auto n = at.find(cell);
                if (n == at.end())
                    continue;
                const int other = holds[n->second];
                if (other != 0 && other != holds[e] && ((other | holds[e]) & sticks)) {
                    ++across[k];
                    ++total;
                }
            }
        if (total == 0 && holds[e] != (sticks | does_not))
            continue;
        for (std::size_t k = 0; k < n_dir; ++k)
            eta2(static_cast<Index>(e), static_cast<Index>(k)) =
                measure[e] * measure[e] * (total > 0 ? static_cast<double>(across[k]) / total : 1.0 / n_par);
    }
    return eta2;
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
