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

/// Puts every diagonal entry of A into its pattern (so that A + mu D keeps the
/// pattern, and the symbolic analysis serves every mu) and returns true when the
/// pattern grew; diagonal_position gets where the diagonal entries sit in A's
/// value array. In place (a 3D tangent is ~100 MB at 30k dofs); A ends compressed.
bool complete_diagonal(SparseMatrix& A, std::vector<int>& diagonal_position);

}  // namespace iga::solver
