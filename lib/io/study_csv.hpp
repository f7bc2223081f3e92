#pragma once
// The table of `igacontact study`: one row per refinement level and quantity,
// written as <deck>_study.csv (shared/spec/results.md, "Additions") with the
// columns
//   level,dofs,wall_s,quantity,value,extrapolated,observed_order,estimated_rel_error
// and, when the deck has an analytic reference, after them
//   reference_value,true_rel_error
// A value that does not exist (no extrapolation from one level, an observed order
// that the levels do not show, a quantity without an analytic value) is an empty
// field, never NaN. Numbers are written with 10 significant digits.

#include <optional>
#include <string>
#include <vector>

namespace iga::io {

struct StudyRow {
    int level = 0;
    long long dofs = 0;
    double wall_s = 0.0;
    std::string quantity;
    double value = 0.0;
    std::optional<double> extrapolated;
    std::optional<double> observed_order;
    std::optional<double> estimated_rel_error;
    std::optional<double> reference_value;  ///< analytic value (decks with output.reference)
    std::optional<double> true_rel_error;   ///< |value - reference| / |reference|
};

/// The CSV text: header line, then one line per row.
std::string study_csv(const std::vector<StudyRow>& rows, bool with_reference);

/// Writes study_csv(rows) to `path` (through a temporary file renamed into place).
/// Throws iga::Error when the file cannot be written.
void write_study_csv(const std::string& path, const std::vector<StudyRow>& rows, bool with_reference);

}  // namespace iga::io
