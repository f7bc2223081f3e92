#pragma once
// The table of `igacontact study`: one row per refinement level and quantity,
// written as <deck>_study.csv (docs/results.md, "Refinement study files") with the
// columns
//   level,dofs,wall_s,quantity,value,extrapolated,observed_order,estimated_rel_error
// and, when the deck has an analytic reference, after them
//   reference_value,true_rel_error
// and last (analysis/refinement_study.hpp)
//   extrapolated_rel_band,asymptotic,estimate
// the grid convergence index of the extrapolated value relative to it, 1/0 where the
// three levels ending at this one are/are not in the asymptotic range, and how far
// the levels support the estimate (asymptotic, not_asymptotic, assumed_order,
// converged, not_converging, zero_limit).
// A value that does not exist (no extrapolation from one level, an observed order
// that the levels do not show, a quantity without an analytic value, an estimate the
// levels do not support) is an empty field, never NaN. Numbers are written with 10
// significant digits.

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
    std::optional<double> extrapolated_rel_band;  ///< GCI / |extrapolated|, of the quantity
    std::optional<bool> asymptotic;               ///< of the three levels ending at this one
    std::string estimate;                         ///< the quantity's EstimateSupport, spelled as in the CSV
};

/// The CSV text: header line, then one line per row.
std::string study_csv(const std::vector<StudyRow>& rows, bool with_reference);

/// Writes study_csv(rows) to `path` (through a temporary file renamed into place).
/// Throws iga::Error when the file cannot be written.
void write_study_csv(const std::string& path, const std::vector<StudyRow>& rows, bool with_reference);

}  // namespace iga::io
