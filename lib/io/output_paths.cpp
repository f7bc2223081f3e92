#include "io/output_paths.hpp"

#include "io/locate.hpp"

#include <filesystem>
#include <system_error>
#include <utility>

namespace iga::io {

namespace fs = std::filesystem;

std::string xdmf_path(const std::string& results_file)
{
    const std::string suffix = ".h5";
    const bool h5 = results_file.size() >= suffix.size() &&
                    results_file.compare(results_file.size() - suffix.size(), suffix.size(), suffix) == 0;
    return (h5 ? results_file.substr(0, results_file.size() - suffix.size()) : results_file) + ".xdmf";
}

namespace {

fs::path normalized(const std::string& path)
{
    std::error_code error;
    fs::path absolute = fs::absolute(path, error);
    if (error)
        return fs::path(path).lexically_normal();
    fs::path resolved = fs::weakly_canonical(absolute, error);  // symlinks of the existing part resolved
    return error ? absolute.lexically_normal() : resolved;
}

bool exists(const std::string& path)
{
    std::error_code error;
    return fs::exists(path, error);
}

bool is_folder(const std::string& path)
{
    std::error_code error;
    return fs::is_directory(path, error);
}

/// What an existing path that is neither a regular file nor a folder is ("" otherwise):
/// writing there would replace a device, a FIFO or a socket by a regular file.
std::string special_kind(const std::string& path)
{
    std::error_code error;
    const fs::file_status status = fs::status(path, error);  // follows symbolic links
    if (error)
        return {};
    switch (status.type()) {
    case fs::file_type::character: return "a character device";
    case fs::file_type::block: return "a block device";
    case fs::file_type::fifo: return "a FIFO (named pipe)";
    case fs::file_type::socket: return "a socket";
    default: return {};
    }
}

}  // namespace

bool same_file(const std::string& a, const std::string& b)
{
    if (exists(a) && exists(b)) {
        std::error_code error;
        const bool same = fs::equivalent(a, b, error);
        if (!error)
            return same;
    }
    return normalized(a) == normalized(b);
}

std::vector<std::string> input_files(const Deck& deck)
{
    std::vector<std::string> files{deck.source_file};
    // geometry.file is written relative to the deck's folder (io/deck.hpp).
    const fs::path deck_dir = fs::path(deck.source_file).parent_path();
    for (const Body& body : deck.bodies)
        if (!body.geometry_file.empty()) {
            const fs::path file(body.geometry_file);
            files.push_back((file.is_absolute() ? file : deck_dir / file).lexically_normal().string());
        }
    return files;
}

OutputOrigin output_origin(bool o_option_given, const std::vector<std::string>& set_overrides)
{
    if (o_option_given)
        return OutputOrigin::o_option;
    for (const std::string& s : set_overrides) {
        const std::string path = s.substr(0, s.find('='));
        if (path == "output" || path == "output.file")
            return OutputOrigin::set_option;
    }
    return OutputOrigin::deck;
}

DeckError output_error(const std::string& deck_file, const std::string& results, OutputOrigin origin,
                       const std::string& reason)
{
    const std::string path = "output.file";
    if (origin == OutputOrigin::deck)
        return DeckError(located_issue(deck_file, path, results, reason));
    DeckIssue issue;
    issue.where.file = "<command line>";
    issue.path = path;
    issue.value = results;
    const std::string o_option = " (the -o option)";
    const bool named = reason.find("-o option") != std::string::npos;
    issue.reason = reason + (origin == OutputOrigin::o_option && !named ? o_option : "");
    return DeckError(std::move(issue));
}

void check_output_paths(const Deck& deck, const std::vector<std::string>& inputs, OutputOrigin origin)
{
    const std::string& results = deck.output.file;
    const bool o_option = origin == OutputOrigin::o_option;
    auto refuse = [&](const std::string& reason) { throw output_error(deck.source_file, results, origin, reason); };
    auto input_role = [&](const std::string& input) {
        return same_file(input, deck.source_file) ? std::string("the deck itself")
                                                  : "an input file of the deck (" + input + ")";
    };
    const std::string results_file = o_option ? "the results file given with the -o option" : "the results file";
    const std::string choose = "; nothing was written. Choose another results file";
    // The same words as the results writer's check, which runs later for library callers.
    if (is_folder(results))
        refuse("cannot create results file " + results + ": '" + results + "' is a folder, not a file");
    if (const std::string kind = special_kind(results); !kind.empty())
        refuse("cannot create results file " + results + ": '" + results + "' is " + kind +
               ", not a regular file; nothing was written. Choose another results file");
    for (const std::string& input : inputs)
        if (same_file(results, input))
            refuse(results_file + " would replace " + input_role(input) + choose);
    if (!deck.output.paraview)
        return;
    const std::string xdmf = xdmf_path(results);
    if (is_folder(xdmf))
        refuse("the ParaView index " + xdmf + " (output.paraview) of " + results_file + " is a folder, not a file");
    if (const std::string kind = special_kind(xdmf); !kind.empty())
        refuse("the ParaView index " + xdmf + " (output.paraview) of " + results_file + " is " + kind +
               ", not a regular file" + choose);
    for (const std::string& input : inputs)
        if (same_file(xdmf, input))
            refuse("the ParaView index " + xdmf + " (output.paraview) of " + results_file + " would replace " +
                   input_role(input) + choose);
}

}  // namespace iga::io
