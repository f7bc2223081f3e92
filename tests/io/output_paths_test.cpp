// Tests of io/output_paths.hpp: the XDMF path beside a results file, path comparison
// that sees through spellings and symbolic links, where output.file came from, and
// the guard that refuses an output path that is the deck or a folder.

#include "io/output_paths.hpp"

#include "core/error.hpp"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace iga::io {
namespace {

namespace fs = std::filesystem;

class OutputPathsTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        folder_ = fs::temp_directory_path() / ("igacontact_output_paths_" + std::to_string(::getpid()) + "_" +
                                               info->name());
        fs::remove_all(folder_);
        fs::create_directories(folder_ / "sub");
        std::ofstream(folder_ / "deck.yaml") << "format: 1\n";
    }
    void TearDown() override { fs::remove_all(folder_); }
    std::string path(const std::string& name) const { return (folder_ / name).string(); }

    Deck deck_writing(const std::string& output) const
    {
        Deck deck;
        deck.source_file = path("deck.yaml");
        deck.output.file = output;
        return deck;
    }

    fs::path folder_;
};

TEST_F(OutputPathsTest, XdmfIndexSitsBesideTheResults)
{
    EXPECT_EQ(xdmf_path("out/run.h5"), "out/run.xdmf");
    EXPECT_EQ(xdmf_path("run"), "run.xdmf");
    EXPECT_EQ(xdmf_path("run.h5.bak"), "run.h5.bak.xdmf");
}

TEST_F(OutputPathsTest, SameFileSeesThroughSpellingsAndLinks)
{
    fs::create_symlink(path("deck.yaml"), path("link.yaml"));
    EXPECT_TRUE(same_file(path("deck.yaml"), path("sub/../deck.yaml")));
    EXPECT_TRUE(same_file(path("deck.yaml"), path("./deck.yaml")));
    EXPECT_TRUE(same_file(path("deck.yaml"), path("link.yaml")));
    EXPECT_FALSE(same_file(path("deck.yaml"), path("deck.h5")));
    EXPECT_TRUE(same_file(path("sub/new.h5"), path("sub/./new.h5"))) << "neither exists: normalized paths";
    EXPECT_FALSE(same_file(path("sub/new.h5"), path("new.h5")));
}

TEST_F(OutputPathsTest, OriginOfOutputFile)
{
    EXPECT_EQ(output_origin(false, {}), OutputOrigin::deck);
    EXPECT_EQ(output_origin(false, {"materials.soft.E=1", "output.paraview=true"}), OutputOrigin::deck);
    EXPECT_EQ(output_origin(false, {"output.file=x.h5"}), OutputOrigin::set_option);
    EXPECT_EQ(output_origin(false, {"output={file: x.h5}"}), OutputOrigin::set_option);
    EXPECT_EQ(output_origin(true, {"output.file=x.h5"}), OutputOrigin::o_option);
}

TEST_F(OutputPathsTest, ResultsOnTheDeckOrAFolderAreRefused)
{
    const std::vector<std::string> inputs{path("deck.yaml")};
    EXPECT_NO_THROW(check_output_paths(deck_writing(path("deck.h5")), inputs, OutputOrigin::deck));
    EXPECT_THROW(check_output_paths(deck_writing(path("sub/../deck.yaml")), inputs, OutputOrigin::deck), DeckError);
    EXPECT_THROW(check_output_paths(deck_writing(path("sub")), inputs, OutputOrigin::deck), DeckError);
    try {
        check_output_paths(deck_writing(path("deck.yaml")), inputs, OutputOrigin::set_option);
        ADD_FAILURE() << "no DeckError";
    } catch (const DeckError& e) {
        EXPECT_EQ(std::string(e.what()), "<command line>: error: output.file = " + path("deck.yaml") +
                                             ": the results file would replace the deck itself; nothing was "
                                             "written. Choose another results file");
    }
    try {
        check_output_paths(deck_writing(path("deck.yaml")), inputs, OutputOrigin::o_option);
        ADD_FAILURE() << "no DeckError";
    } catch (const DeckError& e) {
        EXPECT_NE(std::string(e.what()).find("given with the -o option"), std::string::npos) << e.what();
    }
}

TEST_F(OutputPathsTest, GeometryFilesOfTheDeckAreInputs)
{
    // geometry.file is relative to the deck's folder; an absolute one is kept.
    Deck deck = deck_writing(path("deck.h5"));
    deck.bodies.resize(3);
    deck.bodies[0].geometry_file = "sub/../geom.xml";
    deck.bodies[2].geometry_file = "/abs/other.xml";
    const std::vector<std::string> inputs = input_files(deck);
    ASSERT_EQ(inputs.size(), 3u);
    EXPECT_EQ(inputs[0], path("deck.yaml"));
    EXPECT_EQ(inputs[1], path("geom.xml"));
    EXPECT_EQ(inputs[2], "/abs/other.xml");
    std::ofstream(path("geom.xml")) << "<xml/>\n";
    try {
        check_output_paths(deck_writing(path("./geom.xml")), inputs, OutputOrigin::o_option);
        ADD_FAILURE() << "no DeckError";
    } catch (const DeckError& e) {
        EXPECT_NE(std::string(e.what()).find("would replace an input file of the deck (" + path("geom.xml") + ")"),
                  std::string::npos)
            << e.what();
    }
}

TEST_F(OutputPathsTest, ExistingNonRegularFilesAreRefused)
{
    // A FIFO (and likewise a device such as /dev/null, which a test must not touch):
    // the final rename would replace it by a regular file.
    ASSERT_EQ(::mkfifo(path("pipe.h5").c_str(), 0600), 0);
    try {
        check_output_paths(deck_writing(path("pipe.h5")), {path("deck.yaml")}, OutputOrigin::deck);
        ADD_FAILURE() << "no DeckError";
    } catch (const DeckError& e) {
        EXPECT_NE(std::string(e.what()).find("is a FIFO (named pipe), not a regular file"), std::string::npos)
            << e.what();
    }
    fs::create_symlink("/dev/null", path("null.h5"));
    EXPECT_THROW(check_output_paths(deck_writing(path("null.h5")), {path("deck.yaml")}, OutputOrigin::deck), DeckError);
    Deck paraview = deck_writing(path("run.h5"));
    paraview.output.paraview = true;
    ASSERT_EQ(::mkfifo(path("run.xdmf").c_str(), 0600), 0);
    EXPECT_THROW(check_output_paths(paraview, {path("deck.yaml")}, OutputOrigin::deck), DeckError);
}

TEST_F(OutputPathsTest, XdmfIndexOnTheDeckIsRefusedOnlyWithParaview)
{
    const std::string deck_named_xdmf = path("deck.xdmf");
    std::ofstream(deck_named_xdmf) << "format: 1\n";
    Deck deck = deck_writing(path("deck.h5"));
    deck.source_file = deck_named_xdmf;
    EXPECT_NO_THROW(check_output_paths(deck, {deck_named_xdmf}, OutputOrigin::deck)) << "no XDMF without paraview";
    deck.output.paraview = true;
    EXPECT_THROW(check_output_paths(deck, {deck_named_xdmf}, OutputOrigin::deck), DeckError);
}

}  // namespace
}  // namespace iga::io
