#pragma once
// Woodbury update of a reference factorization: solves K x = b for a matrix that
// differs from a factorized reference K_ref in the rows and columns of a few dofs
// A only (|A| = m): K = K_ref + P^T D P, with P the m x n selection of A and D the
// m x m block of K - K_ref. Under small kinematics the tangent is the constant
// elastic stiffness plus the contact stiffness of the active Gauss points, so a
// factorization of one tangent serves the following ones: only the active contact
// dofs make up A. (Sherman-Morrison-Woodbury; Golub & Van Loan, "Matrix
// Computations", 4th ed., §2.1.4; Hager, "Updating the inverse of a matrix",
// SIAM Review 31, 1989.)
//
// With W = K_ref^-1 P^T (n x m) and G = P W (m x m):
//   y = K_ref^-1 b,   (I + G D) s = P y,   x = y - W D s,
// where s = P x. The columns of W are computed once per dof and reference and
// kept, so a set of active dofs that grows from one Newton iteration to the next
// costs only the columns of the new dofs; each solve costs one reference solve
// and O(n m) more.
//
// The caller decides when an update pays (solver/suitesparse_solver.hpp: against the flops of
// a new factorization) and checks each solution's backward error against K; a
// capacitance I + G D singular to working precision is refused (set_up returns
// false) and the caller factorizes K itself.

#include "core/types.hpp"

#include <Eigen/LU>

#include <functional>
#include <vector>

namespace iga::solver {

class WoodburyUpdate {
public:
    /// Solves K_ref X = B with the reference factorization (a block of right-hand sides).
    using ReferenceSolve = std::function<Matrix(const Matrix&)>;

    /// A new reference of n rows: the stored columns belong to the old one.
    void reset(Index n);

    /// How many columns of K_ref^-1 a set_up() on these dofs would have to compute.
    Index missing_columns(const std::vector<int>& dofs) const;
    /// Columns of K_ref^-1 held (n doubles each).
    Index stored_columns() const { return static_cast<Index>(columns_.size()); }
    /// m = |A| of the last set-up (0: K is K_ref).
    Index size() const { return static_cast<Index>(dofs_.size()); }

    /// Prepares solves with K = K_ref + P^T D P for the dofs A (sorted, unique,
    /// each in 0..n-1) and D (m x m). false: I + G D is singular to working
    /// precision (or a column is not finite); the update must not be used.
    bool set_up(const std::vector<int>& dofs, Matrix D, const ReferenceSolve& solve_reference);

    /// Turns y = K_ref^-1 b into x = K^-1 b, in place.
    void correct(Vector& y) const;

    /// y += P^T D P x: with y = K_ref x this is K x, so K itself need not be kept.
    void add_difference_product(const Vector& x, Vector& y) const;
    /// R += P^T D P (R = K_ref gives K; the pattern grows where K has entries R lacks).
    /// In place when R's pattern holds every nonzero of D (no second copy of R).
    /// upper_only: R holds the upper triangle of a symmetric K_ref (D symmetric), and
    /// only D's upper triangle is added.
    void add_difference(SparseMatrix& R, bool upper_only = false) const;

private:
    const Vector& column(int dof) const
    {
        return columns_[static_cast<std::size_t>(column_of_[static_cast<std::size_t>(dof)])];
    }

    std::vector<int> column_of_;  // per dof: index into columns_, or -1
    std::vector<Vector> columns_; // K_ref^-1 e_j of the dofs met so far
    std::vector<int> dofs_;       // A of the last set-up
    Matrix D_;
    Eigen::PartialPivLU<Matrix> capacitance_;  // I + G D
};

}  // namespace iga::solver
