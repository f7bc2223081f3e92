// Tests for assembly/dof_map.hpp: numbering, constraints, expand/restrict.

#include "assembly/dof_map.hpp"
#include "core/error.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace iga::assembly {
namespace {

// Two bodies of 3 and 4 control points in 2D: 14 full dofs, 3 of them prescribed.
DofMap two_bodies()
{
    return DofMap(2, {3, 4}, {{0, 0.5}, {1, 0.0}, {9, -2.0}});
}

TEST(DofMap, NumbersNodesBodyByBodyAndFreeDofsInOrder)
{
    const DofMap dofs = two_bodies();
    EXPECT_EQ(dofs.n_bodies(), 2);
    EXPECT_EQ(dofs.n_nodes(), 7);
    EXPECT_EQ(dofs.n_nodes(1), 4);
    EXPECT_EQ(dofs.node_offset(0), 0);
    EXPECT_EQ(dofs.node_offset(1), 3);
    EXPECT_EQ(dofs.n_full(), 14);
    EXPECT_EQ(dofs.n_constrained(), 3);
    EXPECT_EQ(dofs.n_free(), 11);
    EXPECT_EQ(dofs.dof(dofs.node_offset(1) + 1, 1), 9);

    int expected_free = 0;
    for (int i = 0; i < dofs.n_full(); ++i) {
        if (i == 0 || i == 1 || i == 9) {
            EXPECT_TRUE(dofs.is_constrained(i));
            EXPECT_EQ(dofs.free_index(i), -1);
        } else {
            EXPECT_EQ(dofs.free_index(i), expected_free);
            EXPECT_EQ(dofs.full_index(expected_free), i);
            ++expected_free;
        }
    }
    EXPECT_EQ(dofs.prescribed(9), -2.0);
    EXPECT_EQ(dofs.prescribed(4), 0.0);
}

TEST(DofMap, ExpandAndRestrictRoundTrip)
{
    const DofMap dofs = two_bodies();
    Vector u_free(dofs.n_free());
    for (int i = 0; i < dofs.n_free(); ++i)
        u_free(i) = 0.1 * (i + 1);
    const double load_factor = 0.25;
    const Vector full = dofs.expand(u_free, load_factor);
    ASSERT_EQ(full.size(), dofs.n_full());
    // Exact: expand and restrict only copy and scale by the load factor.
    EXPECT_EQ(full(0), load_factor * 0.5);
    EXPECT_EQ(full(1), 0.0);
    EXPECT_EQ(full(9), load_factor * -2.0);
    EXPECT_EQ(dofs.restrict(full), u_free);
    for (int i = 0; i < dofs.n_free(); ++i)
        EXPECT_EQ(full(dofs.full_index(i)), u_free(i));
}

TEST(DofMap, ConflictingPrescriptionsAreAnError)
{
    EXPECT_NO_THROW(DofMap(2, {2}, {{1, 1.0}, {1, 1.0}}));  // same value twice: fine
    EXPECT_THROW(DofMap(2, {2}, {{1, 1.0}, {1, 2.0}}), iga::Error);
    EXPECT_THROW(DofMap(2, {2}, {{4, 0.0}}), iga::Error);  // out of range
    EXPECT_THROW(DofMap(2, {2}, {{0, std::numeric_limits<double>::quiet_NaN()}}), iga::Error);
}

TEST(DofMap, EachPrescribedDofFollowsItsAmplitude)
{
    const Amplitude press_release({{0.0, 0.0}, {1.0, 1.0}, {2.0, 0.0}});
    const DofMap dofs(2, {2}, {{0, 0.5}, {1, -2.0, press_release}, {3, 0.0, press_release}, {3, 0.0}});
    // Exact: each value is scaled by its amplitude at t, which is exact at 0.5 and 1.5.
    EXPECT_EQ(dofs.expand(Vector::Zero(1), 0.5), (Vector(4) << 0.25, -1.0, 0.0, 0.0).finished());
    EXPECT_EQ(dofs.expand(Vector::Zero(1), 1.5), (Vector(4) << 0.5, -1.0, 0.0, 0.0).finished());
    EXPECT_EQ(dofs.expand(Vector::Zero(1), 2.0), (Vector(4) << 0.5, -0.0, 0.0, 0.0).finished());
    // One value under two amplitudes cannot be held.
    EXPECT_THROW(DofMap(2, {2}, {{1, 1.0}, {1, 1.0, press_release}}), iga::Error);
}

TEST(DofMap, FullyConstrainedAndEmptyBodies)
{
    const DofMap dofs(3, {1, 0}, {{0, 1.0}, {1, 2.0}, {2, 3.0}});
    EXPECT_EQ(dofs.n_free(), 0);
    const Vector full = dofs.expand(Vector(0), 0.5);
    EXPECT_EQ(full, Vector::LinSpaced(3, 0.5, 1.5));
    // The default ramp holds the full value after t = 1.
    EXPECT_EQ(dofs.expand(Vector(0), 2.0), Vector::LinSpaced(3, 1.0, 3.0));
    EXPECT_EQ(dofs.restrict(full).size(), 0);
}

}  // namespace
}  // namespace iga::assembly
