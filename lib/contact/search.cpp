#include "contact/search.hpp"

#include "core/error.hpp"
#include "nurbs/refine.hpp"

#include <algorithm>

namespace iga::contact {

Box bounding_box(const RowMatrix& points)
{
    IGA_CHECK(points.rows() >= 1, "contact: bounding box of no points");
    return {points.colwise().minCoeff().transpose(), points.colwise().maxCoeff().transpose()};
}

SpanSearch::SpanSearch(const nurbs::Patch& curve, const SearchOptions& options)
{
    IGA_CHECK(curve.n_par() == 1, "contact: span search needs a curve (n_par = 1)");
    IGA_CHECK(options.distance >= 0.0 && options.span_fraction >= 0.0, "contact: search margins must be >= 0");
    const nurbs::KnotVector& knots = curve.knots(0);
    for (const nurbs::Element& element : curve.elements()) {
        const Box tight = bounding_box(nurbs::bezier_control_points(curve, element));
        const double margin = std::max(options.span_fraction * tight.diagonal(), options.distance);
        boxes_.push_back({knots.span_number(element.span[0]), tight.inflated(margin)});
    }
    IGA_CHECK(!boxes_.empty(), "contact: curve without spans");
    std::sort(boxes_.begin(), boxes_.end(),
              [](const SpanBox& a, const SpanBox& b) { return a.box.lower(0) < b.box.lower(0); });
    bounds_ = boxes_.front().box;
    for (const SpanBox& b : boxes_) {
        bounds_.lower = bounds_.lower.cwiseMin(b.box.lower);
        bounds_.upper = bounds_.upper.cwiseMax(b.box.upper);
    }
}

void SpanSearch::candidates(const VecN& x, std::vector<int>& out) const
{
    out.clear();
    for (const SpanBox& b : boxes_) {
        if (b.box.lower(0) > x(0))
            break;  // sorted by lower x: no later box can contain x
        if (b.box.contains(x))
            out.push_back(b.span_number);
    }
    std::sort(out.begin(), out.end());
}

std::vector<int> SpanSearch::candidates(const VecN& x) const
{
    std::vector<int> out;
    candidates(x, out);
    return out;
}

}  // namespace iga::contact
