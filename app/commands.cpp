#include "commands.hpp"

#include "analysis/run.hpp"
#include "analysis/describe.hpp"
#include "analysis/scene.hpp"
#include "core/error.hpp"
#include "core/run_context.hpp"
#include "io/deck_reader.hpp"
#include "io/deck_writer.hpp"
#include "io/results_compare.hpp"
#include "version.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <unistd.h>

namespace iga::app {

namespace {

std::atomic<bool> interrupt_requested{false};

extern "C" void on_interrupt(int signal)
{
    interrupt_requested.store(true);
    // The run stops cleanly at the next increment; a second Ctrl-C ends it at once
    // (the temporary results file is flushed after each increment, so stays readable).
    std::signal(signal, SIG_DFL);
}

/// Parses with CLI11; returns -1 when parsing succeeded, else the exit code
/// (0 for --help/--version, 2 for a usage error).
int parse(CLI::App& cli, int argc, char** argv)
{
    try {
        cli.parse(argc, argv);
        return -1;
    } catch (const CLI::ParseError& e) {
        const int code = cli.exit(e);
        return code == 0 ? exit_ok : exit_bad_input;
    }
}

std::string json_escape(const std::string& s)
{
    std::string out;
    for (char c : s) {
        switch (c) {
        case '"': out += "\\\""; break;
        case '\\': out += "\\\\"; break;
        case '\n': out += "\\n"; break;
        case '\t': out += "\\t"; break;
        default:
            if (static_cast<unsigned char>(c) < 0x20)
                out += fmt::format("\\u{:04x}", static_cast<int>(c));
            else
                out += c;
        }
    }
    return out;
}

std::string json_number(double x)
{
    return std::isfinite(x) ? fmt::format("{:.9g}", x) : "null";
}

/// One JSON line for scripts (`--summary json`): never scrape the log.
std::string summary_json(const analysis::RunOutcome& r)
{
    std::string out = fmt::format(
        "{{\"status\": \"{}\", \"message\": \"{}\", \"results\": \"{}\", \"increments\": {}, "
        "\"newton_iterations\": {}, \"cutbacks\": {}, \"wall_s\": {}",
        json_escape(r.status), json_escape(r.message), json_escape(r.results_file), r.increments,
        r.newton_iterations, r.cutbacks, json_number(r.wall_s));
    for (const auto& [key, value] : r.numbers)
        out += fmt::format(", \"{}\": {}", json_escape(key), json_number(value));
    out += ", \"errors\": {";
    bool first = true;
    for (const auto& [key, value] : r.errors) {
        out += fmt::format("{}\"{}\": {}", first ? "" : ", ", json_escape(key), json_number(value));
        first = false;
    }
    out += "}}";
    return out;
}

}  // namespace

int run_command(int argc, char** argv)
{
    CLI::App cli{"igacontact: isogeometric contact mechanics (two-half-pass Gauss-point-to-segment penalty).\n"
                 "Runs a YAML deck and writes the results to HDF5.",
                 "igacontact"};
    cli.footer("Other commands:\n"
               "  igacontact check DECK [--set PATH=VALUE]...   validate, print the resolved deck and side names\n"
               "  igacontact compare REF.h5 NEW.h5 [options]    regression check of two results files\n"
               "Exit codes: 0 success, 1 the solve failed, 2 bad input or usage, 3 internal error.");
    cli.set_version_flag("--version", std::string("igacontact ") + program_version);

    std::string deck_path, output, summary;
    std::vector<std::string> overrides;
    bool quiet = false, verbose = false;
    cli.add_option("deck", deck_path, "deck file (YAML, format 1)")->required();
    cli.add_option("-o,--output", output, "results file (default: output.file of the deck, or DECK with .h5)");
    cli.add_option("--set", overrides, "override a deck value, PATH=VALUE (VALUE is YAML); repeatable")
        ->allow_extra_args(false);
    cli.add_flag("-q,--quiet", quiet, "print nothing but errors");
    cli.add_flag("-v,--verbose", verbose, "print Newton iterations");
    cli.add_option("--summary", summary, "print one summary line at the end")->check(CLI::IsMember({"json"}));
    int threads = 0;
    cli.add_option("--threads", threads,
                   "threads for the element assembly (default 0: automatic, serial for small scenes; README \"Threads\")")
        ->check(CLI::Range(0, 1024));
    if (const int code = parse(cli, argc, argv); code >= 0)
        return code;

    io::Deck deck = io::read_deck(deck_path, overrides);
    if (!output.empty()) {
        deck.output.file = output;
        deck.resolved_yaml = io::write_resolved_yaml(deck);  // /deck shows the file actually written
    }

    const Verbosity verbosity = quiet ? Verbosity::quiet : (verbose ? Verbosity::verbose : Verbosity::normal);
    // On a terminal the progress line (k/N, load factor, iterations, active Gauss
    // points) replaces the solver's per-increment log line; in files and pipes
    // (not a TTY) the log lines stay, and -q silences both.
    const bool terminal = !quiet && !verbose && isatty(STDERR_FILENO);
    RunContext context(
        [terminal](Verbosity level, const std::string& line) {
            if (!(terminal && level == Verbosity::normal))
                std::cerr << line << '\n';
        },
        verbosity);

    std::signal(SIGINT, on_interrupt);
    std::signal(SIGTERM, on_interrupt);
    analysis::RunOptions options;
    options.stop_requested = [] { return interrupt_requested.load(); };
    options.threads = threads;
    if (terminal)
        options.progress = [](const std::string& line) { std::cerr << line << '\n'; };
    if (!quiet)
        options.warning = [](const std::string& line) { std::cerr << "warning: " << line << '\n'; };

    const analysis::RunOutcome outcome = analysis::run(deck, options, context);

    if (!quiet) {
        if (outcome.status == "completed")
            std::cerr << fmt::format("igacontact: completed {} increment(s), {} Newton iteration(s) in {:.3g} s\n",
                                     outcome.increments, outcome.newton_iterations, outcome.wall_s);
        else
            std::cerr << fmt::format("igacontact: {}: {}\n", outcome.status, outcome.message);
        for (const io::Reaction& r : outcome.reactions)
            std::cerr << fmt::format("reaction on {}: ({:.6g})\n", r.name, fmt::join(r.force, ", "));
        for (const auto& [pair, force] : outcome.obstacle_forces)
            std::cerr << fmt::format("contact force on the obstacle of {}: ({:.6g})\n", pair, fmt::join(force, ", "));
        std::cerr << "results: " << outcome.results_file << '\n';
    }
    if (summary == "json")
        std::cout << summary_json(outcome) << std::endl;
    return outcome.status == "completed" ? exit_ok : exit_failed;
}

int check_command(int argc, char** argv)
{
    CLI::App cli{"Validate a deck, print the resolved deck (defaults filled in) and the side names of each body.",
                 "igacontact check"};
    std::string deck_path;
    std::vector<std::string> overrides;
    cli.add_option("deck", deck_path, "deck file (YAML)")->required();
    cli.add_option("--set", overrides, "override a deck value, PATH=VALUE; repeatable")->allow_extra_args(false);
    if (const int code = parse(cli, argc, argv); code >= 0)
        return code;

    const io::Deck deck = io::read_deck(deck_path, overrides);
    const std::string bodies = analysis::describe_bodies(deck);  // also builds the geometry: may throw DeckError
    // Everything a run checks before solving (Jacobians, pairs, constraints, obstacles).
    const analysis::Scene scene = analysis::build_scene(deck);
    std::cout << "# resolved deck: " << deck_path << '\n' << deck.resolved_yaml;
    if (!deck.resolved_yaml.empty() && deck.resolved_yaml.back() != '\n')
        std::cout << '\n';
    std::cout << bodies;
    if (!scene.reactions.empty()) {
        std::cout << "# reactions reported per increment (force each constraint exerts on its body):\n";
        for (const analysis::ReactionGroup& group : scene.reactions)
            std::cout << fmt::format("#   {} ({} constrained dofs)\n", group.name, group.dofs.size());
    }
    for (const analysis::PairModel& pair : scene.pairs)
        if (pair.obstacle >= 0)
            std::cout << fmt::format("# contact force on the obstacle {} reported for pair {}\n",
                                     pair.label[static_cast<std::size_t>(pair.obstacle)], pair.name);
    std::cerr << deck_path << ": ok\n";
    return exit_ok;
}

int compare_command(int argc, char** argv)
{
    CLI::App cli{"Compare a results file with a reference: every dataset and attribute of REF must be in NEW and\n"
                 "agree to |new - ref| <= atol + rtol |ref|. Timings, versions and wall times are ignored unless --all.",
                 "igacontact compare"};
    std::string reference, candidate;
    io::CompareOptions options;
    bool verbose = false;
    cli.add_option("reference", reference, "reference results file (REF.h5)")->required();
    cli.add_option("new", candidate, "results file to check (NEW.h5)")->required();
    cli.add_option("--rtol", options.rtol, "relative tolerance")->capture_default_str();
    cli.add_option("--atol", options.atol, "absolute tolerance")->capture_default_str();
    cli.add_option("--only", options.only, "compare only paths starting with PATH; repeatable")
        ->allow_extra_args(false);
    cli.add_flag("--all", options.include_volatile, "also compare timings, versions and wall times");
    cli.add_flag("-v,--verbose", verbose, "list every compared item");
    if (const int code = parse(cli, argc, argv); code >= 0)
        return code;

    io::CompareReport report;
    try {
        report = io::compare_results(reference, candidate, options);
    } catch (const Error& e) {
        std::cerr << "igacontact compare: " << e.what() << '\n';
        return exit_bad_input;
    }
    std::cout << io::format_report(report, verbose) << '\n';
    return report.same() ? exit_ok : exit_failed;
}

}  // namespace iga::app
