#include "io/study_csv.hpp"

#include "core/error.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace iga::io {

namespace {

std::string field(const std::optional<double>& x)
{
    return x ? fmt::format("{:.10g}", *x) : std::string();
}

}  // namespace

std::string study_csv(const std::vector<StudyRow>& rows, bool with_reference)
{
    std::string out = "level,dofs,wall_s,quantity,value,extrapolated,observed_order,estimated_rel_error";
    out += with_reference ? ",reference_value,true_rel_error" : "";
    out += ",extrapolated_rel_band,asymptotic,estimate\n";
    for (const StudyRow& r : rows) {
        out += fmt::format("{},{},{:.4g},{},{:.10g},{},{},{}", r.level, r.dofs, r.wall_s, r.quantity, r.value,
                           field(r.extrapolated), field(r.observed_order), field(r.estimated_rel_error));
        if (with_reference)
            out += fmt::format(",{},{}", field(r.reference_value), field(r.true_rel_error));
        out += fmt::format(",{},{},{}\n", field(r.extrapolated_rel_band),
                           r.asymptotic ? (*r.asymptotic ? "1" : "0") : "", r.estimate);
    }
    return out;
}

void write_study_csv(const std::string& path, const std::vector<StudyRow>& rows, bool with_reference)
{
    const std::string temporary = path + ".tmp-" + std::to_string(::getpid());
    std::error_code ec;
    {
        std::ofstream out(temporary, std::ios::binary);
        out << study_csv(rows, with_reference);
        if (!out) {
            std::filesystem::remove(temporary, ec);  // nothing left behind
            throw Error("cannot write " + temporary);
        }
    }
    std::filesystem::rename(temporary, path, ec);
    if (ec) {
        const std::string why = ec.message();
        std::filesystem::remove(temporary, ec);
        throw Error("cannot rename " + temporary + " to " + path + ": " + why);
    }
}

}  // namespace iga::io
