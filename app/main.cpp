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

#include "commands.hpp"
#include "summary_json.hpp"

#include "core/error.hpp"
#include "core/stop.hpp"
#include "version.hpp"

#include <exception>
#include <iostream>
#include <string>

int main(int argc, char** argv)
{
    using namespace iga::app;
    const std::string first = argc > 1 ? argv[1] : "";
    const bool json = first != "check" && first != "compare" && first != "study" && summary_json_requested(argc, argv);
    auto fail = [&](const std::string& status, const std::string& message, int code) {
        if (json)
            std::cout << error_summary_json(status, message, code) << std::endl;
        return code;
    };
    try {
        if (first == "check")
            return check_command(argc - 1, argv + 1);
        if (first == "compare")
            return compare_command(argc - 1, argv + 1);
        if (first == "study")
            return study_command(argc - 1, argv + 1);
        return run_command(argc, argv);
    } catch (const UsageError& e) {
        std::cerr << "igacontact: error: " << e.what() << "\nRun 'igacontact --help' for usage.\n";
        return fail("bad_input", e.what(), exit_bad_input);
    } catch (const iga::Interrupted& e) {
        // A stop during set-up (inside the increments the run writes its file and returns).
        const std::string message = std::string(e.what()) + " during set-up, before any results were written";
        std::cerr << "igacontact: failed: " << message << '\n';
        return fail("failed", message, exit_failed);
    } catch (const iga::DeckError& e) {
        std::cerr << e.what() << '\n';
        return fail("bad_input", e.what(), exit_bad_input);
    } catch (const iga::Error& e) {
        std::cerr << "igacontact: error: " << e.what() << "\nThis is a bug in igacontact " << iga::program_version
                  << "; please report it with the deck.\n";
        return fail("internal_error", e.what(), exit_internal);
    } catch (const std::exception& e) {
        std::cerr << "igacontact: internal error: " << e.what() << '\n';
        return fail("internal_error", e.what(), exit_internal);
    }
}
