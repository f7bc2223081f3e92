#include "commands.hpp"

#include "analysis/accuracy.hpp"
#include "analysis/run.hpp"
#include "analysis/contact_penalty.hpp"
#include "analysis/describe.hpp"
#include "analysis/scene.hpp"
#include "analysis/size_estimate.hpp"
#include "analysis/warnings.hpp"
#include "analysis/zone_refinement.hpp"
#include "core/error.hpp"
#include "core/run_context.hpp"
#include "core/stop.hpp"
#include "io/deck_reader.hpp"
#include "io/deck_writer.hpp"
#include "io/output_paths.hpp"
#include "io/results_compare.hpp"
#include "solver/linear.hpp"
#include "summary_json.hpp"
#include "version.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <unistd.h>

namespace iga::app {

namespace {

std::atomic<bool> interrupt_requested{false};

extern "C" void on_interrupt(int signal)
{
    interrupt_requested.store(true);
    // The run stops cleanly within one element block or Newton trial (core/stop.hpp),
    // abandoning the increment in progress; a second Ctrl-C ends it at once
    // (the temporary results file is flushed after each increment, so stays readable).
    std::signal(signal, SIG_DFL);
}

}  // namespace

/// Parses with CLI11; returns -1 when parsing succeeded, 0 after --help/--version
/// (CLI11 printed them). A usage error throws UsageError, which main() prints as
/// "igacontact: error: ..." like every other error.
int parse_command_line(CLI::App& cli, int argc, char** argv)
{
    try {
        cli.parse(argc, argv);
        return -1;
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success))
            return cli.exit(e) == 0 ? exit_ok : exit_bad_input;
        throw UsageError(e.what());
    }
}

namespace {

/// A stream that drops what it is given (and never fails): the other ranks' output.
std::ostream& null_stream()
{
    struct NullBuffer : std::streambuf {
        int overflow(int c) override { return traits_type::not_eof(c); }
        std::streamsize xsputn(const char*, std::streamsize n) override { return n; }
    };
    static NullBuffer buffer;
    static std::ostream stream(&buffer);
    return stream;
}

}  // namespace

std::ostream& out_stream(const Communicator& comm) { return comm.root() ? std::cout : null_stream(); }
std::ostream& err_stream(const Communicator& comm) { return comm.root() ? std::cerr : null_stream(); }

std::string rank_prefix(const Communicator& comm)
{
    return comm.parallel() ? fmt::format("rank {}: ", comm.rank()) : std::string();
}

int run_command(int argc, char** argv, const Communicator& comm)
{
    CLI::App cli{"igacontact: isogeometric contact mechanics (two-half-pass Gauss-point-to-segment penalty).\n"
                 "Runs a YAML deck and writes the results to HDF5.",
                 "igacontact"};
    cli.footer("Other commands:\n"
               "  igacontact check DECK [--set PATH=VALUE]...   validate, print the resolved deck and side names\n"
               "  igacontact compare REF.h5 NEW.h5 [options]    regression check of two results files\n"
               "  igacontact study DECK [--levels N] [--jobs J]  refinement study: error estimates and their cost\n"
               "Exit codes: 0 success, 1 the solve failed, 2 bad input or usage, 3 internal error.");
    // The backends a build has: scripts (and users) ask this before a `solver.backend: petsc` run.
    cli.set_version_flag("--version", fmt::format("igacontact {} (linear solvers: {})", program_version,
                                                  solver::available_backends()));

    std::string deck_path, output, summary;
    std::vector<std::string> overrides;
    bool quiet = false, verbose = false;
    cli.add_option("deck", deck_path, "deck file (YAML, format 1)")->required();
    cli.add_option("-o,--output", output, "results file (default: output.file of the deck, or DECK with .h5)");
    cli.add_option("--set", overrides, "override a deck value, PATH=VALUE (VALUE is YAML); repeatable")
        ->allow_extra_args(false);
    cli.add_flag("-q,--quiet", quiet, "no progress: print only warnings and errors (a failed run's reason)");
    cli.add_flag("-v,--verbose", verbose, "print Newton iterations");
    cli.add_option("--summary", summary, "print one summary line at the end")->check(CLI::IsMember({"json"}));
    int threads = 0;
    cli.add_option("--threads", threads,
                   "threads for the element assembly (default 0: automatic, serial for small scenes; README \"Threads\")")
        ->check(CLI::Range(0, 1024));
    int refine_levels = 0;
    cli.add_option("--refine-levels", refine_levels,
                   "halve every knot span of every patch K times after the deck's refinement (igacontact study)")
        ->check(CLI::Range(0, 10));
    if (const int code = parse_command_line(cli, argc, argv); code >= 0)
        return code;

    // From here on SIGINT/SIGTERM request a stop, also while the deck is read: a stop
    // before the results file is opened ends the run with exit 1 and writes nothing.
    std::signal(SIGINT, on_interrupt);
    std::signal(SIGTERM, on_interrupt);
    if (comm.parallel())
        require_rereadable_deck(deck_path, fmt::format("the {} ranks of mpirun each", comm.size()));
    io::Deck deck = io::read_deck(deck_path, overrides);
    if (refine_levels > 0) {
        // The size check of the deck (analysis/size_estimate.hpp) sees the deck's own
        // refinement; each halving multiplies the model by about 2^d.
        const double bytes = analysis::estimate_size(deck).bytes * std::exp2(deck.analysis.dimension * refine_levels);
        const analysis::SizeLimits limits = analysis::machine_limits();
        if (limits.memory_bytes > 0 && bytes > limits.memory_bytes)
            throw UsageError(fmt::format("--refine-levels {}: the refined model needs about {:.3g} GB, more than {} "
                                         "{:.3g} GB",
                                         refine_levels, bytes / 1e9, limits.memory_name, limits.memory_bytes / 1e9));
        if (deck.accuracy) {
            // The levels refine from the deck's knots: the halvings become knots of the deck.
            analysis::fold_halvings(deck, refine_levels);
            deck.resolved_yaml = io::write_resolved_yaml(deck);
        }
    }
    if (!output.empty()) {
        deck.output.file = output;
        deck.resolved_yaml = io::write_resolved_yaml(deck);  // /deck shows the file actually written
    }
    // /deck in the results file says how the run was refined.
    if (refine_levels > 0)
        deck.resolved_yaml +=
            deck.accuracy ? fmt::format("# run with --refine-levels {}: every knot span halved {} time(s), written "
                                        "into the insert lists above\n",
                                        refine_levels, refine_levels)
                          : fmt::format("# run with --refine-levels {}: every knot span halved {} time(s) after the "
                                        "refinement above\n",
                                        refine_levels, refine_levels);
    // Never write over the deck (or any input), whichever way the path was given.
    const io::OutputOrigin output_origin = io::output_origin(!output.empty(), overrides);
    io::check_output_paths(deck, io::input_files(deck), output_origin);
    StopRequest(&interrupt_requested).check();  // reading the deck polls nothing

    const Verbosity verbosity = quiet ? Verbosity::quiet : (verbose ? Verbosity::verbose : Verbosity::normal);
    // On a terminal the progress line (k/N, load factor, iterations, active Gauss
    // points) replaces the solver's per-increment log line; in files and pipes
    // (not a TTY) the log lines stay, and -q silences both.
    const bool terminal = !quiet && !verbose && isatty(STDERR_FILENO);
    // On several ranks rank 0 prints; the others run silently (they hold the same
    // warnings, the same outcome, and their results are rank 0's file).
    const bool speaks = comm.root();
    RunContext context(
        [terminal, speaks](Verbosity level, const std::string& line) {
            if (speaks && !(terminal && level == Verbosity::normal))
                std::cerr << line << '\n';
        },
        verbosity);

    analysis::RunOptions options;
    options.stop_requested = [] { return interrupt_requested.load(); };
    context.set_stop(StopRequest(&interrupt_requested));  // polled inside set-up, assembly and Newton
    options.threads = threads;
    options.refine_levels = deck.accuracy ? 0 : refine_levels;  // folded into an accuracy deck's knots above
    options.comm = comm;
    options.output_origin = output_origin;
    if (terminal && speaks)
        options.progress = [](const std::string& line) { std::cerr << line << '\n'; };
    // -q silences progress only: a warning or a failure's reason always reaches stderr.
    if (speaks)
        options.warning = [](const std::string& line) { std::cerr << "warning: " << line << '\n'; };

    const analysis::RunOutcome outcome =
        deck.accuracy ? analysis::run_to_accuracy(deck, options, context) : analysis::run(deck, options, context);
    if (!speaks)
        return outcome.status == "completed" ? exit_ok : exit_failed;

    if (outcome.status != "completed")
        std::cerr << fmt::format("igacontact: {}: {}\n", outcome.status, outcome.message);
    if (!quiet) {
        if (outcome.status == "completed")
            std::cerr << fmt::format("igacontact: completed {} increment(s), {} Newton iteration(s) in {:.3g} s\n",
                                     outcome.increments, outcome.newton_iterations, outcome.wall_s);
        for (const io::Reaction& r : outcome.reactions)
            if (r.name.rfind("items/", 0) != 0)  // the items split the totals: in the results file only
                std::cerr << fmt::format("reaction on {}: ({:.6g})\n", r.name, fmt::join(r.force, ", "));
        for (const auto& [pair, force] : outcome.obstacle_forces)
            std::cerr << fmt::format("contact force on the obstacle of {}: ({:.6g})\n", pair, fmt::join(force, ", "));
        std::cerr << "results: " << outcome.results_file << '\n';
    }
    const int code = outcome.status == "completed" ? exit_ok : exit_failed;
    if (summary == "json")
        std::cout << summary_json(outcome, code) << std::endl;
    // The run has said everything: a signal from here on ends the process as usual.
    // One that came after the results file was closed complete stopped nothing; said,
    // so that an exit 0 after SIGTERM is no mystery.
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    if (outcome.status == "completed" && interrupt_requested.load())
        std::cerr << "igacontact: SIGINT/SIGTERM arrived after the results were complete; the run stands as completed\n";
    return code;
}

void require_rereadable_deck(const std::string& deck_path, const std::string& readers)
{
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::file_status status = fs::status(deck_path, ec);
    if (ec || status.type() == fs::file_type::not_found || status.type() == fs::file_type::regular)
        return;  // a missing file is the deck reader's error, with its own message
    throw UsageError(fmt::format("deck {}: not a regular file (standard input, a pipe or a device can be read only "
                                 "once), and {} read the deck: save it to a file and give its path",
                                 deck_path, readers));
}

int check_command(int argc, char** argv, const Communicator& comm)
{
    std::ostream& out = out_stream(comm);
    std::ostream& err = err_stream(comm);
    CLI::App cli{"Validate a deck, print the resolved deck (defaults filled in) and the side names of each body.",
                 "igacontact check"};
    std::string deck_path;
    std::vector<std::string> overrides;
    cli.add_option("deck", deck_path, "deck file (YAML)")->required();
    cli.add_option("--set", overrides, "override a deck value, PATH=VALUE; repeatable")->allow_extra_args(false);
    if (const int code = parse_command_line(cli, argc, argv); code >= 0)
        return code;

    if (comm.parallel())
        require_rereadable_deck(deck_path, fmt::format("the {} ranks of mpirun each", comm.size()));
    const io::Deck deck = io::read_deck(deck_path, overrides);
    io::check_output_paths(deck, io::input_files(deck), io::output_origin(false, overrides));
    analysis::check_size(deck);  // before describe_bodies builds the geometry
    const std::string bodies = analysis::describe_bodies(deck);  // also builds the geometry: may throw DeckError
    // Everything a run checks before solving (Jacobians, pairs, constraints, obstacles).
    const analysis::Scene scene = analysis::build_scene(deck);
    for (const std::string& line : scene.setup_warnings)  // also said by a run
        err << "warning: " << line << '\n';
    for (const std::string& line : analysis::duplicate_pair_warnings(scene))
        err << "warning: " << line << '\n';
    out << "# resolved deck: " << deck_path << '\n' << deck.resolved_yaml;
    if (!deck.resolved_yaml.empty() && deck.resolved_yaml.back() != '\n')
        out << '\n';
    out << bodies;
    if (!scene.reactions.empty()) {
        out << "# reactions reported per increment (force each constraint exerts on its body):\n";
        for (const analysis::ReactionGroup& group : scene.reactions)
            out << fmt::format("#   {} ({} constrained dofs)\n", group.name, group.dofs.size());
    }
    for (const analysis::PairModel& pair : scene.pairs)
        if (pair.obstacle >= 0)
            out << fmt::format("# contact force on the obstacle {} reported for pair {}\n",
                                     pair.label[static_cast<std::size_t>(pair.obstacle)], pair.name);
    for (const analysis::PairModel& pair : scene.pairs)
        if (pair.penalty_auto)
            out << "# contact pair " << pair.name << ": penalty auto = " << analysis::describe(pair.rule)
                      << "\n";
    for (const analysis::PairModel& pair : scene.pairs)
        if (const contact::FrictionLaw& law = pair.pair.settings().friction; law.active())
            out << fmt::format("# contact pair {}: Coulomb friction, mu = {:g}, tangential penalty {:g}{}\n",
                                     pair.name, law.coefficient, law.tangential_penalty,
                                     pair.augmented ? ", with tangential multipliers (augmented Lagrangian)" : "");
    out.flush();  // the listing before the verdict, also when both streams go to one pipe
    err << deck_path << ": ok\n";
    return exit_ok;
}

int compare_command(int argc, char** argv, const Communicator& comm)
{
    std::ostream& out = out_stream(comm);
    std::ostream& err = err_stream(comm);
    CLI::App cli{"Compare a results file with a reference: every dataset and attribute of REF must be in NEW and\n"
                 "agree to |new - ref| <= atol + rtol |ref|. Timings, versions, counters and solver statistics are ignored "
                 "unless --all.",
                 "igacontact compare"};
    std::string reference, candidate;
    io::CompareOptions options;
    bool verbose = false;
    cli.add_option("reference", reference, "reference results file (REF.h5)")->required();
    cli.add_option("new", candidate, "results file to check (NEW.h5)")->required();
    // A tolerance below 0 (or NaN) is a usage error here, before io::compare_results asserts it.
    const CLI::Validator non_negative(
        [](std::string& text) {
            const double x = std::strtod(text.c_str(), nullptr);
            return x >= 0 ? std::string() : "must be a number >= 0, got " + text;
        },
        "NUMBER >= 0");
    cli.add_option("--rtol", options.rtol, "relative tolerance")->capture_default_str()->check(non_negative);
    cli.add_option("--atol", options.atol, "absolute tolerance")->capture_default_str()->check(non_negative);
    cli.add_option("--only", options.only, "compare only paths starting with PATH; repeatable")
        ->allow_extra_args(false);
    cli.add_flag("--all", options.include_volatile, "also compare timings, versions, counters and solver statistics");
    cli.add_flag("-v,--verbose", verbose, "list every compared item");
    if (const int code = parse_command_line(cli, argc, argv); code >= 0)
        return code;

    io::CompareReport report;
    try {
        report = io::compare_results(reference, candidate, options);
    } catch (const Error& e) {
        err << "igacontact compare: error: " << e.what() << '\n';
        return exit_bad_input;
    }
    out << io::format_report(report, verbose) << '\n';
    return report.same() ? exit_ok : exit_failed;
}

}  // namespace iga::app
