#include "solver/linear.hpp"

#include "solver/condensation.hpp"

#include "core/error.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/UmfPackSupport>

#include <algorithm>

namespace iga::solver {

namespace {

// A backward-stable direct solve leaves ||K x - b|| ~ eps * ||K|| ||x||; UMFPACK
// also refines iteratively. 1e-6 ||b|| is far above that for any K we can use,
// yet catches the garbage a near-singular K that escaped the pivot test gives.
constexpr double backward_error_tolerance = 1e-6;

bool all_finite(const SparseMatrix& K)
{
    const double* values = K.valuePtr();
    return std::all_of(values, values + K.nonZeros(), [](double v) { return std::isfinite(v); });
}

}  // namespace

struct LinearSolver::Backend {
    Eigen::UmfPackLU<SparseMatrix> lu;
    Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> llt;

    Backend()
    {
        // CHOLMOD prints "not positive definite" warnings to stdout by default;
        // the library reports statuses instead (no printing in lib/).
        llt.cholmod().print = 0;
    }
};

const char* status_name(LinearStatus status)
{
    switch (status) {
    case LinearStatus::ok: return "ok";
    case LinearStatus::singular: return "singular";
    case LinearStatus::failed: return "failed";
    }
    return "unknown";
}

const char* kind_name(LinearSolver::Kind kind)
{
    return kind == LinearSolver::Kind::lu ? "lu" : "cholesky";
}

// Cholesky is tried again after this many skipped factorizations at most (the
// back-off doubles from 1 with each refusal in a row).
constexpr int max_cholesky_backoff = 32;

LinearSolver::LinearSolver(Kind kind) : kind_(kind), factorized_kind_(kind), backend_(std::make_unique<Backend>()) {}
LinearSolver::~LinearSolver() = default;
LinearSolver::LinearSolver(LinearSolver&&) noexcept = default;
LinearSolver& LinearSolver::operator=(LinearSolver&&) noexcept = default;

void LinearSolver::set_condensed_dofs(std::vector<int> dofs)
{
    condensation_ = dofs.empty() ? nullptr : std::make_unique<Condensation>(std::move(dofs));
    analysed_ = analysed_lu_ = analysed_llt_ = false;  // the backends and the condensation keep separate analyses
    factorized_ = false;
}

const std::vector<int>& LinearSolver::condensed_dofs() const
{
    static const std::vector<int> none;
    return condensation_ ? condensation_->condensed_dofs() : none;
}

void LinearSolver::set_ordering(Ordering ordering)
{
    Backend& b = *backend_;
    const bool nested = ordering == Ordering::nested_dissection;
    b.llt.cholmod().nmethods = 1;
    b.llt.cholmod().method[0].ordering = nested ? CHOLMOD_METIS : CHOLMOD_AMD;
    b.lu.umfpackControl()(UMFPACK_ORDERING) = nested ? UMFPACK_ORDERING_METIS : UMFPACK_ORDERING_AMD;
    analysed_lu_ = analysed_llt_ = false;  // the next factorization orders again
    factorized_ = false;
}

void LinearSolver::set_kind(Kind kind)
{
    if (kind != kind_) {
        kind_ = kind;
        factorized_ = false;
        cholesky_skips_ = 0;
        cholesky_backoff_ = 1;
    }
}

bool LinearSolver::same_pattern(const SparseMatrix& K) const
{
    if (K.rows() != K_.rows() || K.cols() != K_.cols() || K.nonZeros() != K_.nonZeros())
        return false;
    const int n_outer = static_cast<int>(K.outerSize()) + 1;
    return std::equal(K.outerIndexPtr(), K.outerIndexPtr() + n_outer, K_.outerIndexPtr()) &&
           std::equal(K.innerIndexPtr(), K.innerIndexPtr() + K.nonZeros(), K_.innerIndexPtr());
}

LinearStatus LinearSolver::factorize(const SparseMatrix& K)
{
    IGA_CHECK(K.rows() == K.cols(), "LinearSolver::factorize: the matrix must be square");
    // The same matrix again (a linear scene's next increment): keep the factorization.
    if (factorized_ && K.isCompressed() && same_pattern(K) &&
        std::equal(K.valuePtr(), K.valuePtr() + K.nonZeros(), K_.valuePtr()))
        return LinearStatus::ok;
    factorized_ = false;

    if (analysed_ && K.isCompressed() && same_pattern(K)) {
        // Same pattern: copy the values in place, so nothing is reallocated.
        std::copy(K.valuePtr(), K.valuePtr() + K.nonZeros(), K_.valuePtr());
    } else {
        SparseMatrix copy = K;
        copy.makeCompressed();
        if (!(analysed_ && same_pattern(copy)))
            analysed_ = analysed_lu_ = analysed_llt_ = false;
        K_ = std::move(copy);
    }
    if (!all_finite(K_))
        return LinearStatus::failed;
    if (K_.rows() == 0) {  // no unknowns: nothing to factorize, solve() returns an empty x
        factorized_ = true;
        return LinearStatus::ok;
    }
    if (K_.nonZeros() == 0)  // the backends reject an empty pattern (CHOLMOD would crash)
        return LinearStatus::singular;

    if (condensation_) {
        if (!analysed_) {  // a new pattern (e.g. a contact coupling extended it): new block maps
            condensation_->new_pattern();  // (not counted in n_symbolic(): the backend's analyses only)
            analysed_ = true;
        }
        ++n_numeric_;
        const LinearStatus status = condensation_->factorize(K_);
        factorized_ = status == LinearStatus::ok;
        return status;
    }

    analysed_ = true;  // the backends' analyses below are made for K_'s pattern
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

LinearStatus LinearSolver::factorize_with(Kind kind)
{
    Backend& b = *backend_;
    bool& analysed = kind == Kind::lu ? analysed_lu_ : analysed_llt_;
    if (!analysed) {
        ++n_symbolic_;
        if (kind == Kind::lu) {
            b.lu.analyzePattern(K_);
            if (b.lu.info() != Eigen::Success)
                return LinearStatus::failed;
        } else {
            b.llt.analyzePattern(K_);
            // Eigen reports Success even when cholmod_analyze failed (and left no
            // factor, which factorize() would dereference): check CHOLMOD's status.
            if (b.llt.info() != Eigen::Success || b.llt.cholmod().status < 0)
                return LinearStatus::failed;
        }
        analysed = true;
    }

    ++n_numeric_;
    if (kind == Kind::lu) {
        b.lu.factorize(K_);
        if (b.lu.info() != Eigen::Success)
            return LinearStatus::singular;
    } else {
        b.llt.factorize(K_);
        if (b.llt.info() != Eigen::Success)
            return LinearStatus::failed;
    }
    factorized_ = true;
    factorized_kind_ = kind;
    return LinearStatus::ok;
}

LinearStatus LinearSolver::solve(const Vector& b, Vector& x) const
{
    IGA_CHECK(factorized_, "LinearSolver::solve: needs a successful factorize() first");
    IGA_CHECK(b.size() == K_.rows(), "LinearSolver::solve: right-hand side size differs from the matrix");
    if (K_.rows() == 0) {
        x.resize(0);
        return LinearStatus::ok;
    }

    if (condensation_) {
        if (condensation_->solve(b, x) != LinearStatus::ok)
            return LinearStatus::singular;
    } else if (factorized_kind_ == Kind::lu) {
        x = backend_->lu.solve(b);
    } else {
        x = backend_->llt.solve(b);
        if (backend_->llt.info() != Eigen::Success)
            return LinearStatus::singular;
    }
    if (!x.allFinite())
        return LinearStatus::singular;
    // Also catches Cholesky handed a non-symmetric K: it reads one triangle only,
    // the check multiplies by the whole matrix.
    const double residual = (K_ * x - b).norm();
    if (!(residual <= backward_error_tolerance * b.norm()))
        return LinearStatus::singular;
    return LinearStatus::ok;
}

}  // namespace iga::solver
