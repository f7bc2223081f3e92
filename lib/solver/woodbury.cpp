#include "solver/woodbury.hpp"

#include "core/error.hpp"

#include <algorithm>

namespace iga::solver {

namespace {
// Unit columns solved at a time: bounds the n x block scratch, and blocks of this
// size already let a supernodal solve run at matrix-matrix speed.
constexpr Index column_block = 64;
// rcond of I + G D below this: K is singular to working precision (or the update
// has lost the reference's accuracy); the caller factorizes K instead.
constexpr double singular_rcond = 1e-12;
}  // namespace

void WoodburyUpdate::reset(Index n)
{
    column_of_.assign(static_cast<std::size_t>(n), -1);
    columns_.clear();
    dofs_.clear();
    D_.resize(0, 0);
}

Index WoodburyUpdate::missing_columns(const std::vector<int>& dofs) const
{
    return std::count_if(dofs.begin(), dofs.end(),
                         [&](int dof) { return column_of_[static_cast<std::size_t>(dof)] < 0; });
}

bool WoodburyUpdate::set_up(const std::vector<int>& dofs, Matrix D, const ReferenceSolve& solve_reference)
{
    const auto n = static_cast<Index>(column_of_.size());
    const auto m = static_cast<Index>(dofs.size());
    IGA_CHECK(D.rows() == m && D.cols() == m, "WoodburyUpdate::set_up: D must be m x m");

    // The missing columns K_ref^-1 e_j, a block of unit vectors at a time.
    std::vector<int> missing;
    for (int dof : dofs) {
        IGA_CHECK(dof >= 0 && dof < n, "WoodburyUpdate::set_up: dof out of range");
        if (column_of_[static_cast<std::size_t>(dof)] < 0)
            missing.push_back(dof);
    }
    for (std::size_t first = 0; first < missing.size(); first += column_block) {
        const auto k = std::min<Index>(column_block, static_cast<Index>(missing.size() - first));
        Matrix E = Matrix::Zero(n, k);
        for (Index c = 0; c < k; ++c)
            E(missing[first + static_cast<std::size_t>(c)], c) = 1.0;
        const Matrix Z = solve_reference(E);
        if (Z.rows() != n || !Z.allFinite())
            return false;
        for (Index c = 0; c < k; ++c) {
            column_of_[static_cast<std::size_t>(missing[first + static_cast<std::size_t>(c)])] =
                static_cast<int>(columns_.size());
            columns_.emplace_back(Z.col(c));
        }
    }

    // G = P W: rows A of the columns of A.
    Matrix G(m, m);
    for (Index b = 0; b < m; ++b) {
        const Vector& w = column(dofs[static_cast<std::size_t>(b)]);
        for (Index a = 0; a < m; ++a)
            G(a, b) = w(dofs[static_cast<std::size_t>(a)]);
    }
    const Matrix GD = G * D;
    if (!GD.allFinite())
        return false;
    capacitance_.compute(Matrix::Identity(m, m) + GD);
    if (m > 0) {
        // rcond is scale-free (1 for any 1 x 1 matrix): also compare the smallest
        // pivot with the terms it was formed from, to catch I + G D cancelling.
        const double scale = 1.0 + GD.cwiseAbs().maxCoeff();
        const double pivot = capacitance_.matrixLU().diagonal().cwiseAbs().minCoeff();
        if (!(capacitance_.rcond() > singular_rcond) || !(pivot > singular_rcond * scale))
            return false;
    }
    dofs_ = dofs;
    D_ = std::move(D);
    return true;
}

void WoodburyUpdate::correct(Vector& y) const
{
    const auto m = static_cast<Index>(dofs_.size());
    if (m == 0)
        return;
    Vector Py(m);
    for (Index a = 0; a < m; ++a)
        Py(a) = y(dofs_[static_cast<std::size_t>(a)]);
    const Vector z = D_ * capacitance_.solve(Py);  // D s
    for (Index b = 0; b < m; ++b)
        y -= z(b) * column(dofs_[static_cast<std::size_t>(b)]);
}

void WoodburyUpdate::add_difference_product(const Vector& x, Vector& y) const
{
    const auto m = static_cast<Index>(dofs_.size());
    if (m == 0)
        return;
    Vector Px(m);
    for (Index a = 0; a < m; ++a)
        Px(a) = x(dofs_[static_cast<std::size_t>(a)]);
    const Vector DPx = D_ * Px;
    for (Index a = 0; a < m; ++a)
        y(dofs_[static_cast<std::size_t>(a)]) += DPx(a);
}

void WoodburyUpdate::add_difference(SparseMatrix& R, bool upper_only) const
{
    R.makeCompressed();
    auto stored = [&](Index i, Index j) {
        return D_(i, j) != 0.0 &&
               !(upper_only && dofs_[static_cast<std::size_t>(i)] > dofs_[static_cast<std::size_t>(j)]);
    };
    // Where R already stores every entry of the difference (the contact couplings are
    // in the tangent's pattern from the start), add in place: R is ~100 MB in 3D.
    std::vector<int> position;
    bool in_pattern = true;
    for (Index j = 0; j < D_.cols() && in_pattern; ++j)
        for (Index i = 0; i < D_.rows() && in_pattern; ++i) {
            if (!stored(i, j))
                continue;
            const int col = dofs_[static_cast<std::size_t>(j)];
            const int* first = R.innerIndexPtr() + R.outerIndexPtr()[col];
            const int* last = R.innerIndexPtr() + R.outerIndexPtr()[col + 1];
            const int* it = std::lower_bound(first, last, dofs_[static_cast<std::size_t>(i)]);
            in_pattern = it != last && *it == dofs_[static_cast<std::size_t>(i)];
            position.push_back(static_cast<int>(it - R.innerIndexPtr()));
        }
    if (in_pattern) {
        std::size_t k = 0;
        for (Index j = 0; j < D_.cols(); ++j)
            for (Index i = 0; i < D_.rows(); ++i)
                if (stored(i, j))
                    R.valuePtr()[position[k++]] += D_(i, j);
        return;
    }
    std::vector<Triplet> entries;
    for (Index j = 0; j < D_.cols(); ++j)
        for (Index i = 0; i < D_.rows(); ++i)
            if (stored(i, j))
                entries.emplace_back(dofs_[static_cast<std::size_t>(i)], dofs_[static_cast<std::size_t>(j)], D_(i, j));
    SparseMatrix difference(R.rows(), R.cols());
    difference.setFromTriplets(entries.begin(), entries.end());
    SparseMatrix sum = R + difference;
    R.swap(sum);
    R.makeCompressed();
}

}  // namespace iga::solver
