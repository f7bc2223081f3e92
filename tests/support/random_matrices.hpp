#pragma once
// Test matrices for the linear-solver tests: strictly diagonally dominant by rows
// and columns with margin >= 2 and a few random entries per row, so cond(K) is
// O(10) and a backward-stable solve errs by ~cond * eps ~ 1e-14.

#include "core/types.hpp"

#include <Eigen/Dense>

#include <random>

namespace iga::test {

/// n x n sparse matrix: random off-diagonal entries in [-1, 1] on a random
/// pattern (about 4 per row), diagonal = 2 + row index % 3 + the sum of the
/// off-diagonal magnitudes of its row and column (dominant both ways; SPD when symmetric).
inline SparseMatrix dominant_matrix(int n, bool symmetric, std::mt19937& rng)
{
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    std::uniform_int_distribution<int> column(0, n - 1);
    Matrix dense = Matrix::Zero(n, n);
    for (int i = 0; i < n; ++i) {
        for (int k = 0; k < 2; ++k) {
            const int j = column(rng);
            if (j == i)
                continue;
            const double v = value(rng);
            dense(i, j) += v;
            if (symmetric)
                dense(j, i) += v;
            else
                dense(j, i) += value(rng);
        }
    }
    for (int i = 0; i < n; ++i)
        dense(i, i) = 2.0 + i % 3 + dense.row(i).cwiseAbs().sum() + dense.col(i).cwiseAbs().sum();
    return dense.sparseView();
}

inline Vector random_vector(int n, std::mt19937& rng)
{
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    Vector v(n);
    for (int i = 0; i < n; ++i)
        v(i) = value(rng);
    return v;
}

inline double relative_error(const Vector& x, const Vector& reference)
{
    return (x - reference).norm() / reference.norm();
}

}  // namespace iga::test
