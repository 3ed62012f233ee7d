// Distribution over MPI ranks (docs/distributed.md). Under `mpirun -np N phos ...` (or srun) each
// rank runs the whole command on the same scene and options; the work of a render is split by
// index — pixel tiles, photon-pass index ranges — so that every value is computed exactly as a
// single process computes it, and rank 0 gathers what it needs, then alone writes images,
// checkpoints, progress and statistics. Without MPI (not built in, or not launched by an MPI
// launcher) there is one rank and every call below is a no-op, so callers need no #ifdefs.
//
// Every function that exchanges data is collective: all ranks call it, in the same order.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace phos::dist {

// Makes rank 0 work alone from here on (ranks() == 1, every collective a no-op), for commands
// other than render, which rank 0 runs by itself while the other ranks end.
void go_solo();

// Whether this phos was built with MPI.
bool built_with_mpi();

// Starts MPI when the process was launched by an MPI launcher (OpenMPI's mpirun, SLURM's srun,
// a PMI/PMIx environment); otherwise does nothing (one rank). Call once, first thing in main.
void init(int* argc, char*** argv);
// Ends MPI (if started). Call before returning from main.
void finalize();

int rank();   // this process's rank, 0 without MPI
int ranks();  // the number of ranks, 1 without MPI
inline bool root() { return rank() == 0; }
inline bool distributed() { return ranks() > 1; }

// The threads a rank should use when --threads is not given: 0 (oneTBB's default) with one rank;
// under MPI, the CPUs this process may run on, but no more than the machine's CPUs divided by the
// ranks on this machine (OMPI_COMM_WORLD_LOCAL_SIZE, MPI_LOCALNRANKS or SLURM_NTASKS_PER_NODE), so
// ranks started with --bind-to none do not oversubscribe their machine.
int default_threads();

// Work splitting by index: item i belongs to rank i mod N (tiles: interleaved, so the ranks share
// the image's easy and hard parts); a count split into N contiguous ranges [first, last).
inline bool owns(size_t index) { return index % size_t(ranks()) == size_t(rank()); }
std::pair<uint64_t, uint64_t> share(uint64_t count);

// Collectives (no-ops with one rank).
void broadcast(void* data, size_t bytes);  // from rank 0 to all
void sum(int64_t* values, size_t n);       // element-wise sum over ranks, in place on every rank
void max(uint32_t* values, size_t n);      // element-wise maximum over ranks, in place on every rank
bool any(bool value);                      // true on every rank if it is true on some rank
// Rank 0 receives every rank's bytes (index = rank; its own included); the others get {}.
std::vector<std::string> gather(const std::string& mine);
// Every rank receives every rank's bytes, concatenated in rank order.
std::string all_gather(const std::string& mine);
// The same into `all`, whose capacity is reused: a loop exchanging megabytes per iteration then
// neither allocates nor faults fresh pages each time (with one rank, `all` = `mine`).
void all_gather(std::string_view mine, std::string& all);
// The same for arrays of plain values: every rank's `mine`, concatenated in rank order.
template <class T>
std::vector<T> all_gather(std::span<const T> mine) {
    static_assert(std::is_trivially_copyable_v<T>);
    const std::string all =
        all_gather(std::string(reinterpret_cast<const char*>(mine.data()), mine.size() * sizeof(T)));
    std::vector<T> out(all.size() / sizeof(T));
    if (!out.empty()) std::memcpy(static_cast<void*>(out.data()), all.data(), out.size() * sizeof(T));
    return out;
}

// The start of a distributed render, where the ranks agree that each set up without error (a
// rank that failed calls it with ok = false instead of waiting in a later collective): returns
// whether any rank failed and whether rank 0 did (so that a failure is reported once: by rank 0,
// or by the rank that alone failed). Collective; marks the render started.
struct StartAgreement {
    bool any_failed = false, root_failed = false;
};
StartAgreement agree_start(bool ok);
// Whether agree_start was called; whether the render's collectives are over (mark_finished).
bool started();
void mark_finished();
bool finished();

// Collective: every rank's process id where it runs on the same machine as this rank (by host
// name), 0 where it runs elsewhere; {} with one rank.
std::vector<int> pids_on_this_machine();

// Bytes this rank has sent and received through the calls above (for -v and bench/mpi_scaling.sh).
uint64_t bytes_exchanged();

// Ends every rank of the job at once with `exit_code` (a rank that cannot go on while the others
// wait in a collective). Without MPI: std::exit.
[[noreturn]] void abort_all(int exit_code);

}  // namespace phos::dist
