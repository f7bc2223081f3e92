// The symmetry planes that cut a contact zone (analysis/zone_symmetry.hpp) and the whole
// zone's half-width or radius read from a half or quarter model (level_estimate.hpp,
// side_quantity): a quarter disc held along x on its symmetry line, a sphere octant held on
// two faces; a clamp and a driven side are not mirrors.

#include "analysis/geometry.hpp"
#include "analysis/level_estimate.hpp"
#include "analysis/zone_symmetry.hpp"
#include "io/deck_reader.hpp"
#include "nurbs/side_patch.hpp"

#include "run_support.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

namespace iga::analysis {
namespace {

const std::string hertz_2d = test::source_path("inputs/hertz_accuracy_2d.yaml");
const std::string hertz_3d = test::source_path("inputs/hertz_sphere_plane_3d.yaml");

TEST(ZoneSymmetry, AFaceHeldAlongItsNormalAloneIsASymmetryPlane)
{
    const io::Deck quarter = io::read_deck(hertz_2d);
    const std::vector<SymmetryPlane> planes = symmetry_planes(quarter, *quarter.find_body("cylinder"));
    ASSERT_EQ(planes.size(), 1u);
    EXPECT_EQ(planes[0].axis, 0);
    EXPECT_NEAR(planes[0].coordinate, 0.0, 1e-14);

    const io::Deck octant = io::read_deck(hertz_3d);
    const std::vector<SymmetryPlane> faces = symmetry_planes(octant, *octant.find_body("ball"));
    ASSERT_EQ(faces.size(), 2u);
    EXPECT_EQ(faces[0].axis + faces[1].axis, 1) << "x = 0 and y = 0";

    // Held in every direction: a clamp. Driven along its normal: not a mirror either.
    io::Deck clamped = quarter, driven = quarter;
    clamped.constraints[0].fixed = {true, true};
    driven.constraints[0].value = {0.01, 0.0};
    EXPECT_TRUE(symmetry_planes(clamped, *clamped.find_body("cylinder")).empty());
    EXPECT_TRUE(symmetry_planes(driven, *driven.find_body("cylinder")).empty());
}

TEST(ZoneSymmetry, TheWholeZoneIsTheModelledPartMirroredAcrossThePlanesThatCutIt)
{
    const io::Deck deck = io::read_deck(hertz_2d);
    const io::Body& body = *deck.find_body("cylinder");
    const nurbs::Patch arc = nurbs::extract_side(build_patch(body, 2), Side::v0).patch;
    const std::vector<SymmetryPlane> planes = symmetry_planes(deck, body);

    // Gauss points along the floor at x = 0.01, 0.03, ..., each 0.02 wide.
    io::ContactSideResult side;
    io::GaussPointData& g = side.gauss_points;
    const Index n = 40;
    g.parameter = RowMatrix(n, 1);
    g.reference_coordinates = RowMatrix::Zero(n, 2);
    g.weight = Vector::Constant(n, 0.02);
    g.pressure = Vector::Zero(n);
    for (Index k = 0; k < n; ++k) {
        g.parameter(k, 0) = static_cast<double>(k) / n;
        g.reference_coordinates(k, 0) = 0.01 + 0.02 * static_cast<double>(k);
    }
    const SidePressure field{arc, Vector::Zero(arc.n_control_points())};
    const auto half_width = [&] {
        const int m = zone_mirrors(planes, arc.control_points(), g, zone_points(io::AccuracyQuantity::contact_radius, side));
        return side_quantity(io::AccuracyQuantity::contact_radius, side, {field}, m);
    };

    g.pressure.head(5).setOnes();  // x in [0, 0.1]: the half of a zone of half-width 0.1
    EXPECT_NEAR(half_width(), 0.1, 1e-14);
    g.pressure(0) = 0.0;  // lifted off the plane in a ring, still nearer to it than its extent
    EXPECT_NEAR(half_width(), 0.08, 1e-14);
    g.pressure.setZero();
    g.pressure.segment(20, 5).setOnes();  // x in [0.4, 0.5]: a zone of its own, not cut
    EXPECT_NEAR(half_width(), 0.05, 1e-14);
}

TEST(ZoneSymmetry, AQuarterOfADiscOnAnOctantGivesTheDiscsRadius)
{
    const io::Deck deck = io::read_deck(hertz_3d);
    const io::Body& body = *deck.find_body("ball");
    const nurbs::Patch face = nurbs::extract_side(build_patch(body, 3), Side::v0).patch;
    // Cells of width h within radius a of the lowest point (0, 0, 0), x, y >= 0.
    const double h = 0.01, a = 0.1;
    io::ContactSideResult side;
    io::GaussPointData& g = side.gauss_points;
    std::vector<std::array<double, 2>> points;
    for (double x = h / 2; x < 0.2; x += h)
        for (double y = h / 2; y < 0.2; y += h)
            points.push_back({x, y});
    const auto n = static_cast<Index>(points.size());
    g.parameter = RowMatrix::Zero(n, 2);
    g.reference_coordinates = RowMatrix::Zero(n, 3);
    g.weight = Vector::Constant(n, h * h);
    g.pressure = Vector::Zero(n);
    double area = 0.0;
    for (Index k = 0; k < n; ++k) {
        const auto [x, y] = points[static_cast<std::size_t>(k)];
        g.reference_coordinates.row(k) << x, y, 0.0;
        if (std::hypot(x, y) < a) {
            g.pressure(k) = 1.0;
            area += h * h;
        }
    }
    const SidePressure field{face, Vector::Zero(face.n_control_points())};
    const int m = zone_mirrors(symmetry_planes(deck, body), face.control_points(), g, zone_points(io::AccuracyQuantity::contact_radius, side));
    EXPECT_EQ(m, 2);
    EXPECT_NEAR(side_quantity(io::AccuracyQuantity::contact_radius, side, {field}, m), std::sqrt(4.0 * area / std::numbers::pi),
                1e-14);
    EXPECT_NEAR(side_quantity(io::AccuracyQuantity::contact_radius, side, {field}, m), a, 0.05 * a);
}

}  // namespace
}  // namespace iga::analysis
