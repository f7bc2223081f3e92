#include "io/amplitude_reader.hpp"

#include <fmt/format.h>

namespace iga::io {

std::optional<Amplitude> read_amplitude(const Cursor& c)
{
    if (!c.is_list() || c.size() < 2) {
        c.fail("expected a list of at least 2 points [time, value], e.g. [[0, 0], [1, 1]]");
        return std::nullopt;
    }
    std::vector<AmplitudePoint> points;
    bool ok = true;
    for (const Cursor& item : c.items()) {
        const auto pair = item.to_numbers(2);  // finite numbers, or an issue recorded at the number
        if (!pair) {
            ok = false;
            continue;
        }
        const AmplitudePoint p{(*pair)[0], (*pair)[1]};
        if (points.empty() && p.time != 0.0) {
            item.item(0).fail("the first time must be 0 (the load path starts at t = 0)");
            ok = false;
        } else if (!points.empty() && !(p.time > points.back().time)) {
            item.item(0).fail(fmt::format("times must increase strictly (the point before is at t = {})",
                                                format_number(points.back().time)));
            ok = false;
        }
        points.push_back(p);
    }
    if (!ok)
        return std::nullopt;
    return Amplitude(std::move(points));
}

}  // namespace iga::io
