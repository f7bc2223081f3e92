// igacontact: the command-line front end. The only place that prints and picks
// exit codes: 0 success, 1 the solve failed (or `compare` found differences),
// 2 bad input or usage, 3 internal error. Every error is printed once, on stderr,
// as "igacontact: error: ..." or, for a deck error, "file:line:col: error: ...";
// with `--summary json` every outcome also prints one JSON line on stdout.
//
//   igacontact DECK [-o OUT.h5] [--set PATH=VALUE]... [-q|-v] [--summary json] [--threads N] [--refine-levels K]
//   igacontact check DECK [--set PATH=VALUE]...
//   igacontact compare REF.h5 NEW.h5 [--rtol R] [--atol A] [--only PATH]... [--all] [-v]
//   igacontact study DECK [--levels N] [--jobs J] [--set PATH=VALUE]... [-q]
//   igacontact keys [--markdown FILE]   (not in --help: the deck's keys, for docs/deck.md)
//   mpirun -np N igacontact DECK ...   (the same run on N MPI ranks; rank 0 prints and writes)

#include "commands.hpp"
#include "summary_json.hpp"

#include "core/allocator.hpp"
#include "core/blas_kernels.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/stop.hpp"
#include "io/h5_file.hpp"
#include "version.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
#include <iostream>
#include <string>

namespace {

/// main() proper; the exit code of this process.
int run_main(int argc, char** argv, const iga::Communicator& comm)
{
    using namespace iga::app;
    const std::string first = argc > 1 ? argv[1] : "";
    const bool json = first != "check" && first != "compare" && first != "study" && first != "keys" &&
                      summary_json_requested(argc, argv);
    // Under mpirun every rank meets the same deck and usage errors: rank 0 tells them.
    const bool speaks = comm.root();
    auto fail = [&](const std::string& status, const std::string& message, int code) {
        if (json && speaks)
            std::cout << error_summary_json(status, message, code) << std::endl;
        return code;
    };
    try {
        if (first == "check")
            return check_command(argc - 1, argv + 1, comm);
        if (first == "compare")
            return compare_command(argc - 1, argv + 1, comm);
        if (first == "study")
            return study_command(argc - 1, argv + 1, comm);
        if (first == "keys")
            return keys_command(argc - 1, argv + 1);
        return run_command(argc, argv, comm);
    } catch (const UsageError& e) {
        if (speaks)
            std::cerr << "igacontact: error: " << e.what() << "\nRun 'igacontact --help' for usage.\n";
        return fail("bad_input", e.what(), exit_bad_input);
    } catch (const iga::Interrupted& e) {
        // A stop during set-up (inside the increments the run writes its file and returns).
        const std::string message = std::string(e.what()) + " during set-up, before any results were written";
        if (speaks)
            std::cerr << "igacontact: failed: " << message << '\n';
        return fail("failed", message, exit_failed);
    } catch (const iga::DeckError& e) {
        if (speaks)
            std::cerr << e.what() << '\n';
        return fail("bad_input", e.what(), exit_bad_input);
    } catch (const iga::StorageError& e) {
        // The results file is a temporary until complete: its fate is in e.what().
        const std::string message =
            std::string(e.what()) +
            " (the file system refused a write: full disk, quota, file size limit, read-only or I/O error)";
        if (speaks)
            std::cerr << "igacontact: failed: " << message << '\n';
        iga::parallel::abort_all(exit_failed);  // rank 0 writes: the others may wait for it
        return fail("failed", message, exit_failed);
    } catch (const std::bad_alloc&) {
        // Outside the increments (set-up, the final write), or on several ranks: no
        // file of converged increments to keep. Each rank that ran out says so; one ends them all.
        const std::string message =
            "out of memory (an allocation failed): the model needs more memory than this process may use, the "
            "machine's or a limit such as ulimit -v; no results were written. Refine less, or spread the model over "
            "more memory with mpirun (docs/parallel.md)";
        std::cerr << "igacontact: failed: " << rank_prefix(comm) << message << '\n';
        iga::parallel::abort_all(exit_failed);
        return fail("failed", message, exit_failed);
    } catch (const iga::Error& e) {
        // Not necessarily met by every rank: this rank ends them all (below).
        std::cerr << "igacontact: error: " << rank_prefix(comm) << e.what() << "\nThis is a bug in igacontact "
                  << iga::program_version << "; please report it with the deck.\n";
        iga::parallel::abort_all(exit_internal);
        return fail("internal_error", e.what(), exit_internal);
    } catch (const std::exception& e) {
        std::cerr << "igacontact: internal error: " << rank_prefix(comm) << e.what() << '\n';
        iga::parallel::abort_all(exit_internal);
        return fail("internal_error", e.what(), exit_internal);
    }
}

/// The exit code once standard output is flushed: a write to it that failed (a full
/// device, a closed file) is an error, never a silent exit 0. Checked after every
/// command, for whatever it printed (a summary line, a listing, a verdict, key tables).
int check_standard_output(int code, bool json)
{
    errno = 0;
    std::cout.flush();
    const bool flushed = std::fflush(stdout) == 0;
    const int error = errno;
    if (flushed && std::cout.good() && !std::ferror(stdout))
        return code;
    std::cerr << "igacontact: error: cannot write to standard output"
              << (error != 0 ? std::string(": ") + std::strerror(error) : std::string())
              << (json ? " (the --summary json line is lost)" : "") << '\n';
    return code == iga::app::exit_ok ? iga::app::exit_bad_input : code;
}

}  // namespace

int main(int argc, char** argv)
{
    iga::use_cpu_blas_kernels(argv);     // may start the program again, with OPENBLAS_CORETYPE set
    iga::restore_allocator_defaults();  // before any large allocation (core/allocator.hpp)
    // Under mpirun (or srun) MPI first: every rank then builds the same scene and
    // works on its part (core/parallel.hpp). A plain run starts no MPI.
    iga::io::h5::no_shutdown_at_exit();
    iga::parallel::initialize();
    const int code = check_standard_output(run_main(argc, argv, iga::Communicator::world()),
                                           iga::app::summary_json_requested(argc, argv));
    iga::parallel::finalize();
    return code;
}
