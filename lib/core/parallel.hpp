#pragma once
// Communicator: the processes of a run as the rest of the code sees them. A serial
// run is one process; `mpirun -np N igacontact deck.yaml` runs N MPI ranks of
// MPI_COMM_WORLD. The parallel model (docs/parallel.md):
//   - every rank reads the deck and builds the same scene (geometry, dof map);
//   - the elements and the contact couplings are split over the ranks, and each
//     rank assembles only its own (its summand of r and K);
//   - the residual is summed over the ranks (sum()), so every vector Newton sees
//     is whole and identical on every rank, and every decision (line search,
//     convergence, cutback, Uzawa) is taken by all ranks alike;
//   - the tangent stays distributed: the linear solver sums the ranks' summands
//     into one distributed matrix (solver/petsc_solver.hpp);
//   - rank 0 writes the results file and prints.
// Without MPI (a build without PETSc, or a run not started by mpirun) every
// operation is the identity on one process and costs nothing.

#include "core/types.hpp"

#include <string>
#include <utility>

namespace iga {

class Communicator {
public:
    /// One process, no MPI.
    Communicator() = default;
    /// MPI_COMM_WORLD if MPI is initialized (parallel::initialize), else one process.
    static Communicator world();

    int rank() const { return rank_; }
    int size() const { return size_; }
    bool root() const { return rank_ == 0; }
    bool parallel() const { return size_ > 1; }

    /// In place: v = the sum of v over all ranks (the same size on every rank).
    void sum(Vector& v) const;
    double sum(double x) const;
    long long sum(long long x) const;
    double max(double x) const;
    /// True on every rank when it is true on any rank.
    bool any(bool x) const;
    /// This rank's share [first, last) of n items split into contiguous blocks
    /// (the rows of a distributed matrix, the elements of the assembly).
    std::pair<Index, Index> block_range(Index n) const
    {
        return {n * rank_ / size_, n * (rank_ + 1) / size_};
    }

    /// On every rank: the text of the lowest rank whose text is not empty ("" if none).
    std::string first_message(const std::string& text) const;

private:
    int rank_ = 0;
    int size_ = 1;
};

namespace parallel {

/// Whether this process was started by an MPI launcher (mpirun, srun): the
/// launchers' environment variables say so before MPI_Init.
bool launched_by_mpi();

/// Initializes MPI when launched by an MPI launcher (or when `force`); no effect
/// in a build without MPI. Safe to call more than once.
void initialize(bool force = false);

/// Ends every rank at once with this exit code (MPI_Abort), where a rank cannot go
/// on alone: another rank would wait for it forever. Returns only without MPI.
void abort_all(int code);

/// Finalizes PETSc and MPI if they were initialized (at the end of main).
void finalize();

/// Registered by a backend that initialized a library on top of MPI (PETSc): called
/// by finalize() before MPI_Finalize.
void on_finalize(void (*callback)());

}  // namespace parallel

}  // namespace iga
