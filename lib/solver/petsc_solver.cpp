#include "solver/petsc_solver.hpp"

#include "core/error.hpp"
#include "core/petsc_options.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <petscksp.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

namespace iga::solver {

namespace {

// Same bound as the SuiteSparse backend (suitesparse_solver.cpp): far above the
// round-off of a backward-stable solve, far below the garbage of a near-singular one.
constexpr double backward_error_tolerance = 1e-6;
// Krylov methods, for a solve() that asks for nothing: a relative true residual of
// 1e-8, the accuracy that keeps Newton's convergence quadratic (Newton asks for it,
// or for less at its last step, through solve_to: solver/newton.cpp).
constexpr double krylov_rtol = 1e-8;
// solve_to() asks for what it needs, but no less than this: far below 1e-10 a Krylov
// method's true residual can stagnate at round-off (a refinement solve goes on from there).
constexpr double krylov_rtol_floor = 1e-10;
// The backward-error check of a Krylov solve allows this multiple of its tolerance.
constexpr double krylov_bound_margin = 10.0;
// The solves we measured took 40-200 iterations; a singular tangent (a body held only
// by a contact that has not closed yet) never converges, and each Levenberg-Marquardt
// retry pays the cap again, so it stays within ~5x of a hard solve.
constexpr int krylov_max_iterations = 1000;
constexpr int gmres_restart = 100;
// A reused preconditioner is kept while the Krylov iterations stay within this
// factor of those of its first solve.
constexpr double reuse_iteration_growth = 2.0;
// Smoothed aggregation (GAMG) with the rigid-body modes is the faster multigrid for
// elasticity (box of 32k dofs, degree 2: 45 CG iterations, 9.8 s; BoomerAMG 63
// iterations, 54 s, or 103 and 13 s with the coarsening below), but penalty springs
// of eps h / E' above ~1e2 break its aggregates: 53 / 83 / 637 / > 2000 iterations at
// 1 / 1e2 / 1e4 / 1e6 on two tied boxes, and a sphere pressed into a block at 5e4 did
// not converge where BoomerAMG did (docs/parallel.md).
constexpr double max_aggregation_penalty_ratio = 1e2;
// A Krylov solve is stopped as stalled when, at the pace of its last stall_window
// iterations, it would not reach its tolerance within its iteration cap. A
// preconditioner that does not fit the tangent otherwise runs every solve, and every
// shift Newton then tries, to the cap (issue 31: GMRES + GAMG on two cylinders in
// contact, 1000-iteration failures, over 10 minutes). One GMRES restart cycle: a
// cycle's residual only falls, and a restart rarely speeds it up.
constexpr PetscInt stall_window = gmres_restart;

/// The convergence test of every Krylov solve: PETSc's default, and a stop (reason
/// KSP_DIVERGED_ITS, `stalled` set) when the solve is stalled (stall_window above).
struct StallTest {
    void* converged_default = nullptr;  // KSPConvergedDefault's context
    std::vector<PetscReal> best;        // the smallest residual norm up to each iteration
    bool stalled = false;
    PetscInt iterations = 0;            // where a stalled solve was stopped
};

/// Whether the residual, shrinking as it did over the last stall_window iterations,
/// misses `target` at the iteration cap. `best` holds iterations 0..it.
bool off_pace(const std::vector<PetscReal>& best, PetscInt it, PetscInt max_it, double target)
{
    if (it < stall_window || it >= max_it)
        return false;
    const double now = best[static_cast<std::size_t>(it)];
    const double ratio = now / best[static_cast<std::size_t>(it - stall_window)];
    const double windows_left = static_cast<double>(max_it - it) / static_cast<double>(stall_window);
    return now * std::pow(ratio, windows_left) > target;
}

PetscErrorCode converged_or_stalled(KSP ksp, PetscInt it, PetscReal rnorm, KSPConvergedReason* reason, void* context)
{
    auto& test = *static_cast<StallTest*>(context);
    const PetscErrorCode code = KSPConvergedDefault(ksp, it, rnorm, reason, test.converged_default);
    if (code != 0)
        return code;
    if (it == 0) {
        test.best.clear();
        test.stalled = false;
    }
    // GMRES tests the first residual of a cycle twice (at the end of one, the start of the next).
    const auto k = static_cast<std::size_t>(it);
    if (test.best.size() <= k)
        test.best.resize(k + 1, test.best.empty() ? rnorm : test.best.back());
    test.best[k] = std::min(test.best[k], rnorm);
    if (*reason != KSP_CONVERGED_ITERATING)
        return 0;
    PetscReal rtol = 0, abstol = 0, dtol = 0;
    PetscInt max_it = 0;
    const PetscErrorCode got = KSPGetTolerances(ksp, &rtol, &abstol, &dtol, &max_it);
    if (got != 0)
        return got;
    if (off_pace(test.best, it, max_it, std::max(rtol * test.best.front(), abstol))) {
        test.stalled = true;
        test.iterations = it;
        *reason = KSP_DIVERGED_ITS;
    }
    return 0;
}

PetscErrorCode destroy_stall_test(void* context)
{
    auto* test = static_cast<StallTest*>(context);
    const PetscErrorCode code = KSPConvergedDefaultDestroy(test->converged_default);
    delete test;
    return code;
}

/// The KSP's StallTest, or null when the options replaced it (-ksp_convergence_test).
const StallTest* stall_test(KSP ksp)
{
    PetscErrorCode (*test)(KSP, PetscInt, PetscReal, KSPConvergedReason*, void*) = nullptr;
    void* context = nullptr;
    if (KSPGetConvergenceTest(ksp, &test, &context, nullptr) != 0 || test != converged_or_stalled)
        return nullptr;
    return static_cast<const StallTest*>(context);
}

/// What a Krylov solve that stopped short saw: "gmres + gamg stalled: ..." or
/// "cg + gamg stopped after 2 iterations: DIVERGED_ITS".
std::string krylov_failure_text(KSP ksp, const std::string& method, KSPConvergedReason reason, PetscInt iterations)
{
    const StallTest* test = stall_test(ksp);
    if (!test || !test->stalled || test->best.empty())
        return fmt::format("{} stopped after {} iterations: {}", method, iterations, KSPConvergedReasons[reason]);
    PetscReal rtol = 0;
    PetscInt max_it = 0;
    KSPGetTolerances(ksp, &rtol, nullptr, nullptr, &max_it);
    const double reached = test->best.back() / test->best.front();
    return fmt::format("{} stalled: its residual fell to {:.2g} of the first in {} iterations, too slowly to reach "
                       "{:.0e} within {}",
                       method, reached, test->iterations, rtol, max_it);
}

void check(PetscErrorCode code, const char* what)
{
    if (code == 0)
        return;
    const char* text = nullptr;
    PetscErrorMessage(code, &text, nullptr);
    throw Error(std::string("PETSc: ") + what + " failed" + (text ? std::string(": ") + text : std::string()));
}

void finalize_petsc()
{
    if (PetscInitializeCalled && !PetscFinalizeCalled)
        PetscFinalize();
}

/// The last error PETSc raised: its first message and the functions it came back
/// through. PETSc's error handler is process-wide, as PETSc is, so this record is too.
struct PetscErrorRecord {
    PetscErrorCode code = 0;
    std::string message;
    std::vector<std::string> functions;

    /// Whether PETSc raised it reading an option: a value it could not parse
    /// (PetscOptions*), one rejected while an object read its options
    /// (*SetFromOptions, MUMPS's options read at its first factorization), or a type
    /// name nothing is registered under (-mg_levels_pc_type bogus). A numerical failure
    /// (a zero pivot, a multigrid that cannot be built) comes from neither.
    bool from_options() const
    {
        return code == PETSC_ERR_ARG_UNKNOWN_TYPE ||
               std::any_of(functions.begin(), functions.end(),
                           [](const std::string& f) { return f.find("Options") != std::string::npos; });
    }
};

PetscErrorRecord& last_error()
{
    static PetscErrorRecord record;
    return record;
}

PetscErrorCode record_error(MPI_Comm, int, const char* function, const char*, PetscErrorCode code,
                            PetscErrorType type, const char* message, void* context)
{
    auto& record = *static_cast<PetscErrorRecord*>(context);
    if (type == PETSC_ERROR_INITIAL) {
        record = PetscErrorRecord{};
        record.code = code;
        record.message = message ? message : "";
        while (!record.message.empty() && (record.message.back() == '\n' || record.message.back() == ' '))
            record.message.pop_back();
    }
    if (function)
        record.functions.emplace_back(function);
    return code;
}

/// PETSc once per process, on MPI_COMM_WORLD (MPI initialized by core/parallel
/// under mpirun, else by PETSc as a one-rank world). Our SIGINT/SIGTERM handling
/// stays ours (-no_signal_handler); errors come back as codes, not printed traces,
/// and are recorded (last_error). Its options come from the deck and PETSC_OPTIONS
/// only, both checked before (checked_options): no .petscrc or petscrc file, which
/// PETSc reads from the home and working folders unless -skip_petscrc is given (on
/// a command line: hence the one of the program's name alone). PETSc's standard
/// output (monitors, views) goes to standard error, with our log: standard output
/// is the run's summary (--summary json).
void ensure_petsc()
{
    if (PetscInitializeCalled)
        return;
    check(PetscOptionsSetValue(nullptr, "-no_signal_handler", nullptr), "PetscOptionsSetValue");
    check(PetscOptionsSetValue(nullptr, "-skip_petscrc", "true"), "PetscOptionsSetValue");
    static char program[] = "igacontact";
    static char* arguments[] = {program, nullptr};
    static char** argv = arguments;
    static int argc = 1;
    check(PetscInitialize(&argc, &argv, nullptr, nullptr), "PetscInitialize");
    PETSC_STDOUT = stderr;
    PetscPushErrorHandler(record_error, &last_error());
    parallel::on_finalize(finalize_petsc);
}

/// The options of the deck and of PETSC_OPTIONS, checked on every rank before PETSc
/// reads any (it reads PETSC_OPTIONS when it starts). A refused option ends the
/// construction on every rank alike, with the lowest rank's reason.
struct UserOptions {
    std::vector<PetscOption> deck, environment;
};

UserOptions checked_options(const std::string& deck_text, const Communicator& comm)
{
    UserOptions user;
    const PetscOptionsCheck deck = check_petsc_options(deck_text, PetscOptionsSource::deck);
    if (const std::string problem = comm.first_message(deck.message()); !problem.empty())
        throw PetscOptionsError(PetscOptionsSource::deck, problem);
    user.deck = deck.options;
    user.environment = checked_environment_options(comm);
    return user;
}

/// The options into PETSc's database: the deck's, then the environment's again (PETSc
/// read them when it started), so that PETSC_OPTIONS wins as a command line wins over
/// a file. Each checked option goes in as one name and value, split as checked.
void insert_options(const UserOptions& user)
{
    for (const std::vector<PetscOption>* list : {&user.deck, &user.environment})
        for (const PetscOption& option : *list)
            check(PetscOptionsSetValue(nullptr, option.name.c_str(), option.has_value ? option.value.c_str() : nullptr),
                  "PetscOptionsSetValue");
}

/// An option's name as PETSc's database holds it: without its dashes.
std::string stored_name(const std::string& name)
{
    return name.substr(std::min(name.find_first_not_of('-'), name.size()));
}

/// A default in the options database, unless the options give it already.
void default_option(const char* name, const char* value)
{
    PetscBool given = PETSC_FALSE;
    check(PetscOptionsHasName(nullptr, nullptr, name, &given), "options");
    if (!given)
        check(PetscOptionsSetValue(nullptr, name, value), "options");
}

/// The algebraic multigrid of the policy (see the header).
void set_multigrid(PC pc, const LinearSolverPolicy& policy)
{
    if (policy.penalty_ratio <= max_aggregation_penalty_ratio) {
        check(PCSetType(pc, PCGAMG), "PCSetType");
        return;
    }
    check(PCSetType(pc, PCHYPRE), "PCSetType");
    check(PCHYPRESetType(pc, "boomeramg"), "PCHYPRESetType");
    // Coarsening that keeps the coarse grids of 3D quadratic elements sparse
    // (hypre's advice for 3D elasticity); each a default the user may override.
    default_option("-pc_hypre_boomeramg_strong_threshold", "0.5");
    default_option("-pc_hypre_boomeramg_coarsen_type", "HMIS");
    default_option("-pc_hypre_boomeramg_interp_type", "ext+i");
    default_option("-pc_hypre_boomeramg_P_max", "4");
    default_option("-pc_hypre_boomeramg_agg_nl", "1");
}

/// The Krylov method and preconditioner of the policy (see the header), before the
/// options database is applied (PetscSolver::new_ksp).
KSP make_ksp(const LinearSolverPolicy& policy)
{
    KSP ksp = nullptr;
    check(KSPCreate(PETSC_COMM_WORLD, &ksp), "KSPCreate");
    PC pc = nullptr;
    check(KSPGetPC(ksp, &pc), "KSPGetPC");
    if (policy.method == Method::direct) {
        check(KSPSetType(ksp, KSPPREONLY), "KSPSetType");
        check(PCSetType(pc, policy.symmetric ? PCCHOLESKY : PCLU), "PCSetType");
        check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
    } else {
        check(KSPSetType(ksp, policy.symmetric ? KSPCG : KSPGMRES), "KSPSetType");
        if (!policy.symmetric) {
            check(KSPGMRESSetRestart(ksp, gmres_restart), "KSPGMRESSetRestart");
            check(KSPSetPCSide(ksp, PC_RIGHT), "KSPSetPCSide");
        }
        check(KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
        check(KSPSetTolerances(ksp, krylov_rtol, PETSC_DEFAULT, PETSC_DEFAULT, krylov_max_iterations),
              "KSPSetTolerances");
        auto* test = new StallTest;  // owned by the KSP, freed by destroy_stall_test
        check(KSPConvergedDefaultCreate(&test->converged_default), "KSPConvergedDefaultCreate");
        check(KSPSetConvergenceTest(ksp, converged_or_stalled, test, destroy_stall_test), "KSPSetConvergenceTest");
        if (policy.two_body_contact && !policy.symmetric) {
            // Two bodies pressed together by a two-half-pass pair: the multigrids stall
            // on such a tangent (GAMG and BoomerAMG, and one-level Schwarz with LU
            // blocks on 3 ranks, where the body that only contact holds is cut), so
            // the preconditioner is a MUMPS LU, kept for later tangents while it serves.
            check(PCSetType(pc, PCLU), "PCSetType");
            check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
        } else {
            set_multigrid(pc, policy);
        }
    }
    return ksp;
}

}  // namespace

struct PetscSolver::State {
    Mat A = nullptr;   // the summed K (AIJ): the preconditioner's matrix, and the operator unless `op` is made
    Mat op = nullptr;  // CG's operator for a symmetric K: its upper triangle (SBAIJ), see create_upper_triangle()
    KSP ksp = nullptr;
    Vec b = nullptr, x = nullptr, x_all = nullptr;
    VecScatter to_all = nullptr;
    MatNullSpace near_null = nullptr;
    PetscInt n = -1, first = 0, last = 0;  // global size, owned rows [first, last)
    // The pattern the COO preallocation was made for (this rank's summand).
    std::vector<int> outer, inner;
    Vec diagonal = nullptr, shift_scale = nullptr;
    bool shift_ready = false;  // diagonal and shift_scale hold the unshifted K's
    bool set_up = false;       // the preconditioner matches the operator (or is reused on purpose)
    bool reused = false;       // the next solve runs with a preconditioner of an earlier K
    PetscInt setup_iterations = -1;  // Krylov iterations of the first solve after the last set-up
    PetscInt last_iterations = 0;
    PetscReal own_rtol = krylov_rtol;  // the KSP's relative tolerance: krylov_rtol, or -ksp_rtol
    bool user_rtol = false;            // -ksp_rtol was given: it holds for every solve
    bool last_converged = true;
    // After a failed set-up or solve on a singular matrix PETSc 3.18's GAMG can leave
    // its levels half built and crash in its destroy (measured on a 4 x 4 singular
    // matrix): such a KSP is abandoned (a small leak on a rare path), never destroyed.
    std::vector<KSP> abandoned;
    bool ksp_failed = false;

    void destroy_matrix()
    {
        if (near_null)
            MatNullSpaceDestroy(&near_null);
        if (diagonal)
            VecDestroy(&diagonal);
        if (shift_scale)
            VecDestroy(&shift_scale);
        if (to_all)
            VecScatterDestroy(&to_all);
        if (x_all)
            VecDestroy(&x_all);
        if (b)
            VecDestroy(&b);
        if (x)
            VecDestroy(&x);
        if (A)
            MatDestroy(&A);
        if (op)
            MatDestroy(&op);
    }
    Mat operator_matrix() const { return op ? op : A; }

    // A new matrix for the pattern of M (this rank's summand, compressed), rows
    // [first_row, last_row) owned here, in blocks of bs; the vectors and the scatter
    // that gathers a solution on every rank.
    void create_matrix(const SparseMatrix& M, PetscInt bs, PetscInt first_row, PetscInt last_row, bool by_rows)
    {
        n = static_cast<PetscInt>(M.rows());
        const Index nnz = M.nonZeros();
        first = first_row;
        last = last_row;
        outer.assign(M.outerIndexPtr(), M.outerIndexPtr() + n + 1);
        inner.assign(M.innerIndexPtr(), M.innerIndexPtr() + nnz);
        // COO: the summand's entries, then every owned diagonal. A symmetric K's columns
        // are its rows, so they are listed as rows (by_rows): PETSc's COO set-up sorts
        // entries given in row order 2.3x faster (118k dofs: 1.9 against 4.5 s). (What
        // PETSc then holds is the summand's transpose, equal to it where K is symmetric.)
        const PetscCount n_coo = static_cast<PetscCount>(nnz) + (last - first);
        std::vector<PetscInt> rows(static_cast<std::size_t>(n_coo)), cols(static_cast<std::size_t>(n_coo));
        std::size_t k = 0;
        for (PetscInt j = 0; j < n; ++j)
            for (int p = outer[static_cast<std::size_t>(j)]; p < outer[static_cast<std::size_t>(j) + 1]; ++p, ++k) {
                rows[k] = by_rows ? j : inner[static_cast<std::size_t>(p)];
                cols[k] = by_rows ? inner[static_cast<std::size_t>(p)] : j;
            }
        for (PetscInt i = first; i < last; ++i, ++k)
            rows[k] = cols[k] = i;
        check(MatCreate(PETSC_COMM_WORLD, &A), "MatCreate");
        check(MatSetSizes(A, last - first, last - first, n, n), "MatSetSizes");
        check(MatSetType(A, MATAIJ), "MatSetType");
        check(MatSetBlockSize(A, bs), "MatSetBlockSize");
        check(MatSetPreallocationCOO(A, n_coo, rows.data(), cols.data()), "MatSetPreallocationCOO");
        check(MatCreateVecs(A, &x, &b), "MatCreateVecs");
        check(VecScatterCreateToAll(x, &to_all, &x_all), "VecScatterCreateToAll");
    }

    // The near-null space of A (the rigid-body modes, n x m), orthonormalized as PETSc
    // requires (modified Gram-Schmidt).
    void set_near_null_space(const Matrix& rigid_body_modes)
    {
        const Index m = rigid_body_modes.cols();
        std::vector<Vec> modes(static_cast<std::size_t>(m));
        for (Index c = 0; c < m; ++c) {
            Vec& v = modes[static_cast<std::size_t>(c)];
            check(VecDuplicate(x, &v), "VecDuplicate");
            PetscScalar* a = nullptr;
            check(VecGetArray(v, &a), "VecGetArray");
            for (PetscInt i = first; i < last; ++i)
                a[i - first] = rigid_body_modes(i, c);
            check(VecRestoreArray(v, &a), "VecRestoreArray");
            for (Index e = 0; e < c; ++e) {
                PetscScalar dot = 0;
                check(VecDot(v, modes[static_cast<std::size_t>(e)], &dot), "VecDot");
                check(VecAXPY(v, -dot, modes[static_cast<std::size_t>(e)]), "VecAXPY");
            }
            PetscReal norm = 0;
            check(VecNormalize(v, &norm), "VecNormalize");
        }
        check(MatNullSpaceCreate(PETSC_COMM_WORLD, PETSC_FALSE, static_cast<PetscInt>(m), modes.data(), &near_null),
              "MatNullSpaceCreate");
        check(MatSetNearNullSpace(A, near_null), "MatSetNearNullSpace");
        for (Vec& v : modes)
            VecDestroy(&v);
    }

    // CG's operator for a symmetric K: the upper triangle of A in symmetric blocks of
    // bs (SBAIJ), which CG streams from memory in 2.6x less time than the whole AIJ
    // (118k dofs, degree 2: 36 against 93 ms a product; the solve 8.6 against 20.5 s).
    // GAMG builds its hierarchy from AIJ only, so both are kept (+1/3 matrix memory).
    // Each rank fills its own rows from its rows of the summed A, without
    // communication, into an exact preallocation (PETSc's COO for SBAIJ inserts entry
    // by entry: 5.8 s at 118k dofs with bs 1).
    void create_upper_triangle()
    {
        PetscInt bs = 1;
        check(MatGetBlockSize(A, &bs), "MatGetBlockSize");
        const PetscInt n_blocks = (last - first) / bs, first_block = first / bs, last_block = last / bs;
        std::vector<PetscInt> d_nnz(static_cast<std::size_t>(n_blocks)), o_nnz(static_cast<std::size_t>(n_blocks));
        // seen[J]: the last block row that counted block column J.
        std::vector<PetscInt> seen(static_cast<std::size_t>(n / bs), -1);
        for (PetscInt I = 0; I < n_blocks; ++I)
            for (PetscInt r = (first_block + I) * bs; r < (first_block + I + 1) * bs; ++r) {
                PetscInt nc = 0;
                const PetscInt* c = nullptr;
                check(MatGetRow(A, r, &nc, &c, nullptr), "MatGetRow");
                for (PetscInt q = 0; q < nc; ++q) {
                    const PetscInt J = c[q] / bs;
                    if (J < first_block + I || seen[static_cast<std::size_t>(J)] == I)
                        continue;
                    seen[static_cast<std::size_t>(J)] = I;
                    ++(J < last_block ? d_nnz : o_nnz)[static_cast<std::size_t>(I)];
                }
                check(MatRestoreRow(A, r, &nc, &c, nullptr), "MatRestoreRow");
            }
        check(MatCreate(PETSC_COMM_WORLD, &op), "MatCreate");
        check(MatSetSizes(op, last - first, last - first, n, n), "MatSetSizes");
        check(MatSetType(op, MATSBAIJ), "MatSetType");
        check(MatSetBlockSize(op, bs), "MatSetBlockSize");
        check(MatSeqSBAIJSetPreallocation(op, bs, 0, d_nnz.data()), "MatSeqSBAIJSetPreallocation");
        check(MatMPISBAIJSetPreallocation(op, bs, 0, d_nnz.data(), 0, o_nnz.data()), "MatMPISBAIJSetPreallocation");
        check(MatSetOption(op, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
    }
    // A's values into `op` (after every load of A).
    void copy_upper_triangle()
    {
        for (PetscInt r = first; r < last; ++r) {
            PetscInt nc = 0;
            const PetscInt* c = nullptr;
            const PetscScalar* v = nullptr;
            check(MatGetRow(A, r, &nc, &c, &v), "MatGetRow");
            const PetscInt skip = static_cast<PetscInt>(std::lower_bound(c, c + nc, r) - c);  // columns sorted
            check(MatSetValues(op, 1, &r, nc - skip, c + skip, v + skip, INSERT_VALUES), "MatSetValues");
            check(MatRestoreRow(A, r, &nc, &c, &v), "MatRestoreRow");
        }
        check(MatAssemblyBegin(op, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
        check(MatAssemblyEnd(op, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    }
    ~State()
    {
        if (PetscFinalizeCalled)
            return;  // PETSc freed everything already
        destroy_matrix();
        if (ksp && !ksp_failed)
            KSPDestroy(&ksp);
    }
};

PetscSolver::PetscSolver(const LinearSolverPolicy& policy, const Communicator& comm)
    : policy_(policy), comm_(comm), state_(std::make_unique<State>())
{
    UserOptions user = checked_options(policy.options, comm_);
    ensure_petsc();
    insert_options(user);
    deck_options_ = std::move(user.deck);
    environment_options_ = std::move(user.environment);
    new_ksp();
    PetscBool given = PETSC_FALSE;
    check(PetscOptionsHasName(nullptr, nullptr, "-ksp_rtol", &given), "options");
    state_->user_rtol = given == PETSC_TRUE;
    check(KSPGetTolerances(state_->ksp, &state_->own_rtol, nullptr, nullptr, nullptr), "KSPGetTolerances");
}

PetscSolver::~PetscSolver() = default;

void PetscSolver::new_ksp()
{
    state_->ksp = make_ksp(policy_);
    const PetscErrorCode code = KSPSetFromOptions(state_->ksp);
    if (comm_.any(code != 0)) {
        throw_if_options_error(code != 0);
        check(code, "KSPSetFromOptions");
        throw Error("PETSc: KSPSetFromOptions failed on another rank");
    }
}

void PetscSolver::throw_if_options_error(bool failed_here) const
{
    std::string here;
    if (failed_here && last_error().from_options()) {
        const std::string& message = last_error().message;
        // The option PETSc rejected: the one whose value its message quotes (PETSc
        // names the value, "Unknown type ... bogus", not the option). The
        // environment's come last in the database and win, so they are looked at first.
        auto quoted = [&](const PetscOption& o) {
            if (!o.has_value)
                return false;
            auto inside_word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
            for (std::size_t at = message.find(o.value); at != std::string::npos;
                 at = message.find(o.value, at + 1)) {
                const std::size_t end = at + o.value.size();
                if ((at == 0 || !inside_word(message[at - 1])) && (end == message.size() || !inside_word(message[end])))
                    return true;
            }
            return false;
        };
        const auto env = std::find_if(environment_options_.rbegin(), environment_options_.rend(), quoted);
        const auto deck = std::find_if(deck_options_.rbegin(), deck_options_.rend(), quoted);
        const bool from_environment =
            env != environment_options_.rend() || (deck == deck_options_.rend() && deck_options_.empty());
        const std::string option = env != environment_options_.rend() ? env->text()
                                   : deck != deck_options_.rend()     ? deck->text()
                                                                      : std::string();
        here = std::string(from_environment ? "E" : "D") +
               (option.empty() ? "PETSc rejected an option" : option + ": PETSc rejected it") +
               (message.empty() ? std::string() : " (" + message + ")");
    }
    // Collective: every rank throws, with the lowest rank's reason.
    const std::string text = comm_.first_message(here);
    if (!text.empty())
        throw PetscOptionsError(text[0] == 'E' ? PetscOptionsSource::environment : PetscOptionsSource::deck,
                                text.substr(1));
}

std::vector<std::string> PetscSolver::warnings() const
{
    // PETSc reads some options only when the preconditioner is first set up (MUMPS's,
    // those of multigrid levels): before that, unread says nothing.
    if (statistics_.numeric == 0 || PetscFinalizeCalled)
        return {};
    std::vector<std::string> unread;
    for (const auto& [list, where] : {std::pair{&deck_options_, "solver.options"},
                                      std::pair{&environment_options_, "PETSC_OPTIONS"}})
        for (const PetscOption& option : *list) {
            PetscBool used = PETSC_FALSE;
            if (PetscOptionsUsed(nullptr, stored_name(option.name).c_str(), &used) != 0 || used)
                continue;
            const std::string text = option.name + " (" + where + ")";
            if (std::find(unread.begin(), unread.end(), text) == unread.end())
                unread.push_back(text);
        }
    if (unread.empty())
        return {};
    return {fmt::format("PETSc options {} did not read: {}; PETSc does not know them, or this method and "
                        "preconditioner take no such option",
                        describe_method(), fmt::join(unread, ", "))};
}

std::string PetscSolver::describe_method() const
{
    KSPType ksp_type = nullptr;
    PCType pc_type = nullptr;
    PC pc = nullptr;
    KSPGetType(state_->ksp, &ksp_type);
    KSPGetPC(state_->ksp, &pc);
    PCGetType(pc, &pc_type);
    return std::string(ksp_type ? ksp_type : "?") + " + " + (pc_type ? pc_type : "?");
}

std::string PetscSolver::describe() const
{
    std::string text = "PETSc " + describe_method();
    PC pc = nullptr;
    KSPGetPC(state_->ksp, &pc);
    MatSolverType factor = nullptr;
    if (pc && PCFactorGetMatSolverType(pc, &factor) == 0 && factor)
        text += std::string(" (") + factor + ")";
    return text + ", " + std::to_string(comm_.size()) + " rank(s)";
}

LinearStatus PetscSolver::factorize(const SparseMatrix& K)
{
    const LinearStatus loaded = load(K);
    return loaded == LinearStatus::ok ? prepare() : loaded;
}

LinearStatus PetscSolver::factorize_taking(SparseMatrix& K)
{
    // Once loaded, K's values live in PETSc's matrices: K goes before the set-up of
    // the preconditioner or factorization, where the run's memory peaks.
    const LinearStatus loaded = load(K);
    release(K);
    return loaded == LinearStatus::ok ? prepare() : loaded;
}

LinearStatus PetscSolver::prepare()
{
    State& s = *state_;
    // An iterative method keeps its preconditioner while it serves (see the header).
    const bool reuse = policy_.method == Method::iterative && s.set_up && s.last_converged &&
                       s.setup_iterations >= 0 &&
                       static_cast<double>(s.last_iterations) <=
                           reuse_iteration_growth * static_cast<double>(std::max<PetscInt>(s.setup_iterations, 1));
    check(KSPSetOperators(s.ksp, s.operator_matrix(), s.A), "KSPSetOperators");
    if (reuse) {
        check(KSPSetReusePreconditioner(s.ksp, PETSC_TRUE), "KSPSetReusePreconditioner");
        s.reused = true;
        return LinearStatus::ok;
    }
    return set_up_preconditioner();
}

LinearStatus PetscSolver::factorize_shifted_taking(SparseMatrix& K, double mu)
{
    // K is known to be singular (solver/linear.hpp): its values are loaded, and only
    // the shifted matrix gets a factorization or a preconditioner.
    const LinearStatus loaded = load(K);
    release(K);
    if (loaded != LinearStatus::ok)
        return loaded;
    return factorize_shifted(mu);
}

LinearStatus PetscSolver::load(const SparseMatrix& K)
{
    IGA_CHECK(K.rows() == K.cols(), "PetscSolver::factorize: the matrix must be square");
    State& s = *state_;
    SparseMatrix compressed;
    const SparseMatrix* M = &K;
    if (!K.isCompressed()) {
        compressed = K;
        compressed.makeCompressed();
        M = &compressed;
    }
    const auto n = static_cast<PetscInt>(M->rows());
    const Index nnz = M->nonZeros();
    const bool finite = std::all_of(M->valuePtr(), M->valuePtr() + nnz, [](double v) { return std::isfinite(v); });
    if (comm_.any(!finite))
        return LinearStatus::failed;
    s.shift_ready = false;

    const bool same_pattern = s.A && n == s.n && static_cast<Index>(s.inner.size()) == nnz &&
                              std::equal(s.outer.begin(), s.outer.end(), M->outerIndexPtr()) &&
                              std::equal(s.inner.begin(), s.inner.end(), M->innerIndexPtr());
    if (comm_.any(!same_pattern) || !s.A) {  // a new pattern on some rank: a new matrix
        s.destroy_matrix();
        // Rows split at point boundaries: PETSc's blocks may not straddle ranks.
        const PetscInt bs = policy_.block_size > 1 && n % policy_.block_size == 0 ? policy_.block_size : 1;
        const auto [first, last] = comm_.block_range(n / bs);
        s.create_matrix(*M, bs, static_cast<PetscInt>(first) * bs, static_cast<PetscInt>(last) * bs,
                        policy_.symmetric);
        if (policy_.rigid_body_modes.rows() == n && policy_.rigid_body_modes.cols() > 0)
            s.set_near_null_space(policy_.rigid_body_modes);
        ++statistics_.symbolic;
        s.set_up = false;
        s.setup_iterations = -1;
    }
    // The values in the order of the COO lists (State::create_matrix): the summand's,
    // then zeros for the owned diagonal (held only while PETSc copies them).
    std::vector<PetscScalar> values(M->valuePtr(), M->valuePtr() + nnz);
    values.resize(values.size() + static_cast<std::size_t>(s.last - s.first), 0.0);
    check(MatSetValuesCOO(s.A, values.data(), INSERT_VALUES), "MatSetValuesCOO");
    if (policy_.method == Method::iterative && policy_.symmetric) {
        if (!s.op)  // a new pattern: A is now assembled, and its rows can be read
            s.create_upper_triangle();
        s.copy_upper_triangle();
    }
    return LinearStatus::ok;
}

LinearStatus PetscSolver::set_up_preconditioner()
{
    State& s = *state_;
    check(KSPSetReusePreconditioner(s.ksp, PETSC_FALSE), "KSPSetReusePreconditioner");
    check(KSPSetOperators(s.ksp, s.operator_matrix(), s.A), "KSPSetOperators");
    s.reused = false;
    s.set_up = false;
    ++statistics_.numeric;
    const PetscErrorCode code = KSPSetUp(s.ksp);
    PC pc = nullptr;
    check(KSPGetPC(s.ksp, &pc), "KSPGetPC");
    PCFailedReason reason = PC_NOERROR;
    if (code == 0)
        PCGetFailedReasonRank(pc, &reason);
    if (comm_.any(code != 0 || reason != PC_NOERROR)) {
        throw_if_options_error(code != 0);  // an option rejected at set-up is bad input, not a singular K
        failure_detail_ = describe_method() + ": the preconditioner could not be built" +
                          (reason != PC_NOERROR ? std::string(" (") + PCFailedReasons[reason] + ")" : std::string());
        s.abandoned.push_back(s.ksp);
        new_ksp();
        return LinearStatus::singular;  // a zero pivot, or a preconditioner that cannot be built
    }
    s.set_up = true;
    s.setup_iterations = -1;
    return LinearStatus::ok;
}

LinearStatus PetscSolver::factorize_shifted(double mu)
{
    State& s = *state_;
    IGA_CHECK(s.A != nullptr, "PetscSolver::factorize_shifted: needs a factorize() first");
    if (!s.shift_ready) {
        // diag(K) and D = |diag(K)| with zeros replaced by the mean nonzero entry,
        // both over all ranks (solver/shift.hpp does the same on one process).
        if (!s.diagonal)
            check(VecDuplicate(s.x, &s.diagonal), "VecDuplicate");
        if (!s.shift_scale)
            check(VecDuplicate(s.x, &s.shift_scale), "VecDuplicate");
        check(MatGetDiagonal(s.A, s.diagonal), "MatGetDiagonal");
        check(VecCopy(s.diagonal, s.shift_scale), "VecCopy");
        check(VecAbs(s.shift_scale), "VecAbs");
        PetscScalar* d = nullptr;
        check(VecGetArray(s.shift_scale, &d), "VecGetArray");
        const PetscInt n_local = s.last - s.first;
        double sum = 0;
        long long n_nonzero = 0;
        for (PetscInt i = 0; i < n_local; ++i)
            if (d[i] > 0) {
                sum += d[i];
                ++n_nonzero;
            }
        sum = comm_.sum(sum);
        n_nonzero = comm_.sum(n_nonzero);
        const double fill = n_nonzero > 0 ? sum / static_cast<double>(n_nonzero) : 1.0;
        for (PetscInt i = 0; i < n_local; ++i)
            if (!(d[i] > 0))
                d[i] = fill;
        check(VecRestoreArray(s.shift_scale, &d), "VecRestoreArray");
        s.shift_ready = true;
    }
    Vec shifted = nullptr;
    check(VecDuplicate(s.diagonal, &shifted), "VecDuplicate");
    check(VecWAXPY(shifted, mu, s.shift_scale, s.diagonal), "VecWAXPY");
    check(MatDiagonalSet(s.A, shifted, INSERT_VALUES), "MatDiagonalSet");
    if (s.op)
        check(MatDiagonalSet(s.op, shifted, INSERT_VALUES), "MatDiagonalSet");
    VecDestroy(&shifted);
    return set_up_preconditioner();
}

LinearStatus PetscSolver::solve(const Vector& b, Vector& x)
{
    return solve_with(b, x, 0.0);
}

LinearStatus PetscSolver::solve_to(const Vector& b, Vector& x, double accuracy)
{
    if (policy_.method == Method::direct || state_->user_rtol || !(accuracy < 1.0))
        return solve_with(b, x, 0.0);
    return solve_with(b, x, std::max(accuracy, krylov_rtol_floor));
}

LinearStatus PetscSolver::solve_with(const Vector& b, Vector& x, double rtol)
{
    State& s = *state_;
    IGA_CHECK(s.A != nullptr && b.size() == s.n, "PetscSolver::solve: needs a factorize() of a matrix of b's size");
    {
        PetscScalar* a = nullptr;
        check(VecGetArray(s.b, &a), "VecGetArray");
        std::copy(b.data() + s.first, b.data() + s.last, a);
        check(VecRestoreArray(s.b, &a), "VecRestoreArray");
    }
    // This solve's relative tolerance: the one asked for, else the KSP's own
    // (krylov_rtol, or -ksp_rtol); 0 for a direct method.
    const double krylov_stop = policy_.method == Method::iterative ? (rtol > 0 ? rtol : s.own_rtol) : 0.0;
    auto krylov = [&]() {
        if (policy_.method == Method::iterative) {
            // The other limits stay.
            PetscReal current = 0, abstol = 0, dtol = 0;
            PetscInt max_it = 0;
            check(KSPGetTolerances(s.ksp, &current, &abstol, &dtol, &max_it), "KSPGetTolerances");
            check(KSPSetTolerances(s.ksp, krylov_stop, abstol, dtol, max_it), "KSPSetTolerances");
        }
        // An error inside the solve (a preconditioner that a singular matrix left
        // unusable) is a failed solve of this K, not an error of the program.
        const PetscErrorCode code = KSPSolve(s.ksp, s.b, s.x);
        if (comm_.any(code != 0)) {
            throw_if_options_error(code != 0);  // (a viewer option is read at the end of a solve)
            s.ksp_failed = true;
            s.last_converged = false;
            failure_detail_ = describe_method() + ": the solve stopped with a PETSc error";
            return false;
        }
        KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
        check(KSPGetConvergedReason(s.ksp, &reason), "KSPGetConvergedReason");
        PetscInt iterations = 0;
        check(KSPGetIterationNumber(s.ksp, &iterations), "KSPGetIterationNumber");
        statistics_.iterations += iterations;
        s.last_iterations = iterations;
        s.last_converged = reason > 0;
        if (reason <= 0)
            failure_detail_ = krylov_failure_text(s.ksp, describe_method(), reason, iterations);
        if (s.setup_iterations < 0)
            s.setup_iterations = iterations;
        return reason > 0;
    };
    bool converged = krylov();
    if (!converged && s.reused) {
        // The reused preconditioner no longer serves: a fresh one for this K.
        if (set_up_preconditioner() != LinearStatus::ok)
            return LinearStatus::singular;  // (the set-up abandoned its KSP)
        converged = krylov();
    }
    // A direct method that fails has met a singular K; a Krylov method that stops short
    // may have met a singular K or merely a hard one: it says only what it saw.
    auto failure = [&] {
        s.ksp_failed = true;  // see State::abandoned
        return policy_.method == Method::direct ? LinearStatus::singular : LinearStatus::not_converged;
    };
    if (!converged)
        return failure();

    // The true residual of the whole system, as the direct backend checks it.
    Vec r = nullptr;
    check(VecDuplicate(s.b, &r), "VecDuplicate");
    check(MatMult(s.operator_matrix(), s.x, r), "MatMult");
    check(VecAYPX(r, -1.0, s.b), "VecAYPX");
    PetscReal residual = 0, b_norm = 0;
    check(VecNorm(r, NORM_2, &residual), "VecNorm");
    check(VecNorm(s.b, NORM_2, &b_norm), "VecNorm");
    VecDestroy(&r);

    check(VecScatterBegin(s.to_all, s.x, s.x_all, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
    check(VecScatterEnd(s.to_all, s.x, s.x_all, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
    const PetscScalar* a = nullptr;
    check(VecGetArrayRead(s.x_all, &a), "VecGetArrayRead");
    x = Eigen::Map<const Vector>(a, s.n);
    check(VecRestoreArrayRead(s.x_all, &a), "VecRestoreArrayRead");
    const bool finite = x.allFinite();
    // The Krylov method's own test is on its recursive residual, which may drift from
    // the true one: a tolerance looser than 1e-6 (-ksp_rtol 1e-4) is checked with room.
    const double bound = std::max(backward_error_tolerance, krylov_bound_margin * krylov_stop);
    if (!(std::isfinite(residual) && residual <= bound * b_norm) || comm_.any(!finite)) {
        failure_detail_ = fmt::format("{}: the true residual is {:.3g} of ||b|| (bound {:.0e})", describe_method(),
                                      residual / b_norm, bound);
        return failure();
    }
    failure_detail_.clear();
    return LinearStatus::ok;
}

}  // namespace iga::solver
