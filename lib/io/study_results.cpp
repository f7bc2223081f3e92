#include "io/study_results.hpp"

#include "core/error.hpp"
#include "io/h5_file.hpp"

#include <algorithm>
#include <limits>

namespace iga::io {

namespace {

std::string string_attribute(hid_t object, const std::string& name)
{
    const h5::Array a = h5::read_attribute(object, name);
    return a.type == h5::Array::Type::string && !a.strings.empty() ? a.strings[0] : "";
}

double number(const h5::Array& a)
{
    if (a.type == h5::Array::Type::real && !a.reals.empty())
        return a.reals[0];
    if (a.type == h5::Array::Type::integer && !a.integers.empty())
        return static_cast<double>(a.integers[0]);
    return std::numeric_limits<double>::quiet_NaN();
}

bool has_attribute(hid_t object, const std::string& name)
{
    const auto names = h5::attribute_names(object);
    return std::find(names.begin(), names.end(), name) != names.end();
}

/// The contact zone against Hertz, per carrying side of `pair` (results.md,
/// /reference/<pair>): its half-width (2D) or radius (3D), a (1 + the run's signed
/// relative error), with a as the reference value, and the relative L2 error of the
/// post-processed pressure (its reference is 0: no relative error of it is formed).
/// The first carrying side's errors are stored unprefixed, a second side's with its
/// name in front; the first is the side whose normal force the reference repeats.
void add_hertz_zone(hid_t reference, hid_t pair_group, const std::string& pair, LevelResults& out)
{
    if (!has_attribute(reference, "a"))
        return;
    const double a = number(h5::read_attribute(reference, "a"));
    const std::string size = has_attribute(reference, "contact_radius") ? "contact_radius" : "half_width";
    const double first_force =
        has_attribute(reference, "normal_force") ? number(h5::read_attribute(reference, "normal_force")) : 0.0;
    for (const std::string& side : h5::link_names(pair_group)) {
        const h5::Handle side_group = h5::open_object(pair_group, side);
        if (h5::object_kind(side_group.id()) != h5::ObjectKind::group)
            continue;
        std::string prefix = side + ".";
        if (!has_attribute(reference, prefix + size)) {
            const bool first = has_attribute(side_group.id(), "normal_force") &&
                               number(h5::read_attribute(side_group.id(), "normal_force")) == first_force;
            if (!first || !has_attribute(reference, size))
                continue;
            prefix.clear();
        }
        const std::string zone = size + ":" + pair + ":" + side;
        out.quantities.emplace_back(zone, a * (1 + number(h5::read_attribute(reference, prefix + size))));
        out.reference_values[zone] = a;
        if (has_attribute(reference, prefix + "l2"))
            out.quantities.emplace_back("pressure_l2_error:" + pair + ":" + side,
                                        number(h5::read_attribute(reference, prefix + "l2")));
    }
}

/// Lowest degree of the patch group `g` (degrees dataset), or of its patches/<p>/ (multi-patch bodies).
int lowest_degree(hid_t body)
{
    int lowest = std::numeric_limits<int>::max();
    auto take = [&](hid_t group) {
        const h5::Array d = h5::read_dataset(group, "degrees");
        for (long long p : d.integers)
            lowest = std::min(lowest, static_cast<int>(p));
    };
    if (h5::exists(body, "degrees"))
        take(body);
    if (h5::exists(body, "patches")) {
        const h5::Handle patches = h5::open_object(body, "patches");
        for (const std::string& p : h5::link_names(patches.id())) {
            const h5::Handle patch = h5::open_object(patches.id(), p);
            if (h5::exists(patch.id(), "degrees"))
                take(patch.id());
        }
    }
    return lowest;
}

}  // namespace

LevelResults read_level_results(const std::string& path)
{
    h5::ErrorSilencer silence;
    const h5::Handle file = h5::open_file(path);
    LevelResults out;
    out.status = string_attribute(file.id(), "status");
    out.message = string_attribute(file.id(), "message");
    if (h5::exists(file.id(), "counters")) {
        const h5::Handle counters = h5::open_object(file.id(), "counters");
        if (has_attribute(counters.id(), "dofs"))
            out.dofs = static_cast<long long>(number(h5::read_attribute(counters.id(), "dofs")));
    }
    if (h5::exists(file.id(), "bodies")) {
        const h5::Handle bodies = h5::open_object(file.id(), "bodies");
        int lowest = std::numeric_limits<int>::max();
        for (const std::string& b : h5::link_names(bodies.id())) {
            const h5::Handle body = h5::open_object(bodies.id(), b);
            lowest = std::min(lowest, lowest_degree(body.id()));
        }
        out.min_degree = lowest == std::numeric_limits<int>::max() ? 0 : lowest;
    }
    if (!h5::exists(file.id(), "results"))
        return out;
    const h5::Handle results = h5::open_object(file.id(), "results");
    std::vector<std::pair<std::string, double>> penetrations;
    if (h5::exists(results.id(), "contact")) {
        const h5::Handle contact = h5::open_object(results.id(), "contact");
        for (const std::string& pair : h5::link_names(contact.id())) {
            const h5::Handle pair_group = h5::open_object(contact.id(), pair);
            for (const std::string& side : h5::link_names(pair_group.id())) {
                const h5::Handle side_group = h5::open_object(pair_group.id(), side);
                if (h5::object_kind(side_group.id()) != h5::ObjectKind::group)
                    continue;
                if (has_attribute(side_group.id(), "normal_force"))
                    out.quantities.emplace_back("normal_force:" + pair + ":" + side,
                                                number(h5::read_attribute(side_group.id(), "normal_force")));
                if (h5::exists(side_group.id(), "postprocessed/pressure")) {
                    const h5::Array p = h5::read_dataset(side_group.id(), "postprocessed/pressure");
                    if (!p.reals.empty())
                        out.quantities.emplace_back("peak_pressure:" + pair + ":" + side,
                                                    *std::max_element(p.reals.begin(), p.reals.end()));
                }
                if (has_attribute(side_group.id(), "contact_area"))
                    out.quantities.emplace_back("contact_area:" + pair + ":" + side,
                                                number(h5::read_attribute(side_group.id(), "contact_area")));
            }
            if (has_attribute(pair_group.id(), "max_penetration"))
                penetrations.emplace_back("max_penetration:" + pair,
                                          number(h5::read_attribute(pair_group.id(), "max_penetration")));
            if (h5::exists(file.id(), "reference/" + pair)) {
                const h5::Handle reference = h5::open_object(file.id(), "reference/" + pair);
                if (has_attribute(reference.id(), "p0"))
                    for (const auto& [name, value] : out.quantities)
                        if (name.rfind("peak_pressure:" + pair + ":", 0) == 0)
                            out.reference_values[name] = number(h5::read_attribute(reference.id(), "p0"));
                add_hertz_zone(reference.id(), pair_group.id(), pair, out);
            }
        }
    }
    out.quantities.insert(out.quantities.end(), penetrations.begin(), penetrations.end());
    if (h5::exists(results.id(), "reactions")) {
        const h5::Handle reactions = h5::open_object(results.id(), "reactions");
        static constexpr const char* axis[] = {"x", "y", "z"};
        for (const std::string& name : h5::link_names(reactions.id())) {
            if (h5::object_kind(h5::open_object(reactions.id(), name).id()) != h5::ObjectKind::dataset)
                continue;  // total/ and items/: the study follows the sides (results.md)
            const h5::Array r = h5::read_dataset(reactions.id(), name);
            for (std::size_t k = 0; k < r.reals.size() && k < 3; ++k)
                out.quantities.emplace_back("reaction:" + name + ":" + axis[k], r.reals[k]);
        }
    }
    return out;
}

}  // namespace iga::io
