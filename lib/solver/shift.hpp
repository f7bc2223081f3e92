#pragma once
// The pieces of Newton's Levenberg-Marquardt shift K + mu D (solver/newton.hpp,
// LinearSolver::factorize_shifted) that every backend shares: D from the diagonal
// of K, and K with its whole diagonal in the pattern.

#include "core/types.hpp"

#include <vector>

namespace iga::solver {

/// D = |diag(K)|, a zero entry replaced by the mean nonzero |K_ii|; all zero: 1
/// (no scale at all: the step length is then left to Newton's trust radius).
Vector shift_scale(const Vector& diagonal);

/// K with every diagonal entry present in its pattern (so that K + mu D keeps the
/// pattern, and the symbolic analysis serves every mu), plus the positions of the
/// diagonal entries in its value array. K need not be compressed; the result is.
SparseMatrix with_diagonal(const SparseMatrix& K, std::vector<int>& diagonal_position);

}  // namespace iga::solver
