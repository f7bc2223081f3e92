// `igacontact study DECK [--levels N] [--jobs J] [--set PATH=VALUE]... [-q]`:
// a uniform h-refinement study of any deck (docs/cli.md "study", docs/theory.md "Refinement study").
//
// Level k is an ordinary run of the same executable (/proc/self/exe) with
// `--refine-levels k -o <deck>_study/level<k>.h5` and the same --set values,
// its output in <deck>_study/level<k>.log. Up to --jobs levels run at once, a
// level starting only while the estimated memory of the running levels fits in
// half the machine's memory (analysis/size_estimate.hpp, times 2^(d k)). Each
// child dies with this process (Linux: PR_SET_PDEATHSIG, also after a SIGKILL)
// and runs in its own process group, so a Ctrl-C reaches only this process,
// which passes one SIGINT on to the running levels (they stop after their current
// increment, as a run does), starts no more, and still writes the table of the
// levels that completed. A second Ctrl-C passes a second SIGINT on (the levels
// then end at once). A failed level is reported, not fatal.
//
// Before anything runs, a table, plot, level results or log path that exists and is
// not a regular file (a folder, a symbolic link, a device) is bad input (exit 2), and
// so are a deck that can be read only once (a pipe, standard input) and mpirun. Every
// file is written new (a temporary renamed over it, or unlinked first), never through
// an existing one: a hard link there keeps its other names' contents.
// Writes <deck>_study.csv beside the deck (io/study_csv.hpp), prints the table,
// and draws <deck>_study.png with scripts/plot_study.py (Debian's python3 with
// matplotlib) when it can; else it says how to draw it.

#include "commands.hpp"

#include "analysis/refinement_study.hpp"
#include "analysis/size_estimate.hpp"
#include "core/error.hpp"
#include "core/petsc_options.hpp"
#include "io/deck_reader.hpp"
#include "io/study_csv.hpp"
#include "io/study_results.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <fcntl.h>
#include <signal.h>
#ifdef __linux__
#include <sys/prctl.h>
#endif
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <thread>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>

extern char** environ;

namespace iga::app {

namespace {

namespace fs = std::filesystem;

std::atomic<int> interrupts{0};

extern "C" void on_study_interrupt(int)
{
    interrupts.fetch_add(1);
}

/// Counts SIGINT/SIGTERM; the study loop acts on the count.
void install_interrupt_handler()
{
    struct sigaction action {};
    action.sa_handler = on_study_interrupt;
    sigemptyset(&action.sa_mask);
    action.sa_flags = 0;
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
}

struct Level {
    int index = 0;
    double memory_bytes = 0.0;  ///< estimated (lower bound)
    fs::path results, log;
    pid_t pid = -1;
    std::chrono::steady_clock::time_point start;
    double wall_s = 0.0;
    std::string outcome;  ///< "completed", "failed", "interrupted", "not run"
    std::string message;
};

/// Starts `exe args...` in its own process group, stdin from /dev/null, stdout and
/// stderr to `log` (created afresh; a symbolic link there is not followed). On Linux
/// the child is killed when this process dies, however it dies: a SIGKILLed study
/// cannot pass anything on, so the kernel does (PR_SET_PDEATHSIG). Returns the pid,
/// or -1 with errno set.
pid_t spawn(const std::string& exe, const std::vector<std::string>& args, const fs::path& log)
{
    // Everything the child needs is built before fork(): after it, only async-signal-safe calls.
    std::vector<std::string> all = args;
    all.insert(all.begin(), exe);
    std::vector<char*> argv;
    for (std::string& a : all)
        argv.push_back(a.data());
    argv.push_back(nullptr);
    const std::string log_path = log.string();
    const pid_t parent = ::getpid();
    int report[2];  // the child writes errno here if exec fails; close-on-exec gives EOF on success
    if (::pipe2(report, O_CLOEXEC) != 0)
        return -1;
    const pid_t pid = ::fork();
    if (pid < 0) {
        const int error = errno;
        ::close(report[0]);
        ::close(report[1]);
        errno = error;
        return -1;
    }
    if (pid == 0) {
        ::close(report[0]);
#ifdef __linux__
        if (::prctl(PR_SET_PDEATHSIG, SIGKILL) != 0 || ::getppid() != parent)
            ::_exit(127);  // the study is already gone (or cannot be followed): run nothing
#endif
        ::setpgid(0, 0);  // a Ctrl-C on the terminal reaches the study only, which passes it on
        struct sigaction defaults {};
        defaults.sa_handler = SIG_DFL;
        sigemptyset(&defaults.sa_mask);
        ::sigaction(SIGINT, &defaults, nullptr);  // default handling, whatever the study installed
        ::sigaction(SIGTERM, &defaults, nullptr);
        // Close-on-exec: only the dup2 copies (0, 1, 2) reach the level.
        const int in = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
        // A new file, never writing through what is there: a log path hard-linked to the
        // deck must not empty the deck (unlink removes this name only).
        ::unlink(log_path.c_str());
        const int out = ::open(log_path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
        if (in >= 0 && out >= 0 && ::dup2(in, STDIN_FILENO) >= 0 && ::dup2(out, STDOUT_FILENO) >= 0 &&
            ::dup2(out, STDERR_FILENO) >= 0)
            ::execve(exe.c_str(), argv.data(), environ);
        const int error = errno;
        [[maybe_unused]] const ssize_t written = ::write(report[1], &error, sizeof error);
        ::_exit(127);
    }
    ::close(report[1]);
    int child_error = 0;
    ssize_t n = 0;
    do
        n = ::read(report[0], &child_error, sizeof child_error);
    while (n < 0 && errno == EINTR);  // a Ctrl-C while the child starts
    ::close(report[0]);
    if (n == static_cast<ssize_t>(sizeof child_error)) {
        ::waitpid(pid, nullptr, 0);
        errno = child_error;
        return -1;
    }
    return pid;
}

/// Throws, as bad input located at `path`, if it exists and is not a regular file:
/// the study writes `path` (what) and would fail after running every level.
void check_study_file(const fs::path& path, const std::string& what)
{
    std::error_code ec;
    const fs::file_status status = fs::symlink_status(path, ec);
    if (ec || status.type() == fs::file_type::not_found || status.type() == fs::file_type::regular)
        return;
    const std::string kind = status.type() == fs::file_type::directory ? "a folder"
                             : status.type() == fs::file_type::symlink ? "a symbolic link"
                                                                        : "a device, FIFO or socket";
    DeckIssue issue;
    issue.where.file = path.string();
    issue.reason = "is " + kind + ", not a regular file: the study writes " + what +
                   " there; nothing was run. Move it away and run the study again";
    throw DeckError(std::move(issue));
}

std::string self_executable()
{
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    return ec ? std::string("/proc/self/exe") : self.string();
}

/// scripts/plot_study.py: $IGACONTACT_SCRIPTS_DIR, else the source tree this binary was built from.
std::optional<fs::path> plot_script()
{
    std::vector<fs::path> dirs;
    if (const char* env = std::getenv("IGACONTACT_SCRIPTS_DIR"))
        dirs.emplace_back(env);
#ifdef IGACONTACT_SCRIPTS_DIR
    dirs.emplace_back(IGACONTACT_SCRIPTS_DIR);
#endif
    for (const fs::path& d : dirs)
        if (fs::exists(d / "plot_study.py"))
            return d / "plot_study.py";
    return std::nullopt;
}

std::string shell_quote(const std::string& s)
{
    std::string out = "'";
    for (char c : s)
        out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

std::string cell(const std::optional<double>& x, const char* format)
{
    return x ? fmt::format(fmt::runtime(format), *x) : std::string("-");
}

/// The verdict on one quantity's extrapolation, for the head of its block.
std::string verdict(const io::StudyRow& r, int formal_order)
{
    const std::string band = r.extrapolated_rel_band ? fmt::format(" +- {:.2g} %", 100 * *r.extrapolated_rel_band) : "";
    if (r.estimate == "not_converging")
        return "not converging (the finest levels differ by more than the coarser ones): no estimate";
    if (r.estimate == "zero_limit")
        return fmt::format("extrapolated {}, but its band reaches zero: no relative error",
                           cell(r.extrapolated, "{:.4g}"));
    if (r.estimate == "converged")
        return fmt::format("the two finest levels agree: {}", cell(r.extrapolated, "{:.8g}"));
    if (r.estimate == "assumed_order")
        return fmt::format("extrapolated {}{} (GCI, Fs = 3), order {} assumed: the levels show none",
                           cell(r.extrapolated, "{:.6g}"), band, formal_order);
    std::string text = fmt::format("extrapolated {}{} (GCI, Fs = 1.25), observed order {} (formal {})",
                                   cell(r.extrapolated, "{:.6g}"), band, cell(r.observed_order, "{:.2f}"),
                                   formal_order);
    if (r.estimate == "not_asymptotic")
        text += ": not in the asymptotic range, trust the band, not the digits";
    return text;
}

/// The table on stdout: one block per quantity.
void print_table(const std::vector<io::StudyRow>& rows, bool with_reference, int formal_order)
{
    std::string current;
    for (const io::StudyRow& r : rows) {
        if (r.quantity != current) {
            current = r.quantity;
            std::cout << fmt::format("\n{}  ({})\n", r.quantity, verdict(r, formal_order));
            std::cout << fmt::format("  {:>5} {:>9} {:>9} {:>16} {:>10} {:>5}", "level", "dofs", "wall s", "value",
                                     "est. err", "asym.");
            std::cout << (with_reference ? fmt::format(" {:>10}\n", "true err") : "\n");
        }
        const std::string asymptotic = r.asymptotic ? (*r.asymptotic ? "yes" : "no") : "";
        std::cout << fmt::format("  {:>5} {:>9} {:>9.3g} {:>16.9g} {:>10} {:>5}", r.level, r.dofs, r.wall_s, r.value,
                                 cell(r.estimated_rel_error, "{:.2e}"), asymptotic);
        std::cout << (with_reference ? fmt::format(" {:>10}\n", cell(r.true_rel_error, "{:.2e}")) : "\n");
    }
}

/// The line of a level's log that says why it failed: its last "igacontact: ..." or
/// error line (the run prints its results path after it), else its last line.
std::string failure_reason(const fs::path& log)
{
    std::ifstream in(log);
    std::string line, last, reason;
    while (std::getline(in, line)) {
        if (line.empty())
            continue;
        last = line;
        if (line.rfind("igacontact: ", 0) == 0 || line.find(": error: ") != std::string::npos)
            reason = line;
    }
    return reason.empty() ? last : reason;
}

/// Every file the study writes, checked before anything runs or is created; then
/// the levels' folder created.
void check_study_paths(const fs::path& csv, const fs::path& png, const fs::path& study_dir, int n_levels)
{
    check_study_file(csv, "its table");
    check_study_file(png, "its plot");
    if (std::error_code e; fs::exists(study_dir, e) && !fs::is_directory(study_dir, e)) {
        DeckIssue issue;
        issue.where.file = study_dir.string();
        issue.reason = "is not a folder: the study keeps the levels' results and logs there; nothing was run";
        throw DeckError(std::move(issue));
    }
    for (int k = 0; k < n_levels; ++k) {
        check_study_file(study_dir / fmt::format("level{}.h5", k), fmt::format("the results of level {}", k));
        check_study_file(study_dir / fmt::format("level{}.log", k), fmt::format("the log of level {}", k));
    }
    std::error_code ec;
    fs::create_directories(study_dir, ec);
    if (ec)
        throw UsageError("cannot create " + study_dir.string() + ": " + ec.message());
}

/// Levels 0..n-1, not run yet: their files in `study_dir` and memory estimates (level
/// k about 2^(d k) times the deck's).
std::vector<Level> planned_levels(const io::Deck& deck, const fs::path& study_dir, int n_levels)
{
    const double level0_bytes = analysis::estimate_size(deck).bytes;
    const int d = deck.analysis.dimension;
    std::vector<Level> levels(static_cast<std::size_t>(n_levels));
    for (int k = 0; k < n_levels; ++k) {
        Level& l = levels[static_cast<std::size_t>(k)];
        l.index = k;
        l.memory_bytes = level0_bytes * std::exp2(d * k);
        l.results = study_dir / fmt::format("level{}.h5", k);
        l.log = study_dir / fmt::format("level{}.log", k);
        l.outcome = "not run";
    }
    return levels;
}

/// Runs the levels, up to `jobs` at once while their memory estimates fit in
/// `budget` (0: no limit), passing each Ctrl-C on; fills each level's outcome.
void run_levels(std::vector<Level>& levels, const std::string& exe, const std::string& deck_path,
                const std::vector<std::string>& overrides, int jobs, double budget,
                const std::function<void(const std::string&)>& say)
{
    std::size_t next = 0;
    std::vector<std::size_t> running;
    int interrupts_passed_on = 0;
    while (next < levels.size() || !running.empty()) {
        // Pass each Ctrl-C on to the running levels once; stop starting new ones.
        const int seen = interrupts.load();
        if (seen > interrupts_passed_on) {
            for (std::size_t i : running)
                ::kill(levels[i].pid, SIGINT);
            if (interrupts_passed_on == 0)
                say("study: interrupted: stopping the running level(s); each keeps its converged increments");
            interrupts_passed_on = seen;
        }
        if (seen == 0 && next < levels.size() && static_cast<int>(running.size()) < jobs) {
            double in_use = 0.0;
            for (std::size_t i : running)
                in_use += levels[i].memory_bytes;
            if (running.empty() || budget <= 0 || in_use + levels[next].memory_bytes <= budget) {
                Level& l = levels[next];
                // Not quiet: the level's log keeps the run's whole output.
                std::vector<std::string> args = {deck_path, "--refine-levels", std::to_string(l.index), "-o",
                                                 l.results.string()};
                for (const std::string& o : overrides) {
                    args.push_back("--set");
                    args.push_back(o);
                }
                // A study level is the deck's mesh refined uniformly, solved once: not the
                // levels of its accuracy: block (docs/accuracy_on_demand.md).
                args.push_back("--set");
                args.push_back("accuracy=null");
                l.start = std::chrono::steady_clock::now();
                l.pid = spawn(exe, args, l.log);
                if (l.pid < 0) {
                    l.outcome = "failed";
                    l.message = std::string("cannot start ") + exe + ": " + std::strerror(errno);
                } else {
                    running.push_back(next);
                    say(fmt::format("study: level {} started (pid {}, estimated memory {:.3g} MB)", l.index, l.pid,
                                    l.memory_bytes / 1e6));
                }
                ++next;
                continue;
            }
        }
        if (seen > 0 && running.empty())
            break;
        // Poll (rather than block in waitpid) so that a Ctrl-C is passed on at once.
        int status = 0;
        const auto it = std::find_if(running.begin(), running.end(), [&](std::size_t i) {
            return ::waitpid(levels[i].pid, &status, WNOHANG) == levels[i].pid;
        });
        if (it == running.end()) {
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
            continue;
        }
        Level& l = levels[*it];
        running.erase(it);
        l.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - l.start).count();
        const bool exited = WIFEXITED(status);
        const int code = exited ? WEXITSTATUS(status) : -1;
        if (exited && code == exit_ok) {
            l.outcome = "completed";
        } else {
            l.outcome = interrupts.load() > 0 ? "interrupted" : "failed";
            l.message = exited ? failure_reason(l.log) : fmt::format("killed by signal {}", WTERMSIG(status));
        }
        say(fmt::format("study: level {} {} in {:.3g} s{}", l.index, l.outcome, l.wall_s,
                        l.message.empty() ? "" : ": " + l.message));
    }

}

/// The completed levels' results; a file that does not read as completed marks its
/// level failed. `formal_order` is the lowest degree of their patches.
std::vector<analysis::StudyLevel> read_levels(std::vector<Level>& levels, int& formal_order, bool& with_reference)
{
    std::vector<analysis::StudyLevel> completed;
    for (Level& l : levels) {
        if (l.outcome != "completed")
            continue;
        io::LevelResults r;
        try {
            r = io::read_level_results(l.results.string());
        } catch (const Error& e) {
            l.outcome = "failed";
            l.message = e.what();
            continue;
        }
        if (r.status != "completed") {
            l.outcome = "failed";
            l.message = r.message;
            continue;
        }
        formal_order = formal_order == 0 ? r.min_degree : std::min(formal_order, r.min_degree);
        with_reference = with_reference || !r.reference_values.empty();
        completed.push_back({l.index, r.dofs, l.wall_s, std::move(r.quantities), std::move(r.reference_values)});
    }
    return completed;
}

/// The plot: scripts/plot_study.py with Debian's python3 (numpy, matplotlib), drawn
/// to `drawn` beside it and renamed over `png`; else the command to draw it.
void draw_plot(const fs::path& csv, const fs::path& png, const fs::path& drawn)
{
    const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
    const auto script = plot_script();
    auto plot_command = [&](const fs::path& target) {
        return fmt::format("{} {} {} {}", python,
                           script ? shell_quote(script->string()) : std::string("scripts/plot_study.py"),
                           shell_quote(csv.string()), shell_quote(target.string()));
    };
    const std::string command = plot_command(png);
    // Drawn beside it, then renamed over it: a png path hard-linked to the deck must
    // not turn the deck into a picture.
    bool plotted = script && std::system((plot_command(drawn) + " > /dev/null 2>&1").c_str()) == 0;
    if (plotted) {
        std::error_code renamed;
        fs::rename(drawn, png, renamed);
        plotted = !renamed;
    }
    if (std::error_code ignored; !plotted)
        fs::remove(drawn, ignored);
    if (plotted) {
        std::cout << "plot: " << png.string() << '\n';
    } else {
        std::cerr << "warning: study: no plot written (needs python3 with matplotlib); draw it with:\n  " << command
                  << '\n';
    }
}

}  // namespace

int study_command(int argc, char** argv, const Communicator& comm)
{
    CLI::App cli{"Refinement study of a deck: runs it and N-1 uniformly h-refined versions (every knot span halved\n"
                 "per level), estimates each quantity's discretization error by Richardson extrapolation and writes\n"
                 "<deck>_study.csv (and <deck>_study.png) beside the deck; the runs go to <deck>_study/.",
                 "igacontact study"};
    std::string deck_path;
    std::vector<std::string> overrides;
    int n_levels = 3, jobs = 1;
    bool quiet = false;
    cli.add_option("deck", deck_path, "deck file (YAML)")->required();
    cli.add_option("--levels", n_levels, "refinement levels 0..N-1 (level k halves every span k times)")
        ->capture_default_str()
        ->check(CLI::Range(1, 8));
    cli.add_option("--jobs", jobs, "levels run at once, as far as the memory estimate allows")
        ->capture_default_str()
        ->check(CLI::Range(1, 64));
    cli.add_option("--set", overrides, "override a deck value, PATH=VALUE; repeatable")->allow_extra_args(false);
    cli.add_flag("-q,--quiet", quiet, "print only the table and errors");
    if (const int code = parse_command_line(cli, argc, argv); code >= 0)
        return code;
    if (comm.parallel())
        throw UsageError(fmt::format("study under mpirun: each of the {} ranks would run every level and write the "
                                     "same files. Run 'igacontact study' without mpirun",
                                     comm.size()));
    require_rereadable_deck(deck_path, fmt::format("the study and each of its {} level(s)", n_levels));

    // Bad input is found here, before any level runs (exit 2).
    const io::Deck deck = io::read_deck(deck_path, overrides);
    if (deck.solver.backend == io::SolverBackend::petsc) {
        try {
            checked_environment_options();  // each level would refuse PETSC_OPTIONS alike, into its log
        } catch (const PetscOptionsError& e) {
            throw DeckError(e.environment_issue());
        }
    }
    const fs::path deck_file(deck_path);
    const fs::path folder = deck_file.parent_path();
    const std::string stem = deck_file.stem().string();
    const fs::path study_dir = folder / (stem + "_study");
    const fs::path csv = folder / (stem + "_study.csv");
    const fs::path png = folder / (stem + "_study.png");
    check_study_paths(csv, png, study_dir, n_levels);

    const double memory = analysis::machine_limits().memory_bytes;
    const double budget = memory > 0 ? 0.5 * memory : 0.0;  // the estimate is a lower bound: keep half free
    std::vector<Level> levels = planned_levels(deck, study_dir, n_levels);

    const std::string exe = self_executable();
    install_interrupt_handler();
    auto say = [&](const std::string& line) {
        if (!quiet)
            std::cerr << line << '\n';
    };
    say(fmt::format("study: {} level(s) of {}, up to {} at once; runs in {}", n_levels, deck_path, jobs,
                    study_dir.string()));

    run_levels(levels, exe, deck_path, overrides, jobs, budget, say);

    int formal_order = 0;
    bool with_reference = false;
    const std::vector<analysis::StudyLevel> completed = read_levels(levels, formal_order, with_reference);
    int n_failed = 0;
    for (const Level& l : levels)
        if (l.outcome != "completed")
            ++n_failed;
    if (n_failed > 0) {
        std::string list;
        for (const Level& l : levels)
            if (l.outcome != "completed")
                list += fmt::format("{}{} ({})", list.empty() ? "" : ", ", l.index, l.outcome);
        std::cerr << "study: level(s) left out of the table: " << list << '\n';
    }
    if (completed.empty()) {
        std::cerr << "study: no level completed; nothing written\n";
        return exit_failed;
    }
    formal_order = std::max(formal_order, 1);
    const std::vector<io::StudyRow> rows = analysis::study_rows(completed, formal_order);
    io::write_study_csv(csv.string(), rows, with_reference);
    print_table(rows, with_reference, formal_order);
    std::cout << fmt::format("\nRichardson from the finest consecutive levels; formal order {} (the lowest degree of "
                             "the patches), assumed where the levels show none. +- is Roache's grid convergence "
                             "index of the extrapolated value; asym. says whether the three levels ending at a level "
                             "show the formal order (within 10 %).\n",
                             formal_order);
    std::cout << "table: " << csv.string() << '\n';

    draw_plot(csv, png, folder / fmt::format("{}_study.tmp-{}.png", stem, ::getpid()));
    return n_failed == 0 ? exit_ok : exit_failed;
}

}  // namespace iga::app
