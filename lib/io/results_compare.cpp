#include "io/results_compare.hpp"

#include "core/error.hpp"
#include "io/h5_file.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <limits>

namespace iga::io {

namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();
constexpr std::size_t max_quoted_chars = 60;  // keeps report lines readable when strings differ

h5::Handle open_results(const std::string& path, const char* role)
{
    const std::string what = std::string("cannot open ") + role + " results file " + path;
    std::error_code error;
    if (!std::filesystem::exists(path, error))
        throw Error(what + ": no such file");
    if (H5Fis_hdf5(path.c_str()) <= 0)
        throw Error(what + ": not an HDF5 file");
    try {
        return h5::open_file(path);
    } catch (const Error& e) {
        throw Error(what + ": " + e.what());
    }
}

// True if `path` is `prefix` or lies below it (next character '/' or '@').
bool within(const std::string& path, const std::string& prefix)
{
    if (prefix == "/")
        return true;
    if (path.compare(0, prefix.size(), prefix) != 0)
        return false;
    return path.size() == prefix.size() || path[prefix.size()] == '/' || path[prefix.size()] == '@';
}

std::string child_path(const std::string& parent, const std::string& name)
{
    return parent == "/" ? "/" + name : parent + "/" + name;
}

CompareEntry make_entry(std::string path, CompareEntry::Kind kind, std::string detail = {})
{
    CompareEntry entry;
    entry.path = std::move(path);
    entry.kind = kind;
    entry.detail = std::move(detail);
    return entry;
}

std::string attribute_path(const std::string& object, const std::string& name) { return object + "@" + name; }

std::string quote(const std::string& text)
{
    if (text.size() <= max_quoted_chars)
        return "'" + text + "'";
    return "'" + text.substr(0, max_quoted_chars) + "...'";
}

// Where two strings first differ, by line (the resolved deck is one long string).
std::string describe_string_difference(const std::string& a, const std::string& b)
{
    std::size_t line_start = 0;
    int line = 1;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()) && a[i] == b[i]; ++i) {
        if (a[i] == '\n') {
            line_start = i + 1;
            ++line;
        }
    }
    auto line_of = [&](const std::string& s) { return s.substr(line_start, s.find('\n', line_start) - line_start); };
    return fmt::format("first difference at line {}: {} vs {}", line, quote(line_of(a)), quote(line_of(b)));
}

class Comparer {
public:
    Comparer(hid_t reference, hid_t candidate, const CompareOptions& options)
        : reference_(reference), candidate_(candidate), options_(options), prefix_hit_(options.only.size(), false)
    {
        for (std::string prefix : options.only) {
            while (prefix.size() > 1 && prefix.back() == '/')
                prefix.pop_back();
            if (prefix.empty() || prefix.front() != '/')
                prefix.insert(prefix.begin(), '/');
            prefixes_.push_back(prefix);
        }
    }

    CompareReport run()
    {
        visit_group("/");
        for (std::size_t i = 0; i < prefixes_.size(); ++i)
            if (!prefix_hit_[i])
                add(make_entry(prefixes_[i], CompareEntry::Kind::missing,
                               "nothing under this path in the reference file "
                               "(a typo? volatile items need include_volatile)"));
        return std::move(report_);
    }

private:
    // Marks every `only` prefix that contains path; true if path is in scope.
    bool in_scope(const std::string& path)
    {
        if (prefixes_.empty())
            return true;
        bool hit = false;
        for (std::size_t i = 0; i < prefixes_.size(); ++i)
            if (within(path, prefixes_[i]))
                hit = prefix_hit_[i] = true;
        return hit;
    }

    // True if some `only` prefix lies strictly below the group `path` (so the walk must go through it).
    bool leads_to_scope(const std::string& path) const
    {
        for (const std::string& prefix : prefixes_)
            if (prefix != path && within(prefix, path))
                return true;
        return false;
    }

    /// Items that say how a run went, not what it found: timings, versions, counters and
    /// the solvers' statistics (Newton's residual history, iterations and cutbacks per
    /// increment, the linear solver and the ranks). A serial and a parallel run, or a
    /// direct and an iterative one, that reach the same state differ in these alone.
    bool is_volatile(const std::string& path, const std::string& name) const
    {
        if (options_.include_volatile)
            return false;
        // /deck holds the resolved deck text, whose output path legitimately differs
        // between a run and its stored reference; the results it produced are compared.
        for (const char* group : {"/timings", "/counters", "/convergence", "/parallel"})
            if (within(path, group))
                return true;
        for (const char* root : {"/@program_version", "/@linear_solver", "/@ranks"})
            if (path == root)
                return true;
        if (path == "/deck" || path == "/accuracy/wall_s")
            return true;
        const bool attribute = path.find('@') != std::string::npos;
        return attribute && (name == "wall_s" || name == "newton_iterations" || name == "residual_norm" ||
                             name == "cutbacks");
    }

    void add(CompareEntry entry)
    {
        switch (entry.kind) {
        case CompareEntry::Kind::missing:
            ++report_.n_missing;
            break;
        case CompareEntry::Kind::same:
            ++report_.n_compared;
            break;
        default:
            ++report_.n_compared;
            ++report_.n_different;
        }
        report_.entries.push_back(std::move(entry));
    }

    /// True if `group` of the reference is one of the groups the walk is inside: a link
    /// back to an ancestor (a hard link of a group into itself, a soft link to a parent)
    /// would make the walk endless. Compared by object (HDF5 address or token), not by path.
    bool is_ancestor(hid_t group) const
    {
        for (hid_t ancestor : ancestors_)
            if (h5::same_object(group, ancestor))
                return true;
        return false;
    }

    void visit_group(const std::string& path)
    {
        h5::Handle reference_group = h5::open_object(reference_, path);
        h5::Handle candidate_group = h5::open_object(candidate_, path);
        ancestors_.push_back(reference_group.id());
        struct Leave {
            std::vector<hid_t>& stack;
            ~Leave() { stack.pop_back(); }
        } leave{ancestors_};
        for (const std::string& name : h5::attribute_names(reference_group.id())) {
            const std::string apath = attribute_path(path, name);
            if (is_volatile(apath, name) || !in_scope(apath))
                continue;
            if (H5Aexists(candidate_group.id(), name.c_str()) <= 0) {
                add(make_entry(apath, CompareEntry::Kind::missing));
                continue;
            }
            add(compare_arrays(apath, h5::read_attribute(reference_group.id(), name),
                               h5::read_attribute(candidate_group.id(), name)));
        }
        for (const std::string& name : h5::link_names(reference_group.id())) {
            const std::string cpath = child_path(path, name);
            if (is_volatile(cpath, name))
                continue;
            const bool scoped = in_scope(cpath);
            if (!scoped && !leads_to_scope(cpath))
                continue;
            if (!h5::exists(reference_, cpath))  // dangling soft/external link in REF: nothing to compare
                continue;
            h5::Handle reference_child = h5::open_object(reference_, cpath);
            const h5::ObjectKind kind = h5::object_kind(reference_child.id());
            if (kind == h5::ObjectKind::other)
                continue;
            if (!h5::exists(candidate_, cpath)) {
                add(make_entry(cpath, CompareEntry::Kind::missing));
                continue;
            }
            const h5::ObjectKind candidate_kind = h5::object_kind(h5::open_object(candidate_, cpath).id());
            if (candidate_kind != kind) {
                add(make_entry(cpath, CompareEntry::Kind::type_mismatch,
                               kind == h5::ObjectKind::group ? "group in reference, not in new file"
                                                             : "dataset in reference, not in new file"));
                continue;
            }
            if (kind == h5::ObjectKind::group) {
                if (is_ancestor(reference_child.id()))
                    continue;  // a cycle: the group's content is compared where the walk entered it
                visit_group(cpath);
            }
            else if (scoped)
                add(compare_arrays(cpath, h5::read_dataset(reference_, cpath), h5::read_dataset(candidate_, cpath)));
        }
    }

    CompareEntry compare_arrays(const std::string& path, const h5::Array& a, const h5::Array& b) const
    {
        CompareEntry entry = make_entry(path, CompareEntry::Kind::same);
        if (a.type != b.type || a.type == h5::Array::Type::other) {
            entry.kind = CompareEntry::Kind::type_mismatch;
            entry.detail = a.type == h5::Array::Type::other && a.type == b.type
                               ? "cannot compare values of " + a.type_description
                               : "reference " + a.type_description + ", new " + b.type_description;
            return entry;
        }
        if (a.dims != b.dims) {
            entry.kind = CompareEntry::Kind::shape_mismatch;
            entry.detail = "reference " + h5::format_dims(a.dims) + ", new " + h5::format_dims(b.dims);
            return entry;
        }
        std::size_t n_outside = 0;
        if (a.type == h5::Array::Type::string) {
            for (std::size_t i = 0; i < a.strings.size(); ++i) {
                if (a.strings[i] == b.strings[i])
                    continue;
                if (n_outside++ == 0)
                    entry.detail = a.strings.size() == 1
                                       ? describe_string_difference(a.strings[i], b.strings[i])
                                       : fmt::format("element {}: {} vs {}", i, quote(a.strings[i]),
                                                     quote(b.strings[i]));
            }
            entry.kind = n_outside == 0 ? CompareEntry::Kind::same : CompareEntry::Kind::different;
            return entry;
        }

        entry.numeric = true;
        const bool integers = a.type == h5::Array::Type::integer;
        const std::size_t n = a.n_values();
        std::size_t n_nonfinite = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const double x = integers ? static_cast<double>(a.integers[i]) : a.reals[i];
            const double y = integers ? static_cast<double>(b.integers[i]) : b.reals[i];
            if (integers ? a.integers[i] == b.integers[i] : (x == y || (std::isnan(x) && std::isnan(y))))
                continue;
            double diff = std::abs(x - y);
            double rel = x != 0 ? diff / std::abs(x) : infinity;
            const bool finite = std::isfinite(x) && std::isfinite(y);
            if (!finite) {  // NaN against a number, or infinities that differ
                diff = rel = infinity;
                ++n_nonfinite;
            }
            entry.max_abs = std::max(entry.max_abs, diff);
            entry.max_rel = std::max(entry.max_rel, rel);
            if (integers || !finite || !(diff <= options_.atol + options_.rtol * std::abs(x)))
                ++n_outside;
        }
        entry.kind = n_outside == 0 ? CompareEntry::Kind::same : CompareEntry::Kind::different;
        if (n_outside > 0)
            entry.detail = fmt::format("{} of {} values outside tolerance", n_outside, n) +
                           (n_nonfinite > 0 ? fmt::format(" ({} non-finite)", n_nonfinite) : "");
        return entry;
    }

    hid_t reference_;
    hid_t candidate_;
    const CompareOptions& options_;
    std::vector<std::string> prefixes_;
    std::vector<bool> prefix_hit_;
    CompareReport report_;
    std::vector<hid_t> ancestors_;  ///< the reference groups the walk is inside, outermost first
};

}  // namespace

const char* kind_name(CompareEntry::Kind kind)
{
    switch (kind) {
    case CompareEntry::Kind::same:
        return "same";
    case CompareEntry::Kind::different:
        return "different";
    case CompareEntry::Kind::missing:
        return "missing";
    case CompareEntry::Kind::shape_mismatch:
        return "shape_mismatch";
    case CompareEntry::Kind::type_mismatch:
        return "type_mismatch";
    }
    return "?";
}

CompareReport compare_results(const std::string& reference_path, const std::string& new_path,
                              const CompareOptions& options)
{
    IGA_CHECK(options.rtol >= 0 && options.atol >= 0, "compare tolerances must be >= 0 (and not NaN)");
    h5::ErrorSilencer silence;
    h5::Handle reference = open_results(reference_path, "reference");
    h5::Handle candidate = open_results(new_path, "new");
    return Comparer(reference.id(), candidate.id(), options).run();
}

std::string format_report(const CompareReport& report, bool verbose)
{
    std::string out;
    for (const CompareEntry& entry : report.entries) {
        if (entry.kind == CompareEntry::Kind::same && !verbose)
            continue;
        out += fmt::format("{:<14} {}", kind_name(entry.kind), entry.path);
        if (entry.numeric)
            out += fmt::format(": max abs diff {:.3e}, max rel diff {:.3e}", entry.max_abs, entry.max_rel);
        if (!entry.detail.empty())
            out += (entry.numeric ? "; " : ": ") + entry.detail;
        out += '\n';
    }
    out += fmt::format("compare: {} compared, {} different, {} missing", report.n_compared, report.n_different,
                       report.n_missing);
    return out;
}

}  // namespace iga::io
