#pragma once
// Static condensation for tangents whose change between Newton iterations is
// confined to a few dofs: K = [K_II K_IC; K_CI K_CC], where only the "condensed"
// block rows/columns C (the contact sides' dofs under small kinematics) change
// and K_II, K_IC, K_CI stay constant. K_II is factorized once and the n_C x n_C
// matrix W = K_CI K_II^-1 K_IC kept (formed from K_II^-1 K_IC in chunks of
// columns, so the dense n_I x n_C product is never held whole), so each iteration
// only forms and factorizes the dense Schur complement S = K_CC - W:
//   y = K_II^-1 b_I,  S x_C = b_C - K_CI y,  x_I = K_II^-1 (b_I - K_IC x_C).
// Memory: the K_II factor plus 2 n_C^2 doubles (W, S); time per iteration: the
// dense LU of S, (2/3) n_C^3 flops, and two K_II solves per solve. It pays against
// one sparse LU of the whole tangent per iteration only for small n_C (measured:
// analysis/run.cpp, README "Contact cost").
// Correctness never rests on the assumption: the values of K_II, K_IC and K_CI are
// compared with the cached ones on every factorization, and a change (finite
// kinematics, a Levenberg-Marquardt shift) triggers a new interior factorization.
// Two interior factorizations are cached (the plain and the shifted K_II of a
// regularized first iteration).
//
// Shapes: K is n x n (free dofs), compressed column-major; condensed dofs are
// indices into 0..n-1.

#include "core/types.hpp"
#include "solver/linear.hpp"

#include <Eigen/LU>

#include <memory>
#include <vector>

namespace iga::solver {

class Condensation {
public:
    explicit Condensation(std::vector<int> condensed_dofs);
    ~Condensation();

    /// The next factorize() rebuilds its block maps and interior factorization:
    /// K's sparsity pattern changed (LinearSolver calls it; a change of the number
    /// of nonzeros or rows is detected without it).
    void new_pattern() { pattern_nnz_ = -1; }
    /// Factorizes K (see above). ok, or singular when K_II or S is singular.
    LinearStatus factorize(const SparseMatrix& K);
    /// x = K^-1 b with the last successful factorization.
    LinearStatus solve(const Vector& b, Vector& x) const;

    int n_interior_factorizations() const { return n_interior_; }
    const std::vector<int>& condensed_dofs() const { return condensed_; }  ///< sorted, unique

private:
    struct Interior;
    void build_maps(const SparseMatrix& K);

    std::vector<int> condensed_;       // sorted, unique
    std::vector<int> position_;        // n: index in I (>= 0) or -(index in C) - 1
    std::vector<int> interior_;        // I dofs
    // per nonzero of K: 0 II, 1 IC, 2 CI, 3 CC, and the destination index
    std::vector<unsigned char> category_;
    std::vector<int> destination_;
    SparseMatrix K_II_, K_IC_, K_CI_;  // values refilled each call (fixed patterns)
    Matrix K_CC_;
    std::vector<std::unique_ptr<Interior>> cache_;  // most recent first
    Interior* current_ = nullptr;
    Eigen::PartialPivLU<Matrix> schur_;
    Index pattern_nnz_ = -1;
    Index pattern_n_ = -1;
    int n_interior_ = 0;
};

}  // namespace iga::solver
