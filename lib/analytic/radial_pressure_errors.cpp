#include "analytic/radial_pressure_errors.hpp"

#include "analytic/pressure_errors.hpp"
#include "core/error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace iga::analytic {

RadialCurve radial_curve(double a, const std::vector<double>& r, const std::vector<double>& p)
{
    IGA_CHECK(r.size() == p.size(), "radial_pressure_errors: r and p must have the same length");
    IGA_CHECK(!r.empty(), "radial_pressure_errors: no samples");
    IGA_CHECK(a > 0 && std::isfinite(a), "radial_pressure_errors: the Hertz contact radius must be finite and > 0");
    const double width = radial_bin_fraction * a;
    struct Sum {
        double r = 0, p = 0;
        int count = 0;
    };
    std::map<long long, Sum> bins;  // ordered by bin index: increasing r
    for (std::size_t i = 0; i < r.size(); ++i) {
        IGA_CHECK(std::isfinite(r[i]) && r[i] >= 0, "radial_pressure_errors: distances must be finite and >= 0");
        Sum& bin = bins[static_cast<long long>(std::floor(r[i] / width))];
        bin.r += r[i];
        bin.p += p[i];
        ++bin.count;
    }
    RadialCurve curve;
    for (const auto& [index, bin] : bins) {
        curve.r.push_back(bin.r / bin.count);
        curve.p.push_back(bin.p / bin.count);
    }
    return curve;
}

RadialPressureErrors radial_pressure_errors(const HertzPointContact& hertz, const std::vector<double>& r,
                                            const std::vector<double>& p)
{
    IGA_CHECK(r.size() == p.size(), "radial_pressure_errors: r and p must have the same length");
    IGA_CHECK(!r.empty(), "radial_pressure_errors: no samples");
    const auto finite = [](double v) { return std::isfinite(v); };
    if (!std::all_of(r.begin(), r.end(), finite) || !std::all_of(p.begin(), p.end(), finite)) {
        constexpr double nan = std::numeric_limits<double>::quiet_NaN();
        return {.peak = nan, .radius = nan, .l2 = nan};
    }
    const RadialCurve curve = radial_curve(hertz.a, r, p);
    // The radial curve read as the symmetric section p_h(|x|): the 2D measures with mirror = true.
    const PressureErrors e = elliptic_pressure_errors(hertz.a, hertz.p0, curve.r, curve.p, true);
    return {.peak = e.peak, .radius = e.half_width, .l2 = e.l2};
}

std::vector<double> in_plane_distances(const RowMatrix& points, const VecN& center, const VecN& normal)
{
    IGA_CHECK(points.cols() == center.size() && center.size() == normal.size(),
              "in_plane_distances: points, center and normal must have the same dimension");
    const double length = normal.norm();
    IGA_CHECK(length > 0 && std::isfinite(length), "in_plane_distances: the normal must have finite length > 0");
    const VecN n = normal / length;
    std::vector<double> out(static_cast<std::size_t>(points.rows()));
    for (Index i = 0; i < points.rows(); ++i) {
        const VecN d = points.row(i).transpose() - center;
        out[static_cast<std::size_t>(i)] = (d - d.dot(n) * n).norm();
    }
    return out;
}

}  // namespace iga::analytic
