#pragma once
/// \file
/// \brief iris::mpi — what `iris-render` needs from MPI to share a render's passes between
/// processes: who this process is, the films' exact reduction and the loop's collective
/// decisions. Every function but `launched` is collective unless it says otherwise, and
/// throws std::runtime_error naming the MPI call that failed.
///
/// A process not started by `mpirun`/`mpiexec` never initialises MPI (no singleton
/// start-up, nothing for a sanitizer to see): it is rank 0 of 1.

#include <cstdint>

#include "iris/render/film.hpp"

namespace iris::mpi {

/// \brief Was this process started by an MPI launcher (Open MPI's or PMIx's environment)?
/// Not collective.
bool launched() noexcept;

/// \brief MPI for the lifetime of the object: initialised by the constructor if `launched()`
/// (MPI_THREAD_FUNNELED: only the thread that made it calls MPI), finalised by the
/// destructor. Without a launcher: rank 0 of 1, and every operation is local.
class session {
public:
    session(int& argc, char**& argv);
    ~session();
    session(const session&) = delete;
    session& operator=(const session&) = delete;

    int rank() const noexcept { return m_rank; }
    int size() const noexcept { return m_size; }
    bool active() const noexcept { return m_active; }

    /// \brief The exact sum of every rank's film (film::merge), on rank 0; other ranks get
    /// an empty (0×0) film. The sums travel as 128-bit integers with a user-defined MPI
    /// operation (integer addition: associative and commutative, so any reduction tree
    /// gives the same bits), the counts as MPI_UINT32_T with MPI_SUM; a fade layer's early
    /// sums and counts the same way and its sums of squares (192-bit) with another such
    /// operation. Chunks of 2^20 pixels bound the extra memory. All films must have the
    /// same size, and all or none a fade layer with the same split.
    film reduce(const film& local) const;

    /// \brief The largest of every rank's `value`, on every rank (a flag raised anywhere).
    int max(int value) const;
    double max(double value) const;
    /// \brief Sums over the ranks, on every rank.
    std::uint64_t sum(std::uint64_t value) const;
    double sum(double value) const;
    /// \brief Rank 0's `value`, on every rank.
    double broadcast(double value) const;

    /// \brief End every rank's process with `status` (MPI_Abort); returns only without MPI.
    void abort(int status) const;

private:
    bool m_active = false;
    int m_rank = 0, m_size = 1;
};

}  // namespace iris::mpi
