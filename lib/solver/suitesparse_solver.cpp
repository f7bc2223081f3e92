#include "solver/suitesparse_solver.hpp"

#include "solver/shift.hpp"
#include "solver/woodbury.hpp"

#include "core/error.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/UmfPackSupport>

#include <algorithm>
#include <new>

namespace iga::solver {

namespace {

// A backward-stable direct solve leaves ||K x - b|| ~ eps * ||K|| ||x||; UMFPACK
// also refines iteratively. 1e-6 ||b|| is far above that for any K we can use,
// yet catches the garbage a near-singular K that escaped the pivot test gives.
constexpr double backward_error_tolerance = 1e-6;
// An updated solve (solver/woodbury.hpp) above this backward error is refined
// against K, up to max_refinement_steps steps while each at least halves the
// residual: a direct solve lands near eps ||K|| ||x||, the update's extra rounding
// (cancellation between K_ref^-1 b and the correction under a stiff penalty) can
// leave it orders above that. UMFPACK's own refinement would refine towards
// K_ref, so it is off for updates and for the columns of K_ref^-1. A shifted
// reference's update solves K + mu D: refinement also takes the shift off, by a
// factor ~||(K + mu D)^-1 mu D|| per step (measured at mu = 1e-8: 1e-3 on the 3D
// sphere octant, which reaches the update's rounding in 3 steps; 0.02 on the 2D
// Hertz cylinder, 7 steps from 3e-3 to 1e-14). The halving rule ends the steps
// that no longer pay, so the cap only bounds a slow contraction.
constexpr double refinement_threshold = 1e-14;
constexpr int max_refinement_steps = 8;
constexpr int umfpack_refinement_steps = 2;  // UMFPACK's default, for solves with the factorized K itself

// Woodbury updates: the columns of K_ref^-1 they need are priced at their flops
// times this against the flops of a factorization. A column solve runs slower per
// flop than a factorization (measured: 2.6x for CHOLMOD on the 3D Hertz sphere,
// blocks of 64 columns; 6x for UMFPACK on the squeeze, one column at a time), but a
// column serves every later iteration while the reference lasts (the squeeze: 42
// updates on 136 columns), so the flops alone are the price. The columns may hold
// at most this many doubles per entry of the factors.
constexpr double column_flop_cost = 1.0;
constexpr double column_memory_per_factor_entry = 1.0;

// Kind::cholesky keeps one triangle of K when K is symmetric to this relative
// tolerance (assembled tangents are, to round-off); otherwise the whole K, so
// that solve()'s backward-error check still sees what CHOLMOD ignored.
constexpr double symmetry_tolerance = 1e-12;

bool all_finite(const SparseMatrix& K)
{
    const double* values = K.valuePtr();
    return std::all_of(values, values + K.nonZeros(), [](double v) { return std::isfinite(v); });
}

// Same compressed pattern (a and b compressed).
bool same_sparsity(const SparseMatrix& a, const SparseMatrix& b)
{
    if (a.rows() != b.rows() || a.cols() != b.cols() || a.nonZeros() != b.nonZeros())
        return false;
    const int n_outer = static_cast<int>(a.outerSize()) + 1;
    return std::equal(a.outerIndexPtr(), a.outerIndexPtr() + n_outer, b.outerIndexPtr()) &&
           std::equal(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros(), b.innerIndexPtr());
}

// K (any storage) has R's compressed pattern, and with `values` R's values too;
// upper: R holds an upper triangle, compared with K's.
bool same_entries(const SparseMatrix& K, const SparseMatrix& R, bool upper, bool values)
{
    if (K.rows() != R.rows() || K.cols() != R.cols())
        return false;
    const int* R_inner = R.innerIndexPtr();
    const double* R_values = R.valuePtr();
    for (Index j = 0; j < K.outerSize(); ++j) {
        Index p = R.outerIndexPtr()[j];
        const Index end = R.outerIndexPtr()[j + 1];
        for (SparseMatrix::InnerIterator it(K, j); it && !(upper && it.row() > j); ++it, ++p)
            if (p == end || R_inner[p] != it.row() || (values && R_values[p] != it.value()))
                return false;
        if (p != end)
            return false;
    }
    return true;
}

// Whether K (compressed, square) equals its transpose: entries (i, j) and (j, i)
// agree to symmetry_tolerance of their size, and an entry whose mirror is not
// stored is zero. One pass: the mirrors of column j's upper entries are met in
// increasing rows of the earlier columns, so one cursor per column finds them.
bool symmetric(const SparseMatrix& K)
{
    const int* outer = K.outerIndexPtr();
    const int* inner = K.innerIndexPtr();
    const double* v = K.valuePtr();
    const Index n = K.outerSize();
    std::vector<int> next(static_cast<std::size_t>(n));  // per column: its first unmatched entry below the diagonal
    for (Index c = 0; c < n; ++c)
        next[static_cast<std::size_t>(c)] =
            static_cast<int>(std::upper_bound(inner + outer[c], inner + outer[c + 1], static_cast<int>(c)) - inner);
    for (Index j = 0; j < n; ++j)
        for (int p = outer[j]; p < outer[j + 1] && inner[p] < j; ++p) {  // (i, j) above the diagonal
            const int i = inner[p];
            int& q = next[static_cast<std::size_t>(i)];
            for (; q < outer[i + 1] && inner[q] < j; ++q)  // (r, i) below it, r < j: no (i, r) was stored
                if (v[q] != 0.0)
                    return false;
            if (q < outer[i + 1] && inner[q] == j) {
                if (std::abs(v[p] - v[q]) > symmetry_tolerance * (std::abs(v[p]) + std::abs(v[q])))
                    return false;
                ++q;
            } else if (v[p] != 0.0) {
                return false;
            }
        }
    for (Index c = 0; c < n; ++c)  // below the diagonal, past every mirror met
        for (int q = next[static_cast<std::size_t>(c)]; q < outer[c + 1]; ++q)
            if (v[q] != 0.0)
                return false;
    return true;
}

// K := its upper triangle, compressed, its storage shrunk to fit (K symmetric: the
// lower triangle repeats it).
void keep_upper(SparseMatrix& K)
{
    K.prune([](Index row, Index col, double) { return row <= col; });
    K.makeCompressed();
    K.data().squeeze();
}

// Copies K into `into` (compressed), in place when the pattern is the same.
void copy_compressed(const SparseMatrix& K, SparseMatrix& into)
{
    if (K.isCompressed() && same_sparsity(K, into)) {
        std::copy(K.valuePtr(), K.valuePtr() + K.nonZeros(), into.valuePtr());
        return;
    }
    into = K;
    into.makeCompressed();
}

// The entries where K and R (n x n, R compressed) differ: K - R = P^T D P on the
// sorted dofs A of their rows and columns. false when A would exceed max_dofs.
// R_diagonal, when given, holds R's diagonal instead of R's own entries (a shifted
// reference compared as the unshifted one, bit for bit: no rounding of R_jj - shift).
// upper: R holds the upper triangle of a symmetric matrix; K's upper triangle is
// compared with it, and each difference off the diagonal is mirrored into D.
bool difference_support(const SparseMatrix& K, const SparseMatrix& R, const Vector* R_diagonal, bool upper,
                        Index max_dofs, std::vector<int>& dofs, Matrix& D)
{
    auto reference_value = [R_diagonal](const SparseMatrix::InnerIterator& b, Index j) {
        return R_diagonal && b.row() == j ? (*R_diagonal)(j) : b.value();
    };
    const Index n = R.rows();
    std::vector<char> in_support(static_cast<std::size_t>(n), 0);
    std::vector<Triplet> entries;
    Index n_dofs = 0;
    auto mark = [&](Index k) {
        if (!in_support[static_cast<std::size_t>(k)]) {
            in_support[static_cast<std::size_t>(k)] = 1;
            ++n_dofs;
        }
    };
    for (Index j = 0; j < n; ++j) {
        // Merge the two sorted columns; a row present in one only differs by its value.
        SparseMatrix::InnerIterator a(K, j), b(R, j);
        auto a_left = [&] { return a && !(upper && a.row() > j); };
        while (a_left() || b) {
            double delta = 0;
            Index i = 0;
            if (a_left() && (!b || a.row() < b.row())) {
                i = a.row(), delta = a.value();
                ++a;
            } else if (b && (!a_left() || b.row() < a.row())) {
                i = b.row(), delta = -reference_value(b, j);
                ++b;
            } else {
                i = a.row(), delta = a.value() - reference_value(b, j);
                ++a, ++b;
            }
            if (delta != 0) {
                entries.emplace_back(static_cast<int>(i), static_cast<int>(j), delta);
                if (upper && i != j)
                    entries.emplace_back(static_cast<int>(j), static_cast<int>(i), delta);
                mark(i);
                mark(j);
                if (n_dofs > max_dofs)
                    return false;
            }
        }
    }
    dofs.clear();
    std::vector<int> position(static_cast<std::size_t>(n), -1);
    for (Index k = 0; k < n; ++k)
        if (in_support[static_cast<std::size_t>(k)]) {
            position[static_cast<std::size_t>(k)] = static_cast<int>(dofs.size());
            dofs.push_back(static_cast<int>(k));
        }
    D = Matrix::Zero(n_dofs, n_dofs);
    for (const Triplet& t : entries)
        D(position[static_cast<std::size_t>(t.row())], position[static_cast<std::size_t>(t.col())]) += t.value();
    return true;
}

}  // namespace

// UMFPACK's statistics of the last factorization (flops, entries of L and U),
// which Eigen keeps but does not expose.
template <class Matrix>
class UmfPackWithInfo : public Eigen::UmfPackLU<Matrix> {
public:
    double statistic(int entry) const { return this->m_umfpackInfo(entry); }
    bool out_of_memory() const { return statistic(UMFPACK_STATUS) == UMFPACK_ERROR_out_of_memory; }
};

/// The matrix type of UMFPACK's 64-bit version (umfpack_dl_*).
using LongSparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, SuiteSparse_long>;

struct SuiteSparseSolver::Backend {
    /// UMFPACK's 32-bit version (umfpack_di_*), and the 64-bit one for a factorization
    /// whose sizes overflow it: the int version reports such a factor as out of memory
    /// whatever the machine has (a 3D two-body tangent of 68k dofs, an 8 GB factor
    /// estimate, with 18 GB free). Once a factorization needed it, this solver keeps it.
    UmfPackWithInfo<SparseMatrix> lu;
    UmfPackWithInfo<LongSparseMatrix> lu_long;
    LongSparseMatrix long_matrix;  ///< the matrix lu_long factorized (and refines with)
    bool long_lu = false;
    // The upper triangle: CHOLMOD's supernodal factorization works on the upper form,
    // and reaches it from the lower one by a second transposed copy of the matrix
    // (measured on the 3D sphere octant, 31.7k dofs: 29 MB less peak RSS).
    Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Upper> llt;

    /// Runs f on the UMFPACK object in use.
    template <class F>
    decltype(auto) with_lu(F&& f)
    {
        return long_lu ? f(lu_long) : f(lu);
    }

    /// A factorization that ran out of memory is no statement about the matrix:
    /// Eigen reports it as a numerical issue, which would read as a singular tangent
    /// and send Newton cutting back. It is an allocation failure, thrown as one (the
    /// LU's is handled in factorize_lu, which first tries UMFPACK's 64-bit version).
    void throw_if_cholesky_out_of_memory()
    {
        if (llt.cholmod().status == CHOLMOD_OUT_OF_MEMORY)
            throw std::bad_alloc();
    }

    Backend()
    {
        // CHOLMOD prints "not positive definite" warnings to stdout by default;
        // the library reports statuses instead (no printing in lib/).
        llt.cholmod().print = 0;
    }
};

const char* kind_name(SuiteSparseSolver::Kind kind)
{
    return kind == SuiteSparseSolver::Kind::lu ? "lu" : "cholesky";
}

// Cholesky is tried again after this many skipped factorizations at most (the
// back-off doubles from 1 with each refusal in a row).
constexpr int max_cholesky_backoff = 32;

SuiteSparseSolver::SuiteSparseSolver(Kind kind)
    : kind_(kind), factorized_kind_(kind), backend_(std::make_unique<Backend>())
{
}
SuiteSparseSolver::~SuiteSparseSolver() = default;
SuiteSparseSolver::SuiteSparseSolver(SuiteSparseSolver&&) noexcept = default;
SuiteSparseSolver& SuiteSparseSolver::operator=(SuiteSparseSolver&&) noexcept = default;

void SuiteSparseSolver::set_updates(bool on)
{
    update_ = on ? std::make_unique<WoodburyUpdate>() : nullptr;
    factorized_ = updated_ = false;  // the next factorization is a reference
}

void SuiteSparseSolver::set_ordering(Ordering ordering)
{
    Backend& b = *backend_;
    ordering_ = ordering;
    const bool nested = ordering == Ordering::nested_dissection;
    b.llt.cholmod().nmethods = 1;
    b.llt.cholmod().method[0].ordering = nested ? CHOLMOD_METIS : CHOLMOD_AMD;
    b.lu.umfpackControl()(UMFPACK_ORDERING) = nested ? UMFPACK_ORDERING_METIS : UMFPACK_ORDERING_AMD;
    b.lu_long.umfpackControl()(UMFPACK_ORDERING) = b.lu.umfpackControl()(UMFPACK_ORDERING);
    analysed_lu_ = analysed_llt_ = false;  // the next factorization orders again
    factorized_ = false;
}

void SuiteSparseSolver::set_lu_64bit()
{
    if (!backend_->long_lu) {
        backend_->long_lu = true;
        analysed_lu_ = false;
        if (factorized_kind_ == Kind::lu)
            factorized_ = false;  // the 32-bit factor is not the one solves will use
    }
}

bool SuiteSparseSolver::lu_64bit() const { return backend_->long_lu; }

void SuiteSparseSolver::set_kind(Kind kind)
{
    if (kind != kind_) {
        kind_ = kind;
        factorized_ = false;
        cholesky_skips_ = 0;
        cholesky_backoff_ = 1;
    }
}

bool SuiteSparseSolver::same_pattern(const SparseMatrix& K) const
{
    return same_entries(K, reference_, upper_, false);
}

LinearStatus SuiteSparseSolver::factorize(const SparseMatrix& K)
{
    return factorize_matrix(K, nullptr);
}

LinearStatus SuiteSparseSolver::factorize_taking(SparseMatrix& K)
{
    const LinearStatus status = factorize_matrix(K, &K);
    release(K);  // an update or a kept factorization did not need it
    return status;
}

LinearStatus SuiteSparseSolver::factorize_shifted(double mu)
{
    if (!shift_base_valid_) {
        // The K of the last factorize() becomes the shift base in reference_ itself
        // (a 3D tangent is ~100 MB at 30k dofs: one copy, not two).
        const Index entries = reference_.nonZeros();
        materialize();
        const bool grown = complete_diagonal(reference_, diagonal_position_) || reference_.nonZeros() != entries;
        if (grown)
            analysed_ = analysed_lu_ = analysed_llt_ = false;  // analyse the new pattern
        const Index n = reference_.rows();
        base_diagonal_.resize(n);
        for (Index i = 0; i < n; ++i)
            base_diagonal_(i) = reference_.valuePtr()[diagonal_position_[static_cast<std::size_t>(i)]];
        shift_scale_ = shift_scale(base_diagonal_);
        shift_base_valid_ = true;
    }
    for (Index i = 0; i < reference_.rows(); ++i)
        reference_.valuePtr()[diagonal_position_[static_cast<std::size_t>(i)]] =
            base_diagonal_(i) + mu * shift_scale_(i);
    shift_ = mu;
    updated_ = false;  // solves are with reference_ itself, K + mu D
    factorized_ = false;
    return factorize_reference();
}

LinearStatus SuiteSparseSolver::factorize_shifted_taking(SparseMatrix& K, double mu)
{
    IGA_CHECK(K.rows() == K.cols(), "SuiteSparseSolver::factorize_shifted_taking: the matrix must be square");
    take_reference(K, &K);
    release(K);
    return factorize_shifted(mu);
}

void SuiteSparseSolver::materialize()
{
    if (shift_ > 0)  // the pattern is the shift's: its diagonal positions still hold
        for (Index i = 0; i < reference_.rows(); ++i)
            reference_.valuePtr()[diagonal_position_[static_cast<std::size_t>(i)]] = base_diagonal_(i);
    shift_ = 0;
    if (updated_ && update_->size() > 0) {
        const Index entries = reference_.nonZeros();
        update_->add_difference(reference_, upper_);  // the union of both patterns
        if (reference_.nonZeros() != entries)
            analysed_ = analysed_lu_ = analysed_llt_ = false;
    }
    updated_ = false;
}

LinearStatistics SuiteSparseSolver::statistics() const
{
    LinearStatistics s;
    s.symbolic = n_symbolic_;
    s.numeric = n_numeric_;
    s.updates = n_updates_;
    s.cholesky_fallbacks = n_fallbacks_;
    return s;
}

std::string SuiteSparseSolver::describe() const
{
    std::string text = kind_ == Kind::cholesky ? "SuiteSparse CHOLMOD Cholesky (UMFPACK LU where it refuses)"
                                               : "SuiteSparse UMFPACK LU";
    text += ordering_ == Ordering::nested_dissection ? ", METIS ordering" : ", AMD ordering";
    if (update_)
        text += ", Woodbury updates";
    return text;
}

LinearStatus SuiteSparseSolver::factorize_matrix(const SparseMatrix& K, SparseMatrix* owned)
{
    IGA_CHECK(K.rows() == K.cols(), "SuiteSparseSolver::factorize: the matrix must be square");
    if (factorized_ && update_ && try_update(K))
        return LinearStatus::ok;
    updated_ = false;
    // The same matrix again (a linear scene's next increment): keep the factorization.
    if (factorized_ && shift_ == 0 && same_entries(K, reference_, upper_, true))
        return LinearStatus::ok;
    take_reference(K, owned);
    return factorize_reference();
}

void SuiteSparseSolver::take_reference(const SparseMatrix& K, SparseMatrix* owned)
{
    factorized_ = updated_ = shift_base_valid_ = false;
    shift_ = 0;
    release(lu_matrix_);
    const bool was_upper = upper_;
    // The analyses stand when K has the old reference's pattern.
    const bool same = analysed_ && same_pattern(K);
    if (owned && K.isCompressed()) {
        reference_.swap(*owned);  // the caller handed K over (factorize_taking): no copy
        release(*owned);          // the old reference, now the caller's: freed before the factor is
    } else if (!same || upper_) {
        SparseMatrix copy = K;
        copy.makeCompressed();
        reference_.swap(copy);  // swapped: Eigen 3.4 copies a "moved" sparse matrix
    } else {
        copy_compressed(K, reference_);  // same pattern: the values in place, nothing reallocated
    }
    // Symmetric, for Cholesky: one triangle is the whole matrix.
    upper_ = kind_ == Kind::cholesky && symmetric(reference_);
    if (upper_)
        keep_upper(reference_);
    if (!same || upper_ != was_upper)
        analysed_ = analysed_lu_ = analysed_llt_ = false;
}

LinearStatus SuiteSparseSolver::factorize_reference()
{
    if (!all_finite(reference_))
        return LinearStatus::failed;
    if (reference_.rows() == 0) {  // no unknowns: nothing to factorize, solve() returns an empty x
        factorized_ = true;
        return LinearStatus::ok;
    }
    if (reference_.nonZeros() == 0)  // the backends reject an empty pattern (CHOLMOD would crash)
        return LinearStatus::singular;

    analysed_ = true;  // the backends' analyses below are made for reference_'s pattern
    if (kind_ == Kind::lu)
        return factorize_with(Kind::lu);
    if (cholesky_skips_ > 0) {
        --cholesky_skips_;
        return factorize_with(Kind::lu);
    }
    const LinearStatus status = factorize_with(Kind::cholesky);
    if (status != LinearStatus::failed) {
        cholesky_backoff_ = 1;
        return status;
    }
    if (semidefinite_)
        return LinearStatus::singular;  // semi-definite and refused: singular, LU would only say so again
    ++n_fallbacks_;
    const LinearStatus lu_status = factorize_with(Kind::lu);
    if (lu_status == LinearStatus::singular)
        return lu_status;  // singular, not indefinite: the caller's shifted K + mu D is worth a Cholesky at once
    cholesky_skips_ = cholesky_backoff_;
    cholesky_backoff_ = std::min(2 * cholesky_backoff_, max_cholesky_backoff);
    return lu_status;
}

bool SuiteSparseSolver::try_update(const SparseMatrix& K)
{
    const Index n = reference_.rows();
    if (K.rows() != n || n == 0)
        return false;
    // Memory: the columns held and the new ones within the factor's size.
    const auto max_columns =
        static_cast<Index>(column_memory_per_factor_entry * factor_entries_ / static_cast<double>(n));
    const Index room = max_columns - update_->stored_columns();
    std::vector<int> dofs;
    Matrix D;
    const Vector* unshifted_diagonal = shift_ > 0 ? &base_diagonal_ : nullptr;  // compare with K_u
    if (room <= 0 || !difference_support(K, reference_, unshifted_diagonal, upper_, max_columns, dofs, D) ||
        !D.allFinite())
        return false;  // (a non-finite entry of K differs from the reference: it is in D)
    // Time: the new columns and the dense capacitance against a factorization.
    const auto m = static_cast<double>(dofs.size());
    const Index missing = update_->missing_columns(dofs);
    const double update_flops =
        static_cast<double>(missing) * column_flops_ * column_flop_cost + 2.0 / 3.0 * m * m * m;
    if (missing > room || update_flops >= factor_flops_)
        return false;
    const bool same_as_base = dofs.empty();
    if (!update_->set_up(dofs, std::move(D), [this](const Matrix& B) { return solve_reference(B); }))
        return false;
    shift_base_valid_ = shift_base_valid_ && same_as_base;  // a shift must start from this K
    if (same_as_base && shift_ == 0) {  // K is the reference itself
        updated_ = false;
        return true;
    }
    updated_ = true;  // by Woodbury, or by refining away the reference's shift (solve())
    ++n_updates_;
    return true;
}

Vector SuiteSparseSolver::apply(const Vector& x) const
{
    Vector y = upper_ ? Vector(reference_.selfadjointView<Eigen::Upper>() * x) : Vector(reference_ * x);
    if (!updated_)
        return y;
    if (shift_ > 0)  // K_u x: the shift taken off as stored (the shifted diagonal minus K_u's)
        for (Index i = 0; i < y.size(); ++i)
            y(i) -= (reference_.valuePtr()[diagonal_position_[static_cast<std::size_t>(i)]] - base_diagonal_(i)) * x(i);
    update_->add_difference_product(x, y);
    return y;
}

Matrix SuiteSparseSolver::solve_reference(const Matrix& B) const
{
    if (factorized_kind_ == Kind::lu) {
        return backend_->with_lu([&](auto& lu) -> Matrix {
            lu.umfpackControl()(UMFPACK_IRSTEP) = 0;  // see refinement_threshold
            return lu.solve(B);
        });
    }
    return backend_->llt.solve(B);
}

const SparseMatrix& SuiteSparseSolver::lu_source()
{
    if (!upper_)
        return reference_;
    // UMFPACK factorizes (and refines with) the whole matrix: made from the triangle
    // when Cholesky refused it, and kept while the LU is in use.
    release(lu_matrix_);
    SparseMatrix whole = reference_.selfadjointView<Eigen::Upper>();
    whole.makeCompressed();
    lu_matrix_.swap(whole);
    return lu_matrix_;
}

LinearStatus SuiteSparseSolver::factorize_with(Kind kind)
{
    bool& analysed = kind == Kind::lu ? analysed_lu_ : analysed_llt_;
    const LinearStatus status = kind == Kind::lu ? factorize_lu(lu_source(), analysed) : factorize_cholesky(analysed);
    if (status != LinearStatus::ok)
        return status;
    column_flops_ = 2 * factor_entries_;  // one multiply-add per entry of the factors
    factorized_ = true;
    factorized_kind_ = kind;
    if (update_)
        update_->reset(reference_.rows());
    return LinearStatus::ok;
}

/// UMFPACK on the whole matrix A: the 32-bit version, or the 64-bit one once the 32-bit
/// version has reported a factor too large for it (Backend).
LinearStatus SuiteSparseSolver::factorize_lu(const SparseMatrix& A, bool& analysed)
{
    Backend& b = *backend_;
    bool too_large = false;  // UMFPACK reported out of memory
    auto factorize_as = [&](auto& lu, const auto& matrix) {
        if (!analysed) {
            ++n_symbolic_;
            lu.analyzePattern(matrix);
            too_large = lu.out_of_memory();
            if (too_large || lu.info() != Eigen::Success)
                return LinearStatus::failed;
            analysed = true;
        }
        ++n_numeric_;
        lu.factorize(matrix);
        too_large = lu.out_of_memory();
        if (too_large || lu.info() != Eigen::Success)
            return LinearStatus::singular;
        factor_flops_ = lu.statistic(UMFPACK_FLOPS);
        factor_entries_ = lu.statistic(UMFPACK_LNZ) + lu.statistic(UMFPACK_UNZ);
        return LinearStatus::ok;
    };
    // The 64-bit version needs the matrix with 64-bit indices: a copy, made for it only.
    auto factorize = [&] {
        if (!b.long_lu)
            return factorize_as(b.lu, A);
        b.long_matrix = A;
        b.long_matrix.makeCompressed();
        return factorize_as(b.lu_long, b.long_matrix);
    };
    LinearStatus status = factorize();
    if (too_large && !b.long_lu) {
        b.long_lu = true;
        analysed = false;
        status = factorize();
    }
    if (too_large)
        throw std::bad_alloc();
    return status;
}

LinearStatus SuiteSparseSolver::factorize_cholesky(bool& analysed)
{
    Backend& b = *backend_;
    if (!analysed) {
        ++n_symbolic_;
        b.llt.analyzePattern(reference_);
        b.throw_if_cholesky_out_of_memory();
        // Eigen reports Success even when cholmod_analyze failed (and left no
        // factor, which factorize() would dereference): check CHOLMOD's status.
        if (b.llt.info() != Eigen::Success || b.llt.cholmod().status < 0)
            return LinearStatus::failed;
        analysed = true;
    }
    ++n_numeric_;
    b.llt.factorize(reference_);
    b.throw_if_cholesky_out_of_memory();
    if (b.llt.info() != Eigen::Success)
        return LinearStatus::failed;
    release(lu_matrix_);  // an earlier LU's whole matrix is needed no more
    factor_flops_ = b.llt.cholmod().fl;  // of the last analysis, which is this pattern's
    factor_entries_ = 2 * b.llt.cholmod().lnz;  // L and L^T are both streamed by a solve
    return LinearStatus::ok;
}

LinearStatus SuiteSparseSolver::solve(const Vector& b, Vector& x)
{
    IGA_CHECK(factorized_, "SuiteSparseSolver::solve: needs a successful factorize() first");
    IGA_CHECK(b.size() == reference_.rows(), "SuiteSparseSolver::solve: right-hand side size differs from the matrix");
    if (reference_.rows() == 0) {
        x.resize(0);
        return LinearStatus::ok;
    }

    // With the reference's factorization, corrected by the update if there is one.
    auto solve_once = [this](const Vector& rhs, Vector& y) {
        if (factorized_kind_ == Kind::lu) {
            backend_->with_lu([&](auto& lu) {
                lu.umfpackControl()(UMFPACK_IRSTEP) = updated_ ? 0 : umfpack_refinement_steps;
                y = lu.solve(rhs);
            });
        } else {
            y = backend_->llt.solve(rhs);
            if (backend_->llt.info() != Eigen::Success)
                return false;
        }
        if (updated_)
            update_->correct(y);
        return y.allFinite();
    };
    if (!solve_once(b, x))
        return updated_ ? refactorize_and_solve(b, x) : LinearStatus::singular;
    // Also catches Cholesky handed a non-symmetric K: it reads one triangle only,
    // the check multiplies by the whole matrix.
    Vector r = b - apply(x);
    double residual = r.norm();
    // An update's solution carries the rounding of K_ref^-1 b and of the
    // correction, which cancel where penalty stiffness dominates, and with a shifted
    // reference it solves K + mu D, not K: refine against K while that pays.
    for (int step = 0; updated_ && step < max_refinement_steps && residual > refinement_threshold * b.norm(); ++step) {
        Vector dx;
        if (!solve_once(r, dx))
            break;
        const Vector refined = x + dx;
        Vector r_refined = b - apply(refined);
        if (!(r_refined.norm() < 0.5 * residual))
            break;  // no progress: keep the better x
        x = refined;
        r = std::move(r_refined);
        residual = r.norm();
    }
    if (!(residual <= backward_error_tolerance * b.norm()))
        return updated_ ? refactorize_and_solve(b, x) : LinearStatus::singular;
    return LinearStatus::ok;
}

LinearStatus SuiteSparseSolver::refactorize_and_solve(const Vector& b, Vector& x)
{
    // The update does not serve this K (singular, or the shift too strong to refine
    // away): factorize K itself, which becomes the reference; the call is then a
    // factorization, not an update.
    materialize();
    --n_updates_;
    shift_base_valid_ = false;
    factorized_ = false;
    const LinearStatus status = factorize_reference();
    if (status != LinearStatus::ok)
        return LinearStatus::singular;  // K singular: the caller's shift starts from it (materialized above)
    return solve(b, x);
}

}  // namespace iga::solver
