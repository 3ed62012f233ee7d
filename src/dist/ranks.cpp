// MPI behind the dist/ranks.h interface (OpenMPI from Debian's libopenmpi-dev when found by
// CMake, PHOS_HAS_MPI); one rank otherwise.
#include "dist/ranks.h"

#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <thread>

#ifdef PHOS_HAS_MPI
#include <mpi.h>
#endif

namespace phos::dist {
namespace {

int g_rank = 0, g_ranks = 1;
#ifdef PHOS_HAS_MPI
bool g_started = false;  // MPI_Init was called
#endif
bool g_render_started = false, g_render_finished = false;
uint64_t g_bytes = 0;

}  // namespace

std::pair<uint64_t, uint64_t> share(uint64_t count) {
    const uint64_t n = uint64_t(ranks()), r = uint64_t(rank());
    // first = floor(count * r / n) without overflow for any 64-bit count.
    const auto at = [&](uint64_t k) { return count / n * k + count % n * k / n; };
    return {at(r), at(r + 1)};
}

bool started() { return g_render_started; }
void mark_finished() { g_render_finished = true; }
bool finished() { return g_render_finished; }

StartAgreement agree_start(bool ok) {
    g_render_started = true;
    uint32_t flags[2] = {ok ? 0u : 1u, (!ok && g_rank == 0) ? 1u : 0u};
    max(flags, 2);
    return {flags[0] != 0, flags[1] != 0};
}

int default_threads() {
    if (g_ranks == 1) return 0;
    int local = 1;
    for (const char* v : {"OMPI_COMM_WORLD_LOCAL_SIZE", "MPI_LOCALNRANKS", "SLURM_NTASKS_PER_NODE"})
        if (const char* e = std::getenv(v); e && std::atoi(e) > 0) {
            local = std::atoi(e);
            break;
        }
    const int machine = std::max(1, int(std::thread::hardware_concurrency()));
    cpu_set_t set;
    CPU_ZERO(&set);
    const int allowed = sched_getaffinity(0, sizeof set, &set) == 0 ? CPU_COUNT(&set) : machine;
    return std::max(1, std::min(allowed, machine / local));
}

void go_solo() { g_ranks = 1; }

int rank() { return g_rank; }
int ranks() { return g_ranks; }
uint64_t bytes_exchanged() { return g_bytes; }

std::string all_gather(const std::string& mine) {
    std::string all;
    all_gather(mine, all);
    return all;
}

std::vector<int> pids_on_this_machine() {
    if (!distributed()) return {};
    struct Process {
        int pid;
        char host[256];
    };
    Process me{int(::getpid()), {}};
    ::gethostname(me.host, sizeof me.host - 1);
    const std::vector<Process> all = all_gather(std::span<const Process>(&me, 1));
    std::vector<int> pids(all.size(), 0);
    for (size_t r = 0; r < all.size(); ++r)
        if (std::strncmp(all[r].host, me.host, sizeof me.host) == 0) pids[r] = all[r].pid;
    return pids;
}

#ifdef PHOS_HAS_MPI

bool built_with_mpi() { return true; }

namespace {

// Launched by an MPI launcher: OpenMPI's mpirun, SLURM's srun, or any PMI / PMIx launcher.
bool launched_by_mpi() {
    for (const char* v :
         {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE", "SLURM_STEP_NUM_TASKS"})
        if (std::getenv(v)) return true;
    return false;
}

void check(int code, const char* what) {
    if (code != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + what + " failed");
}

// MPI counts are int: large buffers go in chunks.
constexpr size_t kChunk = size_t(1) << 30;

}  // namespace

void init(int* argc, char*** argv) {
    if (g_started || !launched_by_mpi()) return;
    int provided = 0;
    // Only the main thread calls MPI (the render's oneTBB workers never do).
    check(MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
    g_started = true;
    MPI_Comm_rank(MPI_COMM_WORLD, &g_rank);
    MPI_Comm_size(MPI_COMM_WORLD, &g_ranks);
}

void finalize() {
    if (!g_started) return;
    MPI_Finalize();
    g_started = false;
}

void broadcast(void* data, size_t bytes) {
    if (g_ranks == 1 || bytes == 0) return;
    for (size_t at = 0; at < bytes; at += kChunk) {
        const size_t n = std::min(kChunk, bytes - at);
        check(MPI_Bcast(static_cast<char*>(data) + at, int(n), MPI_BYTE, 0, MPI_COMM_WORLD), "MPI_Bcast");
    }
    g_bytes += bytes;
}

namespace {
// Rank 0's string, resized on the others.
void broadcast_string(std::string& bytes) {
    if (g_ranks == 1) return;
    uint64_t n = bytes.size();
    broadcast(&n, sizeof n);
    bytes.resize(n);
    broadcast(bytes.data(), n);
}

template <class T>
void all_reduce(T* values, size_t n, MPI_Datatype type, MPI_Op op) {
    if (g_ranks == 1 || n == 0) return;
    const size_t chunk = kChunk / sizeof(T);
    for (size_t at = 0; at < n; at += chunk) {
        const size_t k = std::min(chunk, n - at);
        check(MPI_Allreduce(MPI_IN_PLACE, values + at, int(k), type, op, MPI_COMM_WORLD), "MPI_Allreduce");
    }
    g_bytes += 2 * n * sizeof(T);
}
}  // namespace

void sum(int64_t* values, size_t n) { all_reduce(values, n, MPI_INT64_T, MPI_SUM); }
void max(uint32_t* values, size_t n) { all_reduce(values, n, MPI_UINT32_T, MPI_MAX); }

bool any(bool value) {
    uint32_t v = value ? 1 : 0;
    max(&v, 1);
    return v != 0;
}

std::vector<std::string> gather(const std::string& mine) {
    if (g_ranks == 1) return {mine};
    // Sizes first, then each rank's bytes to rank 0 in turn (point to point: any size).
    std::vector<uint64_t> sizes(size_t(g_ranks), 0);
    uint64_t n = mine.size();
    check(MPI_Gather(&n, 1, MPI_UINT64_T, sizes.data(), 1, MPI_UINT64_T, 0, MPI_COMM_WORLD), "MPI_Gather");
    std::vector<std::string> out;
    if (g_rank == 0) {
        out.resize(size_t(g_ranks));
        out[0] = mine;
        for (int r = 1; r < g_ranks; ++r) {
            out[size_t(r)].resize(sizes[size_t(r)]);
            for (size_t at = 0; at < sizes[size_t(r)]; at += kChunk) {
                const size_t k = std::min<size_t>(kChunk, sizes[size_t(r)] - at);
                check(MPI_Recv(out[size_t(r)].data() + at, int(k), MPI_BYTE, r, 7, MPI_COMM_WORLD,
                               MPI_STATUS_IGNORE),
                      "MPI_Recv");
            }
            g_bytes += sizes[size_t(r)];
        }
    } else {
        for (size_t at = 0; at < mine.size(); at += kChunk) {
            const size_t k = std::min(kChunk, mine.size() - at);
            check(MPI_Send(mine.data() + at, int(k), MPI_BYTE, 0, 7, MPI_COMM_WORLD), "MPI_Send");
        }
        g_bytes += mine.size();
    }
    return out;
}

void all_gather(std::string_view mine, std::string& all) {
    if (g_ranks == 1) {
        all.assign(mine);
        return;
    }
    std::vector<uint64_t> sizes(size_t(g_ranks), 0);
    uint64_t n = mine.size();
    check(MPI_Allgather(&n, 1, MPI_UINT64_T, sizes.data(), 1, MPI_UINT64_T, MPI_COMM_WORLD), "MPI_Allgather");
    uint64_t total = 0;
    for (uint64_t k : sizes) total += k;
    if (total >= uint64_t(std::numeric_limits<int>::max())) {  // int counts: large ones go through rank 0
        all.clear();
        for (const std::string& part : gather(std::string(mine))) all += part;
        broadcast_string(all);
        return;
    }
    std::vector<int> counts(static_cast<size_t>(g_ranks)), offsets(static_cast<size_t>(g_ranks));
    for (size_t r = 0, at = 0; r < sizes.size(); at += sizes[r], ++r)
        counts[r] = int(sizes[r]), offsets[r] = int(at);
    all.resize(total);
    check(MPI_Allgatherv(mine.data(), int(n), MPI_BYTE, all.data(), counts.data(), offsets.data(), MPI_BYTE,
                         MPI_COMM_WORLD),
          "MPI_Allgatherv");
    g_bytes += total;
}

void abort_all(int exit_code) {
    if (g_started && g_ranks > 1) MPI_Abort(MPI_COMM_WORLD, exit_code);
    std::exit(exit_code);
}

#else  // built without MPI: one rank

bool built_with_mpi() { return false; }
void init(int*, char***) {}
void finalize() {}
void broadcast(void*, size_t) {}
void sum(int64_t*, size_t) {}
void max(uint32_t*, size_t) {}
bool any(bool value) { return value; }
std::vector<std::string> gather(const std::string& mine) { return {mine}; }
void all_gather(std::string_view mine, std::string& all) { all.assign(mine); }
void abort_all(int exit_code) { std::exit(exit_code); }

#endif

}  // namespace phos::dist
