#include "analysis/level_estimate.hpp"

#include "core/error.hpp"
#include "quadrature/gauss.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace iga::analysis {

namespace {

double pressure_at(const SidePressure& field, const VecN& xi)
{
    const nurbs::BasisValues b = nurbs::rational_basis(field.side, xi, 0);
    double p = 0.0;
    for (std::size_t a = 0; a < b.indices.size(); ++a)
        p += b.R(static_cast<Index>(a)) * field.control_pressure(b.indices[a]);
    return p;
}

/// The area (length) element of a side at xi: |x_u| on a curve, |x_u x x_v| on a surface.
double area_element(const nurbs::Patch& side, const VecN& xi)
{
    const nurbs::PointDerivatives p = nurbs::evaluate(side, xi, 1);
    if (p.dx.cols() == 1)
        return p.dx.col(0).norm();
    const Eigen::Vector3d a = p.dx.col(0), b = p.dx.col(1);
    return a.cross(b).norm();
}

/// Calls f(xi, W) at the Gauss points of every span of `side` (degree + 2 points per span
/// and direction), W the rule's weight times the area element.
template <class F>
void for_each_side_point(const nurbs::Patch& side, F&& f)
{
    int n = 0;
    for (int k = 0; k < side.n_par(); ++k)
        n = std::max(n, side.degree(k) + 2);
    for (const nurbs::Element& e : side.elements()) {
        const quadrature::TensorRule rule = quadrature::element_rule(side, e, n);
        for (Index q = 0; q < rule.points.rows(); ++q) {
            const VecN xi = rule.points.row(q).transpose();
            f(xi, rule.weights(q) * area_element(side, xi));
        }
    }
}

}  // namespace

double side_quantity(io::AccuracyQuantity quantity, const io::ContactSideResult& side, const SidePressure& field)
{
    switch (quantity) {
    case io::AccuracyQuantity::force:
        return side.normal_force;
    case io::AccuracyQuantity::contact_radius: {
        const io::GaussPointData& g = side.gauss_points;
        double measure = 0.0;
        for (Index k = 0; k < g.pressure.size(); ++k)
            if (g.pressure(k) > 0.0)
                measure += g.weight(k);
        return field.side.n_par() == 1 ? measure : std::sqrt(measure / std::numbers::pi);
    }
    case io::AccuracyQuantity::pressure_l2: {
        double norm2 = 0.0;
        for_each_side_point(field.side, [&](const VecN& xi, double w) {
            const double p = pressure_at(field, xi);
            norm2 += w * p * p;
        });
        return std::sqrt(norm2);
    }
    case io::AccuracyQuantity::stick_zone:
        break;
    }
    throw Error("accuracy: the stick zone has no estimate yet");
}

double relative_pressure_difference(const SidePressure& coarse, const SidePressure& fine)
{
    IGA_CHECK(coarse.side.n_par() == fine.side.n_par(), "accuracy: two levels' contact sides differ in dimension");
    double difference2 = 0.0, norm2 = 0.0;
    for_each_side_point(fine.side, [&](const VecN& xi, double w) {
        const double p_fine = pressure_at(fine, xi);
        const double p_coarse = pressure_at(coarse, xi);
        difference2 += w * (p_fine - p_coarse) * (p_fine - p_coarse);
        norm2 += w * p_fine * p_fine;
    });
    return norm2 > 0.0 ? std::sqrt(difference2 / norm2) : std::numeric_limits<double>::infinity();
}

std::optional<double> slow_convergence(const std::vector<double>& d)
{
    const std::size_t n = d.size();
    if (n < 3 || !(d[n - 1] > 0.0 && d[n - 2] > 0.0))
        return std::nullopt;
    const double last = d[n - 2] / d[n - 1], before = d[n - 3] / d[n - 2];
    if (!(last < slow_ratio && before < slow_ratio && last > 1.0 && before > 1.0))
        return std::nullopt;
    return std::min(last, before);
}

}  // namespace iga::analysis
