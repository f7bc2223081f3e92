// A body cut into patches along a C0 knot plane is the same discrete body as the
// uncut patch (deck.md "Multi-patch bodies and named surfaces"): the two
// discretizations span the same space with the same unknowns, so every result
// agrees to round-off of the solve.
//  - 3D: a block of two patches glued at x = 1, with a sagging bottom that
//    spans both patches, pressed on a rigid plane (small kinematics);
//  - 2D, finite kinematics: the same cut-vs-uncut block of multipatch_test.cpp
//    held at its bottom and pushed by a FOLLOWER pressure on a named surface
//    that spans both patches (the pressure follows the deformed top).
// The uncut patch carries a double (C0) knot where the cut runs; the cut patches
// get the rest of the refinement partly through the interface (the conforming
// propagation of nurbs/topology.hpp), so the test also checks that propagation.

#include "multipatch_decks.hpp"
#include "run_support.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>


namespace iga::test {
namespace {

// Same space, same unknowns, a different summation order: round-off of the solve
// (condition number ~1e6 of the penalty system times 1e-16, with a margin).
constexpr double round_off = 1e-9;

/// Rows of `b` matched to rows of `a` by their coordinates (a row of b that has
/// no row of a within `tol` maps to -1).
std::vector<Index> match_rows(const RowMatrix& a, const RowMatrix& b, double tol)
{
    std::vector<Index> out(static_cast<std::size_t>(b.rows()), -1);
    for (Index i = 0; i < b.rows(); ++i)
        for (Index j = 0; j < a.rows(); ++j)
            if ((a.row(j) - b.row(i)).cwiseAbs().maxCoeff() <= tol) {
                out[static_cast<std::size_t>(i)] = j;
                break;
            }
    return out;
}

TEST(MultiPatchEquivalence, TwoPatchesEqualTheUncutPatchToRoundOff3D)
{
    const auto dir = scratch_dir("multipatch_split_3d");
    write_text(dir / "single.yaml", block_deck_3d(block_3d_single(), "block.w0", "w1"));
    write_text(dir / "split.yaml", block_deck_3d(block_3d_split(), "block.bottom", "top"));

    const analysis::RunOutcome one = run_deck((dir / "single.yaml").string(), {}, dir / "single.h5");
    ASSERT_EQ(one.status, "completed") << one.message;
    const analysis::RunOutcome two = run_deck((dir / "split.yaml").string(), {}, dir / "split.h5");
    ASSERT_EQ(two.status, "completed") << two.message;
    const Results a(dir / "single.h5"), b(dir / "split.h5");

    // Control points: u has knots 0.25, 0.5 (C0), 0.75 -> 7; v 0.5 -> 4; w 0.5 -> 3.
    const RowMatrix u = a.matrix("results/displacement/block");
    const RowMatrix u_left = b.matrix("results/displacement/block/left");
    const RowMatrix u_right = b.matrix("results/displacement/block/right");
    const Index n_u = 7, n_l = 4, n_r = n_u - n_l + 1, n_v = 4, n_w = 3;
    ASSERT_EQ(u.rows(), n_u * n_v * n_w);
    ASSERT_EQ(u_left.rows(), n_l * n_v * n_w);
    ASSERT_EQ(u_right.rows(), n_r * n_v * n_w);
    const double scale = u.cwiseAbs().maxCoeff();
    ASSERT_TRUE(at_least(scale, 1e-3)) << "the top moves by 0.01";
    for (Index l = 0; l < n_w; ++l)
        for (Index j = 0; j < n_v; ++j)
            for (Index i = 0; i < n_u; ++i) {
                const Index k = i + n_u * (j + n_v * l);
                const bool left = i < n_l;
                const Index kp = left ? i + n_l * (j + n_v * l) : (i - n_l + 1) + n_r * (j + n_v * l);
                const RowMatrix& part = left ? u_left : u_right;
                for (Index c = 0; c < 3; ++c)
                    EXPECT_TRUE(near(part(kp, c), u(k, c), round_off * scale)) << "cp " << k << " component " << c;
                if (i == n_l - 1) {  // the interface plane: one value in both patches
                    for (Index c = 0; c < 3; ++c)
                        EXPECT_EQ(u_right(n_r * (j + n_v * l), c), part(kp, c));
                }
            }

    // Gauss points: the same points (the cut surface's elements are the uncut
    // face's, numbered piece after piece), matched by reference coordinates.
    const std::string pa = "results/contact/touch/block.w0/", pb = "results/contact/touch/block.bottom/";
    const RowMatrix Xa = a.matrix(pa + "gauss_points/reference_coordinates");
    const RowMatrix Xb = b.matrix(pb + "gauss_points/reference_coordinates");
    const RowMatrix p = a.matrix(pa + "gauss_points/pressure"), q = b.matrix(pb + "gauss_points/pressure");
    ASSERT_EQ(Xa.rows(), Xb.rows());
    constexpr double same_point = 1e-12;  // the same reference point, evaluated on different patches
    const std::vector<Index> gauss = match_rows(Xa, Xb, same_point);
    const double p_scale = p.cwiseAbs().maxCoeff();
    ASSERT_TRUE(at_least(p_scale, 1.0)) << "the bottom touches the plane";
    int active = 0;
    for (Index g = 0; g < Xb.rows(); ++g) {
        const Index m = gauss[static_cast<std::size_t>(g)];
        ASSERT_GE(m, 0) << "Gauss point " << g << " of the cut body is not one of the uncut body's";
        EXPECT_TRUE(near(q(g, 0), p(m, 0), round_off * p_scale)) << "Gauss point " << g;
        active += q(g, 0) > 0.0;
    }
    // The contact zone lies on both patches (the bottom is lowest at the cut).
    const RowMatrix Gb = b.matrix(pb + "gauss_points/reference_coordinates");
    int left_active = 0, right_active = 0;
    for (Index g = 0; g < Gb.rows(); ++g)
        if (q(g, 0) > 0.0)
            (Gb(g, 0) < 1.0 ? left_active : right_active) += 1;
    EXPECT_GT(left_active, 0);
    EXPECT_GT(right_active, 0);

    // Post-processed samples (Sauer's averages, interface control points averaged
    // once): every sample of the cut surface is a sample of the uncut face.
    const RowMatrix Sa = a.matrix(pa + "postprocessed/reference_coordinates");
    const RowMatrix Sb = b.matrix(pb + "postprocessed/reference_coordinates");
    const RowMatrix sa = a.matrix(pa + "postprocessed/pressure"), sb = b.matrix(pb + "postprocessed/pressure");
    const std::vector<Index> samples = match_rows(Sa, Sb, same_point);
    for (Index s = 0; s < Sb.rows(); ++s) {
        const Index m = samples[static_cast<std::size_t>(s)];
        ASSERT_GE(m, 0) << "sample " << s;
        EXPECT_TRUE(near(sb(s, 0), sa(m, 0), round_off * p_scale)) << "sample " << s;
    }
    EXPECT_EQ(a.matrix(pa + "postprocessed/control_point_pressure").rows(),
              b.matrix(pb + "postprocessed/control_point_pressure").rows())
        << "the interface control points are one surface control point each";
    EXPECT_TRUE(near(b.number(pb, "normal_force"), a.number(pa, "normal_force"), round_off * p_scale));
}


// 2D, finite kinematics: block [0, 2] x [0, 1] with a domed top
// y = 1 - 0.1 (x - 1)^2 at the control polygon, rational in u, neo-Hookean,
// clamped at the bottom, a follower pressure of 80 (8 % of E: strains of several
// per cent, where the follower term matters) on the top, in 4 increments.
std::string points_2d(int first, int last, const std::string& indent)
{
    std::string out;
    for (int j = 0; j < 3; ++j)
        for (int i = first; i <= last; ++i) {
            const double y = j == 2 ? 1.0 - 0.1 * (block_xs[i] - 1.0) * (block_xs[i] - 1.0) : 0.5 * j;
            out += fmt::format("{}- [{}, {}, {}]\n", indent, block_xs[i], y, block_ws[i]);
        }
    return out;
}

std::string deck_finite_2d(const std::string& body, const std::string& bottom, const std::string& top)
{
    return fmt::format(R"(format: 1
analysis: {{dimension: 2, plane: strain, kinematics: finite}}
materials:
  - {{name: m, model: neo_hookean, E: 1000.0, nu: 0.3}}
bodies:
  - name: block
    material: m
{}
constraints:
  - {{body: block, side: {}, fix: [x, y]}}
loads:
  - {{body: block, side: {}, pressure: 80.0}}
steps: {{count: 4}}
)",
                       body, bottom, top);
}

TEST(MultiPatchEquivalence, FollowerPressureOnASurfaceAcrossTwoPatchesEqualsTheUncutPatch)
{
    const auto dir = scratch_dir("multipatch_split_finite");
    const std::string single = "    nurbs:\n      degrees: [2, 2]\n"
                               "      knots: [[0, 0, 0, 0.5, 0.5, 1, 1, 1], [0, 0, 0, 1, 1, 1]]\n"
                               "      control_points:\n" +
                               points_2d(0, 4, "        ") + "    refine: {spans: [4, 3]}\n";
    const std::string split = "    patches:\n"
                              "      - name: left\n        nurbs:\n          degrees: [2, 2]\n"
                              "          knots: [[0, 0, 0, 0.5, 0.5, 0.5], [0, 0, 0, 1, 1, 1]]\n"
                              "          control_points:\n" +
                              points_2d(0, 2, "            ") +
                              "        refine: {spans: [2, 1]}\n"
                              "      - name: right\n        nurbs:\n          degrees: [2, 2]\n"
                              "          knots: [[0.5, 0.5, 0.5, 1, 1, 1], [0, 0, 0, 1, 1, 1]]\n"
                              "          control_points:\n" +
                              points_2d(2, 4, "            ") +
                              "        refine: {spans: [2, 3]}\n"
                              "    surfaces: {bottom: [left.v0, right.v0], top: [left.v1, right.v1]}\n";
    write_text(dir / "single.yaml", deck_finite_2d(single, "v0", "v1"));
    write_text(dir / "split.yaml", deck_finite_2d(split, "bottom", "top"));

    const analysis::RunOutcome one = run_deck((dir / "single.yaml").string(), {}, dir / "single.h5");
    ASSERT_EQ(one.status, "completed") << one.message;
    const analysis::RunOutcome two = run_deck((dir / "split.yaml").string(), {}, dir / "split.h5");
    ASSERT_EQ(two.status, "completed") << two.message;
    const Results a(dir / "single.h5"), b(dir / "split.h5");

    const RowMatrix u = a.matrix("results/displacement/block");
    const RowMatrix u_left = b.matrix("results/displacement/block/left");
    const RowMatrix u_right = b.matrix("results/displacement/block/right");
    const Index n_u = 7, n_l = 4, n_r = n_u - n_l + 1, n_v = 5;
    ASSERT_EQ(u.rows(), n_u * n_v);
    ASSERT_EQ(u_left.rows(), n_l * n_v);
    ASSERT_EQ(u_right.rows(), n_r * n_v);
    const double scale = u.cwiseAbs().maxCoeff();
    // Finite strains: the top moves by several per cent of the height.
    constexpr double finite_displacement = 0.02;
    ASSERT_TRUE(at_least(scale, finite_displacement));
    for (Index j = 0; j < n_v; ++j)
        for (Index i = 0; i < n_u; ++i) {
            const Index k = i + n_u * j;
            const bool left = i < n_l;
            const Index kp = left ? i + n_l * j : (i - n_l + 1) + n_r * j;
            const RowMatrix& part = left ? u_left : u_right;
            for (Index c = 0; c < 2; ++c)
                EXPECT_TRUE(near(part(kp, c), u(k, c), round_off * scale)) << "cp " << k << " component " << c;
        }
    // The reaction of the clamped bottom balances the follower pressure's resultant.
    const std::vector<double> ra = a.reals("results/reactions/block.v0");
    const std::vector<double> rb = b.reals("results/reactions/block.bottom");
    ASSERT_EQ(ra.size(), 2u);
    ASSERT_EQ(rb.size(), 2u);
    const double r_scale = std::abs(ra[1]);
    ASSERT_TRUE(at_least(r_scale, 80.0)) << "pressure 80 on a top about 2 long";
    for (std::size_t c = 0; c < 2; ++c)
        EXPECT_TRUE(near(rb[c], ra[c], round_off * r_scale)) << "reaction component " << c;
    // Same Newton path: same number of iterations.
    EXPECT_EQ(two.newton_iterations, one.newton_iterations);
}

}  // namespace
}  // namespace iga::test
