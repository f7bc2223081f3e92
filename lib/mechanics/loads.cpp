#include "mechanics/loads.hpp"

#include "core/error.hpp"

namespace iga::mechanics {

namespace {

/// Cross product of two 3-vectors stored as VecN (the pressure tangent in 3D).
VecN cross(const VecN& a, const VecN& b)
{
    VecN c(3);
    c << a(1) * b(2) - a(2) * b(1), a(2) * b(0) - a(0) * b(2), a(0) * b(1) - a(1) * b(0);
    return c;
}

}  // namespace

SideQuadrature side_quadrature(const nurbs::Patch& parent, Side side, int n_per_direction)
{
    const int d = parent.dim();
    IGA_CHECK(parent.n_par() == d && (d == 2 || d == 3) && side_direction(side) < d,
              "side_quadrature needs a solid patch (n_par == d) and one of its sides");
    const boundary::PatchSide geometry(parent, side);
    std::vector<boundary::GaussPoint> points = boundary::gauss_points(geometry, n_per_direction);

    SideQuadrature out{side, d, std::vector<SideElement>(static_cast<std::size_t>(geometry.n_elements()))};
    for (boundary::GaussPoint& gp : points) {
        SideElement& element = out.elements[static_cast<std::size_t>(gp.element)];
        if (element.indices.empty()) {
            for (const int local : gp.indices)
                element.indices.push_back(geometry.parent_index()[static_cast<std::size_t>(local)]);
            element.outward_sign = geometry.outward_sign();
        }
        element.points.push_back(std::move(gp));
    }
    return out;
}

double reference_measure(const SideQuadrature& side)
{
    double total = 0.0;  // one running sum in point order, as boundary::reference_measure
    for (const SideElement& e : side.elements)
        for (const boundary::GaussPoint& p : e.points)
            total += p.weight;
    return total;
}

LocalForce dead_traction(const SideElement& element, int dim, const VecN& traction)
{
    IGA_CHECK(traction.size() == dim, "traction must have d components");
    const int n_local = element.n_local();
    LocalForce out{element.indices, Vector::Zero(n_local * dim)};
    for (const boundary::GaussPoint& p : element.points)
        for (int a = 0; a < n_local; ++a)
            out.f_ext.segment(a * dim, dim) += (p.N(a) * p.reference.jacobian * p.parametric_weight) * traction;
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
    if (element.outward_sign == 0)
        return out;
    const double sign = element.outward_sign;
    for (const boundary::GaussPoint& p : element.points) {
        // f_ext_ai = -p sum_g R_a sign n_raw_i(x) w_g  (sign n_raw ds = n da).
        const double c = -pressure * sign * p.parametric_weight;
        const MatN tangents =
            finite ? MatN(p.reference.tangents + Matrix(u_local.transpose() * p.dN)) : p.reference.tangents;
        const VecN n = boundary::raw_normal(tangents);
        for (int a = 0; a < n_local; ++a)
            out.f_ext.segment(a * d, d) += (c * p.N(a)) * n;
        if (!finite)
            continue;
        // dn/du_bk: 2D n = (x_s2, -x_s1); 3D n = x_s x x_t.
        for (int b = 0; b < n_local; ++b)
            for (int k = 0; k < d; ++k) {
                VecN dn = VecN::Zero(d);
                if (d == 2) {
                    if (k == 1)
                        dn(0) = p.dN(b, 0);
                    else
                        dn(1) = -p.dN(b, 0);
                } else {
                    const VecN e_k = VecN::Unit(3, k);
                    dn = p.dN(b, 0) * cross(e_k, tangents.col(1)) + p.dN(b, 1) * cross(tangents.col(0), e_k);
                }
                for (int a = 0; a < n_local; ++a)
                    out.df_ext_du.block(a * d, b * d + k, d, 1) += (c * p.N(a)) * dn;
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
