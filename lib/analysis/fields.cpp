#include "analysis/fields.hpp"

#include "mechanics/element_geometry.hpp"
#include "mechanics/stress_recovery.hpp"

#include <cmath>
#include <optional>

namespace iga::analysis {

namespace {

/// Fractions of the knot span by which a point on a singular edge moves inside.
constexpr double inward_steps[] = {0.0, 1e-6, 1e-4, 1e-2};

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

std::optional<mechanics::PointStress> stress_at(const BodyModel& body, mechanics::Kinematics kinematics,
                                                const RowMatrix& u, const VecN& xi)
{
    for (double fraction : inward_steps) {
        try {
            mechanics::PointStress s =
                mechanics::cauchy_stress(body.patch, body.material, kinematics, u, moved_inside(body.patch, xi, fraction));
            if (s.status != mechanics::ResponseStatus::ok || !s.cauchy.allFinite() || !std::isfinite(s.cauchy33))
                return std::nullopt;
            return s;
        } catch (const mechanics::NonPositiveJacobian&) {
            // singular map here: try a little further inside
        }
    }
    return std::nullopt;
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
    const int d = body.patch.dim();
    const Index n = tessellation.mesh.points.rows();
    FieldsResult out;
    io::BodyFields& f = out.fields;
    f.body = body.name;
    f.reference_coordinates = tessellation.mesh.points.leftCols(d);
    f.displacement = tessellation_displacement(tessellation, u).leftCols(d);
    f.stress = RowMatrix::Zero(n, 6);
    f.von_mises = Vector::Zero(n);
    for (Index p = 0; p < n; ++p) {
        const std::optional<mechanics::PointStress> s =
            stress_at(body, kinematics, u, tessellation.parameters[static_cast<std::size_t>(p)]);
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
