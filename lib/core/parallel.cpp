#include "core/parallel.hpp"

#include <cstdlib>
#include <vector>

#ifdef IGACONTACT_HAVE_MPI
#include <mpi.h>
#endif

namespace iga {

namespace {
void (*finalize_callback)() = nullptr;
bool we_initialized_mpi = false;

#ifdef IGACONTACT_HAVE_MPI
bool mpi_running()
{
    int initialized = 0, finalized = 0;
    MPI_Initialized(&initialized);
    MPI_Finalized(&finalized);
    return initialized && !finalized;
}
#endif
}  // namespace

Communicator Communicator::world()
{
    Communicator c;
#ifdef IGACONTACT_HAVE_MPI
    if (mpi_running()) {
        MPI_Comm_rank(MPI_COMM_WORLD, &c.rank_);
        MPI_Comm_size(MPI_COMM_WORLD, &c.size_);
    }
#endif
    return c;
}

void Communicator::sum(Vector& v) const
{
#ifdef IGACONTACT_HAVE_MPI
    if (size_ > 1 && v.size() > 0)
        MPI_Allreduce(MPI_IN_PLACE, v.data(), static_cast<int>(v.size()), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
#else
    (void)v;
#endif
}

double Communicator::sum(double x) const
{
#ifdef IGACONTACT_HAVE_MPI
    if (size_ > 1)
        MPI_Allreduce(MPI_IN_PLACE, &x, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
#endif
    return x;
}

long long Communicator::sum(long long x) const
{
#ifdef IGACONTACT_HAVE_MPI
    if (size_ > 1)
        MPI_Allreduce(MPI_IN_PLACE, &x, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
#endif
    return x;
}

double Communicator::max(double x) const
{
#ifdef IGACONTACT_HAVE_MPI
    if (size_ > 1)
        MPI_Allreduce(MPI_IN_PLACE, &x, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
#endif
    return x;
}

bool Communicator::any(bool x) const
{
#ifdef IGACONTACT_HAVE_MPI
    if (size_ > 1) {
        int flag = x ? 1 : 0;
        MPI_Allreduce(MPI_IN_PLACE, &flag, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
        return flag != 0;
    }
#endif
    return x;
}

std::string Communicator::first_message(const std::string& text) const
{
#ifdef IGACONTACT_HAVE_MPI
    if (size_ > 1) {
        int from = text.empty() ? size_ : rank_;
        MPI_Allreduce(MPI_IN_PLACE, &from, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
        if (from == size_)
            return {};
        long long n = static_cast<long long>(text.size());
        MPI_Bcast(&n, 1, MPI_LONG_LONG, from, MPI_COMM_WORLD);
        std::string out = rank_ == from ? text : std::string(static_cast<std::size_t>(n), '\0');
        MPI_Bcast(out.data(), static_cast<int>(n), MPI_CHAR, from, MPI_COMM_WORLD);
        return out;
    }
#endif
    return text;
}

namespace parallel {

bool launched_by_mpi()
{
    // Open MPI, PMIx (Slurm, Open MPI 4+), MPICH/Hydra and Slurm's own PMI.
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE", "PMI_RANK"})
        if (std::getenv(name) != nullptr)
            return true;
    return false;
}

void initialize(bool force)
{
#ifdef IGACONTACT_HAVE_MPI
    int initialized = 0;
    MPI_Initialized(&initialized);
    if (initialized || !(force || launched_by_mpi()))
        return;
    MPI_Init(nullptr, nullptr);
    we_initialized_mpi = true;
    // Errors of MPI calls return codes instead of aborting inside MPI with its own
    // message; a rank that cannot go on calls abort_all itself.
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
#else
    (void)force;
#endif
}

void abort_all(int code)
{
#ifdef IGACONTACT_HAVE_MPI
    if (mpi_running() && Communicator::world().parallel())
        MPI_Abort(MPI_COMM_WORLD, code);
#else
    (void)code;
#endif
}

void on_finalize(void (*callback)())
{
    finalize_callback = callback;
}

void finalize()
{
    if (finalize_callback) {
        finalize_callback();
        finalize_callback = nullptr;
    }
#ifdef IGACONTACT_HAVE_MPI
    if (mpi_running() && we_initialized_mpi)
        MPI_Finalize();
#endif
}

}  // namespace parallel

}  // namespace iga
