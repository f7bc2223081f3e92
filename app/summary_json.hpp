#pragma once
// `--summary json`: one JSON line on stdout for every outcome of a run, so that
// scripts never scrape the log. Always an object with "status", "message",
// "exit_code" and "warnings" (a list of strings, each a `warning: ...` line of stderr
// without the prefix; empty for a run that did not happen):
//   exit 0 / 1: status "completed" / "failed" (an interrupted run is "failed"), with
//               "results", "increments", "newton_iterations", "cutbacks", "wall_s",
//               the run's numbers and "errors" against the reference;
//   exit 2:     status "bad_input" (bad deck, bad usage, unreadable file), message = the error;
//   exit 3:     status "internal_error", message = the error.

#include "analysis/run.hpp"

#include <string>
#include <vector>

namespace iga::app {

/// True if the command line asks for `--summary json` (or `--summary=json`): scanned
/// before parsing, so that a usage error can still answer in JSON.
bool summary_json_requested(int argc, char** argv);

/// The line for a run that ended (exit 0 or 1).
std::string summary_json(const analysis::RunOutcome& outcome, int exit_code);

/// The line for a run that did not happen: bad input (exit 2) or an internal error (exit 3).
std::string error_summary_json(const std::string& status, const std::string& message, int exit_code);

}  // namespace iga::app
