#pragma once
// Global contact search (Kopacka et al., "Contact detection"): which Bezier
// elements of a master side (a curve in 2D, a surface in 3D) can be near a slave
// point, so that the local search (projection) runs only where a positive gap is
// possible.
//
// Each element's box is the axis-aligned bounding box of its Bezier control
// points in the current configuration (a rational Bezier piece with positive
// weights lies in their convex hull), inflated by max(span_fraction * box
// diagonal, distance). A point outside every box is farther than the margin from
// the side: with a margin above the largest penalty penetration it cannot have a
// positive gap, so it is pruned.
// The boxes sit in a bounding-volume hierarchy (binary tree, split at the median
// of the box centres along the widest axis, a few elements per leaf), so a query
// costs O(log n + k) for n elements and k hits. Element indices are those of
// Patch::elements() (u fastest; in 1D the span numbers). Built in O(n log n).

#include "core/types.hpp"
#include "nurbs/patch.hpp"

#include <vector>

namespace iga::contact {

/// Axis-aligned box, lower <= upper componentwise (d entries each).
struct Box {
    VecN lower;
    VecN upper;

    bool contains(const VecN& x) const
    {
        return (x.array() >= lower.array()).all() && (x.array() <= upper.array()).all();
    }
    bool overlaps(const Box& other) const
    {
        return (lower.array() <= other.upper.array()).all() && (other.lower.array() <= upper.array()).all();
    }
    Box inflated(double margin) const { return {(lower.array() - margin).matrix(), (upper.array() + margin).matrix()}; }
    double diagonal() const { return (upper - lower).norm(); }
    /// The smallest box holding both.
    Box merged(const Box& other) const { return {lower.cwiseMin(other.lower), upper.cwiseMax(other.upper)}; }
};

/// Bounding box of the rows of `points` (n x d, n >= 1).
Box bounding_box(const RowMatrix& points);

struct SearchOptions {
    double distance = 0.0;       ///< absolute margin added around every element box
    double span_fraction = 0.5;  ///< relative margin: fraction of each element box's diagonal
};

class ElementSearch {
public:
    /// Boxes of every element of `side` (n_par = 1 or 2, current control points).
    ElementSearch(const nurbs::Patch& side, const SearchOptions& options);
    /// The same tree over boxes given by the caller (at least one), indexed by their
    /// position: e.g. every element of every patch of a body (analysis/multipatch.cpp).
    explicit ElementSearch(std::vector<Box> boxes);

    /// Element indices (ascending) whose inflated box contains x.
    std::vector<int> candidates(const VecN& x) const;
    /// Same, into `out` (cleared first): the allocation-free form for the Gauss point loop.
    void candidates(const VecN& x, std::vector<int>& out) const;
    /// Element indices (ascending) whose inflated box overlaps `box` (e.g. a slave
    /// element's box: the master elements its Gauss points may project onto).
    void overlapping(const Box& box, std::vector<int>& out) const;

    /// Union of all inflated element boxes.
    const Box& bounds() const { return nodes_.front().box; }
    int n_elements() const { return static_cast<int>(element_boxes_.size()); }
    /// Inflated box of element e.
    const Box& element_box(int e) const { return element_boxes_[e]; }

private:
    struct Node {
        Box box;
        int first = 0;       ///< leaf: range [first, first + count) of order_
        int count = 0;       ///< > 0 for a leaf
        int children[2]{-1, -1};
    };
    void build_tree();
    int build(int first, int count, std::vector<VecN>& centres);
    template <class Test> void query(const Test& hits, std::vector<int>& out) const;

    std::vector<Box> element_boxes_;  ///< by element index
    std::vector<int> order_;          ///< element indices, grouped by leaf
    std::vector<Node> nodes_;         ///< nodes_[0] is the root
};

}  // namespace iga::contact
