#include "analysis/fields.hpp"

#include "mechanics/element_geometry.hpp"
#include "mechanics/stress_recovery.hpp"

#include <Eigen/LU>

#include <cmath>
#include <optional>

namespace iga::analysis {

namespace {

/// det J / (largest column of J)^d below which the map counts as singular: on a
/// collapsed edge round-off leaves det J ~ 1e-16 of its scale, of either sign.
constexpr double singular_ratio = 1e-6;
/// Fractions of the knot span, towards its centre, of the two points that a
/// singular point is extrapolated from. The round-off of the stress grows like
/// 1 / distance^2 near a collapsed edge (measured on the Hertz quarter disc: 1e-11
/// of the stress at 0.1 of the span, 1e-5 at 1e-4), so the points stay well inside.
constexpr double inner_fraction_1 = 0.05, inner_fraction_2 = 0.1;

/// xi moved by `fraction` of its span towards the span's centre, per direction.
VecN moved_inside(const nurbs::Patch& patch, const VecN& xi, double fraction)
{
    VecN out = xi;
    for (int dir = 0; dir < patch.n_par(); ++dir) {
        const nurbs::KnotVector& knots = patch.knots(dir);
        const int span = knots.find_span(xi(dir));
        const double a = knots.knots()[static_cast<std::size_t>(span)];
        const double b = knots.knots()[static_cast<std::size_t>(span) + 1];
        out(dir) += fraction * (0.5 * (a + b) - xi(dir));
    }
    return out;
}

/// False where the geometry map is singular (a collapsed edge or corner) to round-off.
bool regular_point(const nurbs::Patch& patch, const VecN& xi)
{
    const nurbs::BasisValues basis = nurbs::rational_basis(patch, xi, 1);
    const int d = patch.dim();
    Matrix J = Matrix::Zero(d, patch.n_par());  // dX/dxi
    for (std::size_t a = 0; a < basis.indices.size(); ++a)
        J += patch.control_points().row(basis.indices[a]).transpose() * basis.dR.row(static_cast<Index>(a));
    const double scale = J.colwise().norm().maxCoeff();
    const double det = J.determinant();
    return std::isfinite(det) && scale > 0.0 && det > singular_ratio * std::pow(scale, d);
}

/// The stress at a regular point, or nothing (det F <= 0, a failed material evaluation).
std::optional<mechanics::PointStress> direct_stress(const nurbs::Patch& patch, const mechanics::Material& material,
                                                    mechanics::Kinematics kinematics, const RowMatrix& u,
                                                    const VecN& xi)
{
    try {
        mechanics::PointStress s = mechanics::cauchy_stress(patch, material, kinematics, u, xi);
        if (s.status != mechanics::ResponseStatus::ok || !s.cauchy.allFinite() || !std::isfinite(s.cauchy33))
            return std::nullopt;
        return s;
    } catch (const mechanics::NonPositiveJacobian&) {
        return std::nullopt;
    }
}

/// u: the patch's control-point displacements.
std::optional<mechanics::PointStress> stress_at(const nurbs::Patch& patch, const mechanics::Material& material,
                                                mechanics::Kinematics kinematics, const RowMatrix& u, const VecN& xi)
{
    if (regular_point(patch, xi))
        return direct_stress(patch, material, kinematics, u, xi);
    // Singular point: linear extrapolation from two points inside, 2 s(h) - s(2h).
    const auto s1 = direct_stress(patch, material, kinematics, u, moved_inside(patch, xi, inner_fraction_1));
    const auto s2 = direct_stress(patch, material, kinematics, u, moved_inside(patch, xi, inner_fraction_2));
    if (!s1 || !s2)
        return std::nullopt;
    mechanics::PointStress out = *s1;
    out.cauchy = 2.0 * s1->cauchy - s2->cauchy;
    out.cauchy33 = 2.0 * s1->cauchy33 - s2->cauchy33;
    return out;
}

}  // namespace

double von_mises(const Eigen::Ref<const Eigen::Matrix<double, 1, 6>>& s)
{
    const double xx = s(0), yy = s(1), zz = s(2), xy = s(3), yz = s(4), xz = s(5);
    return std::sqrt(0.5 * ((xx - yy) * (xx - yy) + (yy - zz) * (yy - zz) + (zz - xx) * (zz - xx)) +
                     3.0 * (xy * xy + yz * yz + xz * xz));
}

FieldsResult body_fields(const BodyModel& body, const TessellatedBody& tessellation, mechanics::Kinematics kinematics,
                         const RowMatrix& u)
{
    const int d = static_cast<int>(u.cols());
    const Index n = tessellation.mesh.points.rows();
    std::vector<RowMatrix> u_patch;  // each patch's control-point displacements
    for (const PatchModel& patch : body.patches) {
        RowMatrix up(static_cast<Index>(patch.node.size()), d);
        for (std::size_t a = 0; a < patch.node.size(); ++a)
            up.row(static_cast<Index>(a)) = u.row(patch.node[a]);
        u_patch.push_back(std::move(up));
    }
    FieldsResult out;
    io::BodyFields& f = out.fields;
    f.body = body.name;
    f.reference_coordinates = tessellation.mesh.points.leftCols(d);
    f.displacement = tessellation_displacement(tessellation, u).leftCols(d);
    f.stress = RowMatrix::Zero(n, 6);
    f.von_mises = Vector::Zero(n);
    for (Index p = 0; p < n; ++p) {
        const auto k = static_cast<std::size_t>(tessellation.patch[static_cast<std::size_t>(p)]);
        const std::optional<mechanics::PointStress> s = stress_at(body.patches[k].patch, body.material, kinematics,
                                                                  u_patch[k], tessellation.parameters[static_cast<std::size_t>(p)]);
        if (!s) {
            ++out.n_unevaluated;
            continue;
        }
        const MatN& c = s->cauchy;
        f.stress(p, 0) = c(0, 0);
        f.stress(p, 1) = c(1, 1);
        f.stress(p, 2) = s->cauchy33;
        f.stress(p, 3) = 0.5 * (c(0, 1) + c(1, 0));
        if (d == 3) {
            f.stress(p, 4) = 0.5 * (c(1, 2) + c(2, 1));
            f.stress(p, 5) = 0.5 * (c(0, 2) + c(2, 0));
        }
        f.von_mises(p) = von_mises(f.stress.row(p));
    }
    return out;
}

}  // namespace iga::analysis
