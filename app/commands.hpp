#pragma once
// The commands of the CLI. Each parses its own arguments (CLI11) and
// returns the process exit code.

#include "core/parallel.hpp"

#include <iosfwd>
#include <stdexcept>

namespace CLI {
class App;
}

namespace iga::app {

/// Bad usage of the command line (unknown option, missing argument): exit 2.
class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

inline constexpr int exit_ok = 0;
inline constexpr int exit_failed = 1;     ///< the solve failed; `compare`: files differ
inline constexpr int exit_bad_input = 2;  ///< bad deck, bad usage, unreadable file
inline constexpr int exit_internal = 3;   ///< a bug

/// The run; on several MPI ranks (comm) every rank runs it and rank 0 prints.
int run_command(int argc, char** argv, const Communicator& comm);

/// "rank k: " on several ranks, "" on one process: names the rank a message comes from.
std::string rank_prefix(const Communicator& comm);
/// `check` and `compare`: under mpirun every rank does the work (and meets the same
/// errors), rank 0 alone prints the listing and the verdict.
int check_command(int argc, char** argv, const Communicator& comm);
int compare_command(int argc, char** argv, const Communicator& comm);
/// `study` starts its levels itself: under mpirun (several ranks) it is a usage error.
int study_command(int argc, char** argv, const Communicator& comm);  ///< app/study.cpp
int keys_command(int argc, char** argv);   ///< app/keys.cpp (not in --help: a tool of the docs)

/// Where a command prints: std::cout / std::cerr on rank 0 (or a plain run), a stream
/// that drops everything on the other ranks.
std::ostream& out_stream(const Communicator& comm);
std::ostream& err_stream(const Communicator& comm);

/// Refuses (UsageError, exit 2) a deck that can be read only once -- standard input, a
/// pipe, a device -- where it is read more than once: by every rank under mpirun, by
/// every level of a study. `readers` says who reads it, for the message.
void require_rereadable_deck(const std::string& deck_path, const std::string& readers);

/// Parses with CLI11; returns -1 when parsing succeeded, 0 after --help/--version
/// (CLI11 printed them). A usage error throws UsageError.
int parse_command_line(CLI::App& cli, int argc, char** argv);

}  // namespace iga::app
