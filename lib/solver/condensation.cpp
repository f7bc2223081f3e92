#include "solver/condensation.hpp"

#include "core/error.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/LU>
#include <Eigen/UmfPackSupport>

#include <algorithm>
#include <limits>

namespace iga::solver {

namespace {
// rcond of S below this: S is singular to working precision (e.g. a body held
// only by contact at first touch), so the caller may regularize.
constexpr double singular_rcond = 1e-14;
// A Schur pivot this small against the largest entry of K_CC is cancellation
// noise (an unsupported rigid mode), not stiffness.
constexpr double singular_pivot = 1e-12;
}  // namespace

// Columns of K_II^-1 K_IC formed at a time for W: n_I x chunk doubles of scratch.
constexpr Index w_chunk_columns = 32;

struct Condensation::Interior {
    std::vector<double> values;  // K_II, K_IC, K_CI values (in this order) this factorization belongs to
    // Cholesky (K_II is SPD for elastic interiors), LU when it is not.
    Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> llt;
    Eigen::UmfPackLU<SparseMatrix> lu;
    bool use_lu = false;
    Matrix W;                    // K_CI K_II^-1 K_IC, n_C x n_C

    Interior() { llt.cholmod().print = 0; }

    bool factorize(const SparseMatrix& K)
    {
        llt.compute(K);
        if (llt.info() == Eigen::Success && llt.cholmod().status >= 0)
            return true;
        use_lu = true;
        lu.compute(K);
        return lu.info() == Eigen::Success;
    }
    template <class Rhs>
    Matrix solve(const Rhs& b) const
    {
        return use_lu ? Matrix(lu.solve(b)) : Matrix(llt.solve(b));
    }
};

Condensation::Condensation(std::vector<int> condensed_dofs) : condensed_(std::move(condensed_dofs))
{
    std::sort(condensed_.begin(), condensed_.end());
    condensed_.erase(std::unique(condensed_.begin(), condensed_.end()), condensed_.end());
}

Condensation::~Condensation() = default;

void Condensation::build_maps(const SparseMatrix& K)
{
    const int n = static_cast<int>(K.rows());
    position_.assign(static_cast<std::size_t>(n), 0);
    interior_.clear();
    std::vector<char> is_c(static_cast<std::size_t>(n), 0);
    for (int c : condensed_) {
        IGA_CHECK(c >= 0 && c < n, "Condensation: condensed dof out of range");
        is_c[static_cast<std::size_t>(c)] = 1;
    }
    int n_c = 0;
    for (int k = 0; k < n; ++k) {
        if (is_c[static_cast<std::size_t>(k)])
            position_[static_cast<std::size_t>(k)] = -(n_c++) - 1;
        else {
            position_[static_cast<std::size_t>(k)] = static_cast<int>(interior_.size());
            interior_.push_back(k);
        }
    }
    const int n_i = static_cast<int>(interior_.size());

    // Sub-patterns with the value slot of every nonzero of K recorded.
    std::vector<Triplet> ii, ic, ci;
    category_.assign(static_cast<std::size_t>(K.nonZeros()), 0);
    destination_.assign(static_cast<std::size_t>(K.nonZeros()), 0);
    for (Index j = 0; j < K.outerSize(); ++j)
        for (SparseMatrix::InnerIterator it(K, j); it; ++it) {
            const int pr = position_[static_cast<std::size_t>(it.row())];
            const int pc = position_[static_cast<std::size_t>(it.col())];
            const auto slot = static_cast<std::size_t>(&it.valueRef() - K.valuePtr());
            // The triplet value carries the slot + 1, to read back the destination.
            const double tag = static_cast<double>(slot) + 1.0;
            if (pr >= 0 && pc >= 0) {
                category_[slot] = 0;
                ii.emplace_back(pr, pc, tag);
            } else if (pr >= 0) {
                category_[slot] = 1;
                ic.emplace_back(pr, -pc - 1, tag);
            } else if (pc >= 0) {
                category_[slot] = 2;
                ci.emplace_back(-pr - 1, pc, tag);
            } else {
                category_[slot] = 3;
                destination_[slot] = (-pr - 1) + n_c * (-pc - 1);  // column-major dense index
            }
        }
    auto build = [&](SparseMatrix& M, Index rows, Index cols, const std::vector<Triplet>& t, int category) {
        M.resize(rows, cols);
        M.setFromTriplets(t.begin(), t.end());  // no duplicates: K has none
        M.makeCompressed();
        for (Index k = 0; k < M.nonZeros(); ++k) {
            const auto slot = static_cast<std::size_t>(M.valuePtr()[k]) - 1;
            IGA_ASSERT(category_[slot] == category, "Condensation: inconsistent category");
            destination_[slot] = static_cast<int>(k);
        }
    };
    build(K_II_, n_i, n_i, ii, 0);
    build(K_IC_, n_i, n_c, ic, 1);
    build(K_CI_, n_c, n_i, ci, 2);
    K_CC_.setZero(n_c, n_c);
    cache_.clear();
    current_ = nullptr;
    pattern_nnz_ = K.nonZeros();
    pattern_n_ = K.rows();
}

LinearStatus Condensation::factorize(const SparseMatrix& K)
{
    IGA_CHECK(K.isCompressed(), "Condensation::factorize: K must be compressed");
    if (K.nonZeros() != pattern_nnz_ || K.rows() != pattern_n_)
        build_maps(K);

    // Scatter the values of K into the four blocks.
    K_CC_.setZero();
    double* ii = K_II_.valuePtr();
    double* ic = K_IC_.valuePtr();
    double* ci = K_CI_.valuePtr();
    double* cc = K_CC_.data();
    const double* v = K.valuePtr();
    for (Index k = 0; k < K.nonZeros(); ++k) {
        const auto s = static_cast<std::size_t>(k);
        switch (category_[s]) {
        case 0: ii[destination_[s]] = v[k]; break;
        case 1: ic[destination_[s]] = v[k]; break;
        case 2: ci[destination_[s]] = v[k]; break;
        default: cc[destination_[s]] += v[k]; break;
        }
    }

    // Interior factorization: reuse a cached one whose K_II, K_IC, K_CI values are identical.
    auto same_values = [&](const std::vector<double>& cached) {
        const auto n_ii = static_cast<std::size_t>(K_II_.nonZeros());
        const auto n_ic = static_cast<std::size_t>(K_IC_.nonZeros());
        const auto n_ci = static_cast<std::size_t>(K_CI_.nonZeros());
        return cached.size() == n_ii + n_ic + n_ci && std::equal(ii, ii + n_ii, cached.begin()) &&
               std::equal(ic, ic + n_ic, cached.begin() + static_cast<long>(n_ii)) &&
               std::equal(ci, ci + n_ci, cached.begin() + static_cast<long>(n_ii + n_ic));
    };
    current_ = nullptr;
    for (std::size_t k = 0; k < cache_.size(); ++k)
        if (same_values(cache_[k]->values)) {
            std::rotate(cache_.begin(), cache_.begin() + static_cast<long>(k), cache_.begin() + static_cast<long>(k) + 1);
            current_ = cache_.front().get();
            break;
        }
    if (!current_) {
        auto interior = std::make_unique<Interior>();
        interior->values.assign(ii, ii + K_II_.nonZeros());
        interior->values.insert(interior->values.end(), ic, ic + K_IC_.nonZeros());
        interior->values.insert(interior->values.end(), ci, ci + K_CI_.nonZeros());
        ++n_interior_;
        const Index n_c = K_IC_.cols();
        interior->W = Matrix::Zero(n_c, n_c);
        if (K_II_.rows() > 0) {
            if (!interior->factorize(K_II_))
                return LinearStatus::singular;
            for (Index j = 0; j < n_c; j += w_chunk_columns) {
                const Index m = std::min(w_chunk_columns, n_c - j);
                const Matrix Z = interior->solve(Matrix(K_IC_.middleCols(j, m)));  // K_II^-1 K_IC, m columns
                if (!Z.allFinite())
                    return LinearStatus::singular;
                interior->W.middleCols(j, m) = K_CI_ * Z;
            }
        }
        cache_.insert(cache_.begin(), std::move(interior));
        if (cache_.size() > 2)
            cache_.pop_back();
        current_ = cache_.front().get();
    }

    const Matrix S = K_CC_ - current_->W;
    if (!S.allFinite())
        return LinearStatus::singular;
    schur_.compute(S);
    if (S.rows() > 0) {
        // rcond is scale-free (1 for any 1 x 1 matrix): also compare the smallest
        // pivot with the size of the condensed block of K itself.
        const double scale = std::max(K_CC_.cwiseAbs().maxCoeff(), std::numeric_limits<double>::min());
        const double pivot = schur_.matrixLU().diagonal().cwiseAbs().minCoeff();
        if (!(schur_.rcond() > singular_rcond) || !(pivot > singular_pivot * scale))
            return LinearStatus::singular;
    }
    return LinearStatus::ok;
}

LinearStatus Condensation::solve(const Vector& b, Vector& x) const
{
    IGA_CHECK(current_ != nullptr, "Condensation::solve: needs a successful factorize() first");
    const Index n_i = static_cast<Index>(interior_.size());
    const Index n_c = static_cast<Index>(condensed_.size());
    Vector b_i(n_i), b_c(n_c);
    for (Index k = 0; k < b.size(); ++k) {
        const int p = position_[static_cast<std::size_t>(k)];
        if (p >= 0)
            b_i(p) = b(k);
        else
            b_c(-p - 1) = b(k);
    }
    const Vector y = n_i > 0 ? Vector(current_->solve(b_i)) : Vector(0);
    const Vector x_c = n_c > 0 ? Vector(schur_.solve(b_c - K_CI_ * y)) : Vector(0);
    const Vector x_i = n_i > 0 ? Vector(current_->solve(Vector(b_i - K_IC_ * x_c))) : Vector(0);
    x.resize(b.size());
    for (Index k = 0; k < b.size(); ++k) {
        const int p = position_[static_cast<std::size_t>(k)];
        x(k) = p >= 0 ? x_i(p) : x_c(-p - 1);
    }
    return LinearStatus::ok;
}

}  // namespace iga::solver
