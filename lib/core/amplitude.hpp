#pragma once
// Amplitude: the piecewise-linear function a(t) of the pseudo-time t of a load
// path (docs/deck.md, "Load paths") that scales one deck item's full value: a
// load, a prescribed displacement or an obstacle motion acts as a(t) * value.
//
// Points (t_0, a_0), ..., (t_n, a_n), n >= 1, all finite, with t_0 = 0 and times
// strictly increasing. Between points a is linear; after t_n it holds a_n (and
// before t_0 it would hold a_0; the path starts at t = 0). The default is the
// ramp (0, 0), (1, 1): a(t) = t on [0, 1] and 1 after, so that in a deck without
// amplitudes t is the load factor of every item.
//
// LoadPath: where the pseudo-time ends, T = the largest end time of the items'
// amplitudes, and the breakpoints (every point time in (0, T], T included) that
// the load stepping lands on exactly, so no increment straddles a kink.

#include <vector>

namespace iga {

struct AmplitudePoint {
    double time = 0.0;
    double value = 0.0;

    bool operator==(const AmplitudePoint&) const = default;
};

class Amplitude {
public:
    /// The default ramp (0, 0), (1, 1).
    Amplitude();
    /// Throws iga::Error unless the points are as the header says (the deck
    /// reader reports bad points, located, before any is built).
    explicit Amplitude(std::vector<AmplitudePoint> points);

    /// a(t).
    double operator()(double t) const;
    /// t_n: the time after which a is constant.
    double end_time() const { return points_.back().time; }
    const std::vector<AmplitudePoint>& points() const { return points_; }

    bool operator==(const Amplitude&) const = default;

private:
    std::vector<AmplitudePoint> points_;
};

/// The reason the points cannot make an amplitude ("" if they can): the rules of
/// the header, worded for the deck ("needs at least 2 points", ...).
const char* amplitude_problem(const std::vector<AmplitudePoint>& points);

struct LoadPath {
    double end = 1.0;                       ///< T
    std::vector<double> breakpoints{1.0};   ///< increasing, in (0, T], ending with T
};

/// Breakpoints closer than this fraction of T are one (times written as 1 and
/// 1.0000000000001 in two items must not leave a sliver increment between them).
inline constexpr double breakpoint_merge = 1e-12;

/// The path of a deck's scaled items, given their amplitudes (an item without
/// one passes the default ramp); no items: [0, 1].
LoadPath load_path(const std::vector<Amplitude>& amplitudes);

}  // namespace iga
