#pragma once
// Basic numeric types shared by every module.
//
// The spatial dimension is a runtime value (2 or 3), so small vectors and
// matrices are dynamic Eigen types with a compile-time cap of 3 (no heap use).
// Sparse matrices are column-major with int indices, as SuiteSparse expects.

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace iga {

using Index = Eigen::Index;

/// A point or vector in 1..3 dimensions (stack storage).
using VecN = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3, 1>;
/// A small matrix up to 3 x 3 (stack storage): Jacobians, stresses, tangents.
using MatN = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3>;

using Vector = Eigen::VectorXd;
using Matrix = Eigen::MatrixXd;
/// Row-major dense matrix, e.g. n_points x d coordinates as written to HDF5.
using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
using Triplet = Eigen::Triplet<double, int>;

/// Frees K's storage. Eigen 3.4 has no move for sparse matrices, and assigning an
/// empty one (K = SparseMatrix()) keeps K's value and index arrays allocated: a 3D
/// tangent is ~100 MB at 30k dofs.
inline void release(SparseMatrix& K)
{
    SparseMatrix empty;
    K.swap(empty);
}

}  // namespace iga
