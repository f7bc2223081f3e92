#pragma once
// Running the built `igacontact` executable from a test: the command line goes
// through /bin/sh (std::system) with stdout and stderr captured to files in a
// scratch folder, and the exit status decoded (-1 if the process did not exit
// normally, e.g. it crashed). Arguments are passed as a shell string: quote
// anything with spaces or brackets with shell_quote().

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace iga::test {

inline std::string cli_path()
{
    return std::string(IGA_BINARY_DIR) + "/bin/igacontact";
}

/// Single-quoted for /bin/sh.
inline std::string shell_quote(const std::string& s)
{
    std::string out = "'";
    for (char c : s)
        out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

inline std::string read_text(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

struct CliResult {
    int exit_code = -1;
    std::string out;  ///< stdout
    std::string err;  ///< stderr
};

/// Runs `igacontact <arguments>` with the working directory unchanged.
inline CliResult run_cli(const std::string& arguments, const std::filesystem::path& scratch)
{
    const auto out = scratch / "cli_stdout.txt", err = scratch / "cli_stderr.txt";
    const std::string command = shell_quote(cli_path()) + " " + arguments + " > " + shell_quote(out.string()) +
                                " 2> " + shell_quote(err.string()) + " < /dev/null";
    const int status = std::system(command.c_str());
    CliResult result;
    result.exit_code = status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.out = read_text(out);
    result.err = read_text(err);
    return result;
}

}  // namespace iga::test
