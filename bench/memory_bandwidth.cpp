// The machine's memory bandwidth at several thread counts: a streaming read pass and an in-place
// read-modify-write pass (what the k-d build's top levels do to the photon map) over one array
// much larger than the caches. If the read-modify-write rate stops growing with the threads, a
// build whose top levels stream the whole map cannot scale past that ratio on this machine: the
// figure next to bench/photon_throughput.sh's build scaling and its top-s column.
//
//   build/memory_bandwidth [GIB] [THREADS...]      (defaults: 1 GiB; 1 2 4 8 16)
// Each figure is the best of three passes, in GB/s (bytes read, plus bytes written for the
// read-modify-write pass); the scaling is against the first thread count.
//   build/memory_bandwidth --contend GIB THREADS
// runs the read-modify-write pass on THREADS threads, over and over, until it is killed: the
// memory traffic of other cores, for `bench/photon_throughput.sh --contend`.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string_view>
#include <vector>

#include "core/memory.h"

namespace {

using Clock = std::chrono::steady_clock;

// Best time of three runs of `pass` on `threads` threads, each thread on one contiguous slice.
template <class Pass>
double best_seconds(int threads, Pass pass) {
    double best = 1e30;
    for (int run = 0; run < 3; ++run) {
        const auto t0 = Clock::now();
        tbb::task_arena(threads).execute([&] { pass(); });
        best = std::min(best, std::chrono::duration<double>(Clock::now() - t0).count());
    }
    return best;
}

// One in-place read-modify-write pass over x[0, n), each of `threads` threads on one slice.
void read_modify_write(uint64_t* x, size_t n, int threads) {
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, size_t(threads), 1),
        [&](const tbb::blocked_range<size_t>& r) {
            for (size_t s = r.begin(); s < r.end(); ++s)
                for (size_t i = n * s / size_t(threads); i < n * (s + 1) / size_t(threads); ++i) x[i] += 1;
        },
        tbb::static_partitioner());
}

}  // namespace

int main(int argc, char** argv) {
    const bool contend = argc > 1 && std::string_view(argv[1]) == "--contend";
    if (contend && argc != 4) {
        std::fprintf(stderr, "usage: memory_bandwidth --contend GIB THREADS\n");
        return 2;
    }
    const int first_arg = contend ? 2 : 1;
    const double gib = argc > first_arg ? std::atof(argv[first_arg]) : 1.0;
    std::vector<int> threads;
    for (int i = first_arg + 1; i < argc; ++i) threads.push_back(std::atoi(argv[i]));
    if (threads.empty()) threads = {1, 2, 4, 8, 16};
    if (!(gib > 0) || gib > 64) {
        std::fprintf(stderr, "memory_bandwidth: the array must be 0-64 GiB\n");
        return 2;
    }
    if (contend && threads[0] < 1) {
        std::fprintf(stderr, "memory_bandwidth: --contend needs at least 1 thread\n");
        return 2;
    }
    const size_t n = size_t(gib * double(1u << 30)) / sizeof(uint64_t);
    const auto data = std::make_unique_for_overwrite<uint64_t[]>(n);
    uint64_t* x = data.get();
    phos::memory::advise_huge_pages(x, n * sizeof(uint64_t));
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i < r.end(); ++i) x[i] = i;
    });
    if (contend) {
        for (;;) tbb::task_arena(threads[0]).execute([&] { read_modify_write(x, n, threads[0]); });
    }
    const double bytes = double(n * sizeof(uint64_t));
    std::printf(
        "| threads | read GB/s | read-modify-write GB/s | read scaling | read-modify-write scaling |\n");
    std::printf("| --- | --- | --- | --- | --- |\n");
    double read_1 = 0, rmw_1 = 0;
    uint64_t sink = 0;
    for (int t : threads) {
        if (t < 1) continue;
        std::vector<uint64_t> sums(size_t(t) * 8, 0);  // one cache line per slice
        const double read_s = best_seconds(t, [&] {
            tbb::parallel_for(
                tbb::blocked_range<size_t>(0, size_t(t), 1),
                [&](const tbb::blocked_range<size_t>& r) {
                    for (size_t s = r.begin(); s < r.end(); ++s) {
                        uint64_t sum = 0;
                        for (size_t i = n * s / size_t(t); i < n * (s + 1) / size_t(t); ++i) sum += x[i];
                        sums[s * 8] += sum;
                    }
                },
                tbb::static_partitioner());
        });
        const double rmw_s = best_seconds(t, [&] { read_modify_write(x, n, t); });
        for (size_t s = 0; s < sums.size(); s += 8) sink += sums[s];
        const double read = bytes / read_s * 1e-9, rmw = 2 * bytes / rmw_s * 1e-9;
        if (read_1 == 0) read_1 = read, rmw_1 = rmw;
        std::printf("| %d | %.1f | %.1f | %.2fx | %.2fx |\n", t, read, rmw, read / read_1, rmw / rmw_1);
    }
    std::printf("(%.2f GiB array; checksum %llu)\n", gib, static_cast<unsigned long long>(sink % 1000));
    return 0;
}
