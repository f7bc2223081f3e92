#include "boundary/patch_side.hpp"

#include "nurbs/coincidence.hpp"

#include <algorithm>
#include <cmath>

namespace iga::boundary {

namespace {

/// Samples per parametric direction inside each element of a side when deciding the
/// outward sign: several, because one point may sit where the parent is degenerate.
constexpr int sign_samples_per_direction = 3;
/// Below this |cos| between n_raw and dX/dxi_f a sample says nothing about the sign
/// (degenerate or nearly folded parent there).
constexpr double min_relative_dot = 1e-8;

VecN cross(const VecN& a, const VecN& b)
{
    VecN c(3);
    c << a(1) * b(2) - a(2) * b(1), a(2) * b(0) - a(0) * b(2), a(0) * b(1) - a(1) * b(0);
    return c;
}


double bounding_diagonal(const RowMatrix& points)
{
    if (points.rows() == 0)
        return 0.0;
    return (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
}

std::string folded_message(Side side)
{
    return "the orientation of side " + std::string(side_name(side)) +
           " changes along the side (folded or inverted parametrization)";
}

/// The outward sign of `sp` (a side of `parent`, not collapsed): votes of sample points.
int decide_sign(const nurbs::Patch& parent, const nurbs::SidePatch& sp)
{
    const int d = parent.dim();
    const int fixed = side_direction(sp.side);
    const double fixed_value = side_at_end(sp.side) ? parent.knots(fixed).back() : parent.knots(fixed).front();
    const double expected = side_at_end(sp.side) ? 1.0 : -1.0;  // sign of n . dX/dxi_f for an outward n
    const int n_side = d - 1;
    int n_samples = 1;
    for (int k = 0; k < n_side; ++k)
        n_samples *= sign_samples_per_direction;

    // A sample where |n_raw| is round-off (a pole, a face of zero area) says nothing:
    // the side's mean tangent size is diagonal / parameter range.
    double range = 0.0;
    for (int k = 0; k < n_side; ++k)
        range = std::max(range, sp.patch.knots(k).back() - sp.patch.knots(k).front());
    const double c = bounding_diagonal(sp.patch.control_points()) / range;
    const double min_jacobian = degenerate_relative_jacobian * (n_side == 1 ? c : c * c);

    int votes_plus = 0, votes_minus = 0;
    for (const nurbs::Element& e : sp.patch.elements())
        for (int sample = 0; sample < n_samples; ++sample) {
            VecN xi(d);
            for (int dir = 0, k = 0, rest = sample; dir < d; ++dir) {
                if (dir == fixed) {
                    xi(dir) = fixed_value;
                    continue;
                }
                const int i = rest % sign_samples_per_direction;
                rest /= sign_samples_per_direction;
                const double f = (i + 1.0) / (sign_samples_per_direction + 1.0);
                xi(dir) = e.lower[k] + f * (e.upper[k] - e.lower[k]);
                ++k;
            }
            const nurbs::PointDerivatives p = nurbs::evaluate(parent, xi, 1);
            MatN tangents(d, n_side);
            for (int dir = 0, k = 0; dir < d; ++dir)
                if (dir != fixed)
                    tangents.col(k++) = p.dx.col(dir);
            const VecN n_raw = raw_normal(tangents);
            const VecN across = p.dx.col(fixed);
            const double value = n_raw.dot(across);
            const double scale = n_raw.norm() * across.norm();
            if (!std::isfinite(value) || !(n_raw.norm() > min_jacobian) || std::abs(value) <= min_relative_dot * scale)
                continue;
            (value * expected > 0.0 ? votes_plus : votes_minus) += 1;
        }
    if (votes_plus > 0 && votes_minus > 0)
        throw FoldedSide(sp.side);
    return votes_plus > 0 ? 1 : (votes_minus > 0 ? -1 : 0);
}

void check_parent(const nurbs::Patch& parent, Side side)
{
    IGA_CHECK(parent.n_par() == parent.dim() && (parent.dim() == 2 || parent.dim() == 3),
              "boundary: a patch side needs a solid patch (n_par == d, 2 or 3)");
    IGA_CHECK(side_direction(side) < parent.n_par(),
              "boundary: side " + std::string(side_name(side)) + " does not exist on this patch");
}

bool is_collapsed_side(const nurbs::Patch& parent, const nurbs::SidePatch& sp)
{
    return nurbs::is_collapsed(sp, nurbs::coincidence_tolerance(parent.control_points()));
}

}  // namespace

FoldedSide::FoldedSide(Side which) : Error(folded_message(which)), side(which) {}

VecN raw_normal(const MatN& tangents)
{
    const int d = static_cast<int>(tangents.rows());
    IGA_ASSERT(tangents.cols() == d - 1 && (d == 2 || d == 3), "raw_normal needs d x (d - 1) tangents");
    if (d == 2) {
        VecN n(2);
        n << tangents(1, 0), -tangents(0, 0);
        return n;
    }
    return cross(tangents.col(0), tangents.col(1));
}

int outward_sign(const nurbs::Patch& parent, Side side)
{
    check_parent(parent, side);
    const nurbs::SidePatch sp = nurbs::extract_side(parent, side);
    return is_collapsed_side(parent, sp) ? 0 : decide_sign(parent, sp);
}

PatchSide::PatchSide(const nurbs::Patch& parent, Side side)
    : side_((check_parent(parent, side), nurbs::extract_side(parent, side))), elements_(side_.patch.elements())
{
    collapsed_ = is_collapsed_side(parent, side_);
    sign_ = collapsed_ ? 0 : decide_sign(parent, side_);
}

SurfacePoint PatchSide::evaluate(const RowMatrix& points, int element, const VecN& xi, int n_derivs,
                                 nurbs::BasisValues* basis_out) const
{
    const int d = dim();
    const int n_side = d - 1;
    IGA_ASSERT(element >= 0 && element < n_elements(), "PatchSide::evaluate: element out of range");
    IGA_ASSERT(xi.size() == n_side, "PatchSide::evaluate: xi must have d - 1 entries");
    IGA_ASSERT(points.rows() == side_.patch.n_control_points() && points.cols() == d,
               "PatchSide::evaluate: points must be n_cp_side x d");
    IGA_ASSERT(n_derivs == 1 || n_derivs == 2, "PatchSide::evaluate: n_derivs must be 1 or 2");
    const nurbs::Element& e = elements_[static_cast<std::size_t>(element)];

    nurbs::BasisValues basis = nurbs::rational_basis(side_.patch, e.span, xi, n_derivs);
    const nurbs::PointDerivatives g = nurbs::combine(basis, points);

    SurfacePoint p;
    p.x = g.x;
    p.tangents = g.dx;
    p.metric = p.tangents.transpose() * p.tangents;
    const VecN n_raw = raw_normal(p.tangents);
    p.jacobian = collapsed_ ? 0.0 : n_raw.norm();

    // Natural scale of the element: its control points' extent per unit parameter.
    double extent_min[3] = {0, 0, 0}, extent_max[3] = {0, 0, 0};
    for (std::size_t a = 0; a < basis.indices.size(); ++a)
        for (int i = 0; i < d; ++i) {
            const double v = points(basis.indices[a], i);
            extent_min[i] = a == 0 ? v : std::min(extent_min[i], v);
            extent_max[i] = a == 0 ? v : std::max(extent_max[i], v);
        }
    double diagonal2 = 0.0, length = 0.0;
    for (int i = 0; i < d; ++i)
        diagonal2 += (extent_max[i] - extent_min[i]) * (extent_max[i] - extent_min[i]);
    for (int k = 0; k < n_side; ++k)
        length = std::max(length, e.upper[k] - e.lower[k]);
    const double c = std::sqrt(diagonal2) / length;
    const double scale = n_side == 1 ? c : c * c;
    p.degenerate = sign_ == 0 || !(p.jacobian > degenerate_relative_jacobian * scale);

    p.normal = VecN::Zero(d);
    if (sign_ != 0 && !p.degenerate) {
        p.normal = (sign_ / p.jacobian) * n_raw;
    } else if (sign_ != 0) {
        // Limit from inside the element along delta = centre - xi (see the header).
        const nurbs::BasisValues b2 = n_derivs >= 2 ? basis : nurbs::rational_basis(side_.patch, e.span, xi, 2);
        const MatN second = n_derivs >= 2 ? MatN(g.d2x) : MatN(nurbs::combine(b2, points).d2x);
        VecN delta(n_side);
        for (int k = 0; k < n_side; ++k)
            delta(k) = 0.5 * (e.lower[k] + e.upper[k]) - xi(k);
        MatN d_tangents = MatN::Zero(d, n_side);  // D a_a[delta] = x_,ab delta_b
        for (int a = 0; a < n_side; ++a)
            for (int b = 0; b < n_side; ++b)
                d_tangents.col(a) += delta(b) * second.col(nurbs::second_column(n_side, a, b));
        VecN dn;
        if (d == 2) {
            dn = raw_normal(d_tangents);
        } else {
            dn = cross(d_tangents.col(0), p.tangents.col(1)) + cross(p.tangents.col(0), d_tangents.col(1));
        }
        const double size = dn.norm();
        if (std::isfinite(size) && size > degenerate_relative_jacobian * scale)
            p.normal = (sign_ / size) * dn;
    }

    if (n_derivs >= 2) {
        p.second = g.d2x;
        p.curvature = MatN(n_side, n_side);
        for (int a = 0; a < n_side; ++a)
            for (int b = 0; b < n_side; ++b)
                p.curvature(a, b) = p.normal.dot(p.second.col(nurbs::second_column(n_side, a, b)));
    }
    if (basis_out)
        *basis_out = std::move(basis);
    return p;
}

}  // namespace iga::boundary
