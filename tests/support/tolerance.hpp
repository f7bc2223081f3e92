#pragma once
// Test helpers for numerical assertions that reject NaN.
//
// Every tolerance used in a test is a named constexpr with a one-line reason at
// the point of use; these helpers only make the comparison NaN-safe and print
// both values on failure.

#include <cmath>
#include <gtest/gtest.h>

namespace iga::test {

/// Passes when |actual - expected| <= tol and both are finite.
inline ::testing::AssertionResult near(double actual, double expected, double tol)
{
    const double diff = std::abs(actual - expected);
    if (std::isfinite(actual) && std::isfinite(expected) && diff <= tol)
        return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "actual " << actual << ", expected " << expected
                                         << ", |diff| = " << diff << " > tol " << tol;
}

/// Passes when |actual - expected| <= rel * |expected| + abs_floor and both are finite.
inline ::testing::AssertionResult near_rel(double actual, double expected, double rel, double abs_floor = 0.0)
{
    const double diff = std::abs(actual - expected);
    const double tol = rel * std::abs(expected) + abs_floor;
    if (std::isfinite(actual) && std::isfinite(expected) && diff <= tol)
        return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "actual " << actual << ", expected " << expected
                                         << ", |diff| = " << diff << " > tol " << tol;
}

/// Passes when value is finite and value <= bound.
inline ::testing::AssertionResult at_most(double value, double bound)
{
    if (std::isfinite(value) && value <= bound)
        return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "value " << value << " is not finite or exceeds " << bound;
}

/// Passes when value is finite and value >= bound.
inline ::testing::AssertionResult at_least(double value, double bound)
{
    if (std::isfinite(value) && value >= bound)
        return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "value " << value << " is not finite or below " << bound;
}

}  // namespace iga::test
