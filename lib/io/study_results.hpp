#pragma once
// What `igacontact study` reads from the results file of one refinement level
// (docs/results.md): the run's status, its size, the lowest polynomial
// degree of its patches, and the quantities of interest of the last converged
// increment (/results), named as in the study CSV:
//   normal_force:<pair>:<body.side>    attribute normal_force of the side group
//   peak_pressure:<pair>:<body.side>   max of postprocessed/pressure
//   max_penetration:<pair>             attribute max_penetration of the pair group
//   reaction:<body.side>:<x|y|z>       /results/reactions/<body.side>, one per component
// and, where the deck asks for an analytic reference, the analytic value of a
// quantity (peak_pressure of the reference's pair: its p0).

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace iga::io {

struct LevelResults {
    std::string status;   ///< root attribute status: "completed", "failed", "running"
    std::string message;  ///< root attribute message
    long long dofs = 0;   ///< /counters dofs
    int min_degree = 0;   ///< lowest degree over every direction of every patch (0 if none)
    /// Quantities of the last converged increment, in the order above (empty if none converged).
    std::vector<std::pair<std::string, double>> quantities;
    std::map<std::string, double> reference_values;  ///< quantity name -> analytic value
};

/// Reads one level's results file. Throws iga::Error when it cannot be read.
LevelResults read_level_results(const std::string& path);

}  // namespace iga::io
