#include "io/transform_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

namespace iga::io {
namespace {

/// An optional point of the deck's dimension: the origin when `key` is absent.
std::optional<std::vector<double>> point_or_origin(const Cursor& map, std::string_view key, int dim)
{
    if (!map.has(key))
        return std::vector<double>(static_cast<std::size_t>(dim), 0.0);
    return map.read<std::vector<double>>(key, static_cast<std::size_t>(dim));
}

/// A required direction of `n` numbers that is not the zero vector.
std::optional<std::vector<double>> direction(const Cursor& map, std::string_view key, std::size_t n)
{
    const auto v = map.read_required<std::vector<double>>(key, n);
    if (!v)
        return std::nullopt;
    if (std::none_of(v->begin(), v->end(), [](double x) { return x != 0.0; })) {
        map.child(key).fail("must have non-zero length");
        return std::nullopt;
    }
    return v;
}

std::optional<Rotate> read_rotate(const Cursor& c, int dim)
{
    if (!c.check_keys())
        return std::nullopt;
    Rotate r;
    bool ok = true;
    if (dim == 3) {
        const auto axis = direction(c, "axis", 3);
        ok = axis.has_value();
        r.axis = axis.value_or(std::vector<double>{});
    } else if (c.has("axis")) {
        // In the x-y plane the only axis is z; [0, 0, a > 0] is accepted as a
        // restatement of it, and dropped (the resolved deck writes no axis).
        const auto v = c.read<std::vector<double>>("axis", 3);
        if (v && !((*v)[0] == 0.0 && (*v)[1] == 0.0 && (*v)[2] > 0.0)) {
            c.child("axis").fail("a 2D rotation turns about the z axis, counter-clockwise: leave 'axis' out or write [0, 0, 1] "
                      "(for a clockwise turn give a negative angle_deg)");
            ok = false;
        }
        ok = ok && v.has_value();
    }
    const auto angle = c.read<double>("angle_deg");
    r.angle_deg = angle.value_or(0.0);
    const auto about = point_or_origin(c, "about", dim);
    r.about = about.value_or(std::vector<double>{});
    return ok && angle && about ? std::optional(r) : std::nullopt;
}

std::optional<Mirror> read_mirror(const Cursor& c, int dim)
{
    if (!c.check_keys())
        return std::nullopt;
    const auto normal = direction(c, "normal", static_cast<std::size_t>(dim));
    const auto point = point_or_origin(c, "point", dim);
    if (!normal || !point)
        return std::nullopt;
    return Mirror{*normal, *point};
}

std::optional<TransformStep> read_step(const Cursor& item, int dim)
{
    const std::vector<std::string> kinds(transform_step_keys.begin(), transform_step_keys.end());
    const std::string example = dim == 3 ? "{rotate: {axis: [0, 0, 1], angle_deg: 90}}" : "{rotate: {angle_deg: 90}}";
    if (!item.is_map()) {
        item.fail("expected a map with one of " + join_names(kinds) + ", e.g. " + example);
        return std::nullopt;
    }
    const std::vector<std::string> keys = item.keys();
    if (keys.size() != 1) {
        if (keys.empty())
            item.fail_here("needs one of " + join_names(kinds));
        else
            item.fail_here("takes exactly one of " + join_names(kinds) + " (got " + join_names(keys) +
                           "): write each step as its own list item, in the order they apply");
        return std::nullopt;
    }
    const std::string& key = keys.front();
    const auto kind = std::find(kinds.begin(), kinds.end(), key);
    if (kind == kinds.end()) {
        item.check_keys();  // the key, with "did you mean"
        return std::nullopt;
    }
    const Cursor c = item.child(key);
    switch (kind - kinds.begin()) {
    case 0: {
        const auto offset = item.read<std::vector<double>>(key, static_cast<std::size_t>(dim));
        return offset ? std::optional<TransformStep>(Translate{*offset}) : std::nullopt;
    }
    case 1: {
        const auto r = read_rotate(c, dim);
        return r ? std::optional<TransformStep>(*r) : std::nullopt;
    }
    case 2: {
        const auto m = read_mirror(c, dim);
        return m ? std::optional<TransformStep>(*m) : std::nullopt;
    }
    default: {
        const auto s = item.read<double>(key);
        return s ? std::optional<TransformStep>(Scale{*s}) : std::nullopt;
    }
    }
}

}  // namespace

std::vector<TransformStep> read_transform(const Cursor& list, int dim)
{
    std::vector<TransformStep> steps;
    if (!list.is_list()) {
        list.fail(dim == 3 ? "expected a list of steps, e.g. [{translate: [1, 0, 0]}, {rotate: {axis: [0, 0, 1], "
                             "angle_deg: 90}}]"
                           : "expected a list of steps, e.g. [{translate: [1, 0]}, {rotate: {angle_deg: 90}}]");
        return steps;
    }
    for (const Cursor& item : list.items())
        if (auto step = read_step(item, dim))
            steps.push_back(std::move(*step));
    return steps;
}

}  // namespace iga::io
