// `igacontact study DECK [--levels N] [--jobs J] [--set PATH=VALUE]... [-q]`:
// a uniform h-refinement study of any deck (README "Refinement study").
//
// Level k is an ordinary run of the same executable (/proc/self/exe) with
// `--refine-levels k -o <deck>_study/level<k>.h5 -q` and the same --set values,
// its output in <deck>_study/level<k>.log. Up to --jobs levels run at once, a
// level starting only while the estimated memory of the running levels fits in
// half the machine's memory (analysis/size_estimate.hpp, times 2^(d k)). Each
// child runs in its own process group, so a Ctrl-C reaches only this process,
// which passes one SIGINT on to the running levels (they stop after their current
// increment, as a run does), starts no more, and still writes the table of the
// levels that completed. A second Ctrl-C passes a second SIGINT on (the levels
// then end at once). A failed level is reported, not fatal.
//
// Writes <deck>_study.csv beside the deck (io/study_csv.hpp), prints the table,
// and draws <deck>_study.png with scripts/plot_study.py (Debian's python3 with
// matplotlib) when it can; else it says how to draw it.

#include "commands.hpp"

#include "analysis/refinement_study.hpp"
#include "analysis/size_estimate.hpp"
#include "io/deck_reader.hpp"
#include "io/study_csv.hpp"
#include "io/study_results.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
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

std::string last_line(const fs::path& file)
{
    std::ifstream in(file);
    std::string line, last;
    while (std::getline(in, line))
        if (!line.empty())
            last = line;
    return last;
}

/// Starts `exe args...` in its own process group, stdin from /dev/null, stdout and
/// stderr to `log`. Returns the pid, or -1 with errno set.
pid_t spawn(const std::string& exe, const std::vector<std::string>& args, const fs::path& log)
{
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    posix_spawnattr_setpgroup(&attributes, 0);
    // The child starts with default signal handling, whatever this process installed.
    sigset_t defaults;
    sigemptyset(&defaults);
    sigaddset(&defaults, SIGINT);
    sigaddset(&defaults, SIGTERM);
    posix_spawnattr_setsigdefault(&attributes, &defaults);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGDEF);
    std::vector<char*> argv;
    std::vector<std::string> all = args;
    all.insert(all.begin(), exe);
    for (std::string& a : all)
        argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = -1;
    const int rc = posix_spawn(&pid, exe.c_str(), &actions, &attributes, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
    if (rc != 0) {
        errno = rc;
        return -1;
    }
    return pid;
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

/// The table on stdout: one block per quantity.
void print_table(const std::vector<io::StudyRow>& rows, bool with_reference)
{
    std::string current;
    for (const io::StudyRow& r : rows) {
        if (r.quantity != current) {
            current = r.quantity;
            std::cout << fmt::format("\n{}  (extrapolated {}, observed order {})\n", r.quantity,
                                     cell(r.extrapolated, "{:.8g}"), cell(r.observed_order, "{:.2f}"));
            std::cout << fmt::format("  {:>5} {:>9} {:>9} {:>16} {:>10}", "level", "dofs", "wall s", "value",
                                     "est. err");
            std::cout << (with_reference ? fmt::format(" {:>10}\n", "true err") : "\n");
        }
        std::cout << fmt::format("  {:>5} {:>9} {:>9.3g} {:>16.9g} {:>10}", r.level, r.dofs, r.wall_s, r.value,
                                 cell(r.estimated_rel_error, "{:.2e}"));
        std::cout << (with_reference ? fmt::format(" {:>10}\n", cell(r.true_rel_error, "{:.2e}")) : "\n");
    }
}

}  // namespace

int study_command(int argc, char** argv)
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

    // Bad input is found here, before any level runs (exit 2).
    const io::Deck deck = io::read_deck(deck_path, overrides);
    const fs::path deck_file(deck_path);
    const fs::path folder = deck_file.parent_path();
    const std::string stem = deck_file.stem().string();
    const fs::path study_dir = folder / (stem + "_study");
    const fs::path csv = folder / (stem + "_study.csv");
    const fs::path png = folder / (stem + "_study.png");
    std::error_code ec;
    fs::create_directories(study_dir, ec);
    if (ec)
        throw UsageError("cannot create " + study_dir.string() + ": " + ec.message());

    const double level0_bytes = analysis::estimate_size(deck).bytes;
    const double memory = analysis::machine_memory_bytes();
    const double budget = memory > 0 ? 0.5 * memory : 0.0;  // the estimate is a lower bound: keep half free
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

    const std::string exe = self_executable();
    install_interrupt_handler();
    auto say = [&](const std::string& line) {
        if (!quiet)
            std::cerr << line << '\n';
    };
    say(fmt::format("study: {} level(s) of {}, up to {} at once; runs in {}", n_levels, deck_path, jobs,
                    study_dir.string()));

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
                std::vector<std::string> args = {deck_path, "--refine-levels", std::to_string(l.index), "-o",
                                                 l.results.string(), "-q"};
                for (const std::string& o : overrides) {
                    args.push_back("--set");
                    args.push_back(o);
                }
                l.start = std::chrono::steady_clock::now();
                l.pid = spawn(exe, args, l.log);
                if (l.pid < 0) {
                    l.outcome = "failed";
                    l.message = std::string("cannot start ") + exe + ": " + std::strerror(errno);
                } else {
                    running.push_back(next);
                    say(fmt::format("study: level {} started (estimated memory {:.3g} MB)", l.index,
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
            l.message = exited ? last_line(l.log) : fmt::format("killed by signal {}", WTERMSIG(status));
        }
        say(fmt::format("study: level {} {} in {:.3g} s{}", l.index, l.outcome, l.wall_s,
                        l.message.empty() ? "" : ": " + l.message));
    }

    // Read the completed levels.
    std::vector<analysis::StudyLevel> completed;
    int assumed_order = 0;
    bool with_reference = false;
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
        assumed_order = assumed_order == 0 ? r.min_degree : std::min(assumed_order, r.min_degree);
        with_reference = with_reference || !r.reference_values.empty();
        completed.push_back({l.index, r.dofs, l.wall_s, std::move(r.quantities), std::move(r.reference_values)});
    }
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
    assumed_order = std::max(assumed_order, 1);
    const std::vector<io::StudyRow> rows = analysis::study_rows(completed, assumed_order);
    io::write_study_csv(csv.string(), rows, with_reference);
    print_table(rows, with_reference);
    std::cout << fmt::format("\nRichardson from the finest consecutive levels; where no order is observed, order {} "
                             "is assumed (the lowest degree of the patches).\n",
                             assumed_order);
    std::cout << "table: " << csv.string() << '\n';

    // The plot: scripts/plot_study.py with Debian's python3 (numpy, matplotlib).
    const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
    const auto script = plot_script();
    const std::string command = fmt::format("{} {} {} {}", python, script ? shell_quote(script->string())
                                                                                : std::string("scripts/plot_study.py"),
                                            shell_quote(csv.string()), shell_quote(png.string()));
    if (script && std::system((command + " > /dev/null 2>&1").c_str()) == 0) {
        std::cout << "plot: " << png.string() << '\n';
    } else {
        std::cerr << "warning: study: no plot written (needs python3 with matplotlib); draw it with:\n  " << command
                  << '\n';
    }
    return n_failed == 0 ? exit_ok : exit_failed;
}

}  // namespace iga::app
