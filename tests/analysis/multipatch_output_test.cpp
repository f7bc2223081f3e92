// Results of a contact surface of several patch sides (results.md additions,
// docs/results.md "Surfaces of several patch sides"): the 3D block of
// multipatch_decks.hpp cut into two patches, its bottom (left.w0, right.w0) on a
// rigid plane, written with output.paraview.
//  - contact/<pair>/<body.surface>/patch_sides lists the surface's patch sides;
//    gauss_points/patch says which one holds each Gauss point (checked against
//    the Gauss point's position: x <= 1 on the left patch, x >= 1 on the right);
//  - postprocessed/patch_grid_shape gives each patch side's sample grid
//    [n_v, n_u], samples stored patch after patch (checked: the rows of each
//    patch form a tensor grid on that patch's half);
//  - the XDMF, read back with tinyxml2, shows one structured surface grid
//    (2DSMesh) per patch side whose HyperSlabs select exactly that patch's rows of
//    postprocessed/coordinates and postprocessed/pressure in the results file.

#include "io/output_paths.hpp"
#include "multipatch_decks.hpp"
#include "run_support.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>
#include <tinyxml2.h>

#include <sstream>

namespace iga::test {
namespace {

// Reference coordinates of samples on the cut plane x = 1 are evaluated on either
// patch: equal to round-off of the rational evaluation.
constexpr double on_plane = 1e-12;

std::vector<long long> numbers(const std::string& text)
{
    std::istringstream in(text);
    std::vector<long long> out;
    long long v = 0;
    while (in >> v)
        out.push_back(v);
    return out;
}

/// A HyperSlab DataItem: its selection (start, stride, count per dimension) and
/// the HDF path it selects from (the part after "file.h5:").
struct Slab {
    std::vector<long long> selection;
    std::string path;
};

Slab read_slab(const tinyxml2::XMLElement* item)
{
    Slab out;
    EXPECT_NE(item, nullptr);
    if (item == nullptr)
        return out;
    EXPECT_STREQ(item->Attribute("ItemType"), "HyperSlab");
    const tinyxml2::XMLElement* selection = item->FirstChildElement("DataItem");
    const tinyxml2::XMLElement* data = selection ? selection->NextSiblingElement("DataItem") : nullptr;
    if (selection == nullptr || data == nullptr || selection->GetText() == nullptr || data->GetText() == nullptr) {
        ADD_FAILURE() << "a HyperSlab needs a selection and a data item";
        return out;
    }
    out.selection = numbers(selection->GetText());
    const std::string text = data->GetText();
    out.path = text.substr(text.find(':') + 1);
    return out;
}

TEST(MultiPatchOutput, SurfaceOfTwoPatchSidesStoresAndShowsEachPatchSideGrid3D)
{
    const auto dir = scratch_dir("multipatch_output_3d");
    write_text(dir / "split.yaml", block_deck_3d(block_3d_split(), "block.bottom", "top"));
    const auto file = dir / "split.h5";
    const analysis::RunOutcome outcome = run_deck((dir / "split.yaml").string(), {"output.paraview=true"}, file);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    const Results r(file);
    const std::string side = "steps/0001/contact/touch/block.bottom/";

    // The patch sides, in the surface's order.
    const io::h5::Array names = io::h5::read_dataset(r.id(), side + "patch_sides");
    ASSERT_EQ(names.type, io::h5::Array::Type::string);
    ASSERT_EQ(names.strings, (std::vector<std::string>{"left.w0", "right.w0"}));

    // Gauss points: their patch side, consistent with where they are.
    const std::vector<double> patch = r.reals(side + "gauss_points/patch");
    const RowMatrix X = r.matrix(side + "gauss_points/reference_coordinates");
    ASSERT_EQ(static_cast<Index>(patch.size()), X.rows());
    int on[2] = {0, 0};
    for (Index g = 0; g < X.rows(); ++g) {
        const double k = patch[static_cast<std::size_t>(g)];
        ASSERT_TRUE(k == 0.0 || k == 1.0) << "Gauss point " << g << ": patch " << k;
        EXPECT_TRUE(k == 0.0 ? at_most(X(g, 0), 1.0) : at_least(X(g, 0), 1.0)) << "Gauss point " << g;
        ++on[static_cast<int>(k)];
    }
    EXPECT_EQ(on[0], on[1]) << "the halves have the same number of spans";

    // Samples: one grid per patch side, patch after patch; no single grid_shape.
    const std::string post = side + "postprocessed/";
    const io::h5::Array shape_array = io::h5::read_dataset(r.id(), post + "patch_grid_shape");
    ASSERT_EQ(shape_array.type, io::h5::Array::Type::integer);
    ASSERT_EQ(shape_array.dims, (std::vector<hsize_t>{2, 2}));
    const auto shape = [&](Index k, int c) { return shape_array.integers[static_cast<std::size_t>(2 * k + c)]; };
    const RowMatrix S = r.matrix(post + "reference_coordinates");
    const io::h5::Handle post_group = io::h5::open_object(r.id(), post);
    const std::vector<std::string> attributes = io::h5::attribute_names(post_group.id());
    EXPECT_EQ(std::count(attributes.begin(), attributes.end(), "grid_shape"), 0);
    // 2 spans per direction and patch side, 3 samples per span: 7 x 7 each.
    constexpr long long per_direction = 2 * 3 + 1;
    std::vector<long long> first{0};
    for (Index k = 0; k < 2; ++k) {
        const long long n_v = static_cast<long long>(shape(k, 0)), n_u = static_cast<long long>(shape(k, 1));
        EXPECT_EQ(n_v, per_direction);
        EXPECT_EQ(n_u, per_direction);
        // A tensor grid, u (x) fastest, on this patch's half.
        for (long long j = 0; j < n_v; ++j)
            for (long long i = 0; i < n_u; ++i) {
                const Index row = first.back() + j * n_u + i;
                const double x = S(row, 0), y = S(row, 1);
                EXPECT_TRUE(k == 0 ? at_most(x, 1.0 + on_plane) : at_least(x, 1.0 - on_plane)) << "sample " << row;
                EXPECT_TRUE(near(y, S(first.back() + j * n_u, 1), on_plane)) << "sample " << row << ": same row, same y";
                EXPECT_TRUE(near(x, S(first.back() + i, 0), on_plane)) << "sample " << row << ": same column, same x";
            }
        first.push_back(first.back() + n_v * n_u);
    }
    ASSERT_EQ(first.back(), S.rows()) << "the patch grids hold every sample, once";

    // The XDMF: one surface grid per patch side, selecting that patch's rows.
    tinyxml2::XMLDocument xdmf;
    ASSERT_EQ(xdmf.LoadFile(io::xdmf_path(file.string()).c_str()), tinyxml2::XML_SUCCESS);
    const tinyxml2::XMLElement* increments = xdmf.FirstChildElement("Xdmf")->FirstChildElement("Domain")->FirstChildElement("Grid");
    ASSERT_NE(increments, nullptr);
    const tinyxml2::XMLElement* step = increments->FirstChildElement("Grid");
    ASSERT_NE(step, nullptr);
    const std::vector<std::string> patch_sides = {"left.w0", "right.w0"};
    int found = 0;
    for (const tinyxml2::XMLElement* grid = step->FirstChildElement("Grid"); grid; grid = grid->NextSiblingElement("Grid")) {
        const std::string name = grid->Attribute("Name");
        EXPECT_NE(name, "touch block.bottom post-processed") << "no grid over both patch sides";
        for (std::size_t k = 0; k < patch_sides.size(); ++k) {
            if (name != "touch block.bottom post-processed " + patch_sides[k])
                continue;
            SCOPED_TRACE(name);
            ++found;
            const long long n_v = static_cast<long long>(shape(static_cast<Index>(k), 0));
            const long long n_u = static_cast<long long>(shape(static_cast<Index>(k), 1));
            const tinyxml2::XMLElement* topology = grid->FirstChildElement("Topology");
            ASSERT_NE(topology, nullptr);
            EXPECT_STREQ(topology->Attribute("TopologyType"), "2DSMesh");
            EXPECT_EQ(numbers(topology->Attribute("Dimensions")), (std::vector<long long>{n_v, n_u}));
            const Slab points = read_slab(grid->FirstChildElement("Geometry")->FirstChildElement("DataItem"));
            EXPECT_EQ(points.path, "/" + post + "coordinates");
            // start (first, 0), stride (1, 1), count (n_v n_u, 3)
            EXPECT_EQ(points.selection, (std::vector<long long>{first[k], 0, 1, 1, n_v * n_u, 3}));
            const Slab pressure = read_slab(grid->FirstChildElement("Attribute")->FirstChildElement("DataItem"));
            EXPECT_EQ(pressure.path, "/" + post + "pressure");
            EXPECT_EQ(pressure.selection, (std::vector<long long>{first[k], 1, n_v * n_u}));
            // The selected rows exist in the results file with these shapes.
            const RowMatrix coordinates = r.matrix(points.path.substr(1));
            EXPECT_GE(coordinates.rows(), first[k] + n_v * n_u);
            EXPECT_EQ(coordinates.cols(), 3);
        }
    }
    EXPECT_EQ(found, 2);
}

}  // namespace
}  // namespace iga::test
