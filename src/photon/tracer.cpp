// Photon tracing in deterministic batches: a pipeline in one process, rounds under MPI (see tracer.h).
#include "photon/tracer.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_pipeline.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <thread>

#include "core/byte_buffer.h"
#include "core/interrupt.h"
#include "core/memory.h"
#include "core/stats.h"
#include "core/threads.h"
#include "dist/ranks.h"
#include "photon/octahedral_avx2.h"
#include "photon/projection_map.h"

namespace phos::photon {
namespace {

// Sums durations from many threads (the batches' own time): whole nanoseconds in an atomic.
class TimeSum {
public:
    void add(std::chrono::steady_clock::time_point from) {
        ns_.fetch_add(uint64_t(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                   std::chrono::steady_clock::now() - from)
                                   .count()),
                      std::memory_order_relaxed);
    }
    double seconds() const { return double(ns_.load(std::memory_order_relaxed)) * 1e-9; }

private:
    std::atomic<uint64_t> ns_{0};
};

// What one batch of photon indices stored: per map, the photons (their power the raw flux x N,
// see PhotonHit, rescaled by 1 / N once the maps are complete) and the index of the emitted photon
// within the batch (so a map can be cut exactly after the emission that met its target). Slices
// are reused from batch to batch: clear() keeps their capacity.
struct Slice {
    std::vector<Photon> photons[kMapCount];
    std::vector<uint32_t> emission[kMapCount];
    std::vector<uint8_t> bounces[kMapCount];  // only with TraceOptions::record_bounces
    // Each photon's direction, until encode_directions() writes its code into the photon.
    std::vector<Vec3> wi[kMapCount];
    uint64_t rays = 0;
    void clear() {
        for (int m = 0; m < kMapCount; ++m)
            photons[m].clear(), emission[m].clear(), bounces[m].clear(), wi[m].clear();
        rays = 0;
    }
};

// Octahedral encoding of the stored normal costs four decodes and dot products per photon, a
// sixth of the tracing time on box-like scenes; most photons land on a handful of flat surfaces,
// so the last encoding of each of 64 hash slots is remembered (keyed by the exact normal bits).
class NormalCodes {
public:
    uint16_t get(Vec3 n) {
        uint32_t b[3];
        std::memcpy(b, &n, sizeof b);
        const uint32_t h = ((b[0] * 0x9e3779b1u) ^ (b[1] * 0x85ebca6bu) ^ (b[2] * 0xc2b2ae35u)) >> 26;
        Entry& e = entries_[h];
        if (!e.valid || std::memcmp(e.bits, b, sizeof b) != 0) {
            Photon p;
            p.set_normal(n);
            std::memcpy(e.bits, b, sizeof b);
            e.code = p.normal_axis;
            e.valid = true;
        }
        return e.code;
    }

private:
    struct Entry {
        uint32_t bits[3] = {0, 0, 0};
        uint16_t code = 0;
        bool valid = false;
    };
    Entry entries_[64];
};

// Writes the direction codes of a slice's photons, eight per call of the AVX2 encoder where the
// CPU has AVX2 (asked once, here, outside the code compiled for it), else four per call of the SSE
// one: one photon at a time, each code is a chain of dependent divisions and square roots that
// nothing overlaps (7 % of the tracing time; eight lanes instead of four took the tracing of 300 k
// photons from 790 to 768 M instructions).
void encode_directions(Slice& s) {
    static const bool avx2 = __builtin_cpu_supports("avx2");
    for (int m = 0; m < kMapCount; ++m) {
        std::vector<Photon>& P = s.photons[m];
        const std::vector<Vec3>& wi = s.wi[m];
        uint32_t codes[8];
        size_t i = 0;
        if (avx2) {
            for (; i + 8 <= P.size(); i += 8) {
                encode_octahedral8_avx2(&wi[i].x, codes);
                for (size_t k = 0; k < 8; ++k) P[i + k].wi_code = uint16_t(codes[k]);
            }
        }
        // Straight from the array: copying four directions into a stack array first stalled the
        // encoder's loads on store forwarding (0.8 % of the tracing time).
        for (; i + 4 <= P.size(); i += 4) {
            encode_octahedral4<8>(wi.data() + i, codes);
            for (size_t k = 0; k < 4; ++k) P[i + k].wi_code = uint16_t(codes[k]);
        }
        if (i < P.size()) {
            Vec3 d[4] = {wi[i], Vec3(0.0f), Vec3(0.0f), Vec3(0.0f)};
            const size_t n = P.size() - i;
            for (size_t k = 1; k < n; ++k) d[k] = wi[i + k];
            encode_octahedral4<8>(d, codes);
            for (size_t k = 0; k < n; ++k) P[i + k].wi_code = uint16_t(codes[k]);
        }
    }
}

// Puts each map's photons of a slice back in emission order (stable: a photon's own hits keep
// their order), as the one-photon-at-a-time loop stores them. Counting sort on the emission index.
// The scratch arrays are the thread's own and kept: fresh ones for every batch took page faults
// again and again as the allocator handed their memory back to the system.
void sort_by_emission(Slice& s, uint64_t count, bool bounces) {
    thread_local std::vector<uint32_t> start;
    thread_local std::vector<Photon> photons;
    thread_local std::vector<uint32_t> emission;
    thread_local std::vector<uint8_t> bounce;
    for (int m = 0; m < kMapCount; ++m) {
        const size_t n = s.photons[m].size();
        if (n < 2 || std::is_sorted(s.emission[m].begin(), s.emission[m].end())) continue;
        start.assign(count + 1, 0);
        for (uint32_t e : s.emission[m]) ++start[e + 1];
        for (uint64_t e = 0; e < count; ++e) start[e + 1] += start[e];
        photons.resize(n);
        emission.resize(n);
        if (bounces) bounce.resize(n);
        for (size_t i = 0; i < n; ++i) {
            const uint32_t to = start[s.emission[m][i]]++;
            photons[to] = s.photons[m][i];
            emission[to] = s.emission[m][i];
            if (bounces) bounce[to] = s.bounces[m][i];
        }
        s.photons[m].swap(photons);
        s.emission[m].swap(emission);
        if (bounces) s.bounces[m].swap(bounce);
    }
}

// Faults in the pages of a map's reserved but unused capacity on all cores: the commits would
// otherwise take every page fault of the final array (one per 4 kB) in the one thread that runs
// them (33 ms of the 0.70 s that 4 M photons take on 2 threads; 3 ms faulted in here). Writing raw
// bytes to storage that holds no objects yet is allowed; insert() constructs the photons there. The
// range is advised to transparent huge pages first: a 4 kB fault costs ~12 us on these virtual
// machines (pvm guests), and faulting 4 M photons' 80 MB in 4 kB pages takes 0.2 s of a 1.5 s trace.
// Returns the bytes faulted in.
uint64_t fault_in_capacity(std::vector<Photon>& v) {
    // Chunks are the huge pages themselves (2 MiB-aligned): two threads touching halves of one
    // huge page would wait for each other while the kernel clears it.
    constexpr uintptr_t kPage = 4096, kChunk = uintptr_t(1) << 21;
    const uintptr_t lo = reinterpret_cast<uintptr_t>(v.data() + v.size());
    const uintptr_t hi = lo + (v.capacity() - v.size()) * sizeof(Photon);
    if (hi <= lo) return 0;
    memory::advise_huge_pages(reinterpret_cast<void*>(lo), hi - lo);
    const uintptr_t first = lo / kChunk, last = (hi - 1) / kChunk;
    tbb::parallel_for(first, last + 1, [&](uintptr_t c) {
        const uintptr_t from = std::max(lo, c * kChunk), to = std::min(hi, (c + 1) * kChunk);
        for (uintptr_t a = from; a < to; a = (a / kPage + 1) * kPage)
            *reinterpret_cast<unsigned char*>(a) = 0;
    });
    return hi - lo;
}

// Whether photons travel 16 at a time (trace_photons' packets) in trace_batch.
bool packets_apply(const PhotonScene& ps, const TraceOptions& o) {
    return o.packets && o.max_depth >= 0 && packets_possible(ps);
}

void trace_batch(const PhotonScene& ps, const TraceOptions& o, const bool active[kMapCount], uint64_t pass,
                 const ProjectionMap* projection, bool packets, uint64_t first, uint64_t count, Slice& s) {
    PhotonPathOptions po;
    po.max_bounces = o.max_depth;
    po.projection = projection;
    NormalCodes normals;
    // Volume photons: no normal; the volume map takes those after a non-specular scattering, the
    // volume caustic map those after specular bounces only (single scattering is not stored).
    // `ph` without its direction code: encode_directions() writes it from `wi` after the batch.
    // (Inlined at its three calls: a call per stored photon cost ~10 instructions of its ~65.)
    const auto store = [&](int m, const Photon& ph, Vec3 wi, uint64_t j, int bounces)
        __attribute__((always_inline)) {
        if (!active[m]) return;
        s.photons[m].push_back(ph);
        s.wi[m].push_back(wi);
        s.emission[m].push_back(uint32_t(j));
        if (o.record_bounces) s.bounces[m].push_back(uint8_t(std::min(bounces, 255)));
    };
    // What photon j stores at a surface, and whether its path goes on.
    const auto on_surface_of = [&](uint64_t j) {
        return [&, j](const PhotonHit& h) {
            // Normal on the side the photon arrived from: the estimate compares it with the
            // query's normal turned towards the viewer.
            const Vec3 n = dot(h.hit.ng, h.wi) >= 0 ? h.hit.ng : -h.hit.ng;
            Photon ph;
            ph.position = h.hit.p;
            ph.set_power(h.power);
            ph.set_wavelengths(h.lambda);
            ph.normal_axis = normals.get(n);  // = set_normal(n), split axis bits as constructed
            store(kGlobalMap, ph, h.wi, j, h.bounces);
            if (h.after_specular) store(kCausticMap, ph, h.wi, j, h.bounces);
            if (h.after_diffuse) store(kIndirectMap, ph, h.wi, j, h.bounces);
            // Only caustic maps still filling: a path that went diffuse can never store a
            // caustic photon again, so stop it here (most of the caustic map's batches).
            return active[kGlobalMap] || active[kIndirectMap] || active[kVolumeMap] ||
                   (!h.after_diffuse && h.followed_lobes);
        };
    };
    // Photon j's visitor; in packets (no media) only its surface visits are made. After sorting
    // by emission the slice is the one one photon after another would store.
    const auto visitor_of = [&](uint64_t j) {
        const auto on_volume = [&, j](const PhotonVolumeHit& h) {
            Photon ph;  // no normal
            ph.position = h.p;
            ph.set_power(h.power);
            ph.set_wavelengths(h.lambda);
            if (h.after_diffuse) store(kVolumeMap, ph, h.wi, j, h.bounces);
            if (h.after_specular) store(kVolumeCausticMap, ph, h.wi, j, h.bounces);
            // After a scattering in a medium the path can only feed the non-caustic maps.
            return active[kGlobalMap] || active[kIndirectMap] || active[kVolumeMap];
        };
        return Visitor{on_surface_of(j), on_volume};
    };
    s.rays += trace_photons(ps, o.seed, pass, first, count, po, packets, visitor_of);
    encode_directions(s);
    if (packets) sort_by_emission(s, count, o.record_bounces);
}

}  // namespace

namespace {

// Under MPI each rank traces the batches of the round it owns (dist::owns(b)); this gives every
// rank each of the round's `count` batches' slices (rank 0 gathers them and broadcasts the lot),
// so all ranks hold the same maps. Slices past `count` are left from a larger earlier round.
void exchange_slices(std::vector<Slice>& slices, uint64_t count, const bool active[kMapCount],
                     TracedPhotons& out) {
    if (!dist::distributed()) return;
    const auto t0 = std::chrono::steady_clock::now();
    std::string mine;
    {
        ByteWriter w(mine);
        for (size_t b = 0; b < count; ++b) {
            if (!dist::owns(b)) continue;
            const Slice& s = slices[b];
            w.put(uint64_t(b));
            w.put(s.rays);
            for (int m = 0; m < kMapCount; ++m) {
                if (!active[m]) continue;
                w.put_vector(s.photons[m]);
                w.put_vector(s.emission[m]);
                w.put_vector(s.bounces[m]);
            }
        }
    }
    const std::string all = dist::all_gather(mine);  // rank 0 .. N-1, each its own in order
    out.exchanged_bytes += all.size();
    ByteReader r(all, "photon batches from the other ranks");
    while (!r.at_end()) {
        const uint64_t b = r.get<uint64_t>();
        if (b >= count) r.fail("batch index out of range");
        Slice& s = slices[b];
        s.rays = r.get<uint64_t>();
        for (int m = 0; m < kMapCount; ++m) {
            if (!active[m]) continue;
            s.photons[m] = r.get_vector<Photon>();
            s.emission[m] = r.get_vector<uint32_t>();
            s.bounces[m] = r.get_vector<uint8_t>();
        }
    }
    out.exchange_seconds += seconds_since(t0);
}

}  // namespace

const char* map_name(int kind) {
    switch (kind) {
        case kGlobalMap:
            return "global";
        case kCausticMap:
            return "caustic";
        case kIndirectMap:
            return "indirect";
        case kVolumeMap:
            return "volume";
        case kVolumeCausticMap:
            return "volume caustic";
    }
    return "?";
}

namespace {

// The maps of one emission stream, filled batch by batch in batch order (count, then fill): each
// active map takes a batch's photons, cut after the emission that met its target. A map with a
// target ends within one emission of it (an emission stores at most one photon per scattering
// event): its final array is reserved once, its pages faulted in on all cores, and batches are
// copied straight into it. Reserved pages that are never written cost no memory.
class StreamMaps {
public:
    StreamMaps(const TraceOptions& o, const bool wanted[kMapCount], uint64_t cap, TracedPhotons& out)
        : o_(o), cap_(cap), out_(out) {
        for (int m = 0; m < kMapCount; ++m) {
            active_[m] = wanted[m] && (o.target[m] > 0 || o.emit > 0);
            if (!active_[m] || o.target[m] == 0) continue;
            const size_t most = size_t(o.target[m]) + size_t(o.max_depth) + 2;
            out.photons[m].reserve(most);
            fault_in(out.photons[m]);
            if (o.record_bounces) out.bounces[m].reserve(most);
        }
    }
    const bool* active() const { return active_; }
    bool any() const { return mask() != 0; }
    uint8_t mask() const {
        uint8_t bits = 0;
        for (int m = 0; m < kMapCount; ++m) bits |= uint8_t(active_[m]) << m;
        return bits;
    }
    // Appends the slice of the batch of emissions [first, first + count) (batches in order). The
    // statistics count the batches committed while a map was still filling.
    void commit(const Slice& s, uint64_t first, uint64_t count) {
        if (!any()) return;
        const auto t0 = std::chrono::steady_clock::now();
        for (int m = 0; m < kMapCount; ++m) {
            if (!active_[m]) continue;
            std::vector<Photon>& P = out_.photons[m];
            const size_t n = s.photons[m].size();
            size_t end = n;
            if (o_.target[m] > 0 && P.size() + n >= o_.target[m]) {
                end = size_t(o_.target[m] - P.size()) - 1;  // the photon meeting the target
                const uint32_t e = s.emission[m][end];
                while (end < n && s.emission[m][end] == e) ++end;
                out_.emitted[m] = first + e + 1;
                out_.reached[m] = true;
                active_[m] = false;
            }
            if (P.size() + end > P.capacity()) {
                // Only maps without a target (a fixed emission count) grow: by the rate so far.
                const double per_emission = double(P.size() + end) / double(first + count);
                const size_t expect =
                    size_t(per_emission * double(cap_ - std::min(cap_, first + count)) * 1.05);
                P.reserve(P.size() + end + expect);
                fault_in(P);
                if (o_.record_bounces) out_.bounces[m].reserve(P.size() + end + expect);
            }
            P.insert(P.end(), s.photons[m].begin(), s.photons[m].begin() + ptrdiff_t(end));
            if (o_.record_bounces)
                out_.bounces[m].insert(out_.bounces[m].end(), s.bounces[m].begin(),
                                       s.bounces[m].begin() + ptrdiff_t(end));
        }
        out_.rays += s.rays;
        end_ = first + count;
        out_.commit_seconds += seconds_since(t0);
    }

    // The stream has ended: maps still active ran to the emission cap (their N is everything
    // emitted), and the photons, which carry their raw power (flux x N), are divided by N. The
    // power is rounded to its shared exponent twice (raw, then scaled), each rounding within half
    // a mantissa step.
    void finish(const bool wanted[kMapCount]) {
        out_.total_emitted += end_;
        for (int m = 0; m < kMapCount; ++m)
            if (active_[m]) out_.emitted[m] = end_, out_.reached[m] = o_.target[m] == 0;
        for (int m = 0; m < kMapCount; ++m) {
            std::vector<Photon>& P = out_.photons[m];
            if (P.empty() || !wanted[m]) continue;
            const float inv = 1.0f / float(out_.emitted[m]);
            tbb::parallel_for(tbb::blocked_range<size_t>(0, P.size(), size_t(1) << 14),
                              [&](const tbb::blocked_range<size_t>& r) {
                                  for (size_t i = r.begin(); i < r.end(); ++i)
                                      P[i].set_power(P[i].power() * inv);
                              });
        }
    }

private:
    // fault_in_capacity, counted in the statistics: on this project's virtual machines the first
    // touch of memory the host has taken back costs 1-2 s per GB, of memory a process has just
    // freed ~0.06 s (docs/performance.md).
    void fault_in(std::vector<Photon>& v) {
        const auto t0 = std::chrono::steady_clock::now();
        out_.faulted_bytes += fault_in_capacity(v);
        out_.fault_in_seconds += seconds_since(t0);
    }

    const TraceOptions& o_;
    const uint64_t cap_;
    TracedPhotons& out_;
    bool active_[kMapCount];
    uint64_t end_ = 0;
};

// One process: batches flow through a pipeline with no barrier between them. The calling
// thread's oneTBB arena traces up to `in_flight` batches at once; each is committed as soon as it
// and every batch before it are traced, and no batch is started once every map is full. Batch b
// stores into the maps that were still active after the commit of batch b - in_flight (which the
// pipeline's tokens guarantee has happened): a function of the batch index, so what a batch
// traces does not depend on timing; a map cut earlier takes nothing more anyway.
void trace_pipelined(const PhotonScene& ps, const TraceOptions& o, uint64_t pass,
                     const ProjectionMap* projection, bool packets, uint64_t cap, uint64_t in_flight,
                     StreamMaps& maps, TimeSum& batch_time) {
    const uint64_t B = std::max<uint32_t>(o.batch_size, 1);
    const uint8_t initial = maps.mask();
    std::vector<Slice> slices(in_flight);
    // after[b % in_flight]: (b + 1) << 8 | the maps active after batch b's commit. traced[b %
    // in_flight]: b + 1 once batch b's slice is written. The pipeline commits a batch only after
    // its trace and returns only after every stage's call has ended; these acquire-release
    // records (and `calls`, released at the end of every call) also say so where
    // ThreadSanitizer can see it: oneTBB's pipeline synchronises inside its uninstrumented library.
    std::unique_ptr<std::atomic<uint64_t>[]> after(new std::atomic<uint64_t>[in_flight]);
    std::unique_ptr<std::atomic<uint64_t>[]> traced(new std::atomic<uint64_t>[in_flight]);
    std::atomic<uint64_t> calls{0};
    struct EndOfCall {
        std::atomic<uint64_t>& calls;
        ~EndOfCall() { calls.fetch_add(1, std::memory_order_release); }
    };
    std::atomic<bool> full{false};
    // The pipeline's tokens let batch b start only once batch b - in_flight has left the last
    // (in-order) stage; waiting for its record here makes that ordering explicit (it never waits).
    const auto after_commit = [&](uint64_t b) {
        uint64_t v;
        while (((v = after[b % in_flight].load(std::memory_order_acquire)) >> 8) != b + 1)
            std::this_thread::yield();
        return uint8_t(v);
    };
    for (uint64_t i = 0; i < in_flight; ++i) after[i].store(0), traced[i].store(0);
    uint64_t next = 0;  // the next batch to start
    // An interrupt ends tracing at the next batch: the caller renders nothing from incomplete maps.
    const auto start = [&](tbb::flow_control& fc) -> uint64_t {
        const EndOfCall end{calls};
        if (full.load() || next * B >= cap || interrupt::requested()) {
            fc.stop();
            return 0;
        }
        return next++;
    };
    const auto trace = [&](uint64_t b) {
        const EndOfCall end{calls};
        const uint8_t mask = b < in_flight ? initial : after_commit(b - in_flight);
        bool active[kMapCount];
        for (int m = 0; m < kMapCount; ++m) active[m] = mask >> m & 1;
        Slice& s = slices[b % in_flight];
        s.clear();
        const uint64_t first = b * B;
        const auto t0 = std::chrono::steady_clock::now();
        trace_batch(ps, o, active, pass, projection, packets, first, std::min(B, cap - first), s);
        batch_time.add(t0);
        traced[b % in_flight].store(b + 1, std::memory_order_release);
        return b;
    };
    const auto commit = [&](uint64_t b) {
        const EndOfCall end{calls};
        if (traced[b % in_flight].load(std::memory_order_acquire) != b + 1)
            throw std::logic_error("photon tracer: a batch reached its commit before its trace");
        const uint64_t first = b * B;
        maps.commit(slices[b % in_flight], first, std::min(B, cap - first));
        after[b % in_flight].store((b + 1) << 8 | maps.mask(), std::memory_order_release);
        if (!maps.any()) full.store(true);
    };
    using tbb::filter_mode;
    tbb::parallel_pipeline(in_flight,
                           tbb::make_filter<void, uint64_t>(filter_mode::serial_in_order, start) &
                               tbb::make_filter<uint64_t, uint64_t>(filter_mode::parallel, trace) &
                               tbb::make_filter<uint64_t, void>(filter_mode::serial_in_order, commit));
    calls.load(std::memory_order_acquire);
}

// Under MPI: rounds of batches, each rank tracing the batches it owns; after each round the ranks
// exchange their slices (exchange_slices) and every rank commits them all in batch order. A
// round's batches store into the maps active at its start; its size follows the counts stored so
// far (enough emissions to meet the farthest target with 5 % to spare), up to `most_batches`.
void trace_rounds(const PhotonScene& ps, const TraceOptions& o, uint64_t pass,
                  const ProjectionMap* projection, bool packets, uint64_t cap, uint64_t most_batches,
                  StreamMaps& maps, TracedPhotons& out, TimeSum& batch_time) {
    const uint64_t B = std::max<uint32_t>(o.batch_size, 1);
    std::vector<Slice> slices;
    uint64_t next = 0;  // first photon index of the next round
    uint64_t round_batches = 4;
    // (dist::any: an interrupt on one rank ends the rounds of all.)
    while (maps.any() && next < cap && !dist::any(interrupt::requested())) {
        const uint64_t n_round = std::min(round_batches * B, cap - next);
        const uint64_t nb = (n_round + B - 1) / B;
        if (slices.size() < nb) slices.resize(nb);
        bool active[kMapCount];
        std::copy_n(maps.active(), kMapCount, active);
        tbb::parallel_for(uint64_t(0), nb, [&](uint64_t b) {
            slices[b].clear();
            if (interrupt::requested() || !dist::owns(b)) return;
            const uint64_t first = next + b * B;
            const auto t0 = std::chrono::steady_clock::now();
            trace_batch(ps, o, active, pass, projection, packets, first, std::min(B, next + n_round - first),
                        slices[b]);
            batch_time.add(t0);
        });
        exchange_slices(slices, nb, active, out);
        for (uint64_t b = 0; b < nb; ++b) {
            const uint64_t first = next + b * B;
            maps.commit(slices[b], first, std::min(B, next + n_round - first));
        }
        next += n_round;
        double need = 0;
        for (int m = 0; m < kMapCount; ++m) {
            if (!maps.active()[m]) continue;
            if (o.target[m] == 0) {
                need = double(cap - next);
                continue;
            }
            const double have = double(out.photons[m].size());
            need = std::max(
                need, have > 0 ? double(o.target[m] - out.photons[m].size()) * double(next) / have * 1.05
                               : 2.0 * double(next));
        }
        round_batches = std::clamp<uint64_t>(uint64_t(std::ceil(need / double(B))), 1, most_batches);
    }
}

// One emission stream (photon indices 0, 1, 2... of `pass`) filling the maps in `wanted` into
// `out` (see tracer.h for the batches and the cut at a target).
void run_stream(const PhotonScene& ps, const TraceOptions& o, const bool wanted[kMapCount], uint64_t pass,
                const ProjectionMap* projection, TracedPhotons& out) {
    const uint64_t cap =
        std::min<uint64_t>(o.emit > 0 ? o.emit : ~0ull, o.max_emit > 0 ? o.max_emit : 0xffffffffull);
    StreamMaps maps(o, wanted, cap, out);
    if (maps.any() && ps.lights.size() > 0) {
        // Batches in flight (in the pipeline) or per round (under MPI): the most any rank allows.
        uint32_t threads = uint32_t(worker_threads());
        dist::max(&threads, 1);
        const uint64_t in_flight = batches_in_flight(int(threads));
        const bool packets = packets_apply(ps, o);
        TimeSum batch_time;
        const auto t0 = std::chrono::steady_clock::now();
        if (dist::distributed())
            trace_rounds(ps, o, pass, projection, packets, cap, in_flight, maps, out, batch_time);
        else
            trace_pipelined(ps, o, pass, projection, packets, cap, in_flight, maps, batch_time);
        out.pipeline_seconds += seconds_since(t0);
        out.batch_seconds += batch_time.seconds();
        out.threads = worker_threads();
    }
    maps.finish(wanted);
}

}  // namespace

uint64_t batches_in_flight(int threads) {
    const uint64_t t = uint64_t(std::max(threads, 1));
    if (dist::ranks() > 1) return std::clamp<uint64_t>(16 * t * uint64_t(dist::ranks()), 32, 1024);
    return std::clamp<uint64_t>(4 * t, 8, 1024);
}

TracedPhotons trace_photons(const PhotonScene& ps, const TraceOptions& o) {
    TracedPhotons out;
    bool wanted[kMapCount];
    for (int m = 0; m < kMapCount; ++m) wanted[m] = o.wanted[m];
    if (!(o.caustic_projection && (wanted[kCausticMap] || wanted[kVolumeCausticMap]))) {
        run_stream(ps, o, wanted, 0, nullptr, out);
        return out;
    }
    // Caustic photons (surface and volume) through projection maps in their own stream (pass 1,
    // its own N emitted); the other maps keep the full emission (pass 0).
    const bool caustic_only[kMapCount] = {false, wanted[kCausticMap], false, false,
                                          wanted[kVolumeCausticMap]};
    wanted[kCausticMap] = wanted[kVolumeCausticMap] = false;
    run_stream(ps, o, wanted, 0, nullptr, out);
    auto t0 = std::chrono::steady_clock::now();
    const ProjectionMap pm(ps, o.projection_resolution);
    out.caustic_fraction = pm.fraction();
    out.projection_seconds = seconds_since(t0);
    if (!pm.empty()) {
        t0 = std::chrono::steady_clock::now();
        run_stream(ps, o, caustic_only, 1, &pm, out);
        out.caustic_seconds = seconds_since(t0);
    } else {
        // No light can reach a specular object: nothing to store.
        out.reached[kCausticMap] = out.reached[kVolumeCausticMap] = true;
    }
    return out;
}

}  // namespace phos::photon
