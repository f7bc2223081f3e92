// Tests of io::compare_results, the engine of `igacontact compare`: identical
// files agree; perturbations beyond rtol/atol, missing items and shape or type
// changes are reported with the right path and size; volatile items and `only`
// restrict what is compared; NaN matches only NaN.

#include "io/h5_file.hpp"
#include "io/results_compare.hpp"
#include "io/results_writer.hpp"

#include "core/error.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <thread>

namespace iga::io {
namespace {

namespace fs = std::filesystem;
using Kind = CompareEntry::Kind;

// A differences |a - b| computed from a and a(1 + r) carries a rounding error of a few eps|a|.
constexpr double difference_rounding = 1e-12;

// Everything one run writes, so a test can change one piece before writing.
struct SampleRun {
    std::string version = "0.1.0";
    std::string deck = "format: 1\nanalysis:\n  dimension: 2\ncontact:\n  penalty: 1e6\n";
    std::vector<BodyGeometry> bodies;
    std::vector<StepData> steps;
    std::vector<HistoryRow> history;
    RunSummary summary;
};

RowMatrix ramp(Index rows, Index cols, double offset)
{
    RowMatrix m(rows, cols);
    for (Index i = 0; i < rows; ++i)
        for (Index j = 0; j < cols; ++j)
            m(i, j) = offset + 1.5 * static_cast<double>(i) - 0.75 * static_cast<double>(j);
    return m;
}

SampleRun sample_run()
{
    SampleRun run;
    BodyGeometry body;
    body.name = "cylinder";
    body.degrees = {2, 1};
    body.knots = {{0, 0, 0, 1, 1, 1}, {0, 0, 1, 1}};
    body.control_points = ramp(6, 3, 1.0);
    run.bodies = {body};
    for (int k = 1; k <= 2; ++k) {
        StepData step;
        step.index = k;
        step.load_factor = 0.5 * k;
        step.newton_iterations = 3 + k;
        step.residual_norm = 1e-11;
        step.wall_s = 0.01 * k;
        step.displacement = {{"cylinder", ramp(6, 2, 10.0 * k)}};
        ContactSideResult side;
        side.side_name = "cylinder.v0";
        side.normal_force = 100.0 * k;
        GaussPointData& gauss = side.gauss_points;
        gauss.coordinates = ramp(4, 2, 0.0);
        gauss.reference_coordinates = ramp(4, 2, 0.1);
        gauss.parameter = ramp(4, 1, 0.0);
        gauss.gap = Vector::LinSpaced(4, -1e-3, 1e-3);
        gauss.pressure = Vector::LinSpaced(4, 0.0, 1e3);
        gauss.weight = Vector::Constant(4, 0.25);
        PostProcessedData& post = side.postprocessed;
        post.control_point_pressure = Vector::LinSpaced(3, 1.0, 3.0);
        post.coordinates = ramp(5, 2, 2.0);
        post.reference_coordinates = ramp(5, 2, 2.5);
        post.pressure = Vector::LinSpaced(5, 0.0, 4.0);
        ContactPairResult pair;
        pair.name = "cyl_floor";
        pair.sides = {side};
        pair.obstacle_force = {0.0, -100.0 * k};
        step.contact = {pair};
        step.reactions = {{"cylinder.v1", {0.5 * k, 100.0 * k}},
                          {"total/cylinder", {0.5 * k, 100.0 * k}},
                          {"items/0", {0.5 * k, 100.0 * k}}};
        step.fields = {BodyFields{.body = "cylinder", .reference_coordinates = ramp(3, 2, 0.0),
                                  .displacement = ramp(3, 2, 1.0 * k), .stress = ramp(3, 6, 5.0 * k),
                                  .von_mises = Vector::LinSpaced(3, 1.0, 3.0 * k)}};
        run.steps.push_back(step);
        run.history.push_back(HistoryRow{.load_factor = 0.5 * k,
                                         .reactions = step.reactions,
                                         .contact = {{"cyl_floor", "cylinder.v0", 100.0 * k, 1e-3 * k, {0.0, 0.0}, 0.0}}});
    }
    run.summary.status = "completed";
    run.summary.warnings = "contact pair cyl_floor: penalty is large";
    run.summary.timings = {{"total", 2.0}, {"assembly", 1.0}};
    run.summary.counters = {{"projections", 40}, {"search_s", 3}};
    run.summary.convergence = ramp(7, 4, 0.0);
    ReferenceData reference;
    reference.pair = "cyl_floor";
    reference.type = "hertz_cylinder_plane";
    reference.a = 0.1;
    reference.p0 = 2e6;
    reference.errors = {{"peak", 0.01}};
    reference.coordinates = ramp(8, 2, 0.0);
    reference.x = Vector::LinSpaced(8, -1.0, 1.0);
    reference.pressure = Vector::LinSpaced(8, 0.0, 7.0);
    run.summary.references = {reference};
    return run;
}

void write_run(const SampleRun& run, const std::string& path)
{
    ResultsWriter writer(path, run.version, run.deck);
    writer.write_bodies(run.bodies);
    for (const HistoryRow& row : run.history)
        writer.append_history(row);
    for (const StepData& step : run.steps)
        writer.write_step(step);
    writer.finish(run.summary);
}

// CompareOptions with some fields changed (GCC 12 warns on partial designated initializers).
CompareOptions tolerances(double rtol, double atol)
{
    CompareOptions options;
    options.rtol = rtol;
    options.atol = atol;
    return options;
}

CompareOptions only(std::vector<std::string> prefixes)
{
    CompareOptions options;
    options.only = std::move(prefixes);
    return options;
}

CompareOptions with_volatile()
{
    CompareOptions options;
    options.include_volatile = true;
    return options;
}

const CompareEntry* find_entry(const CompareReport& report, const std::string& path)
{
    const auto it = std::find_if(report.entries.begin(), report.entries.end(),
                                 [&](const CompareEntry& e) { return e.path == path; });
    return it == report.entries.end() ? nullptr : &*it;
}

std::vector<std::string> paths_not_same(const CompareReport& report)
{
    std::vector<std::string> paths;
    for (const CompareEntry& e : report.entries)
        if (e.kind != Kind::same)
            paths.push_back(e.path);
    std::sort(paths.begin(), paths.end());
    return paths;
}

class ResultsCompareTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        folder_ = fs::temp_directory_path() /
                  ("igacontact_compare_" + std::to_string(::getpid()) + "_" + info->name());
        fs::remove_all(folder_);
        fs::create_directories(folder_);
        write_run(sample_run(), reference_path());
    }
    void TearDown() override { fs::remove_all(folder_); }

    std::string reference_path() const { return (folder_ / "reference.h5").string(); }
    std::string path(const std::string& name) const { return (folder_ / name).string(); }

    // Writes the sample run changed by `change` and compares it with the reference.
    CompareReport compare_changed(const std::function<void(SampleRun&)>& change, const CompareOptions& options = {})
    {
        SampleRun run = sample_run();
        change(run);
        write_run(run, path("new.h5"));
        return compare_results(reference_path(), path("new.h5"), options);
    }

    fs::path folder_;
};

TEST_F(ResultsCompareTest, IdenticalRunsAreTheSame)
{
    write_run(sample_run(), path("new.h5"));
    const CompareReport report = compare_results(reference_path(), path("new.h5"), {});
    EXPECT_TRUE(report.same()) << format_report(report, false);
    EXPECT_EQ(report.n_different, 0);
    EXPECT_EQ(report.n_missing, 0);
    // Root attributes, deck, body, 2 x (step attributes, displacement, side datasets), convergence,
    // reference: well over 40 items, and /results repeats the last step.
    EXPECT_GT(report.n_compared, 40);
    EXPECT_NE(find_entry(report, "/@status"), nullptr);
    EXPECT_NE(find_entry(report, "/results/displacement/cylinder"), nullptr);
    EXPECT_NE(find_entry(report, "/steps/0002/contact/cyl_floor/cylinder.v0@normal_force"), nullptr);
    EXPECT_EQ(find_entry(report, "/timings@total"), nullptr) << "timings are volatile";
}

TEST_F(ResultsCompareTest, PerturbationBeyondRtolIsDifferent)
{
    const double original = sample_run().steps[1].displacement[0].second(3, 1);
    constexpr double relative_change = 1e-3;  // a thousand times the default rtol of 1e-6
    const CompareReport report = compare_changed([&](SampleRun& run) {
        run.steps[1].displacement[0].second(3, 1) = original * (1 + relative_change);
    });
    EXPECT_FALSE(report.same());
    // The step and the /results link to it: two entries, nothing else.
    EXPECT_EQ(paths_not_same(report),
              (std::vector<std::string>{"/results/displacement/cylinder", "/steps/0002/displacement/cylinder"}));
    EXPECT_EQ(report.n_different, 2);
    const CompareEntry* entry = find_entry(report, "/steps/0002/displacement/cylinder");
    ASSERT_NE(entry, nullptr);
    EXPECT_EQ(entry->kind, Kind::different);
    EXPECT_TRUE(entry->numeric);
    EXPECT_TRUE(test::near_rel(entry->max_abs, std::abs(original) * relative_change, difference_rounding));
    EXPECT_TRUE(test::near_rel(entry->max_rel, relative_change, difference_rounding));
    EXPECT_NE(entry->detail.find("1 of 12 values"), std::string::npos) << entry->detail;
}

TEST_F(ResultsCompareTest, PerturbationWithinRtolIsTheSame)
{
    constexpr double relative_change = 1e-9;  // a thousandth of the default rtol of 1e-6
    const CompareReport report = compare_changed([&](SampleRun& run) {
        run.steps[1].displacement[0].second *= 1 + relative_change;
        run.summary.references[0].pressure *= 1 + relative_change;
    });
    EXPECT_TRUE(report.same()) << format_report(report, false);
    const CompareEntry* entry = find_entry(report, "/steps/0002/displacement/cylinder");
    ASSERT_NE(entry, nullptr);
    EXPECT_EQ(entry->kind, Kind::same);
    EXPECT_GT(entry->max_rel, 0.0) << "the change is measured even when it passes";
    // The measured change of ~1e-9 carries rounding of ~1e-16 / 1e-9 = 1e-7 relative to itself.
    constexpr double measured_change_rounding = 1e-5;
    EXPECT_TRUE(test::near_rel(entry->max_rel, relative_change, measured_change_rounding));
}

TEST_F(ResultsCompareTest, TolerancesCanBeLoosenedAndTightened)
{
    const double original = sample_run().steps[1].displacement[0].second(3, 1);
    constexpr double relative_change = 1e-3;
    SampleRun run = sample_run();
    run.steps[1].displacement[0].second(3, 1) = original * (1 + relative_change);
    write_run(run, path("new.h5"));
    EXPECT_TRUE(compare_results(reference_path(), path("new.h5"), tolerances(1e-2, CompareOptions{}.atol)).same());
    EXPECT_TRUE(compare_results(reference_path(), path("new.h5"), tolerances(0, 1)).same());
    EXPECT_FALSE(compare_results(reference_path(), path("new.h5"), tolerances(1e-4, CompareOptions{}.atol)).same());
}

TEST_F(ResultsCompareTest, AbsoluteToleranceCoversValuesNearZero)
{
    // A zero reference value has max_rel = inf, so only atol decides. (/convergence, a
    // solver statistic, is compared under --all: include_volatile.)
    const CompareReport report = compare_changed(
        [](SampleRun& run) {
            run.summary.convergence(0, 0) = 1e-13;  // reference value 0: only atol (1e-12) can accept this
        },
        with_volatile());
    const CompareEntry* entry = find_entry(report, "/convergence");
    ASSERT_NE(entry, nullptr);
    EXPECT_EQ(entry->kind, Kind::same) << entry->detail;
    EXPECT_EQ(entry->max_rel, std::numeric_limits<double>::infinity());

    CompareOptions tight_options = tolerances(CompareOptions{}.rtol, 0);
    tight_options.include_volatile = true;
    const CompareReport tight = compare_results(reference_path(), path("new.h5"), tight_options);
    EXPECT_EQ(find_entry(tight, "/convergence")->kind, Kind::different);
}

TEST_F(ResultsCompareTest, MissingDatasetAndGroupAreMissing)
{
    const CompareReport report = compare_changed([](SampleRun& run) {
        run.steps[0].contact[0].sides[0].gauss_points.weight = Vector();  // optional: then not written
        run.summary.references.clear();
    });
    EXPECT_FALSE(report.same());
    EXPECT_EQ(report.n_missing, 2);
    EXPECT_EQ(report.n_different, 0);
    EXPECT_EQ(paths_not_same(report),
              (std::vector<std::string>{"/reference",
                                        "/steps/0001/contact/cyl_floor/cylinder.v0/gauss_points/weight"}));
    EXPECT_EQ(find_entry(report, "/reference")->kind, Kind::missing);
}

TEST_F(ResultsCompareTest, ExtraItemsInNewAreNotErrors)
{
    write_run(sample_run(), path("new.h5"));
    // Swap roles: the reference lacks nothing the new file has, but here the "new" one has more.
    SampleRun smaller = sample_run();
    smaller.summary.references.clear();
    write_run(smaller, path("smaller.h5"));
    EXPECT_TRUE(compare_results(path("smaller.h5"), path("new.h5"), {}).same());
    EXPECT_FALSE(compare_results(path("new.h5"), path("smaller.h5"), {}).same());
}

// Second-release items (reactions, obstacle_force, fields, /history, warnings) are
// compared like the rest, and a first-release reference, which has none of them,
// still agrees with a new file on everything it has.
TEST_F(ResultsCompareTest, SecondReleaseItemsAreCompared)
{
    write_run(sample_run(), path("new.h5"));
    const CompareReport same = compare_results(reference_path(), path("new.h5"), {});
    EXPECT_TRUE(same.same()) << format_report(same, false);
    for (const char* item : {"/@warnings", "/history/load_factor", "/history/reactions/cylinder.v1",
                             "/history/contact/cyl_floor/cylinder.v0/normal_force",
                             "/steps/0002/reactions/cylinder.v1", "/steps/0002/contact/cyl_floor@obstacle_force",
                             "/steps/0002/fields/cylinder/stress", "/steps/0002/fields/cylinder/von_mises"})
        EXPECT_NE(find_entry(same, item), nullptr) << item << " was not compared";

    constexpr double relative_change = 1e-3;  // a thousand times the default rtol of 1e-6
    const CompareReport changed = compare_changed([&](SampleRun& run) {
        run.history[1].reactions[0].force[1] *= 1 + relative_change;
        run.steps[0].fields[0].von_mises(2) *= 1 + relative_change;
    });
    EXPECT_EQ(paths_not_same(changed),
              (std::vector<std::string>{"/history/reactions/cylinder.v1", "/steps/0001/fields/cylinder/von_mises"}));
}

// Third release: the per-body totals and per-item reactions live in subgroups of
// reactions/ (steps, /results, /history) and are compared like the sides.
TEST_F(ResultsCompareTest, ReactionTotalsAndItemsAreCompared)
{
    write_run(sample_run(), path("new.h5"));
    const CompareReport same = compare_results(reference_path(), path("new.h5"), {});
    EXPECT_TRUE(same.same()) << format_report(same, false);
    for (const char* item : {"/steps/0002/reactions/total/cylinder", "/steps/0002/reactions/items/0",
                             "/history/reactions/total/cylinder", "/history/reactions/items/0"})
        EXPECT_NE(find_entry(same, item), nullptr) << item << " was not compared";

    constexpr double relative_change = 1e-3;  // a thousand times the default rtol of 1e-6
    const CompareReport changed = compare_changed([&](SampleRun& run) {
        run.steps[0].reactions[1].force[1] *= 1 + relative_change;
        run.history[1].reactions[2].force[1] *= 1 + relative_change;
    });
    EXPECT_EQ(paths_not_same(changed),
              (std::vector<std::string>{"/history/reactions/items/0", "/steps/0001/reactions/total/cylinder"}));
}

TEST_F(ResultsCompareTest, FirstReleaseReferenceAgreesOnWhatItHas)
{
    // A first-release file: no /history, no root attribute warnings, no reactions, fields or obstacle force.
    SampleRun old = sample_run();
    old.history.clear();
    for (StepData& step : old.steps) {
        step.reactions.clear();
        step.fields.clear();
        step.contact[0].obstacle_force.clear();
    }
    write_run(old, path("old.h5"));
    {
        h5::ErrorSilencer silence;
        h5::Handle file(H5Fopen(path("old.h5").c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose, "cannot open old.h5");
        ASSERT_GE(H5Ldelete(file.id(), "history", H5P_DEFAULT), 0);
        ASSERT_GE(H5Adelete(file.id(), "warnings"), 0);
    }
    write_run(sample_run(), path("new.h5"));
    const CompareReport report = compare_results(path("old.h5"), path("new.h5"), {});
    EXPECT_TRUE(report.same()) << format_report(report, false);
    EXPECT_EQ(find_entry(report, "/history"), nullptr);
    EXPECT_GT(report.n_compared, 40) << "everything else is still compared";
}

TEST_F(ResultsCompareTest, WrongShapeIsShapeMismatch)
{
    const CompareReport report = compare_changed([](SampleRun& run) {
        run.steps[0].displacement[0].second = ramp(7, 2, 10.0);  // one control point more
    });
    const CompareEntry* entry = find_entry(report, "/steps/0001/displacement/cylinder");
    ASSERT_NE(entry, nullptr);
    EXPECT_EQ(entry->kind, Kind::shape_mismatch);
    EXPECT_EQ(entry->detail, "reference (6, 2), new (7, 2)");
    EXPECT_EQ(report.n_different, 1);
}

TEST_F(ResultsCompareTest, StringsCompareExactly)
{
    CompareOptions all;
    all.include_volatile = true;  // /deck is volatile by default (its output path differs between runs)
    const CompareReport report = compare_changed(
        [](SampleRun& run) {
            run.deck.replace(run.deck.find("1e6"), 3, "1e7");
            run.summary.status = "failed";
        },
        all);
    EXPECT_EQ(paths_not_same(report), (std::vector<std::string>{"/@status", "/deck"}));
    EXPECT_EQ(find_entry(report, "/deck")->detail, "first difference at line 5: '  penalty: 1e6' vs '  penalty: 1e7'");
}

TEST_F(ResultsCompareTest, IntegersCompareExactly)
{
    // Iteration counts are solver statistics, compared under --all (include_volatile).
    const CompareReport report =
        compare_changed([](SampleRun& run) { run.steps[0].newton_iterations += 1; }, with_volatile());
    EXPECT_EQ(paths_not_same(report), (std::vector<std::string>{"/steps/0001@newton_iterations"}));
    // An integer differing by 1 in 4 (25 %) passes rtol = 1 for reals but never for integers.
    CompareOptions loose = tolerances(1.0, CompareOptions{}.atol);
    loose.include_volatile = true;
    EXPECT_FALSE(compare_results(reference_path(), path("new.h5"), loose).same());
}

TEST_F(ResultsCompareTest, VolatileItemsAreIgnoredUnlessAsked)
{
    auto change_volatile = [](SampleRun& run) {
        run.version = "9.9.9";
        run.steps[0].wall_s = 123.0;
        run.summary.timings["total"] = 99.0;
        run.summary.counters["search_s"] = 77;
    };
    const CompareReport by_default = compare_changed(change_volatile);
    EXPECT_TRUE(by_default.same()) << format_report(by_default, false);
    EXPECT_EQ(find_entry(by_default, "/@program_version"), nullptr);

    const CompareReport all_items = compare_changed(change_volatile, with_volatile());
    EXPECT_EQ(paths_not_same(all_items),
              (std::vector<std::string>{"/@program_version", "/counters@search_s", "/steps/0001@wall_s",
                                        "/timings@total"}));

}

// A serial and a parallel (or direct and iterative) run of one deck reach the same
// state by different solver paths: their counters (woodbury_updates exists only in the
// serial one) and residual histories differ, their results do not.
TEST_F(ResultsCompareTest, CountersAndSolverStatisticsAreNotResults)
{
    auto other_solver = [](SampleRun& run) {
        run.summary.counters["projections"] = 41;
        run.summary.counters.erase("search_s");
        run.summary.convergence(0, 2) *= 1.5;
        run.steps[0].residual_norm *= 3.0;
        run.steps[0].newton_iterations += 1;
        run.steps[0].cutbacks += 1;
    };
    const CompareReport by_default = compare_changed(other_solver);
    EXPECT_TRUE(by_default.same()) << format_report(by_default, false);
    const CompareReport all_items = compare_changed(other_solver, with_volatile());
    EXPECT_EQ(paths_not_same(all_items),
              (std::vector<std::string>{"/convergence", "/counters@projections", "/counters@search_s",
                                        "/steps/0001@cutbacks", "/steps/0001@newton_iterations",
                                        "/steps/0001@residual_norm"}));
    // A result still differs by default.
    const CompareReport result = compare_changed([](SampleRun& run) { run.steps[0].load_factor += 0.25; });
    EXPECT_FALSE(result.same());
}

TEST_F(ResultsCompareTest, OnlyRestrictsTheComparison)
{
    auto change = [](SampleRun& run) {
        run.steps[1].displacement[0].second(0, 0) += 1.0;
        run.summary.status = "failed";
    };
    const CompareReport step1 = compare_changed(change, only({"/steps/0001"}));
    EXPECT_TRUE(step1.same()) << format_report(step1, false);
    EXPECT_GT(step1.n_compared, 10);
    for (const CompareEntry& entry : step1.entries)
        EXPECT_EQ(entry.path.rfind("/steps/0001", 0), 0u) << entry.path;

    const CompareReport displacement = compare_changed(change, only({"/steps/0002/displacement/"}));
    EXPECT_EQ(displacement.n_compared, 1);
    EXPECT_EQ(paths_not_same(displacement), std::vector<std::string>{"/steps/0002/displacement/cylinder"});

    const CompareReport root = compare_changed(change, only({"/@status", "/reference"}));
    EXPECT_EQ(paths_not_same(root), std::vector<std::string>{"/@status"});

    // Whole path components: "/steps/000" is not a prefix of "/steps/0001", and a prefix
    // that names nothing in the reference is reported, so a typo cannot pass.
    const CompareReport typo = compare_changed(change, only({"/steps/000"}));
    EXPECT_FALSE(typo.same());
    EXPECT_EQ(typo.n_compared, 0);
    EXPECT_EQ(paths_not_same(typo), std::vector<std::string>{"/steps/000"});
}

class TinyFileCompareTest : public ResultsCompareTest {
protected:
    // Writes a file holding one dataset "values" (reals) and one attribute "n" on the root.
    void write_tiny(const std::string& name, const std::vector<double>& values)
    {
        h5::ErrorSilencer silence;
        h5::Handle file = h5::create_file(path(name));
        h5::write_dataset(file.id(), "values", values, {static_cast<hsize_t>(values.size())});
    }
};

TEST_F(TinyFileCompareTest, NanMatchesOnlyNan)
{
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    write_tiny("a.h5", {1.0, nan, inf});
    write_tiny("b.h5", {1.0, nan, inf});
    write_tiny("c.h5", {1.0, 2.0, inf});
    write_tiny("d.h5", {1.0, nan, -inf});
    EXPECT_TRUE(compare_results(path("a.h5"), path("b.h5"), {}).same()) << "NaN against NaN, inf against inf";
    EXPECT_FALSE(compare_results(path("a.h5"), path("c.h5"), {}).same()) << "NaN in the reference only";
    EXPECT_FALSE(compare_results(path("c.h5"), path("a.h5"), {}).same()) << "NaN in the new file only";
    EXPECT_FALSE(compare_results(path("a.h5"), path("d.h5"), tolerances(1e300, CompareOptions{}.atol)).same())
        << "opposite infinities";
    const CompareReport report = compare_results(path("c.h5"), path("a.h5"), tolerances(1e300, 1e300));
    EXPECT_FALSE(report.same()) << "no tolerance accepts a NaN";
    EXPECT_NE(report.entries.at(0).detail.find("non-finite"), std::string::npos);
}

TEST_F(TinyFileCompareTest, RealAgainstIntegerIsTypeMismatch)
{
    write_tiny("a.h5", {1.0, 2.0});
    {
        h5::ErrorSilencer silence;
        h5::Handle file = h5::create_file(path("b.h5"));
        const std::vector<int> values{1, 2};
        h5::write_dataset(file.id(), "values", std::span<const int>(values));
    }
    const CompareReport report = compare_results(path("a.h5"), path("b.h5"), {});
    ASSERT_EQ(report.entries.size(), 1u);
    EXPECT_EQ(report.entries[0].kind, Kind::type_mismatch);
    EXPECT_EQ(report.entries[0].detail, "reference float64, new int32");
}

// Issue 32: a group hard-linked into itself (and a soft link back to the root) made the
// walk endless. The comparison runs in a child process that the test kills after
// `hang_limit`, so a regression fails instead of hanging the suite.
TEST_F(TinyFileCompareTest, LinkCyclesEndTheWalk)
{
    for (const char* name : {"a.h5", "b.h5"}) {
        h5::ErrorSilencer silence;
        h5::Handle file = h5::create_file(path(name));
        h5::Handle group = h5::create_group(file.id(), "g");
        h5::write_dataset(group.id(), "values", std::vector<double>{1.0, 2.0}, {2});
        ASSERT_GE(H5Lcreate_hard(file.id(), "g", group.id(), "loop", H5P_DEFAULT, H5P_DEFAULT), 0);
        ASSERT_GE(H5Lcreate_soft("/", group.id(), "up", H5P_DEFAULT, H5P_DEFAULT), 0);
    }
    constexpr auto hang_limit = std::chrono::seconds(30);  // the walk takes milliseconds
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        int code = 1;
        try {
            const CompareReport report = compare_results(path("a.h5"), path("b.h5"), {});
            code = report.same() && report.n_compared == 1 ? 0 : 1;
        } catch (...) {
            code = 2;
        }
        ::_exit(code);
    }
    int status = 0;
    const auto end = std::chrono::steady_clock::now() + hang_limit;
    while (::waitpid(child, &status, WNOHANG) == 0) {
        if (std::chrono::steady_clock::now() > end) {
            ::kill(child, SIGKILL);
            ::waitpid(child, &status, 0);
            FAIL() << "compare did not end within " << hang_limit.count() << " s (a link cycle followed forever)";
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0) << "1: not the same or not exactly /g/values compared; 2: an exception";
}

TEST_F(TinyFileCompareTest, UnreadableFilesThrowClearErrors)
{
    std::ofstream(path("text.h5")) << "not HDF5 at all";
    write_tiny("a.h5", {1.0});
    try {
        compare_results(path("a.h5"), path("text.h5"), {});
        FAIL() << "expected iga::Error";
    } catch (const Error& error) {
        EXPECT_EQ(std::string(error.what()), "cannot open new results file " + path("text.h5") + ": not an HDF5 file");
    }
    try {
        compare_results(path("missing.h5"), path("a.h5"), {});
        FAIL() << "expected iga::Error";
    } catch (const Error& error) {
        EXPECT_EQ(std::string(error.what()),
                  "cannot open reference results file " + path("missing.h5") + ": no such file");
    }
}

TEST_F(ResultsCompareTest, ReportListsDifferencesAndASummaryLine)
{
    const CompareReport report = compare_changed([](SampleRun& run) {
        run.steps[1].displacement[0].second(0, 0) += 1.0;
        run.summary.references.clear();
    });
    const std::string text = format_report(report, false);
    const std::string summary = "compare: " + std::to_string(report.n_compared) + " compared, 2 different, 1 missing";
    EXPECT_TRUE(text.ends_with(summary)) << text;
    EXPECT_NE(text.find("different      /steps/0002/displacement/cylinder: max abs diff 1.000e+00"), std::string::npos)
        << text;
    EXPECT_NE(text.find("missing        /reference"), std::string::npos) << text;
    EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 3) << "one line per non-same entry:\n" << text;

    const std::string verbose = format_report(report, true);
    EXPECT_EQ(std::count(verbose.begin(), verbose.end(), '\n'), static_cast<long>(report.entries.size()));
    EXPECT_NE(verbose.find("same           /@status"), std::string::npos) << verbose;
}

}  // namespace
}  // namespace iga::io
