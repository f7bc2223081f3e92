#include "mechanics/loads.hpp"

#include "core/error.hpp"
#include "nurbs/side_patch.hpp"
#include "quadrature/gauss.hpp"

#include <algorithm>

namespace iga::mechanics {

namespace {

/// Cross product of two 3-vectors stored as VecN.
VecN cross(const VecN& a, const VecN& b)
{
    VecN c(3);
    c << a(1) * b(2) - a(2) * b(1), a(2) * b(0) - a(0) * b(2), a(0) * b(1) - a(1) * b(0);
    return c;
}

double sign(double value) { return value > 0.0 ? 1.0 : (value < 0.0 ? -1.0 : 0.0); }

}  // namespace

VecN raw_normal(const Matrix& tangents)
{
    const int d = static_cast<int>(tangents.rows());
    IGA_ASSERT(tangents.cols() == d - 1, "raw_normal needs d x (d - 1) tangents");
    if (d == 2) {
        VecN n(2);
        n << tangents(1, 0), -tangents(0, 0);
        return n;
    }
    return cross(tangents.col(0), tangents.col(1));
}

SideQuadrature side_quadrature(const nurbs::Patch& parent, Side side, int n_per_direction)
{
    const int d = parent.dim();
    const int fixed = side_direction(side);
    IGA_CHECK(parent.n_par() == d && (d == 2 || d == 3) && fixed < d,
              "side_quadrature needs a solid patch (n_par == d) and one of its sides");
    const nurbs::SidePatch sp = nurbs::extract_side(parent, side);
    const double fixed_value = side_at_end(side) ? parent.knots(fixed).back() : parent.knots(fixed).front();
    const double outward = side_at_end(side) ? 1.0 : -1.0;

    int n = n_per_direction;
    if (n <= 0) {
        int p = 0;
        for (int dir = 0; dir < sp.patch.n_par(); ++dir)
            p = std::max(p, sp.patch.degree(dir));
        n = p + 1;
    }

    // A collapsed side (all control points on one point, up to rounding relative to the
    // patch size) has a tangent that is round-off, not geometry: it carries nothing.
    const RowMatrix& P = parent.control_points();
    const double extent = (P.colwise().maxCoeff() - P.colwise().minCoeff()).norm();
    constexpr double collapse_tolerance = 1e-12;
    const bool collapsed = nurbs::is_collapsed(sp, collapse_tolerance * extent);

    SideQuadrature out{side, d, {}};
    for (const nurbs::Element& e : sp.patch.elements()) {
        const quadrature::TensorRule rule = quadrature::element_rule(sp.patch, e, n);
        SideElement element;
        for (Index q = 0; q < rule.weights.size(); ++q) {
            const VecN s = rule.points.row(q).transpose();
            const nurbs::BasisValues basis = nurbs::rational_basis(sp.patch, e.span, s, 1);
            if (element.indices.empty())
                for (int local : basis.indices)
                    element.indices.push_back(sp.parent_index[local]);
            const nurbs::PointDerivatives x = nurbs::combine(basis, sp.patch.control_points());
            const VecN n_raw = raw_normal(x.dx);

            // The parent's derivative across the side fixes the outward sign.
            VecN xi_parent(d);
            for (int dir = 0, k = 0; dir < d; ++dir)
                xi_parent(dir) = dir == fixed ? fixed_value : s(k++);
            const nurbs::PointDerivatives across = nurbs::evaluate(parent, xi_parent, 1);
            const double measure = collapsed ? 0.0 : n_raw.norm();
            const double orientation = measure > 0.0 ? outward * sign(n_raw.dot(across.dx.col(fixed))) : 0.0;

            element.points.push_back({s, x.x, basis.R, basis.dR, x.dx, rule.weights(q), measure, orientation});
        }
        out.elements.push_back(std::move(element));
    }
    return out;
}

double reference_measure(const SideQuadrature& side)
{
    double total = 0.0;
    for (const SideElement& e : side.elements)
        for (const SidePoint& p : e.points)
            total += p.weight * p.measure;
    return total;
}

LocalForce dead_traction(const SideElement& element, int dim, const VecN& traction)
{
    IGA_CHECK(traction.size() == dim, "traction must have d components");
    const int n_local = element.n_local();
    LocalForce out{element.indices, Vector::Zero(n_local * dim)};
    for (const SidePoint& p : element.points)
        for (int a = 0; a < n_local; ++a)
            out.f_ext.segment(a * dim, dim) += (p.R(a) * p.measure * p.weight) * traction;
    return out;
}

LocalForceTangent follower_pressure(const SideElement& element, int dim, double pressure, Kinematics kinematics,
                                    const Matrix& u_local)
{
    const int d = dim;
    const int n_local = element.n_local();
    const int n_dofs = n_local * d;
    const bool finite = kinematics == Kinematics::finite;
    IGA_CHECK(!finite || (u_local.rows() == n_local && u_local.cols() == d), "u_local must be n_local x d");

    LocalForceTangent out{element.indices, Vector::Zero(n_dofs), finite ? Matrix::Zero(n_dofs, n_dofs) : Matrix()};
    for (const SidePoint& p : element.points) {
        if (p.orientation == 0.0)
            continue;
        // f_ext_ai = -p sum_g R_a orientation n_raw_i(x) w_g  (n_raw ds = n da).
        const double c = -pressure * p.orientation * p.weight;
        const Matrix tangents = finite ? Matrix(p.dX + u_local.transpose() * p.dR) : p.dX;
        const VecN n = raw_normal(tangents);
        for (int a = 0; a < n_local; ++a)
            out.f_ext.segment(a * d, d) += (c * p.R(a)) * n;
        if (!finite)
            continue;
        // dn/du_bk: 2D n = (x_s2, -x_s1); 3D n = x_s x x_t.
        for (int b = 0; b < n_local; ++b)
            for (int k = 0; k < d; ++k) {
                VecN dn = VecN::Zero(d);
                if (d == 2) {
                    if (k == 1)
                        dn(0) = p.dR(b, 0);
                    else
                        dn(1) = -p.dR(b, 0);
                } else {
                    const VecN e_k = VecN::Unit(3, k);
                    dn = p.dR(b, 0) * cross(e_k, tangents.col(1)) + p.dR(b, 1) * cross(tangents.col(0), e_k);
                }
                for (int a = 0; a < n_local; ++a)
                    out.df_ext_du.block(a * d, b * d + k, d, 1) += (c * p.R(a)) * dn;
            }
    }
    return out;
}

LocalForce gravity(const ElementGeometry& geometry, double density, const VecN& g)
{
    const int d = geometry.dim;
    IGA_CHECK(g.size() == d, "gravity must have d components");
    const int n_local = geometry.n_local();
    LocalForce out{geometry.indices, Vector::Zero(n_local * d)};
    for (const QuadraturePoint& q : geometry.points)
        for (int a = 0; a < n_local; ++a)
            out.f_ext.segment(a * d, d) += (density * q.R(a) * q.weight) * g;
    return out;
}

}  // namespace iga::mechanics
