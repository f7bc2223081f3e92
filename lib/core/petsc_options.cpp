#include "core/petsc_options.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>

namespace iga {

namespace {

// The prefixes of the linear solver's options: the KSP, its PC, the matrix and its
// factorization packages (MUMPS), vectors, and the inner solvers of multigrid
// levels, block preconditioners and the like, which PETSc names by these prefixes.
constexpr std::array solver_families = {"ksp_", "pc_",       "mat_",      "mg_",           "sub_",
                                        "redundant_", "fieldsplit_", "telescope_", "redistribute_", "vec_"};

// What the following bounds keep out: a Krylov method allowed to run a million
// iterations has stopped being a solve; GMRES keeps `restart` vectors of the
// system's size (1000 at a million dofs: 8 GB), ten times our default of 100.
constexpr long long max_krylov_iterations = 1000000;
constexpr long long max_gmres_restart = 1000;

const char* const solver_only =
    "PETSc options here may tune the linear solver only (-ksp_*, -pc_*, -mat_* and the inner solvers' -mg_*, "
    "-sub_*, ...; docs/parallel.md)";

std::string lower(std::string_view text)
{
    std::string out(text);
    std::transform(out.begin(), out.end(), out.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return out;
}

bool starts_with(std::string_view text, std::string_view prefix) { return text.substr(0, prefix.size()) == prefix; }

bool ends_with(std::string_view text, std::string_view suffix)
{
    return text.size() >= suffix.size() && text.substr(text.size() - suffix.size()) == suffix;
}

/// An option name as PETSc's PetscOptionsValidKey sees one: one or two dashes, a
/// letter, and not a number ("-inf", "-1e5" are values).
bool is_key(const std::string& word)
{
    if (word.size() < 2 || word[0] != '-')
        return false;
    const std::size_t first = word[1] == '-' ? 2 : 1;
    if (first >= word.size() || !std::isalpha(static_cast<unsigned char>(word[first])))
        return false;
    const char* begin = word.c_str() + (first - 1);  // strtod reads the sign
    char* end = nullptr;
    (void)std::strtod(begin, &end);
    return end == begin || *end == '_' || std::isalnum(static_cast<unsigned char>(*end));
}

/// The reason a process-wide option (outside the solver's families) is refused.
std::string process_option_reason(const std::string& name)
{
    auto is = [&](std::string_view n) { return name == n; };
    auto from = [&](std::string_view p) { return starts_with(name, p); };
    std::string what;
    if (is("help") || is("h"))
        what = "makes PETSc print its help on standard output (and, with `intro`, end the run without results)";
    else if (is("version"))
        what = "makes PETSc print its version";
    else if (from("log"))
        what = "makes PETSc write a performance log (to standard output or to a file)";
    else if (is("history"))
        what = "makes PETSc write a history file";
    else if (from("info"))
        what = "makes PETSc print its internal messages, or write them to a file";
    else if (from("options_"))
        what = "reads PETSc options from a file, or prints the options database";
    else if (is("prefix_push") || is("prefix_pop"))
        what = "renames the options that follow it";
    else if (is("citations"))
        what = "makes PETSc write a file of citations";
    else if (from("dll_") || from("python"))
        what = "loads code into the process";
    else if (from("viewer") || from("draw") || from("saws") || from("x_virtual") || from("nox") || is("display"))
        what = "configures PETSc's viewers and windows";
    else if (is("skip_petscrc") || is("no_signal_handler"))
        what = "is set by igacontact itself";
    else if (from("malloc") || from("memory") || from("objects") || from("fp_trap") || from("check") ||
             from("on_error") || from("start_in_debugger") || from("stop_for_debugger") || from("debug") ||
             from("sleep"))
        what = "is a debugging option of PETSc's, acting on the whole process";
    else
        return std::string("is not an option of the linear solver: ") + solver_only;
    return what + "; " + solver_only;
}

/// The parts of a name ("ksp_monitor_true_residual" -> ksp, monitor, true, residual).
std::vector<std::string> parts_of(const std::string& name)
{
    std::vector<std::string> parts;
    std::size_t start = 0;
    while (start <= name.size()) {
        const std::size_t end = std::min(name.find('_', start), name.size());
        if (end > start)
            parts.push_back(name.substr(start, end - start));
        start = end + 1;
    }
    return parts;
}

/// The reason a name in the solver's families is refused, or "".
std::string solver_option_reason(const std::string& name)
{
    for (const std::string& part : parts_of(name)) {
        if (part.find("draw") != std::string::npos || part.find("plot") != std::string::npos || part == "lg")
            return "draws in a window";
        if (part == "dump" || part == "save" || part == "load" || part.find("file") != std::string::npos ||
            part == "dir" || part == "tmpdir" || part == "path" || part == "output")
            return "makes PETSc write or read a file";
        if (part.find("print") != std::string::npos || part.find("verbose") != std::string::npos ||
            part == "logging" || part == "log")
            return "makes a library print its own output on standard output";
        if (part.find("viewer") != std::string::npos || part == "socket" || part == "saws")
            return "configures PETSc's viewers";
        if (part.find("python") != std::string::npos)
            return "loads Python code";
    }
    // MUMPS: ICNTL(1)-(3) are its output streams (a Fortran unit other than 6 is a
    // file fort.N), ICNTL(4) its print level (on standard output); ICNTL(22) is its
    // out-of-core mode, which writes scratch files.
    for (int k = 1; k <= 4; ++k)
        if (ends_with(name, "mat_mumps_icntl_" + std::to_string(k)))
            return "sets MUMPS's output streams or print level (its own output, to standard output or files fort.N)";
    if (ends_with(name, "mat_mumps_icntl_22"))
        return "sets MUMPS's out-of-core mode, which writes scratch files";
    return {};
}

/// Whether a name has a part that makes it a viewer option (a view, a monitor, a
/// converged reason), which takes a viewer as its value.
bool is_viewer_option(const std::string& name)
{
    for (const std::string& part : parts_of(name))
        if (starts_with(part, "view") || starts_with(part, "monitor") || part == "reason")
            return true;
    return false;
}

/// What PETSc's viewer of this type does, if it is one other than ASCII ("" if not a viewer type).
std::string viewer_type_effect(const std::string& type)
{
    if (type == "binary" || type == "hdf5" || type == "vtk" || type == "adios" || type == "exodusii" ||
        type == "cgns" || type == "matlab" || type == "vu")
        return "PETSc's " + type + " viewer writes a file";
    if (type == "draw" || type == "glvis")
        return "PETSc's " + type + " viewer opens a window";
    if (type == "socket" || type == "mathematica" || type == "saws")
        return "PETSc's " + type + " viewer connects to another program";
    if (type == "string" || type == "python" || type == "pyvista")
        return "PETSc's " + type + " viewer is not one a run can print with";
    return {};
}

const char* const stdout_only =
    "views and monitors may print to standard output only (-ksp_monitor, -ksp_view ::ascii_info_detail), which "
    "igacontact sends to standard error";

/// The reason a value written as a viewer ("TYPE:FILE:FORMAT:MODE") is refused, or "".
std::string viewer_value_reason(const std::string& value)
{
    std::vector<std::string> fields;
    std::size_t start = 0;
    while (true) {
        const std::size_t colon = value.find(':', start);
        fields.push_back(value.substr(start, colon == std::string::npos ? std::string::npos : colon - start));
        if (colon == std::string::npos)
            break;
        start = colon + 1;
    }
    const std::string type = lower(fields[0]);
    if (const std::string effect = viewer_type_effect(type); !effect.empty())
        return effect + "; " + stdout_only;
    if (!type.empty() && type != "ascii")
        return "is not a viewer that prints to standard output; " + std::string(stdout_only);
    if (fields.size() > 1 && !fields[1].empty() && fields[1] != "stdout" && fields[1] != "stderr")
        return "PETSc would write the file " + fields[1] + "; " + stdout_only;
    if (fields.size() > 3)
        return "a file mode (`:" + fields[3] + "`) is for a file; " + std::string(stdout_only);
    return {};
}

std::optional<double> parse_real(const std::string& text)
{
    if (text.empty())
        return std::nullopt;
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size())
        return std::nullopt;
    return value;
}

std::optional<long long> parse_integer(const std::string& text)
{
    long long value = 0;
    const char* begin = text.c_str() + (starts_with(text, "+") ? 1 : 0);
    const char* end = text.c_str() + text.size();
    const auto [ptr, error] = std::from_chars(begin, end, value);
    if (begin == end || error != std::errc() || ptr != end)
        return std::nullopt;
    return value;
}

/// The reason a number of the options PETSc takes without a check is refused, or "".
std::string number_reason(const std::string& name, const PetscOption& option)
{
    auto real_in = [&](double low, bool low_open, double high, bool high_open,
                       const std::string& range) -> std::string {
        const std::optional<double> v = option.has_value ? parse_real(option.value) : std::nullopt;
        if (!v || !std::isfinite(*v) || (low_open ? !(*v > low) : !(*v >= low)) ||
            (high_open ? !(*v < high) : !(*v <= high)))
            return "must be a finite number " + range;
        return {};
    };
    auto integer_in = [&](long long low, long long high, const std::string& why) -> std::string {
        const std::optional<long long> v = option.has_value ? parse_integer(option.value) : std::nullopt;
        if (!v || *v < low || *v > high)
            return "must be an integer in [" + std::to_string(low) + ", " + std::to_string(high) + "]" + why;
        return {};
    };
    auto integer = [&](const std::string& why) -> std::string {
        const std::optional<long long> v = option.has_value ? parse_integer(option.value) : std::nullopt;
        if (!v || *v < std::numeric_limits<int>::min() || *v > std::numeric_limits<int>::max())
            return "must be an integer" + why;
        return {};
    };
    constexpr double inf = HUGE_VAL;
    if (ends_with(name, "ksp_rtol"))
        return real_in(0.0, false, 1.0, true, "in [0, 1) (the relative decrease of the residual)");
    if (ends_with(name, "ksp_atol"))
        return real_in(0.0, false, inf, false, ">= 0 (the absolute size of the residual)");
    if (ends_with(name, "ksp_divtol"))
        return real_in(1.0, false, inf, false, ">= 1 (the growth of the residual taken as divergence)");
    if (ends_with(name, "ksp_max_it"))
        return integer_in(1, max_krylov_iterations, " (Krylov iterations per solve)");
    if (ends_with(name, "ksp_gmres_restart"))
        return integer_in(1, max_gmres_restart, " (GMRES keeps this many vectors of the system's size)");
    const std::size_t mumps = name.find("mat_mumps_");
    if (mumps != std::string::npos) {
        const std::string rest = name.substr(mumps + 10);
        if (starts_with(rest, "icntl_"))
            return integer(" (a MUMPS control integer, ICNTL)");
        if (starts_with(rest, "cntl_"))
            return real_in(-inf, true, inf, true, "(a MUMPS control real, CNTL)");
    }
    return {};
}

bool value_character(char c)
{
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == ',' || c == '+' || c == '-' ||
           c == ':';
}

/// The reason one option is refused, or "".
std::string option_reason(const PetscOption& option)
{
    const std::size_t dashes = starts_with(option.name, "--") ? 2 : 1;
    const std::string name = lower(std::string_view(option.name).substr(dashes));
    for (char c : name)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_')
            return "is not an option name (letters, digits and _ after the dash)";
    const bool in_family = std::any_of(solver_families.begin(), solver_families.end(),
                                       [&](const char* family) { return starts_with(name, family); });
    if (!in_family)
        return process_option_reason(name);
    if (std::string why = solver_option_reason(name); !why.empty())
        return why;
    if (option.has_value) {
        for (char c : option.value)
            if (!value_character(c))
                return std::string("holds '") + c +
                       "': a value may hold letters, digits and _ . , + - : only (no file path)";
        const std::string value = lower(option.value);
        if (value.find("python") != std::string::npos)
            return "loads Python code";
        if (is_viewer_option(name) || value.find(':') != std::string::npos || !viewer_type_effect(value).empty())
            if (std::string why = viewer_value_reason(option.value); !why.empty())
                return why;
    }
    return number_reason(name, option);
}

}  // namespace

std::string PetscOptionsCheck::message() const
{
    return ok() ? std::string() : refused + ": " + reason;
}

DeckIssue PetscOptionsError::environment_issue() const
{
    DeckIssue issue;
    issue.where.file = "environment";
    issue.path = variable_;
    const char* value = std::getenv(variable_.c_str());
    issue.value = value ? value : "";
    issue.reason = what();
    return issue;
}

std::vector<PetscOption> checked_environment_options(const Communicator& comm)
{
    const char* yaml = std::getenv("PETSC_OPTIONS_YAML");
    const std::string yaml_problem = comm.first_message(
        yaml && *yaml ? "igacontact takes PETSc options from solver.options and PETSC_OPTIONS only; unset it" : "");
    if (!yaml_problem.empty())
        throw PetscOptionsError(PetscOptionsSource::environment, yaml_problem, "PETSC_OPTIONS_YAML");
    const char* env = std::getenv("PETSC_OPTIONS");
    const PetscOptionsCheck check = check_petsc_options(env ? env : "", PetscOptionsSource::environment);
    if (const std::string problem = comm.first_message(check.message()); !problem.empty())
        throw PetscOptionsError(PetscOptionsSource::environment, problem);
    return check.options;
}

PetscOptionsCheck check_petsc_options(std::string_view text, PetscOptionsSource source)
{
    PetscOptionsCheck check;
    auto refuse = [&](std::string refused, std::string reason) {
        check.refused = std::move(refused);
        check.reason = std::move(reason);
        return check;
    };
    // The words, and the characters no option needs.
    std::vector<std::string> words;
    std::string word;
    for (char c : text) {
        const auto u = static_cast<unsigned char>(c);
        const bool blank = c == ' ' || (source == PetscOptionsSource::deck && (c == '\t' || c == '\n' || c == '\r'));
        if (blank) {
            if (!word.empty())
                words.push_back(std::move(word));
            word.clear();
            continue;
        }
        if (c == '"' || c == '\'')
            return refuse(word + c, "holds a quote, which PETSc would read as grouping words; no option needs one");
        if (u < 0x20 || u >= 0x7f)
            return refuse(word.empty() ? std::string("(a control or non-ASCII character)") : word,
                          source == PetscOptionsSource::environment
                              ? "holds a character other than a printable ASCII one or a space (PETSc splits "
                                "PETSC_OPTIONS at spaces only)"
                              : "holds a character other than a printable ASCII one or a blank");
        word += c;
    }
    if (!word.empty())
        words.push_back(std::move(word));

    for (std::size_t k = 0; k < words.size();) {
        if (!is_key(words[k]))
            return refuse(words[k], check.options.empty()
                                        ? "is not an option: options start with a dash (-ksp_type cg)"
                                        : "is not an option, nor the value of one (" + check.options.back().text() +
                                              " has its value already): options start with a dash");
        PetscOption option{words[k], {}, false};
        if (k + 1 < words.size() && !is_key(words[k + 1])) {
            option.value = words[k + 1];
            option.has_value = true;
            k += 2;
        } else {
            k += 1;
        }
        if (std::string why = option_reason(option); !why.empty())
            return refuse(option.text(), std::move(why));
        check.options.push_back(std::move(option));
    }
    return check;
}

}  // namespace iga
