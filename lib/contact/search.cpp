#include "contact/search.hpp"

#include "core/error.hpp"
#include "nurbs/refine.hpp"

#include <algorithm>
#include <array>
#include <numeric>

namespace iga::contact {
namespace {

// Elements per leaf: a few box tests are cheaper than another level of nodes.
constexpr int leaf_size = 4;

}  // namespace

Box bounding_box(const RowMatrix& points)
{
    IGA_CHECK(points.rows() >= 1, "contact: bounding box of no points");
    return {points.colwise().minCoeff().transpose(), points.colwise().maxCoeff().transpose()};
}

ElementSearch::ElementSearch(const nurbs::Patch& side, const SearchOptions& options)
{
    IGA_CHECK(side.n_par() == 1 || side.n_par() == 2, "contact: element search needs a curve or a surface side");
    IGA_CHECK(options.distance >= 0.0 && options.span_fraction >= 0.0, "contact: search margins must be >= 0");
    std::array<std::vector<Eigen::MatrixXd>, 3> extraction;
    for (int k = 0; k < side.n_par(); ++k)
        extraction[k] = nurbs::bezier_extraction(side.knots(k));
    const std::vector<nurbs::Element> elements = side.elements();
    IGA_CHECK(!elements.empty(), "contact: side without elements");
    element_boxes_.reserve(elements.size());
    for (const nurbs::Element& element : elements) {
        const Box tight = bounding_box(nurbs::bezier_control_points(side, element, extraction));
        const double margin = std::max(options.span_fraction * tight.diagonal(), options.distance);
        element_boxes_.push_back(tight.inflated(margin));
    }
    build_tree();
}

ElementSearch::ElementSearch(std::vector<Box> boxes) : element_boxes_(std::move(boxes))
{
    IGA_CHECK(!element_boxes_.empty(), "contact: element search over no boxes");
    build_tree();
}

void ElementSearch::build_tree()
{
    std::vector<VecN> centres;
    centres.reserve(element_boxes_.size());
    for (const Box& box : element_boxes_)
        centres.push_back(0.5 * (box.lower + box.upper));
    order_.resize(element_boxes_.size());
    std::iota(order_.begin(), order_.end(), 0);
    nodes_.reserve(2 * element_boxes_.size() / leaf_size + 2);
    build(0, static_cast<int>(order_.size()), centres);
}

int ElementSearch::build(int first, int count, std::vector<VecN>& centres)
{
    const int id = static_cast<int>(nodes_.size());
    nodes_.push_back({});
    Box box = element_boxes_[order_[first]];
    for (int i = first + 1; i < first + count; ++i)
        box = box.merged(element_boxes_[order_[i]]);
    nodes_[id].box = box;
    if (count <= leaf_size) {
        nodes_[id].first = first;
        nodes_[id].count = count;
        return id;
    }
    // Split at the median centre along the widest axis of the centres.
    VecN lo = centres[order_[first]], hi = lo;
    for (int i = first + 1; i < first + count; ++i) {
        lo = lo.cwiseMin(centres[order_[i]]);
        hi = hi.cwiseMax(centres[order_[i]]);
    }
    Index axis = 0;
    (hi - lo).maxCoeff(&axis);
    const int half = count / 2;
    std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
                     [&](int a, int b) { return centres[a](axis) < centres[b](axis); });
    const int left = build(first, half, centres);
    const int right = build(first + half, count - half, centres);
    nodes_[id].children[0] = left;
    nodes_[id].children[1] = right;
    return id;
}

template <class Test>
void ElementSearch::query(const Test& hits, std::vector<int>& out) const
{
    out.clear();
    // Depth is about log2(n / leaf_size); 64 covers any element count that fits in memory.
    std::array<int, 64> stack{};
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& node = nodes_[stack[--top]];
        if (!hits(node.box))
            continue;
        if (node.count > 0) {
            for (int i = node.first; i < node.first + node.count; ++i)
                if (hits(element_boxes_[order_[i]]))
                    out.push_back(order_[i]);
        } else {
            stack[top++] = node.children[0];
            stack[top++] = node.children[1];
        }
    }
    std::sort(out.begin(), out.end());
}

void ElementSearch::candidates(const VecN& x, std::vector<int>& out) const
{
    query([&](const Box& b) { return b.contains(x); }, out);
}

std::vector<int> ElementSearch::candidates(const VecN& x) const
{
    std::vector<int> out;
    candidates(x, out);
    return out;
}

void ElementSearch::overlapping(const Box& box, std::vector<int>& out) const
{
    query([&](const Box& b) { return b.overlaps(box); }, out);
}

}  // namespace iga::contact
