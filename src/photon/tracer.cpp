// Photon tracing in deterministic batches and rounds (see tracer.h).
#include "photon/tracer.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include "core/byte_buffer.h"
#include "core/interrupt.h"
#include "core/memory.h"
#include "core/threads.h"
#include "dist/ranks.h"
#include "photon/projection_map.h"

namespace phos::photon {
namespace {

// What one batch of photon indices stored: per map, the photons (their power the raw flux x N,
// see PhotonHit, rescaled by 1 / N once the maps are complete) and the index of the emitted photon
// within the batch (so a map can be cut exactly after the emission that met its target). Slices
// are reused from round to round: clear() keeps their capacity.
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

// Writes the direction codes of a slice's photons, four per call of the four-lane encoder: one
// photon at a time, each code is a chain of dependent divisions and square roots that nothing
// overlaps (7 % of the tracing time).
void encode_directions(Slice& s) {
    for (int m = 0; m < kMapCount; ++m) {
        std::vector<Photon>& P = s.photons[m];
        const std::vector<Vec3>& wi = s.wi[m];
        uint32_t codes[4];
        size_t i = 0;
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

// Faults in the pages of a map's reserved but unused capacity on all cores: resize() would
// otherwise take every page fault of the final array (one per 4 kB) in one thread between rounds
// (33 ms of the 0.70 s that 4 M photons take on 2 threads; 3 ms after this). Writing raw bytes
// to storage that holds no objects yet is allowed; resize() constructs the photons there. The
// range is advised to transparent huge pages first: a 4 kB fault costs ~12 us on these virtual
// machines (pvm guests), and faulting 4 M photons' 80 MB in 4 kB pages took 0.2 s of a 1.5 s trace.
void fault_in_capacity(std::vector<Photon>& v) {
    // Chunks are the huge pages themselves (2 MiB-aligned): two threads touching halves of one
    // huge page would wait for each other while the kernel clears it.
    constexpr uintptr_t kPage = 4096, kChunk = uintptr_t(1) << 21;
    const uintptr_t lo = reinterpret_cast<uintptr_t>(v.data() + v.size());
    const uintptr_t hi = lo + (v.capacity() - v.size()) * sizeof(Photon);
    if (hi <= lo) return;
    memory::advise_huge_pages(reinterpret_cast<void*>(lo), hi - lo);
    const uintptr_t first = lo / kChunk, last = (hi - 1) / kChunk;
    tbb::parallel_for(first, last + 1, [&](uintptr_t c) {
        const uintptr_t from = std::max(lo, c * kChunk), to = std::min(hi, (c + 1) * kChunk);
        for (uintptr_t a = from; a < to; a = (a / kPage + 1) * kPage)
            *reinterpret_cast<unsigned char*>(a) = 0;
    });
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
    const auto store = [&](int m, const Photon& ph, Vec3 wi, uint64_t j, int bounces) {
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
            ph.normal_axis = normals.get(n);  // = set_normal(n), split axis bits as constructed
            store(kGlobalMap, ph, h.wi, j, h.bounces);
            if (h.after_specular) store(kCausticMap, ph, h.wi, j, h.bounces);
            if (h.after_diffuse) store(kIndirectMap, ph, h.wi, j, h.bounces);
            // Only caustic maps still filling: a path that went diffuse can never store a
            // caustic photon again, so stop it here (most of the caustic map's rounds).
            return active[kGlobalMap] || active[kIndirectMap] || active[kVolumeMap] ||
                   (!h.after_diffuse && (h.bsdf.flags() & shading::kSpecular));
        };
    };
    // Photon j's visitor; in packets (no media) only its surface visits are made. After sorting
    // by emission the slice is the one one photon after another would store.
    const auto visitor_of = [&](uint64_t j) {
        const auto on_volume = [&, j](const PhotonVolumeHit& h) {
            Photon ph;  // no normal
            ph.position = h.p;
            ph.set_power(h.power);
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

// Under MPI each rank traces the batches it owns (dist::owns(b)); this gives every rank every
// batch's slice (rank 0 gathers them and broadcasts the lot), so all ranks hold the same maps.
void exchange_slices(std::vector<Slice>& slices, const bool active[kMapCount], TracedPhotons& out) {
    if (!dist::distributed()) return;
    const auto t0 = std::chrono::steady_clock::now();
    std::string mine;
    {
        ByteWriter w(mine);
        for (size_t b = 0; b < slices.size(); ++b) {
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
        if (b >= slices.size()) r.fail("batch index out of range");
        Slice& s = slices[b];
        s.rays = r.get<uint64_t>();
        for (int m = 0; m < kMapCount; ++m) {
            if (!active[m]) continue;
            s.photons[m] = r.get_vector<Photon>();
            s.emission[m] = r.get_vector<uint32_t>();
            s.bounces[m] = r.get_vector<uint8_t>();
        }
    }
    out.exchange_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
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

// One emission stream (photon indices 0, 1, 2... of `pass`) filling the maps in `wanted` into
// `out` (see tracer.h for the rounds and the cut at a target).
void run_stream(const PhotonScene& ps, const TraceOptions& o, const bool wanted[kMapCount], uint64_t pass,
                const ProjectionMap* projection, TracedPhotons& out) {
    bool active[kMapCount];
    bool any = false;
    for (int m = 0; m < kMapCount; ++m) {
        active[m] = wanted[m] && (o.target[m] > 0 || o.emit > 0);
        any |= active[m];
        // A map with a target ends within one emission of it (an emission stores at most one
        // photon per scattering event): its final array is reserved once and filled in place.
        // Reserved pages that are never written cost no memory.
        if (active[m] && o.target[m] > 0) {
            const size_t most = size_t(o.target[m]) + size_t(o.max_depth) + 2;
            out.photons[m].reserve(most);
            fault_in_capacity(out.photons[m]);
            if (o.record_bounces) out.bounces[m].reserve(most);
        }
    }
    const bool packets = packets_apply(ps, o);
    const uint64_t cap =
        std::min<uint64_t>(o.emit > 0 ? o.emit : ~0ull, o.max_emit > 0 ? o.max_emit : 0xffffffffull);
    const uint64_t B = std::max<uint32_t>(o.batch_size, 1);
    uint64_t next = 0;  // first photon index of the next round
    uint64_t round_batches = 4;
    // A round's batches hold their photons until its end, and a slice's first use takes its pages'
    // faults (~12 us per 4 kB on these virtual machines): rounds of at most 16 batches per thread
    // (every rank's most threads; 32 at least) keep that memory small, yet give each thread enough
    // batches that the round's last one leaves the others idle only briefly. On 1 or 2 threads the
    // old limit of 256 batches took 19 k page faults for 4 M photons and 1.46 s on 1 thread; 16 or
    // 32 batches took 3.3 k / 4.3 k and 1.2 s. 16 threads keep 256.
    // Round sizes change nothing in the maps (batches are fixed ranges of indices, a map is cut
    // after the exact emission that met its target), so this may depend on the threads.
    uint32_t threads = uint32_t(worker_threads());
    dist::max(&threads, 1);
    const uint64_t most_batches = round_batch_limit(int(threads));
    std::vector<Slice> slices;
    std::vector<size_t> take[kMapCount], offset[kMapCount];  // per batch: photons kept, where they go
    // An interrupt ends tracing at the next round (its batches are skipped): the caller renders
    // nothing from incomplete maps.
    // (dist::any: under MPI an interrupt on one rank ends the rounds of all.)
    while (any && next < cap && ps.lights.size() > 0 && !dist::any(interrupt::requested())) {
        const uint64_t n_round = std::min(round_batches * B, cap - next);
        const uint64_t nb = (n_round + B - 1) / B;
        if (slices.size() < nb) slices.resize(nb);
        tbb::parallel_for(uint64_t(0), nb, [&](uint64_t b) {
            slices[b].clear();
            if (interrupt::requested() || !dist::owns(b)) return;
            const uint64_t first = next + b * B;
            trace_batch(ps, o, active, pass, projection, packets, first, std::min(B, next + n_round - first),
                        slices[b]);
        });
        exchange_slices(slices, active, out);
        // Count, then fill: the batches' photons in batch order, each map cut after the emission
        // that met its target, copied in parallel straight into the final arrays.
        for (int m = 0; m < kMapCount; ++m) {
            take[m].assign(nb, 0);
            offset[m].assign(nb, 0);
            if (!active[m]) continue;
            size_t size = out.photons[m].size();
            for (uint64_t b = 0; b < nb && active[m]; ++b) {
                const Slice& s = slices[b];
                const size_t n = s.photons[m].size();
                size_t end = n;
                if (o.target[m] > 0 && size + n >= o.target[m]) {
                    end = size_t(o.target[m] - size) - 1;  // the photon meeting the target
                    const uint32_t e = s.emission[m][end];
                    while (end < n && s.emission[m][end] == e) ++end;
                    out.emitted[m] = next + b * B + e + 1;
                    out.reached[m] = true;
                    active[m] = false;
                }
                offset[m][b] = size;
                take[m][b] = end;
                size += end;
            }
            if (size > out.photons[m].capacity()) {
                // Only maps without a target (a fixed emission count) grow: by the rate so far.
                const double per_emission = double(size) / double(next + n_round);
                const size_t expect =
                    size_t(per_emission * double(cap - std::min(cap, next + n_round)) * 1.05);
                out.photons[m].reserve(size + expect);
                fault_in_capacity(out.photons[m]);
                if (o.record_bounces) out.bounces[m].reserve(size + expect);
            }
            out.photons[m].resize(size);
            if (o.record_bounces) out.bounces[m].resize(size);
        }
        tbb::parallel_for(uint64_t(0), nb, [&](uint64_t b) {
            const Slice& s = slices[b];
            for (int m = 0; m < kMapCount; ++m) {
                if (take[m][b] == 0) continue;
                std::copy_n(s.photons[m].begin(), take[m][b],
                            out.photons[m].begin() + ptrdiff_t(offset[m][b]));
                if (o.record_bounces)
                    std::copy_n(s.bounces[m].begin(), take[m][b],
                                out.bounces[m].begin() + ptrdiff_t(offset[m][b]));
            }
        });
        for (uint64_t b = 0; b < nb; ++b) out.rays += slices[b].rays;
        next += n_round;
        // Size the next round from the storage rate so far (counts only: deterministic): enough
        // emissions to meet the farthest target with 5 % to spare, between 1 and 256 batches.
        double need = 0;
        any = false;
        for (int m = 0; m < kMapCount; ++m) {
            if (!active[m]) continue;
            any = true;
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
    std::vector<Slice>().swap(slices);  // tracing no longer needs them
    out.total_emitted += next;
    // Maps still active ran to the emission cap: their N is everything emitted.
    for (int m = 0; m < kMapCount; ++m)
        if (active[m]) out.emitted[m] = next, out.reached[m] = o.target[m] == 0;
    // The photons carry their raw power (flux x N): divide by N now that N is known. The power is
    // rounded to RGBE twice (raw, then scaled), each rounding within half a mantissa step. Four
    // photons at a time (scale_rgbe4, the scalar functions' bits): one at a time this pass took
    // 2.6 % of the tracing time.
    for (int m = 0; m < kMapCount; ++m) {
        std::vector<Photon>& P = out.photons[m];
        if (P.empty() || !wanted[m]) continue;
        const float inv = 1.0f / float(out.emitted[m]);
        tbb::parallel_for(tbb::blocked_range<size_t>(0, P.size(), size_t(1) << 14),
                          [&](const tbb::blocked_range<size_t>& r) {
                              size_t i = r.begin();
                              for (; i + 4 <= r.end(); i += 4) {
                                  uint32_t w[4] = {P[i].power_rgbe, P[i + 1].power_rgbe, P[i + 2].power_rgbe,
                                                   P[i + 3].power_rgbe};
                                  scale_rgbe4(w, inv);
                                  for (size_t k = 0; k < 4; ++k) P[i + k].power_rgbe = w[k];
                              }
                              for (; i < r.end(); ++i) P[i].set_power(P[i].power() * inv);
                          });
    }
}

}  // namespace

uint64_t round_batch_limit(int threads) {
    return std::clamp<uint64_t>(16ull * uint64_t(std::max(threads, 1)) * uint64_t(dist::ranks()), 32, 1024);
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
    out.projection_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!pm.empty()) {
        t0 = std::chrono::steady_clock::now();
        run_stream(ps, o, caustic_only, 1, &pm, out);
        out.caustic_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    } else {
        // No light can reach a specular object: nothing to store.
        out.reached[kCausticMap] = out.reached[kVolumeCausticMap] = true;
    }
    return out;
}

}  // namespace phos::photon
