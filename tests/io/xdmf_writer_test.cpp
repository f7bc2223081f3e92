// The XDMF index at the text level: with fields, every body grid announces the
// six stress columns (HyperSlabs of fields/<body>/stress, n_t x 6, in the file's
// order xx, yy, zz, xy, yz, xz) and von_mises (n_t), at the step's group; without
// fields nothing under fields/ is referenced.

#include "io/xdmf_writer.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <regex>
#include <string>
#include <vector>

namespace iga::io {
namespace {

struct Announced {
    std::string dims;
    std::string path;
};

std::vector<Announced> hdf_items(const std::string& xdmf)
{
    const std::regex item(R"re(<DataItem Dimensions="([0-9 ]+)"[^>]*Format="HDF">results\.h5:([^<]+)</DataItem>)re");
    std::vector<Announced> out;
    for (auto it = std::sregex_iterator(xdmf.begin(), xdmf.end(), item); it != std::sregex_iterator(); ++it)
        out.push_back({(*it)[1], (*it)[2]});
    return out;
}

const std::vector<XdmfStep> two_steps = {{1, 0.5, {}}, {2, 1.0, {}}};

TEST(XdmfWriter, FieldsAreSixStressColumnsAndVonMisesAtEachStep)
{
    const std::vector<XdmfMesh> meshes = {{"block", 25, 16, 4, true}, {"cube", 125, 64, 8, true}};
    const std::string xdmf = xdmf_text("results.h5", meshes, two_steps);

    for (const XdmfStep& step : two_steps)
        for (const XdmfMesh& mesh : meshes) {
            const std::string group = "/steps/000" + std::to_string(step.index) + "/fields/" + mesh.body;
            int n_stress = 0, n_von_mises = 0;
            for (const Announced& a : hdf_items(xdmf)) {
                if (a.path == group + "/stress") {
                    ++n_stress;
                    EXPECT_EQ(a.dims, std::to_string(mesh.n_points) + " 6");
                }
                if (a.path == group + "/von_mises") {
                    ++n_von_mises;
                    EXPECT_EQ(a.dims, std::to_string(mesh.n_points));
                }
            }
            EXPECT_EQ(n_stress, 6) << group;
            EXPECT_EQ(n_von_mises, 1) << group;
        }

    // Each stress attribute selects its own column: start (0, k), stride (1, 1), count (n_t, 1).
    const std::vector<std::string> components = {"xx", "yy", "zz", "xy", "yz", "xz"};
    for (std::size_t k = 0; k < components.size(); ++k) {
        const std::string name = "<Attribute Name=\"stress_" + components[k] + "\"";
        const std::size_t at = xdmf.find(name);
        ASSERT_NE(at, std::string::npos) << name;
        const std::size_t end = xdmf.find("</Attribute>", at);
        const std::string attribute = xdmf.substr(at, end - at);
        EXPECT_NE(attribute.find("ItemType=\"HyperSlab\" Dimensions=\"25 1\""), std::string::npos) << attribute;
        EXPECT_NE(attribute.find(">0 " + std::to_string(k) + " 1 1 25 1<"), std::string::npos) << attribute;
    }
    EXPECT_NE(xdmf.find("<Attribute Name=\"von_mises\" AttributeType=\"Scalar\" Center=\"Node\">"), std::string::npos);
}

TEST(XdmfWriter, WithoutFieldsNothingUnderFieldsIsReferenced)
{
    const std::string xdmf = xdmf_text("results.h5", {{"block", 25, 16, 4, false}}, two_steps);
    for (const Announced& a : hdf_items(xdmf))
        EXPECT_EQ(a.path.find("/fields/"), std::string::npos) << a.path;
    EXPECT_EQ(xdmf.find("stress"), std::string::npos);
    EXPECT_EQ(hdf_items(xdmf).size(), 2u * 3u);  // cells, points, displacement per step
}


// A curve of two patch sides (2D): one polyline per patch side, named after it,
// each selecting its own rows of the samples stored patch side after patch side.
TEST(XdmfWriter, CurveOfTwoPatchSidesIsOnePolylinePerPatchSide)
{
    XdmfContactSide side{"/steps/0001/contact/c/block.bottom", "c block.bottom", 24, 16, 2, 0, 0,
                         {{1, 9}, {1, 7}}, {"p2.v0", "p3.v0"}};
    const std::string xdmf = xdmf_text("results.h5", {}, {{1, 1.0, {side}}});
    EXPECT_EQ(xdmf.find("<Grid Name=\"c block.bottom post-processed\""), std::string::npos)
        << "no polyline through both patch sides";
    const std::vector<std::pair<std::string, std::pair<long long, long long>>> expected = {
        {"p2.v0", {0, 9}}, {"p3.v0", {9, 7}}};
    for (const auto& [name, rows] : expected) {
        SCOPED_TRACE(name);
        const std::size_t at = xdmf.find("<Grid Name=\"c block.bottom post-processed " + name + "\"");
        ASSERT_NE(at, std::string::npos);
        const std::string grid = xdmf.substr(at, xdmf.find("</Grid>", at) - at);
        const auto [first, count] = rows;
        EXPECT_NE(grid.find(fmt::format("TopologyType=\"Polyline\" NumberOfElements=\"1\" NodesPerElement=\"{}\"", count)),
                  std::string::npos)
            << grid;
        // coordinates (16 x 2): start (first, 0), stride (1, 1), count (count, 2)
        EXPECT_NE(grid.find(fmt::format(">{} 0 1 1 {} 2<", first, count)), std::string::npos) << grid;
        // pressure (16): start first, stride 1, count
        EXPECT_NE(grid.find(fmt::format(">{} 1 {}<", first, count)), std::string::npos) << grid;
        EXPECT_NE(grid.find("results.h5:/steps/0001/contact/c/block.bottom/postprocessed/coordinates"), std::string::npos);
        EXPECT_NE(grid.find("results.h5:/steps/0001/contact/c/block.bottom/postprocessed/pressure"), std::string::npos);
    }
}

}  // namespace
}  // namespace iga::io
