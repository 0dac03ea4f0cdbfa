// iris::mpi over the MPI C API.
#include "iris/mpi/mpi.hpp"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <mpi.h>

namespace iris::mpi {
namespace {

void check(int rc, const char* call) {
    if (rc == MPI_SUCCESS) return;
    char text[MPI_MAX_ERROR_STRING];
    int n = 0;
    MPI_Error_string(rc, text, &n);
    throw std::runtime_error(fmt::format("{} failed: {}", call, std::string(text, static_cast<std::size_t>(n))));
}

/// \brief The user operation: element-wise 128-bit integer addition (commutative).
extern "C" void add_exact(void* in, void* inout, int* len, MPI_Datatype*) {
    const auto* a = static_cast<const exact_int*>(in);
    auto* b = static_cast<exact_int*>(inout);
    for (int i = 0; i < *len; ++i) b[i] += a[i];
}

constexpr std::size_t chunk_pixels = std::size_t{1} << 20;

}  // namespace

bool launched() noexcept {
    for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE", "MPI_LOCALNRANKS"})
        if (std::getenv(v) != nullptr) return true;
    return false;
}

session::session(int& argc, char**& argv) {
    if (!launched()) return;
    int provided = 0;
    check(MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
    m_active = true;
    // errors come back as return codes (check() throws), not as an abort inside MPI
    check(MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN), "MPI_Comm_set_errhandler");
    check(MPI_Comm_rank(MPI_COMM_WORLD, &m_rank), "MPI_Comm_rank");
    check(MPI_Comm_size(MPI_COMM_WORLD, &m_size), "MPI_Comm_size");
}

session::~session() {
    if (m_active) MPI_Finalize();
}

film session::reduce(const film& local) const {
    if (!m_active || m_size == 1) return local;  // one rank: its film is the sum (with any fade layer)
    const std::size_t pixels = local.sums().size();
    std::vector<exact_xyz> sums(m_rank == 0 ? pixels : 0);
    std::vector<std::uint32_t> counts(m_rank == 0 ? pixels : 0), dropped(m_rank == 0 ? pixels : 0);
    MPI_Datatype int128;
    check(MPI_Type_contiguous(static_cast<int>(sizeof(exact_int)), MPI_BYTE, &int128), "MPI_Type_contiguous");
    check(MPI_Type_commit(&int128), "MPI_Type_commit");
    MPI_Op add;
    check(MPI_Op_create(&add_exact, 1, &add), "MPI_Op_create");
    try {
        for (std::size_t begin = 0; begin < pixels; begin += chunk_pixels) {
            const std::size_t n = std::min(chunk_pixels, pixels - begin);
            const int n3 = static_cast<int>(3 * n), n1 = static_cast<int>(n);
            check(MPI_Reduce(local.sums().data() + begin, m_rank == 0 ? sums.data() + begin : nullptr, n3, int128, add, 0,
                             MPI_COMM_WORLD),
                  "MPI_Reduce (sums)");
            check(MPI_Reduce(local.counts().data() + begin, m_rank == 0 ? counts.data() + begin : nullptr, n1,
                             MPI_UINT32_T, MPI_SUM, 0, MPI_COMM_WORLD),
                  "MPI_Reduce (counts)");
            check(MPI_Reduce(local.dropped_counts().data() + begin, m_rank == 0 ? dropped.data() + begin : nullptr, n1,
                             MPI_UINT32_T, MPI_SUM, 0, MPI_COMM_WORLD),
                  "MPI_Reduce (dropped)");
        }
    } catch (...) {
        MPI_Op_free(&add);
        MPI_Type_free(&int128);
        throw;
    }
    MPI_Op_free(&add);
    MPI_Type_free(&int128);
    if (m_rank != 0) return film(0, 0);
    return film::from_parts(local.width(), local.height(), std::move(sums), std::move(counts), std::move(dropped));
}

int session::max(int value) const {
    if (!m_active) return value;
    int r = 0;
    check(MPI_Allreduce(&value, &r, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD), "MPI_Allreduce (max)");
    return r;
}

double session::max(double value) const {
    if (!m_active) return value;
    double r = 0;
    check(MPI_Allreduce(&value, &r, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD), "MPI_Allreduce (max)");
    return r;
}

std::uint64_t session::sum(std::uint64_t value) const {
    if (!m_active) return value;
    std::uint64_t r = 0;
    check(MPI_Allreduce(&value, &r, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD), "MPI_Allreduce (sum)");
    return r;
}

double session::sum(double value) const {
    if (!m_active) return value;
    double r = 0;
    check(MPI_Allreduce(&value, &r, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD), "MPI_Allreduce (sum)");
    return r;
}

double session::broadcast(double value) const {
    if (!m_active) return value;
    check(MPI_Bcast(&value, 1, MPI_DOUBLE, 0, MPI_COMM_WORLD), "MPI_Bcast");
    return value;
}

void session::abort(int status) const {
    if (m_active) MPI_Abort(MPI_COMM_WORLD, status);
}

}  // namespace iris::mpi
