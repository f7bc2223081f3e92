// Tests of io::ResultsWriter against docs/results.md: every name, shape
// and attribute of the contract is read back with the HDF5 C API (through
// io/h5_file.hpp), plus the crash-safety promises (temporary file, rename on
// finish, untouched final path on abandon, flushed steps readable after a crash).

#include "io/h5_file.hpp"
#include "io/results_writer.hpp"

#include "core/error.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace iga::io {
namespace {

namespace fs = std::filesystem;
using h5::Array;

const std::string deck_text = "format: 1\nanalysis:\n  dimension: 2\n# ünïcode survives\n";
const std::string version = "0.1.0-test";

// A deterministic matrix whose entries all differ, so a transposed or shifted write shows.
RowMatrix numbered(Index rows, Index cols, double offset)
{
    RowMatrix m(rows, cols);
    for (Index i = 0; i < rows; ++i)
        for (Index j = 0; j < cols; ++j)
            m(i, j) = offset + 10.0 * static_cast<double>(i) + static_cast<double>(j) + 0.25;
    return m;
}

Vector numbered(Index n, double offset)
{
    Vector v(n);
    for (Index i = 0; i < n; ++i)
        v(i) = offset + 0.5 * static_cast<double>(i);
    return v;
}

BodyGeometry cylinder_body()
{
    BodyGeometry body;
    body.name = "cylinder";
    body.degrees = {2, 2};
    body.knots = {{0, 0, 0, 1, 1, 1}, {0, 0, 0, 0.5, 1, 1, 1}};
    body.control_points = numbered(12, 3, 0.0);  // 3 x 4 control points, columns x, y, w
    body.side_names = {{"contact", "v0"}, {"top", "v1"}};
    return body;
}

StepData step_without_contact()
{
    StepData step;
    step.index = 1;
    step.load_factor = 0.5;
    step.newton_iterations = 4;
    step.residual_norm = 3e-11;
    step.cutbacks = 0;
    step.wall_s = 0.125;
    step.displacement = {{"cylinder", numbered(12, 2, 100.0)}};
    return step;
}

ContactSideResult cylinder_side()
{
    ContactSideResult side;
    side.side_name = "cylinder.v0";
    side.gauss_points.coordinates = numbered(5, 2, 1.0);
    side.gauss_points.reference_coordinates = numbered(5, 2, 2.0);
    side.gauss_points.parameter = numbered(5, 1, 0.0);
    side.gauss_points.gap = numbered(5, -1e-3);
    side.gauss_points.pressure = numbered(5, 7.0);
    side.gauss_points.weight = numbered(5, 0.1);
    side.postprocessed.control_point_pressure = numbered(3, 9.0);
    side.postprocessed.coordinates = numbered(7, 2, 3.0);
    side.postprocessed.reference_coordinates = numbered(7, 2, 4.0);
    side.postprocessed.pressure = numbered(7, 5.0);
    side.normal_force = 1234.5;
    side.attributes = {{"n_active", 3.0}, {"max_penetration", 2e-3}};
    return side;
}

StepData step_with_contact()
{
    StepData step = step_without_contact();
    step.index = 2;
    step.load_factor = 1.0;
    step.newton_iterations = 6;
    step.cutbacks = 1;
    step.displacement = {{"cylinder", numbered(12, 2, 200.0)}};
    ContactPairResult pair;
    pair.name = "cyl_floor";
    pair.sides = {cylinder_side()};
    pair.attributes = {{"candidates", 10.0}, {"projections", 25.0}};
    step.contact = {pair};
    return step;
}

RunSummary completed_summary()
{
    RunSummary summary;
    summary.status = "completed";
    summary.timings = {{"total", 1.5}, {"assembly", 0.5}, {"contact_search", 0.1}, {"projection", 0.1},
                       {"linear_solve", 0.2}, {"output", 0.05}};
    summary.counters = {{"projections", 42}, {"linear_solves", 5'000'000'000LL}};
    summary.convergence = numbered(10, 4, 0.0);
    ReferenceData reference;
    reference.pair = "cyl_floor";
    reference.type = "hertz_cylinder_plane";
    reference.a = 0.05;
    reference.p0 = 3.2e6;
    reference.inputs = {{"radius", 1.0}, {"force", 1e5}, {"E_star", 2.2e11}};
    reference.errors = {{"peak", 0.01}, {"half_width", 0.02}, {"l2", 0.03}};
    reference.coordinates = numbered(9, 2, 6.0);
    reference.x = numbered(9, -2.0);
    reference.pressure = numbered(9, 0.0);
    reference.center = {0.0, -1.0};
    reference.tangent = {1.0, 0.0};
    summary.references = {reference};
    return summary;
}

class ResultsWriterTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        folder_ = fs::temp_directory_path() /
                  ("igacontact_writer_" + std::to_string(::getpid()) + "_" + info->name());
        fs::remove_all(folder_);
        fs::create_directories(folder_);
    }
    void TearDown() override { fs::remove_all(folder_); }

    std::string path(const std::string& name) const { return (folder_ / name).string(); }

    // Names of the files in the test folder (to see temporary files).
    std::vector<std::string> folder_contents() const
    {
        std::vector<std::string> names;
        for (const auto& entry : fs::directory_iterator(folder_))
            names.push_back(entry.path().filename().string());
        std::sort(names.begin(), names.end());
        return names;
    }

    fs::path folder_;
};

void expect_real(const Array& a, const std::vector<hsize_t>& dims, const double* expected)
{
    ASSERT_EQ(a.type, Array::Type::real);
    ASSERT_EQ(a.dims, dims);
    for (std::size_t i = 0; i < a.reals.size(); ++i)
        EXPECT_EQ(a.reals[i], expected[i]) << "element " << i;  // stored float64 round-trips bit for bit
}

void expect_dataset(hid_t file, const std::string& path, const RowMatrix& expected)
{
    SCOPED_TRACE(path);
    expect_real(h5::read_dataset(file, path), {hsize_t(expected.rows()), hsize_t(expected.cols())}, expected.data());
}

void expect_dataset(hid_t file, const std::string& path, const Vector& expected)
{
    SCOPED_TRACE(path);
    expect_real(h5::read_dataset(file, path), {hsize_t(expected.size())}, expected.data());
}

double real_attribute(hid_t file, const std::string& object, const std::string& name)
{
    const Array a = h5::read_attribute(h5::open_object(file, object).id(), name);
    EXPECT_EQ(a.type, Array::Type::real) << object << "@" << name;
    EXPECT_TRUE(a.dims.empty()) << object << "@" << name << " should be a scalar";
    return a.reals.empty() ? std::nan("") : a.reals[0];
}

long long integer_attribute(hid_t file, const std::string& object, const std::string& name)
{
    const Array a = h5::read_attribute(h5::open_object(file, object).id(), name);
    EXPECT_EQ(a.type, Array::Type::integer) << object << "@" << name;
    EXPECT_TRUE(a.dims.empty()) << object << "@" << name << " should be a scalar";
    return a.integers.empty() ? -999 : a.integers[0];
}

std::string string_attribute(hid_t file, const std::string& object, const std::string& name)
{
    const Array a = h5::read_attribute(h5::open_object(file, object).id(), name);
    EXPECT_EQ(a.type, Array::Type::string) << object << "@" << name;
    EXPECT_TRUE(a.dims.empty()) << object << "@" << name << " should be a scalar";
    return a.strings.empty() ? "<none>" : a.strings[0];
}

void write_complete_run(const std::string& final_path)
{
    ResultsWriter writer(final_path, version, deck_text);
    writer.write_bodies({cylinder_body()});
    writer.write_step(step_without_contact());
    writer.write_step(step_with_contact());
    writer.finish(completed_summary());
    EXPECT_FALSE(writer.is_open());
}

TEST_F(ResultsWriterTest, StepGroupNamesHaveAtLeastFourDigits)
{
    EXPECT_EQ(step_group_name(1), "0001");
    EXPECT_EQ(step_group_name(42), "0042");
    EXPECT_EQ(step_group_name(9999), "9999");
    EXPECT_EQ(step_group_name(12345), "12345");
    EXPECT_THROW(step_group_name(0), Error);
}

TEST_F(ResultsWriterTest, RootAttributesAndDeck)
{
    write_complete_run(path("run.h5"));
    h5::ErrorSilencer silence;
    h5::Handle file = h5::open_file(path("run.h5"));
    const hid_t f = file.id();
    EXPECT_EQ(string_attribute(f, "/", "format"), "igacontact-results");
    EXPECT_EQ(integer_attribute(f, "/", "format_version"), 1);
    EXPECT_EQ(string_attribute(f, "/", "program_version"), version);
    EXPECT_EQ(string_attribute(f, "/", "status"), "completed");
    EXPECT_EQ(string_attribute(f, "/", "message"), "");
    const Array deck = h5::read_dataset(f, "/deck");
    ASSERT_EQ(deck.type, Array::Type::string);
    EXPECT_TRUE(deck.dims.empty()) << "/deck is a scalar string";
    EXPECT_EQ(deck.strings.at(0), deck_text);
}

TEST_F(ResultsWriterTest, BodiesHoldTheAnalysedGeometry)
{
    write_complete_run(path("run.h5"));
    h5::ErrorSilencer silence;
    h5::Handle file = h5::open_file(path("run.h5"));
    const hid_t f = file.id();
    const BodyGeometry body = cylinder_body();
    const Array degrees = h5::read_dataset(f, "/bodies/cylinder/degrees");
    EXPECT_EQ(degrees.type, Array::Type::integer);
    EXPECT_EQ(degrees.dims, std::vector<hsize_t>{2});
    EXPECT_EQ(degrees.integers, (std::vector<long long>{2, 2}));
    expect_real(h5::read_dataset(f, "/bodies/cylinder/knots/u"), {6}, body.knots[0].data());
    expect_real(h5::read_dataset(f, "/bodies/cylinder/knots/v"), {7}, body.knots[1].data());
    EXPECT_FALSE(h5::exists(f, "/bodies/cylinder/knots/w")) << "a 2D body has no w knots";
    expect_dataset(f, "/bodies/cylinder/control_points", body.control_points);
    const Array sides = h5::read_dataset(f, "/bodies/cylinder/side_names");
    EXPECT_EQ(sides.dims, (std::vector<hsize_t>{2, 2}));
    EXPECT_EQ(sides.strings, (std::vector<std::string>{"contact", "v0", "top", "v1"}));
}

TEST_F(ResultsWriterTest, StepsHoldAttributesDisplacementAndContact)
{
    write_complete_run(path("run.h5"));
    h5::ErrorSilencer silence;
    h5::Handle file = h5::open_file(path("run.h5"));
    const hid_t f = file.id();
    EXPECT_EQ(h5::link_names(h5::open_object(f, "/steps").id()), (std::vector<std::string>{"0001", "0002"}));

    const StepData first = step_without_contact();
    EXPECT_EQ(real_attribute(f, "/steps/0001", "load_factor"), first.load_factor);
    EXPECT_EQ(integer_attribute(f, "/steps/0001", "newton_iterations"), first.newton_iterations);
    EXPECT_EQ(real_attribute(f, "/steps/0001", "residual_norm"), first.residual_norm);
    EXPECT_EQ(integer_attribute(f, "/steps/0001", "cutbacks"), first.cutbacks);
    EXPECT_EQ(real_attribute(f, "/steps/0001", "wall_s"), first.wall_s);
    expect_dataset(f, "/steps/0001/displacement/cylinder", first.displacement[0].second);
    EXPECT_TRUE(h5::link_names(h5::open_object(f, "/steps/0001/contact").id()).empty());

    const StepData second = step_with_contact();
    EXPECT_EQ(integer_attribute(f, "/steps/0002", "cutbacks"), 1);
    expect_dataset(f, "/steps/0002/displacement/cylinder", second.displacement[0].second);
    const std::string pair = "/steps/0002/contact/cyl_floor";
    EXPECT_EQ(real_attribute(f, pair, "candidates"), 10.0);
    const std::string side = pair + "/cylinder.v0";
    const ContactSideResult expected = cylinder_side();
    EXPECT_EQ(real_attribute(f, side, "normal_force"), expected.normal_force);
    EXPECT_EQ(real_attribute(f, side, "n_active"), 3.0);
    expect_dataset(f, side + "/gauss_points/coordinates", expected.gauss_points.coordinates);
    expect_dataset(f, side + "/gauss_points/reference_coordinates", expected.gauss_points.reference_coordinates);
    // In 2D the parameter is one value per Gauss point: a 1-D dataset of length n_g.
    expect_dataset(f, side + "/gauss_points/parameter", Vector(expected.gauss_points.parameter.col(0)));
    expect_dataset(f, side + "/gauss_points/gap", expected.gauss_points.gap);
    expect_dataset(f, side + "/gauss_points/pressure", expected.gauss_points.pressure);
    expect_dataset(f, side + "/gauss_points/weight", expected.gauss_points.weight);
    expect_dataset(f, side + "/postprocessed/control_point_pressure", expected.postprocessed.control_point_pressure);
    expect_dataset(f, side + "/postprocessed/coordinates", expected.postprocessed.coordinates);
    expect_dataset(f, side + "/postprocessed/reference_coordinates", expected.postprocessed.reference_coordinates);
    expect_dataset(f, side + "/postprocessed/pressure", expected.postprocessed.pressure);
}

TEST_F(ResultsWriterTest, ResultsIsAHardLinkToTheLastStep)
{
    write_complete_run(path("run.h5"));
    h5::ErrorSilencer silence;
    h5::Handle file = h5::open_file(path("run.h5"));
    h5::Handle results = h5::open_object(file.id(), "/results");
    EXPECT_TRUE(h5::same_object(results.id(), h5::open_object(file.id(), "/steps/0002").id()));
    EXPECT_FALSE(h5::same_object(results.id(), h5::open_object(file.id(), "/steps/0001").id()));
    EXPECT_EQ(real_attribute(file.id(), "/results", "load_factor"), 1.0);
}

TEST_F(ResultsWriterTest, FinishWritesTimingsCountersConvergenceAndReference)
{
    write_complete_run(path("run.h5"));
    h5::ErrorSilencer silence;
    h5::Handle file = h5::open_file(path("run.h5"));
    const hid_t f = file.id();
    const RunSummary summary = completed_summary();
    for (const auto& [name, seconds] : summary.timings)
        EXPECT_EQ(real_attribute(f, "/timings", name), seconds) << name;
    EXPECT_EQ(integer_attribute(f, "/counters", "projections"), 42);
    EXPECT_EQ(integer_attribute(f, "/counters", "linear_solves"), 5'000'000'000LL) << "counters are 64-bit";
    expect_dataset(f, "/convergence", summary.convergence);

    const ReferenceData& reference = summary.references[0];
    const std::string group = "/reference/cyl_floor";
    expect_dataset(f, group + "/coordinates", reference.coordinates);
    expect_dataset(f, group + "/x", reference.x);
    expect_dataset(f, group + "/pressure", reference.pressure);
    EXPECT_EQ(string_attribute(f, group, "type"), "hertz_cylinder_plane");
    EXPECT_EQ(real_attribute(f, group, "a"), reference.a);
    EXPECT_EQ(real_attribute(f, group, "p0"), reference.p0);
    for (const auto& [name, value] : reference.inputs)
        EXPECT_EQ(real_attribute(f, group, name), value) << name;
    for (const auto& [name, value] : reference.errors)
        EXPECT_EQ(real_attribute(f, group, name), value) << name;
    const Array center = h5::read_attribute(h5::open_object(f, group).id(), "center");
    EXPECT_EQ(center.dims, std::vector<hsize_t>{2});
    EXPECT_EQ(center.reals, reference.center);
}

TEST_F(ResultsWriterTest, FailedRunKeepsConvergedStepsStatusAndMessage)
{
    {
        ResultsWriter writer(path("failed.h5"), version, deck_text);
        writer.write_bodies({cylinder_body()});
        writer.write_step(step_without_contact());
        RunSummary summary;
        summary.status = "failed";
        summary.message = "Newton did not converge after 8 cutbacks";
        writer.finish(summary);
    }
    h5::ErrorSilencer silence;
    h5::Handle file = h5::open_file(path("failed.h5"));
    EXPECT_EQ(string_attribute(file.id(), "/", "status"), "failed");
    EXPECT_EQ(string_attribute(file.id(), "/", "message"), "Newton did not converge after 8 cutbacks");
    EXPECT_TRUE(h5::exists(file.id(), "/steps/0001/displacement/cylinder"));
    EXPECT_TRUE(h5::same_object(h5::open_object(file.id(), "/results").id(),
                                h5::open_object(file.id(), "/steps/0001").id()));
    const Array convergence = h5::read_dataset(file.id(), "/convergence");
    EXPECT_EQ(convergence.dims, (std::vector<hsize_t>{0, 4})) << "an empty table keeps its 4 columns";
    EXPECT_FALSE(h5::exists(file.id(), "/reference")) << "no reference was asked for";
}

TEST_F(ResultsWriterTest, ThreeDimensionalParameterIsATable)
{
    StepData step = step_with_contact();
    step.index = 1;
    step.contact[0].sides[0].gauss_points.parameter = numbered(5, 2, 0.0);
    {
        ResultsWriter writer(path("run3d.h5"), version, deck_text);
        writer.write_step(step);
        RunSummary summary;
        summary.status = "completed";
        writer.finish(summary);
    }
    h5::ErrorSilencer silence;
    h5::Handle file = h5::open_file(path("run3d.h5"));
    expect_dataset(file.id(), "/steps/0001/contact/cyl_floor/cylinder.v0/gauss_points/parameter",
                   step.contact[0].sides[0].gauss_points.parameter);
}

TEST_F(ResultsWriterTest, FinalFileAppearsOnlyAtFinish)
{
    const std::string final_path = path("run.h5");
    ResultsWriter writer(final_path, version, deck_text);
    const std::string temp_name = fs::path(writer.temp_path()).filename().string();
    EXPECT_EQ(temp_name, "run.h5.tmp-" + std::to_string(::getpid()));
    writer.write_bodies({cylinder_body()});
    writer.write_step(step_without_contact());
    EXPECT_FALSE(fs::exists(final_path)) << "the final file must not exist before finish()";
    EXPECT_EQ(folder_contents(), std::vector<std::string>{temp_name});
    writer.finish(completed_summary());
    EXPECT_EQ(folder_contents(), std::vector<std::string>{"run.h5"}) << "no temporary file may remain";
    EXPECT_THROW(writer.write_step(step_with_contact()), Error) << "the writer is closed after finish()";
}

TEST_F(ResultsWriterTest, AbortedRunLeavesAnExistingFileUntouched)
{
    const std::string final_path = path("run.h5");
    const std::string old_contents = "results of an earlier run";
    std::ofstream(final_path) << old_contents;
    try {
        ResultsWriter writer(final_path, version, deck_text);
        writer.write_bodies({cylinder_body()});
        writer.write_step(step_without_contact());
        throw std::runtime_error("simulated failure in the middle of a run");
    } catch (const std::runtime_error&) {
    }
    std::stringstream contents;
    contents << std::ifstream(final_path).rdbuf();
    EXPECT_EQ(contents.str(), old_contents);
    EXPECT_EQ(folder_contents(), std::vector<std::string>{"run.h5"}) << "the temporary file must be deleted";
}

TEST_F(ResultsWriterTest, MissingFolderGivesAClearError)
{
    const std::string final_path = path("no_such_folder/run.h5");
    try {
        ResultsWriter writer(final_path, version, deck_text);
        FAIL() << "expected iga::Error";
    } catch (const DeckError&) {
        FAIL() << "an unwritable output path is reported as iga::Error, not DeckError";
    } catch (const Error& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("cannot create results file " + final_path), std::string::npos) << message;
        EXPECT_NE(message.find("does not exist"), std::string::npos) << message;
    }
}

TEST_F(ResultsWriterTest, AFolderRemovedUnderTheRunIsTheFileSystemsRefusalNotABug)
{
    const std::string folder = path("levels");
    fs::create_directory(folder);
    ResultsWriter writer(folder + "/run.h5", version, deck_text);
    writer.write_bodies({cylinder_body()});
    writer.write_step(step_without_contact());
    fs::remove_all(folder);  // another process cleans up while the run writes
    try {
        writer.finish(completed_summary());
        FAIL() << "expected iga::StorageError";
    } catch (const StorageError& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("cannot rename"), std::string::npos) << message;
        EXPECT_NE(message.find("no longer there"), std::string::npos) << "the temporary file went with its folder: " << message;
    }
}

TEST_F(ResultsWriterTest, FolderThatIsAFileGivesAClearError)
{
    std::ofstream(path("plain_file")) << "x";
    try {
        ResultsWriter writer(path("plain_file/run.h5"), version, deck_text);
        FAIL() << "expected iga::Error";
    } catch (const Error& error) {
        EXPECT_NE(std::string(error.what()).find("is not a folder"), std::string::npos) << error.what();
    }
}

// A run killed after some steps leaves a temporary file from which every
// flushed step can be read (results.md: "flushed so that what was written stays readable").
TEST_F(ResultsWriterTest, FlushedStepsSurviveACrash)
{
    // The default "fast" death-test style forks, so the child shares this test's folder.
    const std::string final_path = path("crash.h5");
    EXPECT_EXIT(
        {
            ResultsWriter writer(final_path, version, deck_text);
            writer.write_bodies({cylinder_body()});
            writer.write_step(step_without_contact());
            writer.write_step(step_with_contact());
            std::_Exit(7);  // dies without closing the file, like a killed process
        },
        ::testing::ExitedWithCode(7), "");
    const std::vector<std::string> left = folder_contents();
    ASSERT_EQ(left.size(), 1u);
    EXPECT_EQ(left[0].rfind("crash.h5.tmp-", 0), 0u) << left[0];
    h5::ErrorSilencer silence;
    h5::Handle file = h5::open_file(path(left[0]));
    EXPECT_EQ(string_attribute(file.id(), "/", "status"), "running");
    expect_dataset(file.id(), "/results/displacement/cylinder", step_with_contact().displacement[0].second);
    expect_dataset(file.id(), "/steps/0001/displacement/cylinder", step_without_contact().displacement[0].second);
}

// --- second release: reactions, obstacle force, stress fields, /history, warnings ----------

StepData step_with_second_release_items()
{
    StepData step = step_with_contact();
    step.contact[0].obstacle_force = {0.5, -1234.5};
    step.reactions = {{"cylinder.v1", {1.25, 1234.5}}, {"cylinder.u0", {-0.75, 0.0}}};
    BodyFields fields;
    fields.body = "cylinder";
    fields.reference_coordinates = numbered(9, 2, 10.0);
    fields.displacement = numbered(9, 2, 20.0);
    fields.stress = numbered(9, 6, 30.0);
    fields.von_mises = numbered(9, 40.0);
    step.fields = {fields};
    return step;
}

HistoryRow history_row(double load_factor)
{
    HistoryRow row;
    row.load_factor = load_factor;
    row.reactions = {{"cylinder.v1", {1.0 * load_factor, 2.0 * load_factor}},
                     {"cylinder.u0", {-3.0 * load_factor, 0.25}}};
    row.contact = {{"cyl_floor", "cylinder.v0", 100.0 * load_factor, 1e-4 * load_factor, {0.0, 0.0}, 0.0}};
    return row;
}

TEST_F(ResultsWriterTest, StepsHoldReactionsObstacleForceAndFields)
{
    {
        ResultsWriter writer(path("run.h5"), version, deck_text);
        writer.write_bodies({cylinder_body()});
        writer.write_step(step_without_contact());
        writer.write_step(step_with_second_release_items());
        writer.finish(completed_summary());
    }
    h5::ErrorSilencer silence;
    h5::Handle file = h5::open_file(path("run.h5"));
    const hid_t f = file.id();
    const StepData step = step_with_second_release_items();
    for (const Reaction& reaction : step.reactions) {
        SCOPED_TRACE(reaction.name);
        expect_real(h5::read_dataset(f, "/steps/0002/reactions/" + reaction.name), {2}, reaction.force.data());
    }
    EXPECT_FALSE(h5::exists(f, "/steps/0001/reactions")) << "no reactions given for step 1";
    const Array obstacle = h5::read_attribute(h5::open_object(f, "/steps/0002/contact/cyl_floor").id(), "obstacle_force");
    expect_real(obstacle, {2}, step.contact[0].obstacle_force.data());
    const std::vector<std::string> pair_attributes =
        h5::attribute_names(h5::open_object(f, "/steps/0001/contact").id());
    EXPECT_TRUE(pair_attributes.empty()) << "step 1 has no contact pair, so no obstacle_force";

    const BodyFields& fields = step.fields[0];
    expect_dataset(f, "/steps/0002/fields/cylinder/reference_coordinates", fields.reference_coordinates);
    expect_dataset(f, "/steps/0002/fields/cylinder/displacement", fields.displacement);
    expect_dataset(f, "/steps/0002/fields/cylinder/stress", fields.stress);
    expect_dataset(f, "/steps/0002/fields/cylinder/von_mises", fields.von_mises);
    EXPECT_FALSE(h5::exists(f, "/steps/0001/fields")) << "fields only when StepData::fields is given";
    expect_dataset(f, "/results/fields/cylinder/stress", fields.stress);
}

TEST_F(ResultsWriterTest, ObstacleForceOnlyForPairsThatHaveOne)
{
    {
        ResultsWriter writer(path("run.h5"), version, deck_text);
        writer.write_bodies({cylinder_body()});
        writer.write_step(step_with_contact());  // obstacle_force empty: two deformable sides
        writer.finish(completed_summary());
    }
    h5::ErrorSilencer silence;
    h5::Handle file = h5::open_file(path("run.h5"));
    const std::vector<std::string> names = h5::attribute_names(h5::open_object(file.id(), "/steps/0002/contact/cyl_floor").id());
    EXPECT_EQ(std::count(names.begin(), names.end(), "obstacle_force"), 0);
}

TEST_F(ResultsWriterTest, FieldsWithInconsistentShapesAreABug)
{
    ResultsWriter writer(path("run.h5"), version, deck_text);
    writer.write_bodies({cylinder_body()});
    StepData step = step_with_second_release_items();
    step.fields[0].stress = numbered(9, 4, 0.0);  // 4 stress components instead of 6
    EXPECT_THROW(writer.write_step(step), Error);
}

TEST_F(ResultsWriterTest, HistoryHasOneRowPerAppendedIncrement)
{
    constexpr int n_rows = 3;
    {
        ResultsWriter writer(path("run.h5"), version, deck_text);
        writer.write_bodies({cylinder_body()});
        for (int k = 1; k <= n_rows; ++k)
            writer.append_history(history_row(0.25 * k));
        writer.write_step(step_with_contact());  // only the last increment stored under /steps
        writer.finish(completed_summary());
    }
    h5::ErrorSilencer silence;
    h5::Handle file = h5::open_file(path("run.h5"));
    const hid_t f = file.id();
    const std::vector<double> load_factor{0.25, 0.5, 0.75};
    expect_real(h5::read_dataset(f, "/history/load_factor"), {n_rows}, load_factor.data());
    // n x d, row k = the reaction at increment k.
    const std::vector<double> v1{0.25, 0.5, 0.5, 1.0, 0.75, 1.5};
    expect_real(h5::read_dataset(f, "/history/reactions/cylinder.v1"), {n_rows, 2}, v1.data());
    const std::vector<double> u0{-0.75, 0.25, -1.5, 0.25, -2.25, 0.25};
    expect_real(h5::read_dataset(f, "/history/reactions/cylinder.u0"), {n_rows, 2}, u0.data());
    const std::vector<double> force{25.0, 50.0, 75.0};
    expect_real(h5::read_dataset(f, "/history/contact/cyl_floor/cylinder.v0/normal_force"), {n_rows}, force.data());
    const std::vector<double> penetration{1e-4 * 0.25, 1e-4 * 0.5, 1e-4 * 0.75};  // as history_row computes them
    expect_real(h5::read_dataset(f, "/history/contact/cyl_floor/cylinder.v0/max_penetration"), {n_rows},
                penetration.data());
}

TEST_F(ResultsWriterTest, HistoryAndWarningsAreWrittenForAFailedRun)
{
    {
        ResultsWriter writer(path("failed.h5"), version, deck_text);
        writer.write_bodies({cylinder_body()});
        writer.append_history(history_row(0.5));
        writer.write_step(step_without_contact());
        RunSummary summary;
        summary.status = "failed";
        summary.message = "Newton did not converge";
        summary.warnings = "penalty is large\ncontact pair touch never closed";
        writer.finish(summary);
    }
    h5::ErrorSilencer silence;
    h5::Handle file = h5::open_file(path("failed.h5"));
    EXPECT_EQ(string_attribute(file.id(), "/", "status"), "failed");
    EXPECT_EQ(string_attribute(file.id(), "/", "warnings"), "penalty is large\ncontact pair touch never closed");
    const std::vector<double> load_factor{0.5};
    expect_real(h5::read_dataset(file.id(), "/history/load_factor"), {1}, load_factor.data());
}

TEST_F(ResultsWriterTest, NoWarningsIsAnEmptyStringAndNoRowsAnEmptyHistory)
{
    write_complete_run(path("run.h5"));
    h5::ErrorSilencer silence;
    h5::Handle file = h5::open_file(path("run.h5"));
    EXPECT_EQ(string_attribute(file.id(), "/", "warnings"), "");
    const Array load_factor = h5::read_dataset(file.id(), "/history/load_factor");
    EXPECT_EQ(load_factor.dims, std::vector<hsize_t>{0});
    EXPECT_FALSE(h5::exists(file.id(), "/history/reactions"));
}

TEST_F(ResultsWriterTest, HistoryRowsWithOtherNamesThanTheFirstAreABug)
{
    ResultsWriter writer(path("run.h5"), version, deck_text);
    writer.append_history(history_row(0.5));
    HistoryRow renamed = history_row(1.0);
    renamed.reactions[0].name = "cylinder.v0";
    EXPECT_THROW(writer.append_history(renamed), Error);
    HistoryRow shorter = history_row(1.0);
    shorter.contact.clear();
    EXPECT_THROW(writer.append_history(shorter), Error);
}

// The output-cost defect: /steps held its thousands of members in one local heap that every
// flush rewrote (the old file format). With the HDF5 1.8 format a large /steps is stored dense.
TEST_F(ResultsWriterTest, ManyStepsUseDenseLinkStorage)
{
    constexpr int n_steps = 40;  // well above HDF5's compact-storage limit of 8 links
    {
        ResultsWriter writer(path("run.h5"), version, deck_text);
        writer.write_bodies({cylinder_body()});
        StepData step = step_without_contact();
        for (int k = 1; k <= n_steps; ++k) {
            step.index = k;
            writer.write_step(step);
        }
        writer.finish(completed_summary());
    }
    h5::ErrorSilencer silence;
    h5::Handle file = h5::open_file(path("run.h5"));
    H5G_info_t info;
    ASSERT_GE(H5Gget_info(h5::open_object(file.id(), "/steps").id(), &info), 0);
    EXPECT_EQ(info.nlinks, static_cast<hsize_t>(n_steps));
    EXPECT_EQ(info.storage_type, H5G_STORAGE_TYPE_DENSE);
}

}  // namespace
}  // namespace iga::io
