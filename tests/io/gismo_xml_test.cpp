// The G+Smo XML reader (io/gismo_xml.hpp): the supported subset read back
// exactly (2D multi-patch, 3D NURBS volume, NURBS weights), the example files
// in inputs/, and every malformed case as one located error at the right line.

#include "io/gismo_xml.hpp"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace iga::io {
namespace {

namespace fs = std::filesystem;

/// Writes `text` to a fresh file `name` in a per-test folder and returns its path.
std::string write_file(const std::string& name, const std::string& text)
{
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const fs::path dir = fs::temp_directory_path() / "igacontact_gismo_xml" / info->name();
    fs::create_directories(dir);
    const fs::path path = dir / name;
    std::ofstream(path) << text;
    return path.string();
}

/// The message read_gismo_xml throws for `path`, or "" when it reads.
std::string error_of(const std::string& path, int dimension)
{
    try {
        read_gismo_xml(path, dimension);
    } catch (const DeckError& e) {
        return e.what();
    }
    return "";
}

// Values are copied from text to double by one correctly rounded conversion,
// so a value read back equals the same literal compiled here bit for bit.
constexpr double exact = 0.0;

// A quarter annulus (radii 1 and 2, first quadrant): u radial (degree 1), v along
// the arc (degree 2, middle weight cos 45 deg), as G+Smo writes a TensorNurbs2.
// Line numbers are quoted by the tests below: keep the lines where they are.
const std::string quarter_annulus = R"(<?xml version="1.0"?>
<xml>
 <Geometry type="TensorNurbs2" id="7">
  <Basis type="TensorNurbsBasis2">
   <Basis type="TensorBSplineBasis2">
    <Basis type="BSplineBasis" index="0">
     <KnotVector degree="1">0 0 1 1</KnotVector>
    </Basis>
    <Basis type="BSplineBasis" index="1">
     <KnotVector degree="2">0 0 0 1 1 1</KnotVector>
    </Basis>
   </Basis>
   <weights>1 1 0.70710678118654757 0.70710678118654757 1 1</weights>
  </Basis>
  <coefs geoDim="2">1 0
2 0
1 1
2 2
0 1
0 2</coefs>
 </Geometry>
</xml>
)";

TEST(GismoXml, QuarterAnnulusNurbsReadsBackExactly)
{
    const auto patches = read_gismo_xml(write_file("annulus.xml", quarter_annulus), 2);
    ASSERT_EQ(patches.size(), 1u);
    const ImportedPatch& p = patches[0];
    EXPECT_EQ(p.name, "p7");
    EXPECT_EQ(p.line, 3);
    EXPECT_EQ(p.nurbs.degrees, (std::vector<int>{1, 2}));
    EXPECT_EQ(p.nurbs.knots, (std::vector<std::vector<double>>{{0, 0, 1, 1}, {0, 0, 0, 1, 1, 1}}));
    const double w = 0.70710678118654757;
    const std::vector<std::vector<double>> expected = {{1, 0, 1}, {2, 0, 1}, {1, 1, w}, {2, 2, w}, {0, 1, 1}, {0, 2, 1}};
    ASSERT_EQ(p.nurbs.control_points.size(), expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i)
        for (std::size_t k = 0; k < 3; ++k)
            EXPECT_TRUE(std::abs(p.nurbs.control_points[i][k] - expected[i][k]) <= exact)
                << "control point " << i << " entry " << k << ": " << p.nurbs.control_points[i][k];
}

TEST(GismoXml, QuarterAnnulusArcIsOnTheCircle)
{
    // The rows run with u (radial) fastest: rows 1, 3, 5 are the outer arc (radius 2).
    // A rational quadratic Bezier arc evaluated by hand: only a correct ordering of
    // coefficients and weights puts every point at radius 2.
    const auto patches = read_gismo_xml(write_file("annulus.xml", quarter_annulus), 2);
    const auto& cp = patches.at(0).nurbs.control_points;
    // Round-off of a handful of products and one division on values of order 1.
    constexpr double radius_tolerance = 1e-14;
    for (double t = 0.0; t <= 1.0; t += 0.125) {
        const double b[3] = {(1 - t) * (1 - t), 2 * t * (1 - t), t * t};
        double x = 0, y = 0, wsum = 0;
        for (int j = 0; j < 3; ++j) {
            const auto& row = cp[static_cast<std::size_t>(1 + 2 * j)];
            x += b[j] * row[2] * row[0];
            y += b[j] * row[2] * row[1];
            wsum += b[j] * row[2];
        }
        const double r = std::hypot(x / wsum, y / wsum);
        EXPECT_TRUE(std::isfinite(r) && std::abs(r - 2.0) < radius_tolerance) << "t = " << t << ": r = " << r;
    }
}

TEST(GismoXml, FourSquaresMultiPatchFromInputs)
{
    const auto patches = read_gismo_xml(std::string(IGA_SOURCE_DIR) + "/inputs/four_squares.xml", 2);
    ASSERT_EQ(patches.size(), 4u);
    // p2 and p3 form the bottom (y = 0): their v0 sides (rows 0 and 1) lie on it.
    const double lower_left[4][2] = {{0.5, 0.5}, {0.0, 0.5}, {0.0, 0.0}, {0.5, 0.0}};
    double area = 0.0;
    for (int k = 0; k < 4; ++k) {
        const ImportedPatch& p = patches[static_cast<std::size_t>(k)];
        EXPECT_EQ(p.name, std::string("p").append(std::to_string(k)));
        EXPECT_EQ(p.nurbs.degrees, (std::vector<int>{1, 1}));
        ASSERT_EQ(p.nurbs.control_points.size(), 4u);
        const auto& cp = p.nurbs.control_points;
        EXPECT_EQ(cp[0][0], lower_left[k][0]);
        EXPECT_EQ(cp[0][1], lower_left[k][1]);
        EXPECT_EQ(cp[1][0], lower_left[k][0] + 0.5);  // u runs along x: first parameter fastest
        EXPECT_EQ(cp[2][1], lower_left[k][1] + 0.5);
        for (const auto& row : cp)
            EXPECT_EQ(row[2], 1.0);  // B-spline: unit weights
        area += (cp[3][0] - cp[0][0]) * (cp[3][1] - cp[0][1]);
    }
    EXPECT_EQ(area, 1.0);
}

TEST(GismoXml, WithoutMultiPatchEveryGeometryInFileOrder)
{
    const std::string text = R"(<xml>
 <Geometry type="TensorBSpline2" id="5">
  <Basis type="TensorBSplineBasis2">
   <Basis type="BSplineBasis" index="0"><KnotVector degree="1">0 0 1 1</KnotVector></Basis>
   <Basis type="BSplineBasis" index="1"><KnotVector degree="1">0 0 1 1</KnotVector></Basis>
  </Basis>
  <coefs geoDim="3">0 0 0  1 0 0  0 1 0  1 1 0</coefs>
 </Geometry>
 <Geometry type="TensorBSpline2" id="2">
  <Basis type="TensorBSplineBasis2">
   <Basis type="BSplineBasis" index="1"><KnotVector degree="1">0 0 1 1</KnotVector></Basis>
   <Basis type="BSplineBasis" index="0"><KnotVector degree="2">0 0 0 1 1 1</KnotVector></Basis>
  </Basis>
  <coefs geoDim="2">1 0 1.5 0 2 0 1 1 1.5 1 2 1</coefs>
 </Geometry>
</xml>
)";
    const auto patches = read_gismo_xml(write_file("two.xml", text), 2);
    ASSERT_EQ(patches.size(), 2u);
    EXPECT_EQ(patches[0].name, "p5");
    EXPECT_EQ(patches[1].name, "p2");
    EXPECT_EQ(patches[1].line, 9);
    // geoDim 3 with z = 0 in a 2D deck: the zero coordinate is dropped.
    EXPECT_EQ(patches[0].nurbs.control_points[3], (std::vector<double>{1, 1, 1}));
    // The index attribute, not the order of the <Basis> elements, names the direction.
    EXPECT_EQ(patches[1].nurbs.degrees, (std::vector<int>{2, 1}));
    EXPECT_EQ(patches[1].nurbs.control_points.size(), 6u);
}

TEST(GismoXml, IdIndexKeepsTheMultiPatchOrder)
{
    const std::string square = R"(
  <Basis type="TensorBSplineBasis2">
   <Basis type="BSplineBasis" index="0"><KnotVector degree="1">0 0 1 1</KnotVector></Basis>
   <Basis type="BSplineBasis" index="1"><KnotVector degree="1">0 0 1 1</KnotVector></Basis>
  </Basis>
  <coefs geoDim="2">0 0 1 0 0 1 1 1</coefs>)";
    const std::string text = "<xml>\n<Geometry type=\"TensorBSpline2\" id=\"0\">" + square +
                             "</Geometry>\n<Geometry type=\"TensorBSpline2\" id=\"1\">" + square +
                             "</Geometry>\n<Geometry type=\"Unsupported\" id=\"9\"/>\n"
                             "<MultiPatch parDim=\"2\"><patches type=\"id_index\">1 0</patches>"
                             "<interfaces>0 2 1 1 0 1 1 1</interfaces><boundary>0 1\n1 2</boundary></MultiPatch>\n"
                             "</xml>\n";
    // The Geometry the MultiPatch does not list is not read (its type would be an error).
    const auto patches = read_gismo_xml(write_file("index.xml", text), 2);
    ASSERT_EQ(patches.size(), 2u);
    EXPECT_EQ(patches[0].name, "p1");
    EXPECT_EQ(patches[1].name, "p0");
}

TEST(GismoXml, TensorNurbs3Volume)
{
    // A quarter of a thick-walled tube: u radial (1 to 2, degree 1), v the arc
    // (degree 2, weights), w along z (0 to 3, degree 2 with an interior knot).
    const double w = 0.70710678118654757;
    std::string coefs, weights;
    const double zs[4] = {0.0, 0.75, 2.25, 3.0};
    for (double z : zs)
        for (int j = 0; j < 3; ++j)
            for (double r : {1.0, 2.0}) {
                const double x = j == 0 ? r : j == 1 ? r : 0.0;
                const double y = j == 0 ? 0.0 : r;
                coefs += std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(z) + "\n";
                weights += j == 1 ? "0.70710678118654757 " : "1 ";
            }
    const std::string text = R"(<?xml version="1.0" encoding="UTF-8"?>
<xml>
 <Geometry type="TensorNurbs3" id="0">
  <Basis type="TensorNurbsBasis3">
   <Basis type="TensorBSplineBasis3">
    <Basis type="BSplineBasis" index="0"><KnotVector degree="1">0 0 1 1</KnotVector></Basis>
    <Basis type="BSplineBasis" index="1"><KnotVector degree="2">0 0 0 1 1 1</KnotVector></Basis>
    <Basis type="BSplineBasis" index="2"><KnotVector degree="2">0 0 0 0.5 1 1 1</KnotVector></Basis>
   </Basis>
   <weights>)" + weights + R"(</weights>
  </Basis>
  <coefs geoDim="3">)" + coefs + R"(</coefs>
 </Geometry>
 <MultiPatch parDim="3" id="1"><patches type="id_range">0 0</patches></MultiPatch>
</xml>
)";
    const auto patches = read_gismo_xml(write_file("tube.xml", text), 3);
    ASSERT_EQ(patches.size(), 1u);
    const NurbsData& n = patches[0].nurbs;
    EXPECT_EQ(n.degrees, (std::vector<int>{1, 2, 2}));
    EXPECT_EQ(n.knots[2], (std::vector<double>{0, 0, 0, 0.5, 1, 1, 1}));
    ASSERT_EQ(n.control_points.size(), 24u);
    // index(i, j, k) = i + 2 (j + 3 k): the last point is outer radius, arc end, top.
    EXPECT_EQ(n.control_points[23], (std::vector<double>{0, 2, 3, 1}));
    EXPECT_EQ(n.control_points[0 + 2 * (1 + 3 * 2)], (std::vector<double>{1, 1, 2.25, w}));
    // The same file is a dimension mismatch in a 2D deck.
    const std::string message = error_of(write_file("tube.xml", text), 2);
    EXPECT_NE(message.find("tube.xml:38: error: MultiPatch.parDim = 3: a multi-patch of 3-parameter patches, but "
                           "analysis.dimension is 2"),
              std::string::npos)
        << message;
}

TEST(GismoXml, DiscOfFivePatchesFromInputs)
{
    const auto patches = read_gismo_xml(std::string(IGA_SOURCE_DIR) + "/inputs/disc_five_patches.xml", 2);
    ASSERT_EQ(patches.size(), 5u);
    // Each ring patch's v1 side (rows 3..5) is an exact quarter circle of radius 1.
    constexpr double radius_tolerance = 1e-14;  // round-off of a few products of order-1 values
    for (std::size_t k = 1; k < 5; ++k) {
        const auto& cp = patches[k].nurbs.control_points;
        ASSERT_EQ(cp.size(), 6u);
        for (double t = 0.0; t <= 1.0; t += 0.25) {
            const double b[3] = {(1 - t) * (1 - t), 2 * t * (1 - t), t * t};
            double x = 0, y = 0, wsum = 0;
            for (std::size_t j = 0; j < 3; ++j) {
                x += b[j] * cp[3 + j][2] * cp[3 + j][0];
                y += b[j] * cp[3 + j][2] * cp[3 + j][1];
                wsum += b[j] * cp[3 + j][2];
            }
            const double r = std::hypot(x / wsum, y / wsum);
            EXPECT_TRUE(std::isfinite(r) && std::abs(r - 1.0) < radius_tolerance) << patches[k].name << " t " << t;
        }
        // Its v0 side (rows 0..2) is a side of the centre square: three of p0's control points.
        for (std::size_t j = 0; j < 3; ++j) {
            bool found = false;
            for (const auto& q : patches[0].nurbs.control_points)
                found = found || (q[0] == cp[j][0] && q[1] == cp[j][1] && cp[j][2] == 1.0);
            EXPECT_TRUE(found) << patches[k].name << " row " << j;
        }
    }
}

// ---------------------------------------------------------------------------
// Malformed files: one located error each, at the line of the offending text.

const std::string good_patch = R"( <Geometry type="TensorBSpline2" id="0">
  <Basis type="TensorBSplineBasis2">
   <Basis type="BSplineBasis" index="0">
    <KnotVector degree="1">0 0 1 1</KnotVector>
   </Basis>
   <Basis type="BSplineBasis" index="1">
    <KnotVector degree="1">0 0 1 1</KnotVector>
   </Basis>
  </Basis>
  <coefs geoDim="2">
   0 0
   1 0
   0 1
   1 1
  </coefs>
 </Geometry>
)";  // lines 2..17 of a file that starts with "<xml>\n": coefs on line 11, its rows on 12..15

/// `text` with the first occurrence of `from` replaced by `to` (built with append:
/// GCC 12 warns falsely, -Wrestrict, on replace() and operator+ of temporaries here).
std::string replaced(const std::string& text, const std::string& from, const std::string& to)
{
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at == std::string::npos)
        return text;
    std::string out = text.substr(0, at);
    out.append(to).append(text, at + from.size());
    return out;
}

/// `good_patch` inside <xml> with `from` replaced by `to` (the first occurrence).
std::string broken(const std::string& from, const std::string& to, const std::string& tail = "")
{
    std::string out = "<xml>\n";
    out.append(replaced(good_patch, from, to)).append(tail).append("</xml>\n");
    return out;
}

/// A TensorBSpline3 whose degree-1 knot vectors (0 0 1 2 ... 3000 3000) give 3001
/// functions each, and one control point in <coefs> (on line 8).
std::string huge_knot_volume()
{
    std::string knots = "0";
    for (int i = 0; i <= 3000; ++i)
        knots.append(" ").append(std::to_string(i));
    knots.append(" 3000");
    std::string out = "<xml>\n <Geometry type=\"TensorBSpline3\" id=\"0\">\n  <Basis type=\"TensorBSplineBasis3\">\n";
    for (int dir = 0; dir < 3; ++dir)
        out.append("   <Basis type=\"BSplineBasis\" index=\"")
            .append(std::to_string(dir))
            .append("\"><KnotVector degree=\"1\">")
            .append(knots)
            .append("</KnotVector></Basis>\n");
    out.append("  </Basis>\n  <coefs geoDim=\"3\">0 0 0</coefs>\n </Geometry>\n</xml>\n");
    return out;
}

struct MalformedCase {
    const char* name;
    std::string text;  ///< file content; empty: no file at all
    int dimension;
    std::string expected;  ///< the start of the message, after "<file>"
};

std::vector<MalformedCase> malformed_cases()
{
    const std::string nurbs_patch = R"(<xml>
 <Geometry type="TensorNurbs2" id="3">
  <Basis type="TensorNurbsBasis2">
   <Basis type="TensorBSplineBasis2">
    <Basis type="BSplineBasis" index="0"><KnotVector degree="1">0 0 1 1</KnotVector></Basis>
    <Basis type="BSplineBasis" index="1"><KnotVector degree="1">0 0 1 1</KnotVector></Basis>
   </Basis>
   <weights>1 1
            -0.5 1</weights>
  </Basis>
  <coefs geoDim="2">0 0 1 0 0 1 1 1</coefs>
 </Geometry>
</xml>
)";
    const std::string three_weights = replaced(nurbs_patch, "-0.5 1", "1");
    const std::string no_weights = replaced(nurbs_patch, "   <weights>1 1\n            -0.5 1</weights>\n", "");
    return {
        {"missing_file", "", 2, ": error: cannot read the G+Smo XML file: no such file"},
        {"not_xml", "<xml>\n <Geometry type=\"TensorBSpline2\">\n  <coefs>1 2</coef>\n</xml>\n", 2,
         ":3: error: not well-formed XML (mismatched element"},
        {"plain_text", "degrees: [1, 1]\nknots: []\n", 2, ":1: error: not well-formed XML"},
        {"wrong_root", "<gismo>\n</gismo>\n", 2,
         ":1: error: not a G+Smo XML file: the root element is <gismo>, expected <xml>"},
        {"no_geometry", "<xml>\n</xml>\n", 2, ":1: error: no <Geometry> element in the file"},
        {"unknown_type", broken("TensorBSpline2\" id", "THBSpline2\" id"), 2,
         ":2: error: Geometry(id=0).type = THBSpline2: unsupported geometry type (supported: TensorBSpline2, "
         "TensorNurbs2, TensorBSpline3, TensorNurbs3)"},
        {"dimension_mismatch_type", broken("", ""), 3,
         ":2: error: Geometry(id=0).type = TensorBSpline2: a 2-parameter patch, but analysis.dimension is 3"},
        {"wrong_basis", broken("TensorBSplineBasis2", "TensorNurbsBasis2"), 2,
         ":3: error: Geometry(id=0).Basis.type = TensorNurbsBasis2: expected <Basis type=\"TensorBSplineBasis2\"> "
         "here"},
        {"missing_knot_vector", broken("    <KnotVector degree=\"1\">0 0 1 1</KnotVector>\n   </Basis>\n  </Basis>",
                                       "   </Basis>\n  </Basis>"),
         2, ":7: error: Geometry(id=0).KnotVector(index=1): missing <KnotVector degree=\"p\">knots</KnotVector>"},
        {"missing_direction", broken("   <Basis type=\"BSplineBasis\" index=\"1\">\n    <KnotVector degree=\"1\">0 0 1 "
                                     "1</KnotVector>\n   </Basis>\n",
                                     ""),
         2, ":3: error: Geometry(id=0).KnotVector(index=1): missing the knot vector of direction 1"},
        {"missing_degree", broken("<KnotVector degree=\"1\">0 0 1 1</KnotVector>\n   </Basis>\n  </Basis>",
                                  "<KnotVector>0 0 1 1</KnotVector>\n   </Basis>\n  </Basis>"),
         2, ":8: error: Geometry(id=0).KnotVector(index=1): <KnotVector> needs the attribute degree=\"...\""},
        {"decreasing_knots", broken("0 0 1 1</KnotVector>\n   </Basis>\n  </Basis>",
                                    "0 0\n 1 0.5 1</KnotVector>\n   </Basis>\n  </Basis>"),
         2, ":9: error: Geometry(id=0).KnotVector(index=1) = 0.5: knots must be non-decreasing (the knot before is 1)"},
        {"knots_not_open", broken("0 0 1 1</KnotVector>", "0 0.2 1 1</KnotVector>"), 2,
         ":5: error: Geometry(id=0).KnotVector(index=0): not an open knot vector"},
        {"non_numeric_knot", broken("0 0 1 1</KnotVector>", "0 0 one 1</KnotVector>"), 2,
         ":5: error: Geometry(id=0).KnotVector(index=0) = one: not a finite number"},
        {"non_numeric_coef", broken("   0 1\n", "   0 1,\n"), 2,
         ":14: error: Geometry(id=0).coefs = 1,: not a finite number"},
        {"nan_coef", broken("   1 1\n", "   1 nan\n"), 2, ":15: error: Geometry(id=0).coefs = nan: not a finite number"},
        {"too_few_coefs", broken("   1 1\n", ""), 2,
         ":11: error: Geometry(id=0).coefs: expected 8 numbers (2 x 2 control points from the knot vectors, 2 "
         "coordinates each), got 6"},
        {"missing_coefs", broken("  <coefs geoDim=\"2\">\n   0 0\n   1 0\n   0 1\n   1 1\n  </coefs>\n", ""), 2,
         ":2: error: Geometry(id=0).coefs: missing <coefs geoDim=\"d\">"},
        {"geo_dim_too_small", R"(<xml>
 <Geometry type="TensorBSpline3" id="0">
  <Basis type="TensorBSplineBasis3">
   <Basis type="BSplineBasis" index="0"><KnotVector degree="1">0 0 1 1</KnotVector></Basis>
   <Basis type="BSplineBasis" index="1"><KnotVector degree="1">0 0 1 1</KnotVector></Basis>
   <Basis type="BSplineBasis" index="2"><KnotVector degree="1">0 0 1 1</KnotVector></Basis>
  </Basis>
  <coefs geoDim="2">0 0 1 0 0 1 1 1 0 0 1 0 0 1 1 1</coefs>
 </Geometry>
</xml>
)",
         3, ":8: error: Geometry(id=0).coefs.geoDim = 2: the control points have 2 coordinates, but analysis.dimension "
            "is 3"},
        {"geo_dim_not_integer", broken("geoDim=\"2\"", "geoDim=\"two\""), 2,
         ":11: error: Geometry(id=0).coefs.geoDim = two: not an integer"},
        {"nonzero_z", broken("geoDim=\"2\">\n   0 0\n   1 0\n   0 1\n   1 1\n",
                             "geoDim=\"3\">\n   0 0 0\n   1 0 0\n   0 1 0.25\n   1 1 0\n"),
         2,
         ":14: error: Geometry(id=0).coefs = 0.25: control point 3 has z = 0.25: a geoDim 3 geometry fits a 2D deck "
         "only when its extra coordinates are zero"},
        {"negative_weight", nurbs_patch, 2,
         ":9: error: Geometry(id=3).weights = -0.5: weight 3 (control point 3) must be > 0"},
        {"zero_weight", replaced(nurbs_patch, "-0.5", "0"), 2, ":9: error: Geometry(id=3).weights = 0: weight 3 (control point 3) must be > 0"},
        {"wrong_weight_count", three_weights, 2,
         ":8: error: Geometry(id=3).weights: expected 4 weights (2 x 2 control points from the knot vectors), got 3"},
        {"missing_weights", no_weights, 2, ":3: error: Geometry(id=3).weights: missing <weights>"},
        {"duplicate_id", broken("", "", good_patch), 2,
         ":18: error: Geometry(id=0): duplicate Geometry id 0 (first at line 2)"},
        {"multipatch_unknown_id",
         broken("", "", " <MultiPatch parDim=\"2\" id=\"1\">\n  <patches type=\"id_range\">0 1</patches>\n </MultiPatch>\n"),
         2, ":19: error: MultiPatch.patches = 1: no <Geometry id=\"1\"> in the file (Geometry ids: 0)"},
        {"multipatch_unknown_index",
         broken("", "", " <MultiPatch parDim=\"2\">\n  <patches type=\"id_index\">\n  0\n  4\n  </patches>\n </MultiPatch>\n"),
         2, ":21: error: MultiPatch.patches = 4: no <Geometry id=\"4\"> in the file (Geometry ids: 0)"},
        {"multipatch_bad_type",
         broken("", "", " <MultiPatch parDim=\"2\">\n  <patches type=\"list\">0</patches>\n </MultiPatch>\n"), 2,
         ":19: error: MultiPatch.patches.type = list: expected id_range (first last) or id_index"},
        {"multipatch_par_dim",
         broken("", "", " <MultiPatch parDim=\"3\">\n  <patches type=\"id_range\">0 0</patches>\n </MultiPatch>\n"),
         2, ":18: error: MultiPatch.parDim = 3: a multi-patch of 3-parameter patches, but analysis.dimension is 2"},
        {"multipatch_no_patches", broken("", "", " <MultiPatch parDim=\"2\">\n </MultiPatch>\n"), 2,
         ":18: error: MultiPatch: missing <patches type=\"id_range\">"},
        // An id_range ending at INT_MAX (an int counter never passes it), and one of two
        // billion ids in a file of one Geometry (reported at its first missing id).
        {"multipatch_range_to_int_max",
         broken("", "",
                " <MultiPatch parDim=\"2\">\n  <patches type=\"id_range\">2147483647 2147483647</patches>\n "
                "</MultiPatch>\n"),
         2, ":19: error: MultiPatch.patches = 2147483647: no <Geometry id=\"2147483647\"> in the file (Geometry ids: 0)"},
        {"multipatch_range_two_billion",
         broken("", "",
                " <MultiPatch parDim=\"2\">\n  <patches type=\"id_range\">0 2000000000</patches>\n </MultiPatch>\n"),
         2, ":19: error: MultiPatch.patches = 1: no <Geometry id=\"1\"> in the file (Geometry ids: 0)"},
        // Three knot vectors of 3003 knots imply 3001^3 = 2.7e10 control points (216 GB
        // of weights alone); <coefs> holds one: the count is checked before allocating.
        {"knots_imply_billions_of_control_points", huge_knot_volume(), 3,
         ":8: error: Geometry(id=0).coefs: expected 81081027003 numbers (3001 x 3001 x 3001 control points from "
         "the knot vectors, 3 coordinates each), got 3"},
    };
}

TEST(GismoXml, MalformedFilesAreLocatedErrors)
{
    for (const MalformedCase& c : malformed_cases()) {
        SCOPED_TRACE(c.name);
        const std::string file = c.text.empty() ? (fs::temp_directory_path() / "igacontact_no_such_dir" / "four.xml").string()
                                                : write_file(std::string(c.name) + ".xml", c.text);
        const std::string message = error_of(file, c.dimension);
        EXPECT_EQ(message.rfind(file + c.expected, 0), 0u) << "got:      " << message << "\nexpected: " << file
                                                           << c.expected;
        // One problem, one line: the reader does not pile follow-up errors on the first.
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

TEST(GismoXml, APathThatIsNotAFileSaysWhatItIs)
{
    const fs::path folder = fs::path(write_file("placeholder", "")).parent_path();
    const std::string dir = (folder / "geom.xml").string();
    fs::create_directories(dir);
    EXPECT_EQ(error_of(dir, 2), dir + ": error: cannot read the G+Smo XML file: it is a folder, not a file");
    const std::string fifo = (folder / "pipe.xml").string();
    fs::remove(fifo);
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    // Refused before it is opened: opening a FIFO for reading would block.
    EXPECT_EQ(error_of(fifo, 2), fifo + ": error: cannot read the G+Smo XML file: it is a FIFO (named pipe), not a file");
    fs::remove(fifo);
}

TEST(GismoXml, IndependentProblemsAreAllReported)
{
    // Two broken patches: both are reported, in file order, in one DeckError.
    const std::string second = replaced(replaced(good_patch, "id=\"0\"", "id=\"1\""), "   1 1\n", "");
    const std::string text = broken("0 0 1 1</KnotVector>", "0 0 x 1</KnotVector>", second);
    const std::string file = write_file("two_problems.xml", text);
    const std::string message = error_of(file, 2);
    EXPECT_NE(message.find(file + ":5: error: Geometry(id=0).KnotVector(index=0) = x: not a finite number\n" + file +
                           ":27: error: Geometry(id=1).coefs: expected 8 numbers"),
              std::string::npos)
        << message;
}

}  // namespace
}  // namespace iga::io
