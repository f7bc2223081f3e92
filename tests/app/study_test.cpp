// `igacontact study` on the built executable: a tiny Hertz deck in three levels
// writes <deck>_study.csv with the documented columns and sane values; a bad
// deck is exit 2 with nothing written; Ctrl-C (SIGINT) stops the running level
// and still writes the table of the levels that finished.

#include "cli_support.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace iga::test {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

fs::path scratch_dir(const std::string& name)
{
    const fs::path dir = fs::path(IGA_BINARY_DIR) / "test_scratch" / "app" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

// A quarter cylinder (R = 1) on a rigid floor, degree 2, 16 x 4 spans at level 0:
// three levels run in about a second.
const std::string tiny_hertz = R"(format: 1
analysis: {dimension: 2, plane: strain, kinematics: small}
materials:
  - {name: rubber, model: linear_elastic, E: 1000.0, nu: 0.3}
bodies:
  - name: cylinder
    material: rubber
    shape: {type: quarter_disc, center: [0.0, 1.0], radius: 1.0}
    refine: {elevate: [0, 1], spans: [16, 4]}
  - name: floor
    rigid: {plane: {point: [0.0, 0.0], normal: [0.0, 1.0]}}
constraints:
  - {body: cylinder, side: u0, fix: [x]}
loads:
  - {body: cylinder, side: v1, force: [0.0, -5.0]}
contact:
  - {name: cyl_floor, between: [cylinder.v0, floor], penalty: 1.0e5}
output:
  reference: {pair: cyl_floor, type: hertz_cylinder_plane, radius: 1.0, force: 10.0}
)";

std::vector<std::vector<std::string>> read_csv(const fs::path& path)
{
    std::vector<std::vector<std::string>> rows;
    std::istringstream in(read_text(path));
    for (std::string line; std::getline(in, line);) {
        std::vector<std::string> fields;
        std::string field;
        std::istringstream fs(line);
        while (std::getline(fs, field, ','))
            fields.push_back(field);
        if (!line.empty() && line.back() == ',')
            fields.emplace_back();
        rows.push_back(fields);
    }
    return rows;
}

double number(const std::string& s)
{
    try {
        return std::stod(s);
    } catch (...) {
        return std::nan("");
    }
}

TEST(Study, TinyHertzWritesTheDocumentedCsv)
{
    const fs::path dir = scratch_dir("study_tiny");
    const fs::path deck = dir / "tiny.yaml";
    std::ofstream(deck) << tiny_hertz;
    const CliResult r = run_cli("study " + shell_quote(deck.string()) + " --levels 3 -q", dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto rows = read_csv(dir / "tiny_study.csv");
    ASSERT_FALSE(rows.empty());
    // The spec's columns, then the true-error columns (the deck has a reference), then
    // the band and the flags of the estimate.
    EXPECT_EQ(rows[0], (std::vector<std::string>{"level", "dofs", "wall_s", "quantity", "value", "extrapolated",
                                                 "observed_order", "estimated_rel_error", "reference_value",
                                                 "true_rel_error", "extrapolated_rel_band", "asymptotic",
                                                 "estimate"}));
    std::map<std::string, std::vector<std::vector<std::string>>> by_quantity;
    for (std::size_t i = 1; i < rows.size(); ++i) {
        ASSERT_EQ(rows[i].size(), 13u) << "row " << i;
        by_quantity[rows[i][3]].push_back(rows[i]);
    }
    for (const char* q : {"normal_force:cyl_floor:cylinder.v0", "peak_pressure:cyl_floor:cylinder.v0",
                          "max_penetration:cyl_floor"}) {
        SCOPED_TRACE(q);
        const auto& levels = by_quantity[q];
        ASSERT_EQ(levels.size(), 3u);
        for (int k = 0; k < 3; ++k) {
            EXPECT_EQ(levels[static_cast<std::size_t>(k)][0], std::to_string(k));
            EXPECT_GT(number(levels[static_cast<std::size_t>(k)][2]), 0.0);  // wall_s
            EXPECT_TRUE(std::isfinite(number(levels[static_cast<std::size_t>(k)][4])));
            EXPECT_TRUE(std::isfinite(number(levels[static_cast<std::size_t>(k)][7])));  // estimated error
        }
        // Every level halves every span: about 2^2 times the dofs of the one before.
        for (int k = 1; k < 3; ++k)
            EXPECT_GT(number(levels[static_cast<std::size_t>(k)][1]), 2.5 * number(levels[static_cast<std::size_t>(k) - 1][1]));
    }
    // The contact force balances the applied load (force control) at every level.
    constexpr double equilibrium = 1e-8;  // Newton tolerance 1e-10 on a residual of order 5
    for (const auto& row : by_quantity["normal_force:cyl_floor:cylinder.v0"])
        EXPECT_TRUE(near(number(row[4]), 5.0, equilibrium));
    // The peak pressure converges: the estimated error shrinks level by level, the
    // observed order lies between 0.5 and 3 (contact limits it below the degree's),
    // and the true error against Hertz is filled in (p0 = 59.143).
    const auto& peak = by_quantity["peak_pressure:cyl_floor:cylinder.v0"];
    EXPECT_GT(number(peak[0][7]), number(peak[1][7]));
    EXPECT_GT(number(peak[1][7]), number(peak[2][7]));
    const double order = number(peak[0][6]);
    EXPECT_TRUE(std::isfinite(order) && order > 0.5 && order < 3.0) << order;
    // An observed order: the band is Roache's GCI with Fs = 1.25, |q_2 - q_extr| 1.25 times
    // over (q_2's estimated error); the finest level says whether the order is the formal 2.
    const double band = number(peak[0][10]);
    constexpr double csv_digits = 1e-9;  // both written with 10 significant digits
    EXPECT_TRUE(near_rel(band, 1.25 * number(peak[2][7]), csv_digits));
    EXPECT_TRUE(peak[0][12] == "asymptotic" || peak[0][12] == "not_asymptotic") << peak[0][12];
    EXPECT_EQ(peak[0][11], "");
    EXPECT_EQ(peak[1][11], "");
    EXPECT_EQ(peak[2][11], std::fabs(order - 2.0) <= 0.2 ? "1" : "0");
    constexpr double hertz_p0_digits = 1e-4;  // p0 = 59.1431... printed with 10 digits
    EXPECT_TRUE(near_rel(number(peak[0][8]), 59.1431, hertz_p0_digits));
    EXPECT_TRUE(std::isfinite(number(peak[0][9])));
    // Issue 32: the quantities users refine for. The half-width against Hertz (a = 0.1076
    // for F = 10 on R = 1, E* = 1098.9), the length in contact and the pressure's L2 error
    // at every level; the half-width's true error is formed, the L2 error's is not (0).
    const auto& half_width = by_quantity["half_width:cyl_floor:cylinder.v0"];
    ASSERT_EQ(half_width.size(), 3u);
    constexpr double hertz_a_digits = 1e-3;  // a = 2 sqrt(F R / (pi E*)) = 0.107640...
    EXPECT_TRUE(near_rel(number(half_width[0][8]), 0.10764, hertz_a_digits)) << half_width[0][8];
    // 16 spans on a quarter circle put about one span across the zone at level 0: the
    // half-width is resolved to a span, and its true error shrinks level by level.
    EXPECT_GT(std::fabs(number(half_width[0][9])), std::fabs(number(half_width[1][9])));
    EXPECT_GT(std::fabs(number(half_width[1][9])), std::fabs(number(half_width[2][9])));
    ASSERT_EQ(by_quantity["contact_area:cyl_floor:cylinder.v0"].size(), 3u);
    const auto& l2 = by_quantity["pressure_l2_error:cyl_floor:cylinder.v0"];
    ASSERT_EQ(l2.size(), 3u);
    for (const auto& row : l2) {
        EXPECT_GT(number(row[4]), 0.0);
        EXPECT_EQ(row[9], "") << "no relative error of an error";
    }
    // The symmetry side's reaction is round-off: left out. The levels' files are in <deck>_study/.
    EXPECT_EQ(by_quantity.count("reaction:cylinder.u0:x"), 0u);
    for (int k = 0; k < 3; ++k) {
        EXPECT_TRUE(fs::exists(dir / "tiny_study" / ("level" + std::to_string(k) + ".h5")));
        // The level's log keeps the run's own output (stderr and stdout).
        const std::string log = read_text(dir / "tiny_study" / ("level" + std::to_string(k) + ".log"));
        EXPECT_NE(log.find("igacontact: completed"), std::string::npos) << "level " << k << " log: " << log;
    }
    EXPECT_FALSE(fs::exists(dir / "tiny.h5")) << "the deck's own results file is never written";
}

TEST(Study, BadDeckIsExit2AndWritesNothing)
{
    const fs::path dir = scratch_dir("study_bad");
    const fs::path deck = dir / "bad.yaml";
    std::ofstream(deck) << tiny_hertz;
    const CliResult r =
        run_cli("study " + shell_quote(deck.string()) + " --set contact.cyl_floor.penalti=1 --levels 2", dir);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("did you mean 'penalty'"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "bad_study"));
    EXPECT_FALSE(fs::exists(dir / "bad_study.csv"));
}

// Issue 32: the study wrote its level logs and its plot through whatever was at their
// paths: a log or png hard-linked to the deck emptied the deck or turned it into a PNG.
// Each is written new; the other name keeps its contents.
TEST(Study, HardLinksAtItsPathsKeepTheDeck)
{
    const fs::path dir = scratch_dir("study_hard_links");
    const fs::path deck = dir / "tiny.yaml";
    std::ofstream(deck) << tiny_hertz;
    fs::create_directories(dir / "tiny_study");
    fs::create_hard_link(deck, dir / "tiny_study" / "level0.log");
    fs::create_hard_link(deck, dir / "tiny_study.png");
    const CliResult r = run_cli("study " + shell_quote(deck.string()) + " --levels 2 -q", dir);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(read_text(deck), tiny_hertz) << "the deck changed";
    EXPECT_NE(read_text(dir / "tiny_study" / "level0.log"), tiny_hertz) << "level 0 wrote no log of its own";
}

// Issue 32: `study` of a FIFO hung (the study read the deck, each level waited for
// another writer). A deck that can be read only once is refused before anything runs.
TEST(Study, ADeckThatCanBeReadOnlyOnceIsRefused)
{
    const fs::path dir = scratch_dir("study_fifo");
    const fs::path fifo = dir / "deck.yaml";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    // No writer: a study that opens the FIFO waits; timeout ends it (exit 124).
    const std::string command = "timeout 30 " + shell_quote(cli_path()) + " study " + shell_quote(fifo.string()) +
                                " > /dev/null 2> " + shell_quote((dir / "err.txt").string());
    const int status = std::system(command.c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 2) << read_text(dir / "err.txt");
    EXPECT_NE(read_text(dir / "err.txt").find("not a regular file"), std::string::npos) << read_text(dir / "err.txt");
    EXPECT_FALSE(fs::exists(dir / "deck_study"));
}

TEST(Study, SigintKeepsTheFinishedLevels)
{
    // The block stretch with 400 increments: levels 0..2 take about 0.4, 0.9 and
    // 2.5 s, level 3 about four times level 2: the signal arrives while level 3 runs.
    const fs::path dir = scratch_dir("study_sigint");
    const fs::path deck = dir / "stretch.yaml";
    fs::copy_file(std::string(IGA_SOURCE_DIR) + "/inputs/block_stretch_finite_2d.yaml", deck);
    const fs::path err = dir / "stderr.txt";
    const pid_t pid = ::fork();
    if (pid == 0) {
        if (!std::freopen(err.c_str(), "w", stderr) || !std::freopen((dir / "stdout.txt").c_str(), "w", stdout))
            ::_exit(126);
        const std::string exe = cli_path(), deck_arg = deck.string();
        ::execl(exe.c_str(), exe.c_str(), "study", deck_arg.c_str(), "--levels", "4", "--set", "steps.count=400",
                "--set", "steps.adaptive=false", static_cast<char*>(nullptr));
        ::_exit(127);
    }
    ASSERT_GT(pid, 0);
    // Wait until levels 0..2 have finished (the log says so) and level 3 has started.
    const auto deadline = std::chrono::steady_clock::now() + 120s;
    bool last_level_running = false;
    while (std::chrono::steady_clock::now() < deadline && !last_level_running) {
        last_level_running = read_text(err).find("level 3 started") != std::string::npos;
        std::this_thread::sleep_for(20ms);
    }
    ASSERT_TRUE(last_level_running) << read_text(err);
    // ... and has opened its results file (the level-3 file under a temporary name until
    // it ends): a signal during its set-up would leave no file at all, and on a loaded
    // machine the set-up takes longer than any fixed wait.
    auto level3_file_open = [&] {
        std::error_code ec;
        for (const auto& entry : fs::directory_iterator(dir / "stretch_study", ec))
            if (entry.path().filename().string().rfind("level3.h5", 0) == 0)
                return true;
        return false;
    };
    while (std::chrono::steady_clock::now() < deadline && !level3_file_open())
        std::this_thread::sleep_for(20ms);
    std::this_thread::sleep_for(200ms);
    ::kill(pid, SIGINT);
    int status = 0;
    bool ended = false;
    const auto stop_deadline = std::chrono::steady_clock::now() + 60s;
    while (std::chrono::steady_clock::now() < stop_deadline) {
        if (::waitpid(pid, &status, WNOHANG) == pid) {
            ended = true;
            break;
        }
        std::this_thread::sleep_for(20ms);
    }
    if (!ended) {
        ::kill(pid, SIGKILL);
        ::waitpid(pid, nullptr, 0);
    }
    ASSERT_TRUE(ended) << "the study did not stop after SIGINT:\n" << read_text(err);
    ASSERT_TRUE(WIFEXITED(status));
    const std::string log = read_text(err);
    if (log.find("level 3 completed") != std::string::npos)
        GTEST_SKIP() << "level 3 finished before the signal arrived (a very fast machine)";
    EXPECT_EQ(WEXITSTATUS(status), 1) << log;
    EXPECT_NE(log.find("level 3 interrupted"), std::string::npos) << log;
    // The table holds the finished levels 0..2 only; the interrupted level left a
    // readable results file of its own (as any interrupted run does).
    const auto rows = read_csv(dir / "stretch_study.csv");
    ASSERT_GE(rows.size(), 4u) << log;
    for (std::size_t i = 1; i < rows.size(); ++i)
        EXPECT_TRUE(rows[i][0] == "0" || rows[i][0] == "1" || rows[i][0] == "2") << rows[i][0];
    EXPECT_TRUE(fs::exists(dir / "stretch_study" / "level3.h5"));
}

/// True while `pid` runs: it exists and is not a zombie (a dead child not yet reaped).
bool running(pid_t pid)
{
    std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
    std::string line;
    if (!std::getline(stat, line))
        return false;
    const auto paren = line.rfind(')');  // "pid (name) S ...": the state follows the name
    return paren != std::string::npos && paren + 2 < line.size() && line[paren + 2] != 'Z';
}

TEST(Study, LevelsDieWithAKilledStudy)
{
    // SIGKILL cannot be caught or passed on: the running level must still end with
    // the study (its own process group keeps it from the terminal's Ctrl-C, so
    // nothing else would stop it). 100000 increments keep level 0 busy for minutes.
    const fs::path dir = scratch_dir("study_sigkill");
    const fs::path deck = dir / "stretch.yaml";
    fs::copy_file(std::string(IGA_SOURCE_DIR) + "/inputs/block_stretch_finite_2d.yaml", deck);
    const fs::path err = dir / "stderr.txt";
    const pid_t study = ::fork();
    if (study == 0) {
        if (!std::freopen(err.c_str(), "w", stderr) || !std::freopen((dir / "stdout.txt").c_str(), "w", stdout))
            ::_exit(126);
        const std::string exe = cli_path(), deck_arg = deck.string();
        ::execl(exe.c_str(), exe.c_str(), "study", deck_arg.c_str(), "--levels", "1", "--set", "steps.count=100000",
                "--set", "steps.adaptive=false", static_cast<char*>(nullptr));
        ::_exit(127);
    }
    ASSERT_GT(study, 0);
    const std::string started = "level 0 started (pid ";
    const auto deadline = std::chrono::steady_clock::now() + 60s;
    std::string log;
    while (std::chrono::steady_clock::now() < deadline && log.find(started) == std::string::npos) {
        std::this_thread::sleep_for(20ms);
        log = read_text(err);
    }
    const auto at = log.find(started);
    const pid_t level = at == std::string::npos ? -1 : std::atoi(log.c_str() + at + started.size());
    ::kill(study, SIGKILL);
    ::waitpid(study, nullptr, 0);
    ASSERT_GT(level, 0) << log;
    constexpr auto grace = 5s;  // the kernel signals at once; this only absorbs a loaded machine
    const auto until = std::chrono::steady_clock::now() + grace;
    while (running(level) && std::chrono::steady_clock::now() < until)
        std::this_thread::sleep_for(20ms);
    const bool survived = running(level);
    if (survived)
        ::kill(level, SIGKILL);  // leave nothing running
    EXPECT_FALSE(survived) << "level 0 (pid " << level << ") kept running after the study was killed";
}

}  // namespace
}  // namespace iga::test
