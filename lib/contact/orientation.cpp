#include "contact/orientation.hpp"

#include "core/error.hpp"

#include <cmath>
#include <string>

namespace iga::contact {

int outward_sign(const nurbs::Patch& parent, Side side)
{
    if (parent.n_par() != 2 || parent.dim() != 2)
        throw Error("contact: outward_sign needs a 2D surface patch (n_par = 2, d = 2); got n_par = " +
                    std::to_string(parent.n_par()) + ", d = " + std::to_string(parent.dim()) +
                    " (3D contact with surface sides is not supported yet)");
    const int fixed = side_direction(side);
    IGA_CHECK(fixed < 2, "contact: side " + std::string(side_name(side)) + " does not exist on a 2D patch");
    const int free = 1 - fixed;
    const nurbs::KnotVector& free_knots = parent.knots(free);
    const double eta = side_at_end(side) ? parent.knots(fixed).back() : parent.knots(fixed).front();
    const double expected = side_at_end(side) ? 1.0 : -1.0;  // sign of n . dX/deta for an outward n

    // Sample inside every span of the side: a single point could sit where the
    // parent is degenerate (dX/deta = 0 at a collapsed corner).
    constexpr int samples_per_span = 3;
    // Below this |sin| between the side tangent and dX/deta the sample says
    // nothing about the orientation (degenerate or nearly folded parent).
    constexpr double min_relative_cross = 1e-8;
    const std::vector<double> breaks = free_knots.breakpoints();
    int votes_plus = 0, votes_minus = 0;
    for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
        for (int s = 0; s < samples_per_span; ++s) {
            const double xi = breaks[k] + (s + 1.0) / (samples_per_span + 1.0) * (breaks[k + 1] - breaks[k]);
            VecN param(2);
            param(free) = xi;
            param(fixed) = eta;
            const nurbs::PointDerivatives p = nurbs::evaluate(parent, param, 1);
            const Eigen::Vector2d t = p.dx.col(free);
            const Eigen::Vector2d d_eta = p.dx.col(fixed);
            const double value = t(1) * d_eta(0) - t(0) * d_eta(1);  // (t_y, -t_x) . dX/deta
            const double scale = t.norm() * d_eta.norm();
            if (!std::isfinite(value) || !(scale > 0.0) || std::abs(value) <= min_relative_cross * scale)
                continue;
            (value * expected > 0.0 ? votes_plus : votes_minus) += 1;
        }
    }
    if (votes_plus == 0 && votes_minus == 0)
        throw Error("contact: side " + std::string(side_name(side)) +
                    " has no point where its outward normal is defined (collapsed side?)");
    if (votes_plus > 0 && votes_minus > 0)
        throw Error("contact: the orientation of side " + std::string(side_name(side)) +
                    " changes along the side (folded or inverted parametrization)");
    return votes_plus > 0 ? 1 : -1;
}

}  // namespace iga::contact
