// Contact patch test between two MULTI-PATCH bodies (deck.md "Multi-patch bodies
// and named surfaces"): both contact surfaces are named surfaces spanning two
// patches, the patch interfaces of the two bodies lie at different places, and
// the knots of the two faces do not line up. As in contact_patch_test.cpp
// (E = 1e6, nu = 0, penalty 1e9, top pushed down by Delta = 0.01, H = 1):
// p = Delta / (H/E + 1/eps), linear fields lie in both spaces, and each half pass
// integrates a constant pressure against its own surface's basis, so every
// Gauss-point pressure on both surfaces is exact up to round-off -- including the
// points whose closest point lies on the other body's neighbouring patch.
//  - 2D: lower [0, 1] x [0, 0.5] cut at x = 0.35, upper [0, 1] x [0.5, 1] cut at x = 0.6;
//  - 3D: lower [0, 1]^2 x [0, 0.5] cut at x = 0.4, upper [0, 1]^2 x [0.5, 1] cut at y = 0.55.

#include "multipatch_decks.hpp"
#include "run_support.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>

namespace iga::test {
namespace {

constexpr double E = 1.0e6, penalty = 1.0e9, Delta = 0.01, H = 1.0;
const double exact_pressure = Delta / (H / E + 1.0 / penalty);
// Round-off of the penalty pressure, as in contact_patch_test.cpp (measured 2e-11
// there: the gap p/eps ~ 1e-5 is a difference of displacements ~1e-2); a point
// projected onto the wrong patch or dropped at an interface is O(1e-2) and more.
constexpr double uniform_tolerance = 1e-9;

/// A bilinear (2D) patch [x0, x1] x [y0, y1] named `name`, with its own spans.
std::string rectangle(const std::string& name, double x0, double x1, double y0, double y1, int spans_x)
{
    return fmt::format("      - name: {}\n"
                       "        nurbs: {{degrees: [1, 1], knots: [[0, 0, 1, 1], [0, 0, 1, 1]],\n"
                       "                control_points: [[{x0}, {y0}, 1], [{x1}, {y0}, 1], [{x0}, {y1}, 1], [{x1}, {y1}, 1]]}}\n"
                       "        refine: {{spans: [{}, 2]}}\n",
                       name, spans_x, fmt::arg("x0", x0), fmt::arg("x1", x1), fmt::arg("y0", y0), fmt::arg("y1", y1));
}

/// A trilinear (3D) box patch with corner c and size s, named `name`, with its own spans.
std::string box(const std::string& name, const std::array<double, 3>& c, const std::array<double, 3>& s,
                const std::array<int, 3>& spans)
{
    std::string out = fmt::format("      - name: {}\n        nurbs:\n          degrees: [1, 1, 1]\n"
                                  "          knots: [[0, 0, 1, 1], [0, 0, 1, 1], [0, 0, 1, 1]]\n"
                                  "          control_points:\n",
                                  name);
    for (int k = 0; k < 8; ++k)
        out += fmt::format("            - [{}, {}, {}, 1]\n", c[0] + s[0] * (k & 1), c[1] + s[1] * ((k >> 1) & 1),
                           c[2] + s[2] * ((k >> 2) & 1));
    out += fmt::format("        refine: {{spans: [{}, {}, {}]}}\n", spans[0], spans[1], spans[2]);
    return out;
}

/// Every Gauss-point pressure of both surfaces: exact; Gauss points on both
/// patches of each surface (gauss_points/patch).
void expect_exact_uniform_pressure(const Results& r, const std::array<std::string, 2>& sides)
{
    for (const std::string& side : sides) {
        SCOPED_TRACE(side);
        const std::string g = "results/contact/interface/" + side + "/";
        const std::vector<double> p = r.reals(g + "gauss_points/pressure");
        const std::vector<double> patch = r.reals(g + "gauss_points/patch");
        ASSERT_FALSE(p.empty());
        ASSERT_EQ(patch.size(), p.size());
        int on[2] = {0, 0};
        for (std::size_t k = 0; k < p.size(); ++k) {
            EXPECT_TRUE(near_rel(p[k], exact_pressure, uniform_tolerance)) << "Gauss point " << k << ", patch " << patch[k];
            ++on[patch[k] == 0.0 ? 0 : 1];
        }
        EXPECT_GT(on[0], 0);
        EXPECT_GT(on[1], 0);
        EXPECT_TRUE(near_rel(r.number(g, "normal_force"), exact_pressure, uniform_tolerance)) << "unit interface area";
    }
}

TEST(MultiPatchContactPatchTest, TwoHalfPassIsExactBetweenTwoPatchSurfacesWithInterfacesApart2D)
{
    const auto dir = scratch_dir("multipatch_contact_patch_2d");
    const std::string deck = "format: 1\nanalysis: {dimension: 2, plane: strain, kinematics: small}\n"
                             "materials: [{name: solid, model: linear_elastic, E: 1.0e6, nu: 0.0}]\n"
                             "bodies:\n"
                             "  - name: lower\n    material: solid\n    patches:\n" +
                             rectangle("a", 0.0, 0.35, 0.0, 0.5, 2) + rectangle("b", 0.35, 1.0, 0.0, 0.5, 3) +
                             "    refine: {elevate: [1, 1]}\n"
                             "    surfaces: {bottom: [a.v0, b.v0], face: [a.v1, b.v1]}\n"
                             "  - name: upper\n    material: solid\n    patches:\n" +
                             rectangle("c", 0.0, 0.6, 0.5, 1.0, 3) + rectangle("d", 0.6, 1.0, 0.5, 1.0, 2) +
                             "    refine: {elevate: [1, 1]}\n"
                             "    surfaces: {face: [c.v0, d.v0], top: [c.v1, d.v1]}\n"
                             "constraints:\n"
                             "  - {body: lower, side: bottom, fix: [y]}\n"
                             "  - {body: lower, side: a.u0, fix: [x]}\n"
                             "  - {body: upper, side: c.u0, fix: [x]}\n"
                             "  - {body: upper, side: top, displacement: [0.0, -0.01]}\n"
                             "contact:\n"
                             "  - {name: interface, between: [upper.face, lower.face], formulation: two_half_pass, "
                             "penalty: 1.0e9}\n";
    write_text(dir / "deck.yaml", deck);
    const auto file = dir / "patch.h5";
    const analysis::RunOutcome outcome = run_deck((dir / "deck.yaml").string(), {}, file);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    expect_exact_uniform_pressure(Results(file), {"upper.face", "lower.face"});
}

TEST(MultiPatchContactPatchTest, TwoHalfPassIsExactBetweenTwoPatchSurfacesWithInterfacesApart3D)
{
    const auto dir = scratch_dir("multipatch_contact_patch_3d");
    const std::string deck = "format: 1\nanalysis: {dimension: 3, kinematics: small}\n"
                             "materials: [{name: solid, model: linear_elastic, E: 1.0e6, nu: 0.0}]\n"
                             "bodies:\n"
                             "  - name: lower\n    material: solid\n    patches:\n" +
                             box("a", {0.0, 0.0, 0.0}, {0.4, 1.0, 0.5}, {2, 2, 1}) +
                             box("b", {0.4, 0.0, 0.0}, {0.6, 1.0, 0.5}, {2, 2, 1}) +
                             "    refine: {elevate: [1, 1, 1]}\n"
                             "    surfaces: {bottom: [a.w0, b.w0], ymin: [a.v0, b.v0], face: [a.w1, b.w1]}\n"
                             "  - name: upper\n    material: solid\n    patches:\n" +
                             box("c", {0.0, 0.0, 0.5}, {1.0, 0.55, 0.5}, {3, 2, 1}) +
                             box("d", {0.0, 0.55, 0.5}, {1.0, 0.45, 0.5}, {3, 2, 1}) +
                             "    refine: {elevate: [1, 1, 1]}\n"
                             "    surfaces: {xmin: [c.u0, d.u0], face: [c.w0, d.w0], top: [c.w1, d.w1]}\n"
                             "constraints:\n"
                             "  - {body: lower, side: bottom, fix: [z]}\n"
                             "  - {body: lower, side: a.u0, fix: [x]}\n"
                             "  - {body: lower, side: ymin, fix: [y]}\n"
                             "  - {body: upper, side: xmin, fix: [x]}\n"
                             "  - {body: upper, side: c.v0, fix: [y]}\n"
                             "  - {body: upper, side: top, displacement: [~, ~, -0.01]}\n"
                             "contact:\n"
                             "  - {name: interface, between: [upper.face, lower.face], formulation: two_half_pass, "
                             "penalty: 1.0e9}\n";
    write_text(dir / "deck.yaml", deck);
    const auto file = dir / "patch.h5";
    const analysis::RunOutcome outcome = run_deck((dir / "deck.yaml").string(), {}, file);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    expect_exact_uniform_pressure(Results(file), {"upper.face", "lower.face"});
}

}  // namespace
}  // namespace iga::test
