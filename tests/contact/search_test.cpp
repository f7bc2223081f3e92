// Global element search on curves (2D) and surfaces (3D): the bounding-volume
// hierarchy returns exactly the elements whose inflated boxes hold the point
// (checked against a linear scan), which always include the element of the
// true foot point for points within the margin, and nothing for far points.

#include "contact/projection.hpp"
#include "contact/search.hpp"

#include "fixtures.hpp"
#include "surface_fixtures.hpp"
#include "support/tolerance.hpp"

#include <algorithm>
#include <gtest/gtest.h>
#include <random>

namespace iga::contact {
namespace {

using test::vec3;

/// The linear scan the hierarchy replaces: every element whose box holds x.
std::vector<int> scan(const ElementSearch& search, const VecN& x)
{
    std::vector<int> out;
    for (int e = 0; e < search.n_elements(); ++e)
        if (search.element_box(e).contains(x))
            out.push_back(e);
    return out;
}

nurbs::Patch fine_sphere(int n_spans)
{
    return nurbs::refine_uniform(nurbs::refine_uniform(test::sphere_octant(1.0), 0, n_spans), 1, n_spans);
}

TEST(ElementSearch, HierarchyFindsExactlyTheBoxesHoldingThePoint)
{
    const nurbs::Patch sphere = fine_sphere(12);
    const ElementSearch search(sphere, SearchOptions{.distance = 0.02});
    ASSERT_EQ(search.n_elements(), 144);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> coordinate(-0.2, 1.3);
    int non_empty = 0;
    for (int k = 0; k < 2000; ++k) {
        const VecN x = vec3(coordinate(rng), coordinate(rng), coordinate(rng));
        const std::vector<int> c = search.candidates(x);
        EXPECT_EQ(c, scan(search, x)) << "seed 3, sample " << k;  // same set, ascending
        non_empty += c.empty() ? 0 : 1;
    }
    EXPECT_GT(non_empty, 100);  // the sample really exercises hits, not only misses
}

TEST(ElementSearch, CandidatesHoldTheFootPointElement)
{
    const nurbs::Patch sphere = fine_sphere(8);
    const double margin = 0.05;
    const ElementSearch search(sphere, SearchOptions{.distance = margin});
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> polar(0.0, 1.5707), azimuth(0.0, 1.5707), radius(1.0 - margin, 1.0 + margin);
    for (int k = 0; k < 200; ++k) {
        const double t = polar(rng), f = azimuth(rng);
        const VecN x = radius(rng) * vec3(std::sin(t) * std::cos(f), std::sin(t) * std::sin(f), std::cos(t));
        const Projection p = project_to_surface(sphere, +1, x);  // all elements
        ASSERT_EQ(p.status, Projection::Status::ok) << "seed 7, sample " << k;
        const std::vector<int> c = search.candidates(x);
        EXPECT_TRUE(std::binary_search(c.begin(), c.end(), p.element)) << "seed 7, sample " << k;
        // Restricted to the candidates, the projection finds the same foot point.
        ProjectionOptions options;
        options.candidate_elements = c;
        const Projection q = project_to_surface(sphere, +1, x, options);
        constexpr double same_foot = 1e-12;  // both converge to round-off
        EXPECT_TRUE(test::at_most((q.point - p.point).norm(), same_foot)) << "seed 7, sample " << k;
        EXPECT_LE(q.candidates, static_cast<int>(c.size()));
    }
}

TEST(ElementSearch, OverlappingMatchesAScanOfTheBoxes)
{
    const nurbs::Patch sphere = fine_sphere(6);
    const ElementSearch search(sphere, SearchOptions{.distance = 0.01});
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> coordinate(-0.1, 1.1), size(0.0, 0.3);
    std::vector<int> out;
    for (int k = 0; k < 300; ++k) {
        const VecN lower = vec3(coordinate(rng), coordinate(rng), coordinate(rng));
        const Box box{lower, lower + vec3(size(rng), size(rng), size(rng))};
        search.overlapping(box, out);
        std::vector<int> expected;
        for (int e = 0; e < search.n_elements(); ++e)
            if (search.element_box(e).overlaps(box))
                expected.push_back(e);
        EXPECT_EQ(out, expected) << "seed 5, sample " << k;
    }
}

TEST(ElementSearch, FarPointsHaveNoCandidatesAndBoundsCoverTheSide)
{
    const nurbs::Patch sphere = fine_sphere(4);
    const ElementSearch search(sphere, SearchOptions{.distance = 0.1});
    EXPECT_TRUE(search.candidates(vec3(3, 3, 3)).empty());
    EXPECT_TRUE(search.candidates(vec3(0.1, 0.1, 0.1)).empty());  // near the centre, far from the shell
    EXPECT_FALSE(search.candidates(vec3(0.0, 0.0, 1.05)).empty());  // above the pole
    EXPECT_TRUE(search.bounds().contains(vec3(1.05, 0.0, 0.0)));
    EXPECT_FALSE(search.bounds().overlaps(Box{vec3(2, 2, 2), vec3(3, 3, 3)}));
}

TEST(ElementSearch, LongCurveMatchesAScan)
{
    // 2D, many spans: deep hierarchy, same answers as the scan.
    const nurbs::Patch arc = nurbs::refine_uniform(test::quarter_arc(1.0), 0, 500);
    const ElementSearch search(arc, SearchOptions{.distance = 0.001});
    ASSERT_EQ(search.n_elements(), 500);
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> angle(-0.1, 1.7), radius(0.99, 1.01);
    for (int k = 0; k < 500; ++k) {
        const double t = angle(rng), r = radius(rng);
        const VecN x = test::vec2(r * std::cos(t), r * std::sin(t));
        EXPECT_EQ(search.candidates(x), scan(search, x)) << "seed 9, sample " << k;
    }
}

}  // namespace
}  // namespace iga::contact
