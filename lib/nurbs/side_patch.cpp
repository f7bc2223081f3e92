#include "nurbs/side_patch.hpp"

#include "core/error.hpp"

#include <string>

namespace iga::nurbs {

SidePatch extract_side(const Patch& patch, Side side)
{
    const int n = patch.n_par();
    const int fixed = side_direction(side);
    IGA_CHECK(n >= 2, "extract_side: the patch must have at least 2 parametric directions");
    IGA_CHECK(fixed < n, "extract_side: side " + std::string(side_name(side)) + " does not exist on a patch with " +
                             std::to_string(n) + " parametric directions");

    std::vector<KnotVector> knots;
    std::array<int, 3> n_side{1, 1, 1};  // counts along the side's own directions
    std::array<int, 3> parent_dir{0, 0, 0};
    int m = 0;
    for (int d = 0; d < n; ++d)
        if (d != fixed) {
            knots.push_back(patch.knots(d));
            n_side[m] = patch.n_basis(d);
            parent_dir[m] = d;
            ++m;
        }
    const int fixed_index = side_at_end(side) ? patch.n_basis(fixed) - 1 : 0;

    const int n_cp = n_side[0] * n_side[1];
    RowMatrix points(n_cp, patch.dim());
    Vector weights(n_cp);
    std::vector<int> parent_index(n_cp);
    int a = 0;
    for (int j = 0; j < n_side[1]; ++j)
        for (int i = 0; i < n_side[0]; ++i, ++a) {
            std::array<int, 3> ijk{0, 0, 0};
            ijk[fixed] = fixed_index;
            ijk[parent_dir[0]] = i;
            if (m > 1)
                ijk[parent_dir[1]] = j;
            const int parent = patch.control_point_index(ijk);
            parent_index[a] = parent;
            points.row(a) = patch.control_points().row(parent);
            weights(a) = patch.weights()(parent);
        }
    return SidePatch{side, Patch(std::move(knots), std::move(points), std::move(weights)), std::move(parent_index)};
}

bool is_collapsed(const SidePatch& side, double tolerance)
{
    const RowMatrix& P = side.patch.control_points();
    for (Index a = 0; a < P.rows(); ++a)
        for (Index b = a + 1; b < P.rows(); ++b)
            if (!((P.row(a) - P.row(b)).norm() <= tolerance))  // NaN counts as not collapsed
                return false;
    return true;
}

bool is_collapsed_to_line(const SidePatch& side, double tolerance)
{
    if (side.patch.n_par() < 2)
        return false;
    const RowMatrix& P = side.patch.control_points();
    const int n0 = side.patch.n_basis(0), n1 = side.patch.n_basis(1);
    const auto along = [&](int dir) {  // every line of control points along `dir` is one point
        for (int line = 0; line < (dir == 0 ? n1 : n0); ++line)
            for (int k = 1; k < (dir == 0 ? n0 : n1); ++k) {
                const int a = dir == 0 ? line * n0 : line;
                const int b = dir == 0 ? line * n0 + k : line + k * n0;
                if (!((P.row(a) - P.row(b)).norm() <= tolerance))
                    return false;
            }
        return true;
    };
    return along(0) || along(1);
}

}  // namespace iga::nurbs
