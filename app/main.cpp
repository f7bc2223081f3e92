// igacontact: the command-line front end. The only place that prints and picks
// exit codes: 0 success, 1 the solve failed (or `compare` found differences),
// 2 bad input or usage, 3 internal error.
//
//   igacontact DECK [-o OUT.h5] [--set PATH=VALUE]... [-q|-v] [--summary json] [--threads N]
//   igacontact check DECK [--set PATH=VALUE]...
//   igacontact compare REF.h5 NEW.h5 [--rtol R] [--atol A] [--only PATH]... [--all] [-v]

#include "commands.hpp"

#include "core/error.hpp"
#include "version.hpp"

#include <cstring>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

int main(int argc, char** argv)
{
    try {
        const std::string first = argc > 1 ? argv[1] : "";
        if (first == "check")
            return iga::app::check_command(argc - 1, argv + 1);
        if (first == "compare")
            return iga::app::compare_command(argc - 1, argv + 1);
        return iga::app::run_command(argc, argv);
    } catch (const iga::DeckError& e) {
        std::cerr << e.what() << '\n';
        return iga::app::exit_bad_input;
    } catch (const iga::Error& e) {
        std::cerr << "igacontact: " << e.what() << "\nThis is a bug in igacontact " << iga::program_version
                  << "; please report it with the deck.\n";
        return iga::app::exit_internal;
    } catch (const std::exception& e) {
        std::cerr << "igacontact: internal error: " << e.what() << '\n';
        return iga::app::exit_internal;
    }
}
