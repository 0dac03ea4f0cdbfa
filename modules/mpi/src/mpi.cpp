// iris::mpi over the MPI C API.
#include "iris/mpi/mpi.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <stdexcept>
#include <span>
#include <string>
#include <utility>
#include <optional>
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

/// \brief The user operations: element-wise exact addition of the film's sums (three
/// 128-bit integers) and of the fade layer's sums of squares (three 192-bit ones).
extern "C" void add_exact(void* in, void* inout, int* len, MPI_Datatype*) {
    const auto* a = static_cast<const exact_xyz*>(in);
    auto* b = static_cast<exact_xyz*>(inout);
    for (int i = 0; i < *len; ++i) {
        b[i].x += a[i].x;
        b[i].y += a[i].y;
        b[i].z += a[i].z;
    }
}
extern "C" void add_exact_one(void* in, void* inout, int* len, MPI_Datatype*) {  // the spectral layer's sums
    const auto* a = static_cast<const exact_int*>(in);
    auto* b = static_cast<exact_int*>(inout);
    for (int i = 0; i < *len; ++i) b[i] += a[i];
}
using square_xyz = std::array<fade::square_sum, 3>;
extern "C" void add_squares(void* in, void* inout, int* len, MPI_Datatype*) {
    const auto* a = static_cast<const square_xyz*>(in);
    auto* b = static_cast<square_xyz*>(inout);
    for (int i = 0; i < *len; ++i)
        for (std::size_t c = 0; c < 3; ++c) b[i][c].add(a[i][c]);
}

/// \brief An MPI datatype of `bytes` contiguous bytes and an operation on it, freed with it.
class exact_op {
public:
    exact_op(std::size_t bytes, MPI_User_function* f) {
        check(MPI_Type_contiguous(static_cast<int>(bytes), MPI_BYTE, &type), "MPI_Type_contiguous");
        check(MPI_Type_commit(&type), "MPI_Type_commit");
        check(MPI_Op_create(f, 1, &op), "MPI_Op_create");
    }
    ~exact_op() {
        MPI_Op_free(&op);
        MPI_Type_free(&type);
    }
    exact_op(const exact_op&) = delete;
    exact_op& operator=(const exact_op&) = delete;
    MPI_Datatype type{};
    MPI_Op op{};
};

/// \brief Sum `local` over the ranks into `root_out` (rank 0's; others pass an empty one),
/// in chunks (MPI counts are ints).
template <class T>
void reduce_to_root(std::span<const T> local, std::vector<T>& root_out, bool root, MPI_Datatype type, MPI_Op op,
                    const char* what) {
    constexpr std::size_t chunk = std::size_t{1} << 20;
    if (root) root_out.resize(local.size());
    for (std::size_t begin = 0; begin < local.size(); begin += chunk) {
        const std::size_t n = std::min(chunk, local.size() - begin);
        check(MPI_Reduce(local.data() + begin, root ? root_out.data() + begin : nullptr, static_cast<int>(n), type, op, 0,
                         MPI_COMM_WORLD),
              what);
    }
}

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
    const bool root = m_rank == 0;
    const exact_op sums_op(sizeof(exact_xyz), &add_exact), squares_op(sizeof(square_xyz), &add_squares);
    std::vector<exact_xyz> sums;
    std::vector<std::uint32_t> counts, dropped;
    reduce_to_root(local.sums(), sums, root, sums_op.type, sums_op.op, "MPI_Reduce (sums)");
    reduce_to_root(local.counts(), counts, root, MPI_UINT32_T, MPI_SUM, "MPI_Reduce (counts)");
    reduce_to_root(local.dropped_counts(), dropped, root, MPI_UINT32_T, MPI_SUM, "MPI_Reduce (dropped)");
    std::optional<film::fade_parts> fade;
    if (const film::fade_parts* l = local.fade_state()) {  // every rank runs the same preset: all fade or none
        fade.emplace();
        fade->split = l->split;
        using span_xyz = std::span<const exact_xyz>;
        using span_u32 = std::span<const std::uint32_t>;
        using span_sq = std::span<const square_xyz>;
        reduce_to_root(span_xyz(l->early_sum), fade->early_sum, root, sums_op.type, sums_op.op, "MPI_Reduce (fade: early sums)");
        reduce_to_root(span_u32(l->early_count), fade->early_count, root, MPI_UINT32_T, MPI_SUM,
                       "MPI_Reduce (fade: early counts)");
        reduce_to_root(span_sq(l->early_sq), fade->early_sq, root, squares_op.type, squares_op.op, "MPI_Reduce (fade: squares)");
        reduce_to_root(span_sq(l->late_sq), fade->late_sq, root, squares_op.type, squares_op.op, "MPI_Reduce (fade: squares)");
    }
    std::optional<film::spectral_parts> spectral;
    if (const film::spectral_parts* l = local.spectral_state()) {  // every rank renders with the same options
        const exact_op band_op(sizeof(exact_int), &add_exact_one);
        spectral.emplace();
        spectral->bands = l->bands;
        reduce_to_root(std::span<const exact_int>(l->sums), spectral->sums, root, band_op.type, band_op.op,
                       "MPI_Reduce (spectral sums)");
        check(MPI_Reduce(&l->dropped, &spectral->dropped, 1, MPI_UINT64_T, MPI_SUM, 0, MPI_COMM_WORLD),
              "MPI_Reduce (spectral dropped)");
    }
    if (!root) return film(0, 0);
    return film::from_parts(local.width(), local.height(), std::move(sums), std::move(counts), std::move(dropped),
                            std::move(fade), std::move(spectral));
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
