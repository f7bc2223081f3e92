#pragma once
// Global contact search (Kopacka et al., "Contact detection"): which spans of a
// master curve can be near a slave point, so that the local search (projection)
// runs only where a positive gap is possible.
//
// Each span's box is the axis-aligned bounding box of its Bezier control points
// in the current configuration (the Bezier piece lies in their convex hull,
// physics.md section 4.2), inflated by max(span_fraction * box diagonal,
// distance). A point outside every box is farther than the margin from the
// curve: with a margin above the largest penalty penetration it cannot have a
// positive gap, so it is pruned. Boxes are kept sorted by their lower x
// (a sorted list is enough for 2D).

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
};

/// Bounding box of the rows of `points` (n x d, n >= 1).
Box bounding_box(const RowMatrix& points);

struct SearchOptions {
    double distance = 0.0;       ///< absolute margin added around every span box
    double span_fraction = 0.5;  ///< relative margin: fraction of each span box's diagonal
};

class SpanSearch {
public:
    /// Boxes of every span of `curve` (n_par = 1, current control points).
    SpanSearch(const nurbs::Patch& curve, const SearchOptions& options);

    /// Span numbers k (0..n_spans-1, ascending) whose inflated box contains x.
    std::vector<int> candidates(const VecN& x) const;
    /// Same, into `out` (cleared first): the allocation-free form for the Gauss point loop.
    void candidates(const VecN& x, std::vector<int>& out) const;

    /// Union of all inflated span boxes.
    const Box& bounds() const { return bounds_; }
    int n_spans() const { return static_cast<int>(boxes_.size()); }

private:
    struct SpanBox {
        int span_number;
        Box box;
    };
    std::vector<SpanBox> boxes_;  ///< sorted by box.lower(0)
    Box bounds_;
};

}  // namespace iga::contact
