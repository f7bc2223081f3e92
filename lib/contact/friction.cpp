#include "contact/friction.hpp"

#include "core/error.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace iga::contact {

TangentialResponse coulomb_response(const FrictionLaw& law, const FrictionHistory& committed, const VecN& multiplier,
                                    const VecN& y, const VecN& normal, double pressure, const VecN& d_pressure,
                                    double normal_radius)
{
    const Index d = y.size();
    IGA_CHECK(committed.anchor.size() == d && multiplier.size() == d && normal.size() == d && d_pressure.size() == d,
              "friction: anchor, multiplier, normal and dp/dy need the point's dimension");
    TangentialResponse out;
    out.traction = VecN::Zero(d);
    out.d_traction = Matrix::Zero(d, d);
    out.frame_traction = VecN::Zero(d);
    out.next = committed;
    if (!(pressure > 0.0) || !law.active()) {
        out.next.anchor = y;  // open: it will stick where it touches
        return out;
    }
    const double eps = law.tangential_penalty;
    const Matrix P = Matrix::Identity(d, d) - normal * normal.transpose();
    // The multiplier shifts the anchor: s = P lambda_T - eps P (y - a) = -eps P (y - a - lambda_T / eps).
    const VecN w = y - committed.anchor - multiplier / eps;
    const VecN gt = P * w;
    Matrix G = P;
    if (std::isfinite(normal_radius))
        G -= (normal.dot(w) * P + normal * gt.transpose()) / normal_radius;
    out = coulomb_return_map(law, -eps * gt, -eps * G, pressure, d_pressure, committed.slipping,
                             trial_round_off(law, std::max(y.norm(), committed.anchor.norm())));
    out.next = committed;
    out.frame_traction = out.traction;
    out.elastic_slip = (out.traction - P * multiplier).norm() / eps;
    out.next.slipping = out.status == StickSlip::slip;
    if (out.status == StickSlip::slip) {
        out.next.anchor = y + (out.traction - multiplier) / eps;  // where the traction is reproduced
        out.next.slip = committed.slip + out.slip_increment;
    }
    return out;
}

TangentialResponse coulomb_return_map(const FrictionLaw& law, const VecN& trial, const Matrix& d_trial,
                                      double pressure, const Vector& d_pressure, bool was_slipping,
                                      double round_off)
{
    const Index d = trial.size();
    const Index m = d_trial.cols();
    IGA_CHECK(d_trial.rows() == d && d_pressure.size() == m, "friction: trial and pressure derivatives disagree");
    TangentialResponse out;
    const double s_norm = trial.norm();
    const double limit = law.coefficient * pressure;
    const bool on_cone = was_slipping && s_norm >= limit - std::max(cone_band * limit, round_off);
    if (s_norm <= limit && !on_cone) {
        out.status = StickSlip::stick;
        out.traction = trial;
        out.d_traction = d_trial;
        return out;
    }
    const double eps = law.tangential_penalty;
    out.status = StickSlip::slip;
    const VecN direction = trial / s_norm;
    out.traction = limit * direction;
    out.d_traction = (limit / s_norm) * (Matrix::Identity(d, d) - direction * direction.transpose()) * d_trial +
                     law.coefficient * direction * d_pressure.transpose();
    out.slip_increment = std::max(0.0, s_norm - limit) / eps;
    return out;
}

Matrix tangent_basis(const VecN& normal, const VecN& along)
{
    const Index d = normal.size();
    Matrix t(d, d - 1);
    if (d == 2) {
        t(0, 0) = -normal(1);
        t(1, 0) = normal(0);
        return t;
    }
    VecN t1 = along - normal.dot(along) * normal;
    if (!(t1.norm() > 1e-12 * along.norm())) {  // along parallel to n: any tangent will do
        const Index k = normal.cwiseAbs().minCoeff() == std::abs(normal(0)) ? 0 : 1;
        VecN e = VecN::Zero(3);
        e(k) = 1.0;
        t1 = e - normal.dot(e) * normal;
    }
    t1.normalize();
    t.col(0) = t1;
    t.col(1) = Eigen::Vector3d(normal(0), normal(1), normal(2)).cross(Eigen::Vector3d(t1(0), t1(1), t1(2)));
    return t;
}

}  // namespace iga::contact
