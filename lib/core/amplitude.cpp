#include "core/amplitude.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <cmath>

namespace iga {

Amplitude::Amplitude() : points_{{0.0, 0.0}, {1.0, 1.0}} {}

Amplitude::Amplitude(std::vector<AmplitudePoint> points) : points_(std::move(points))
{
    const char* problem = amplitude_problem(points_);
    IGA_CHECK(*problem == '\0', std::string("Amplitude: ") + problem);
}

double Amplitude::operator()(double t) const
{
    if (!(t > points_.front().time))
        return points_.front().value;
    if (t >= points_.back().time)
        return points_.back().value;
    // The first point after t; t lies in [lo.time, hi.time).
    const auto hi = std::upper_bound(points_.begin(), points_.end(), t,
                                     [](double time, const AmplitudePoint& p) { return time < p.time; });
    const AmplitudePoint& lo = *(hi - 1);
    // Written so that the ramp gives a(t) = t exactly: (1 - 0) * ((t - 0) / (1 - 0)).
    return lo.value + (hi->value - lo.value) * ((t - lo.time) / (hi->time - lo.time));
}

const char* amplitude_problem(const std::vector<AmplitudePoint>& points)
{
    if (points.size() < 2)
        return "needs at least 2 points [time, value]";
    for (const AmplitudePoint& p : points)
        if (!std::isfinite(p.time) || !std::isfinite(p.value))
            return "times and values must be finite";
    if (points.front().time != 0.0)
        return "the first time must be 0 (the start of the load path)";
    for (std::size_t k = 1; k < points.size(); ++k)
        if (!(points[k].time > points[k - 1].time))
            return "times must increase strictly";
    return "";
}

LoadPath load_path(const std::vector<Amplitude>& amplitudes)
{
    LoadPath path;
    if (amplitudes.empty())
        return path;
    std::vector<double> times;
    for (const Amplitude& a : amplitudes)
        for (const AmplitudePoint& p : a.points())
            if (p.time > 0.0)
                times.push_back(p.time);
    std::sort(times.begin(), times.end());
    path.end = times.back();
    path.breakpoints.clear();
    const double merge = breakpoint_merge * path.end;
    for (double t : times)
        if (path.breakpoints.empty() || t - path.breakpoints.back() > merge)
            path.breakpoints.push_back(t);
        else
            path.breakpoints.back() = t;  // the later of two merged times: T itself stays the end
    return path;
}

}  // namespace iga
