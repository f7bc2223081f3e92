#pragma once
// ResultsWriter: writes one run's HDF5 results file (docs/results.md,
// format "igacontact-results", version 1).
//
// Crash safety (results.md, last paragraph): everything goes to
// "<final_path>.tmp-<pid>" next to the final file, which is not touched until
// finish() renames the temporary file onto it (rename() is atomic on POSIX).
// The temporary file is flushed after every step, so what was written stays
// readable if the process dies. A failed run still calls finish() with
// status "failed": the converged steps and the message end up in the final file.
//
// Cost per step: flat. Writing step 10 000 costs what step 1 costs (about 0.2 ms
// for a small body; scripts/bench_output.py): the file uses the HDF5 1.8 format
// (dense link storage for /steps), a fixed 256 KB metadata cache (a flush visits
// every cache entry), and objects are never looked up by name when all goes well
// (H5Iget_name of an object in a step under construction searches the whole
// file). /history is kept in memory (a few numbers per increment) and written by
// finish(), also for a failed run; a killed run has /steps but no /history.
//
// Call order: constructor, write_bodies() (once), write_step() per converged
// increment (increasing index), then finish() or abandon(). Every HDF5 failure
// throws iga::Error with a message naming the file and object. HDF5 types stay
// inside the implementation.

#include "io/results_data.hpp"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace iga::io {

class ResultsWriter {
public:
    /// Creates the temporary file and writes the root attributes (format,
    /// format_version = 1, program_version, status = "running", message = "")
    /// and /deck. Throws iga::Error("cannot create results file <final_path>: <reason>")
    /// if its folder does not exist or is not writable.
    ResultsWriter(std::string final_path, const std::string& program_version, const std::string& resolved_deck);
    /// Calls abandon() if finish() was not called (exceptions, bugs): the final path is untouched.
    ~ResultsWriter();
    ResultsWriter(ResultsWriter&&) noexcept;
    ResultsWriter& operator=(ResultsWriter&&) noexcept;
    ResultsWriter(const ResultsWriter&) = delete;
    ResultsWriter& operator=(const ResultsWriter&) = delete;

    /// /bodies/<body>/{degrees, knots/u, knots/v(, knots/w), control_points(, side_names)}.
    void write_bodies(const std::vector<BodyGeometry>& bodies);

    /// /paraview/<body>/{points (n_t x d), cells (n_cells x nodes_per_cell, int32)}.
    void write_tessellation(const std::vector<Tessellation>& bodies);

    /// /steps/<kkkk>/ (kkkk = index, zero-padded to 4 digits) with its attributes,
    /// displacement/<body> and contact/<pair>/<body.side>/...; then points the
    /// hard link /results at it and flushes the file. Also reactions/<body.side>
    /// (d-vectors, when StepData::reactions is not empty), the attribute obstacle_force
    /// of a contact pair (when not empty) and fields/<body>/{reference_coordinates,
    /// displacement, stress, von_mises} (when StepData::fields is not empty).
    void write_step(const StepData& step);

    /// Remembers one /history row (every converged increment, in order); /history is
    /// written by finish(): load_factor (n), reactions/<name> (n x d),
    /// contact/<pair>/<side>/{normal_force, max_penetration} (n). Every row has the same
    /// names, in the same order, as the first (else iga::Error).
    void append_history(const HistoryRow& row);

    /// Writes status/message/warnings (root attributes; warnings "" when none), /history,
    /// /timings, /counters, /convergence and /reference, closes the file and renames it onto the final path. The writer is closed afterwards.
    /// `interrupted` (may be empty) is asked twice before the rename, after the
    /// writes and after the close: once it is true, a "completed" status becomes
    /// "failed" with `interrupted_message` (a stop during the writing of the results
    /// never leaves a completed file behind a non-zero exit). Returns the status written.
    std::string finish(const RunSummary& summary, const std::function<bool()>& interrupted = {},
                       const std::string& interrupted_message = {});

    /// Closes and deletes the temporary file; the final path is untouched. No-op when closed.
    void abandon() noexcept;

    bool is_open() const;
    const std::string& final_path() const { return final_path_; }
    const std::string& temp_path() const { return temp_path_; }

private:
    struct State;  // the open HDF5 file
    std::string final_path_;
    std::string temp_path_;
    std::unique_ptr<State> state_;
};

/// The name of step `index` under /steps: "0001", ..., "9999", "10000", ...
std::string step_group_name(int index);

}  // namespace iga::io
