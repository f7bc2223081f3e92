#include "summary_json.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

namespace iga::app {

namespace {

std::string json_escape(const std::string& s)
{
    std::string out;
    for (char c : s) {
        switch (c) {
        case '"': out += "\\\""; break;
        case '\\': out += "\\\\"; break;
        case '\n': out += "\\n"; break;
        case '\t': out += "\\t"; break;
        default:
            if (static_cast<unsigned char>(c) < 0x20)
                out += fmt::format("\\u{:04x}", static_cast<int>(c));
            else
                out += c;
        }
    }
    return out;
}

std::string json_number(double x)
{
    return std::isfinite(x) ? fmt::format("{:.9g}", x) : "null";
}

std::string json_string_list(const std::vector<std::string>& items)
{
    std::string out = "[";
    for (std::size_t k = 0; k < items.size(); ++k)
        out += fmt::format("{}\"{}\"", k == 0 ? "" : ", ", json_escape(items[k]));
    return out + "]";
}

}  // namespace

bool summary_json_requested(int argc, char** argv)
{
    for (int k = 1; k < argc; ++k) {
        if (std::strcmp(argv[k], "--summary=json") == 0)
            return true;
        if (std::strcmp(argv[k], "--summary") == 0 && k + 1 < argc && std::strcmp(argv[k + 1], "json") == 0)
            return true;
    }
    return false;
}

std::string summary_json(const analysis::RunOutcome& r, int exit_code)
{
    std::string out = fmt::format(
        "{{\"status\": \"{}\", \"message\": \"{}\", \"exit_code\": {}, \"results\": \"{}\", \"increments\": {}, "
        "\"newton_iterations\": {}, \"cutbacks\": {}, \"wall_s\": {}",
        json_escape(r.status), json_escape(r.message), exit_code, json_escape(r.results_file), r.increments,
        r.newton_iterations, r.cutbacks, json_number(r.wall_s));
    for (const auto& [key, value] : r.numbers)
        out += fmt::format(", \"{}\": {}", json_escape(key), json_number(value));
    out += ", \"errors\": {";
    bool first = true;
    for (const auto& [key, value] : r.errors) {
        out += fmt::format("{}\"{}\": {}", first ? "" : ", ", json_escape(key), json_number(value));
        first = false;
    }
    out += "}, \"warnings\": " + json_string_list(r.warnings);
    if (r.accuracy) {
        const analysis::AccuracySummary& a = *r.accuracy;
        out += fmt::format(", \"accuracy\": {{\"pair\": \"{}\", \"quantity\": \"{}\", \"target\": {}, \"reached\": {}, "
                           "\"estimated_error\": {}, \"wall_s\": {}, \"levels\": [",
                           json_escape(a.pair), json_escape(a.quantity), json_number(a.target),
                           a.reached ? "true" : "false", json_number(a.estimated_error), json_number(a.wall_s));
        for (std::size_t k = 0; k < a.levels.size(); ++k) {
            const analysis::AccuracyLevel& l = a.levels[k];
            out += fmt::format("{}{{\"level\": {}, \"dofs\": {}, \"wall_s\": {}, \"value\": {}, \"difference\": {}, "
                               "\"estimated_error\": {}, \"error_bound\": {}, \"reference_error\": {}, "
                               "\"refined\": \"{}\"}}",
                               k == 0 ? "" : ", ", l.level, json_number(l.dofs), json_number(l.wall_s),
                               json_number(l.value), json_number(l.difference), json_number(l.estimated_error),
                               json_number(l.error_bound), json_number(l.reference_error), json_escape(l.refined));
        }
        out += "]}";
    }
    return out + "}";
}

std::string error_summary_json(const std::string& status, const std::string& message, int exit_code)
{
    return fmt::format("{{\"status\": \"{}\", \"message\": \"{}\", \"exit_code\": {}, \"warnings\": []}}",
                       json_escape(status), json_escape(message), exit_code);
}

}  // namespace iga::app
