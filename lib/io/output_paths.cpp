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
    // Files named inside the deck (G+Smo geometry) join this list when the reader has them.
    return {deck.source_file};
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

void check_output_paths(const Deck& deck, const std::vector<std::string>& inputs, OutputOrigin origin)
{
    const std::string& results = deck.output.file;
    const bool o_option = origin == OutputOrigin::o_option;
    auto refuse = [&](const std::string& reason) {
        const std::string path = "output.file";
        if (origin == OutputOrigin::deck)
            throw DeckError(located_issue(deck.source_file, path, results, reason));
        DeckIssue issue;
        issue.where.file = "<command line>";
        issue.path = path;
        issue.value = results;
        issue.reason = reason;
        throw DeckError(std::move(issue));
    };
    auto input_role = [&](const std::string& input) {
        return same_file(input, deck.source_file) ? std::string("the deck itself")
                                                  : "an input file of the deck (" + input + ")";
    };
    const std::string results_file = o_option ? "the results file given with the -o option" : "the results file";
    const std::string choose = "; nothing was written. Choose another results file";
    // The same words as the results writer's check, which runs later for library callers.
    if (is_folder(results))
        refuse("cannot create results file " + results + ": '" + results + "' is a folder, not a file" +
               (o_option ? " (the -o option)" : ""));
    for (const std::string& input : inputs)
        if (same_file(results, input))
            refuse(results_file + " would replace " + input_role(input) + choose);
    if (!deck.output.paraview)
        return;
    const std::string xdmf = xdmf_path(results);
    if (is_folder(xdmf))
        refuse("the ParaView index " + xdmf + " (output.paraview) of " + results_file + " is a folder, not a file");
    for (const std::string& input : inputs)
        if (same_file(xdmf, input))
            refuse("the ParaView index " + xdmf + " (output.paraview) of " + results_file + " would replace " +
                   input_role(input) + choose);
}

}  // namespace iga::io
