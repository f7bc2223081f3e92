#pragma once
// The engine of `igacontact compare REF NEW`: compares two results files
// (docs/results.md) item by item, for regression tests.
//
// Every group, dataset and attribute present in REF is looked up in NEW (things
// only in NEW are not errors; the hard link /results is compared like any
// group, so its contents appear under /results and under /steps/<kkkk>).
// Reals pass when |a - b| <= atol + rtol |a| elementwise, a from REF; NaN
// matches only NaN and an infinity only the same infinity. Integers and strings
// compare exactly. Volatile items are skipped unless include_volatile: the
// /timings group, the root attribute program_version, attributes wall_s, and
// anything under /counters whose name ends in "_s".
// Entry paths: "/steps/0001/displacement/cylinder" for objects,
// "<object path>@<attribute>" for attributes ("/@status" for the root).

#include <string>
#include <vector>

namespace iga::io {

struct CompareOptions {
    double rtol = 1e-6;
    double atol = 1e-12;
    /// Path prefixes (whole path components, e.g. "/steps/0002" or "/reference"); empty = everything.
    /// A prefix that matches nothing in REF is reported as missing, so a typo cannot pass silently.
    std::vector<std::string> only;
    bool include_volatile = false;
};

struct CompareEntry {
    enum class Kind { same, different, missing, shape_mismatch, type_mismatch };
    std::string path;
    Kind kind = Kind::same;
    double max_abs = 0;  ///< max |a - b| over the elements (numbers only)
    double max_rel = 0;  ///< max |a - b| / |a| (infinite where a = 0 and b != a)
    bool numeric = false;  ///< max_abs and max_rel are meaningful (a numeric dataset or attribute)
    std::string detail;  ///< e.g. "3 of 40 values outside tolerance", "reference (4, 2), new (5, 2)"
};

struct CompareReport {
    std::vector<CompareEntry> entries;  ///< one per compared or missing item, in walk order
    int n_compared = 0;                 ///< datasets and attributes compared
    int n_different = 0;                ///< different, shape_mismatch and type_mismatch entries
    int n_missing = 0;                  ///< items in REF absent from NEW
    bool same() const { return n_different == 0 && n_missing == 0; }
};

/// Throws iga::Error if a file cannot be opened or is not an HDF5 file.
CompareReport compare_results(const std::string& reference_path, const std::string& new_path,
                              const CompareOptions& options);

/// One line per entry that is not `same` (every entry when verbose), then
/// "compare: <n> compared, <n> different, <n> missing".
std::string format_report(const CompareReport& report, bool verbose);

const char* kind_name(CompareEntry::Kind kind);

}  // namespace iga::io
