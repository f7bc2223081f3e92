#include "analysis/level_estimate.hpp"

#include "core/error.hpp"
#include "quadrature/gauss.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
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

/// Calls f(e, element, xi, W) at the Gauss points of every span of `side` (degree + 2
/// points per span and direction), e the element's index in side.elements(), W the rule's
/// weight times the area element.
template <class F>
void for_each_side_point(const nurbs::Patch& side, F&& f)
{
    int n = 0;
    for (int k = 0; k < side.n_par(); ++k)
        n = std::max(n, side.degree(k) + 2);
    const std::vector<nurbs::Element> elements = side.elements();
    for (std::size_t e = 0; e < elements.size(); ++e) {
        const quadrature::TensorRule rule = quadrature::element_rule(side, elements[e], n);
        for (Index q = 0; q < rule.points.rows(); ++q) {
            const VecN xi = rule.points.row(q).transpose();
            f(e, elements[e], xi, rule.weights(q) * area_element(side, xi));
        }
    }
}

}  // namespace

double side_quantity(io::AccuracyQuantity quantity, const io::ContactSideResult& side, const SurfacePressure& field,
                     int mirrors)
{
    IGA_CHECK(!field.empty(), "accuracy: a contact surface has at least one patch side");
    const int n_par = field.front().side.n_par();
    switch (quantity) {
    case io::AccuracyQuantity::force:
        return side.normal_force;
    case io::AccuracyQuantity::contact_radius:
    case io::AccuracyQuantity::stick_zone: {
        double measure = 0.0;  // of the modelled part
        for (const Index k : zone_points(quantity, side))
            measure += side.gauss_points.weight(k);
        const double whole = std::ldexp(measure, std::min(mirrors, n_par));
        if (n_par == 2)
            return std::sqrt(whole / std::numbers::pi);
        return quantity == io::AccuracyQuantity::contact_radius ? 0.5 * whole : whole;
    }
    case io::AccuracyQuantity::pressure_l2: {
        double norm2 = 0.0;
        for (const SidePressure& piece : field)
            for_each_side_point(piece.side, [&](std::size_t, const nurbs::Element&, const VecN& xi, double w) {
                const double p = pressure_at(piece, xi);
                norm2 += w * p * p;
            });
        return std::sqrt(norm2);
    }
    }
    throw Error("accuracy: unknown quantity");
}

std::vector<Index> zone_points(io::AccuracyQuantity quantity, const io::ContactSideResult& side)
{
    const io::GaussPointData& g = side.gauss_points;
    const bool stick = quantity == io::AccuracyQuantity::stick_zone;
    IGA_CHECK(!stick || g.status.size() == static_cast<std::size_t>(g.pressure.size()),
              "accuracy: the side " + side.side_name + " has no friction states for stick_zone");
    std::vector<Index> zone;
    for (Index k = 0; k < g.pressure.size(); ++k)
        if (g.pressure(k) > 0.0 && (!stick || g.status[static_cast<std::size_t>(k)] == stick_status))
            zone.push_back(k);
    return zone;
}

double zone_resolution(io::AccuracyQuantity quantity, const io::ContactSideResult& side)
{
    const io::GaussPointData& g = side.gauss_points;
    const std::vector<Index> zone = zone_points(quantity, side);
    if (zone.size() <= 1)
        return 1.0;
    double measure = 0.0;
    for (const Index k : zone)
        measure += g.weight(k);
    const bool curve = g.parameter.cols() == 1;
    if (curve && g.patch.empty()) {  // a curve: the zone's two ends along it, but not an end of the side
        const auto by_parameter = [&](Index a, Index b) { return g.parameter(a, 0) < g.parameter(b, 0); };
        const auto [first, last] = std::minmax_element(zone.begin(), zone.end(), by_parameter);
        const auto [side_first, side_last] = std::minmax_element(g.parameter.col(0).begin(), g.parameter.col(0).end());
        double edges = 0.0;
        if (g.parameter(*first, 0) > *side_first)
            edges += g.weight(*first);
        if (g.parameter(*last, 0) < *side_last)
            edges += g.weight(*last);
        return edges / measure;
    }
    VecN centroid = VecN::Zero(g.reference_coordinates.cols());
    for (const Index k : zone)
        centroid += g.weight(k) * g.reference_coordinates.row(k).transpose();
    centroid /= measure;
    Index outer = zone.front();
    double distance = 0.0;
    for (const Index k : zone)
        if (const double r = (g.reference_coordinates.row(k).transpose() - centroid).norm(); r > distance) {
            distance = r;
            outer = k;
        }
    const double width = curve ? g.weight(outer) : std::sqrt(g.weight(outer));
    return distance > 0.0 ? std::min(1.0, width / distance) : 1.0;
}

PressureDifference pressure_difference(const SurfacePressure& coarse, const SurfacePressure& fine)
{
    IGA_CHECK(coarse.size() == fine.size(), "accuracy: two levels' contact surfaces differ in their patch sides");
    PressureDifference out;
    double difference2 = 0.0, norm2 = 0.0;
    for (std::size_t piece = 0; piece < fine.size(); ++piece) {
        const SidePressure& c = coarse[piece];
        const SidePressure& f = fine[piece];
        IGA_CHECK(c.side.n_par() == f.side.n_par(), "accuracy: two levels' contact sides differ in dimension");
        const int n_par = f.side.n_par();
        RowMatrix& element2 =
            out.element2.emplace_back(RowMatrix::Zero(static_cast<Index>(f.side.elements().size()), n_par));
        std::array<double, 3> change{};  // the fine pressure's change across the element, per direction
        for_each_side_point(f.side, [&](std::size_t e, const nurbs::Element& element, const VecN& xi, double w) {
            const nurbs::BasisValues b = nurbs::rational_basis(f.side, xi, 1);
            double p_fine = 0.0;
            change.fill(0.0);
            for (std::size_t a = 0; a < b.indices.size(); ++a) {
                const double p_a = f.control_pressure(b.indices[a]);
                p_fine += b.R(static_cast<Index>(a)) * p_a;
                for (int k = 0; k < n_par; ++k)
                    change[static_cast<std::size_t>(k)] += b.dR(static_cast<Index>(a), k) * p_a;
            }
            double total = 0.0;
            for (int k = 0; k < n_par; ++k) {
                const auto kk = static_cast<std::size_t>(k);
                change[kk] *= element.upper[kk] - element.lower[kk];
                total += change[kk] * change[kk];
            }
            const double p_coarse = pressure_at(c, xi);
            const double d2 = w * (p_fine - p_coarse) * (p_fine - p_coarse);
            for (int k = 0; k < n_par; ++k) {  // the direction the pressure changes in is the one to refine
                const double ck = change[static_cast<std::size_t>(k)];
                element2(static_cast<Index>(e), k) += d2 * (total > 0.0 ? ck * ck / total : 1.0 / n_par);
            }
            difference2 += d2;
            norm2 += w * p_fine * p_fine;
        });
    }
    out.relative = norm2 > 0.0 ? std::sqrt(difference2 / norm2) : std::numeric_limits<double>::infinity();
    return out;
}

double reference_pressure_error(const io::ReferenceData& ref, const SurfacePressure& field)
{
    IGA_CHECK(!field.empty(), "accuracy: a contact surface has at least one patch side");
    const int d = field.front().side.dim();
    IGA_CHECK(static_cast<int>(ref.center.size()) == d && (ref.normal.size() == 3 || static_cast<int>(ref.tangent.size()) == d),
              "accuracy: the reference of pair '" + ref.pair + "' has no centre and direction");
    const VecN c = Eigen::Map<const Eigen::VectorXd>(ref.center.data(), d);
    const bool point = ref.normal.size() == 3;
    const VecN axis = point ? VecN(Eigen::Map<const Eigen::VectorXd>(ref.normal.data(), 3).normalized())
                            : VecN(Eigen::Map<const Eigen::VectorXd>(ref.tangent.data(), d).normalized());
    double error2 = 0.0, norm2 = 0.0;
    for (const SidePressure& piece : field)
        for_each_side_point(piece.side, [&](std::size_t, const nurbs::Element&, const VecN& xi, double w) {
            const VecN offset = nurbs::evaluate(piece.side, xi, 0).x - c;
            const double s = point ? (offset - offset.dot(axis) * axis).norm() : std::abs(offset.dot(axis));
            const double exact = s < ref.a ? ref.p0 * std::sqrt(1.0 - (s / ref.a) * (s / ref.a)) : 0.0;
            const double p = pressure_at(piece, xi);
            error2 += w * (p - exact) * (p - exact);
            norm2 += w * exact * exact;
        });
    return norm2 > 0.0 ? std::sqrt(error2 / norm2) : std::numeric_limits<double>::infinity();
}

std::optional<double> slow_convergence(const std::vector<double>& d)
{
    const std::size_t n = d.size();
    if (n < slow_levels + 1)
        return std::nullopt;
    double rate = 0.0;  // the largest of the last ratios, each below slow_ratio
    for (std::size_t k = n - slow_levels; k < n; ++k) {
        if (!(d[k] > 0.0 && d[k - 1] > 0.0))
            return std::nullopt;
        const double ratio = d[k - 1] / d[k];
        if (!(ratio > 1.0 && ratio < slow_ratio))
            return std::nullopt;
        rate = std::max(rate, ratio);
    }
    return rate;
}

}  // namespace iga::analysis
