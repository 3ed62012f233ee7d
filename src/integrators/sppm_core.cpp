// Shared machinery of PPM and SPPM (see sppm_core.h).
#include "integrators/sppm_core.h"

#include <immintrin.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "core/error.h"
#include "core/log.h"
#include "dist/ranks.h"
#include "integrators/direct_light.h"
#include "integrators/sppm.h"
#include "photon/open_ball.h"
#include "photon/photon_path.h"
#include "render/progressive_budget.h"
#include "shading/phase.h"
#include "spectrum/color.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)
}  // namespace phos::integrators

namespace phos::integrators::sppm {

using shading::Bsdf;

struct PhotonAccumulator::Locals {
    tbb::enumerable_thread_specific<std::vector<LocalSlot>> per_thread;
};

PhotonAccumulator::PhotonAccumulator(size_t slots) : slots_(new Slot[slots]), count_(slots) {
    for (size_t i = 0; i < slots; ++i) {
        for (auto& p : slots_[i].phi) p.store(0, std::memory_order_relaxed);
        slots_[i].m.store(0, std::memory_order_relaxed);
    }
    // Per-thread sums avoid 4 locked adds per gathered photon (a third of the photon loop's time
    // measured on cornell-diffuse); up to 1 GiB of copies, atomics beyond.
    const double bytes = double(slots) * sizeof(LocalSlot) * double(tbb::this_task_arena::max_concurrency());
    if (bytes <= double(1u << 30)) locals_ = std::make_unique<Locals>();
}

PhotonAccumulator::~PhotonAccumulator() = default;

namespace {
GatherPoint make_gather_point(const VisiblePoint& vp, int max_depth, const Prepared& P) {
    GatherPoint g;
    if (vp.volume()) {
        g.kind = GatherPoint::kVolume;
        g.max_bounces = max_depth - 1 - vp.depth;
        g.g = P.media[vp.medium].phase().g;
        return g;
    }
    if (!vp.bsdf) return g;
    const Bsdf& b = *vp.bsdf;
    const float s = dot(vp.wo, b.geometric_normal()) >= 0 ? 1.0f : -1.0f;
    g.ng = b.geometric_normal() * s;
    g.ns = b.frame().n * s;
    g.max_bounces = max_depth - 1 - vp.depth;
    g.kind = b.is_lambertian() ? GatherPoint::kLambert : GatherPoint::kSurface;
    g.kd = b.diffuse_spectrum();
    return g;
}

// contribution() at a volume point or a surface point that is not Lambert-only.
Rgb contribution_evaluated(const GatherPoint& g, const VisiblePoint& vp, Vec3 wi,
                           const spectrum::ColourWeights& power, const Wavelengths& lambda) {
    if (g.kind == GatherPoint::kVolume)
        return power.total() * shading::henyey_greenstein(dot(-vp.wo, wi), g.g);
    return power.of(vp.bsdf->eval(vp.wo, wi, lambda));
}

// Bsdf::eval of a Lambert lobe times the photon's power: kd/π for wi on wo's side of ng and ns,
// kd at the photon's wavelengths `lambda`. (Always inlined: the gather's innermost loop runs it.)
[[gnu::always_inline]] inline Rgb lambert_contribution(
    const GatherPoint& g, Vec3 wi, const spectrum::ColourWeights& power,
    const std::array<float, spectrum::kSpectrumSamples>& lambda) {
    return dot(wi, g.ng) > 0 && dot(wi, g.ns) > 0 ? power.of(g.kd.sample(lambda)) * float(1 / M_PI)
                                                  : Rgb(0.0f);
}

// What a photon arriving along wi with `power` at its wavelengths `lambda` after `bounces` adds to
// point i's sums, as colour (f(wo, wi) × power; phase(wo, wi) × power for a volume point: the BSDF
// at the photon's own wavelengths), or black when it adds nothing. Small, so the gather's loop
// inlines it: most points are Lambert-only.
inline Rgb contribution(const GatherPoint& g, const VisiblePoint& vp, bool volume_photon, Vec3 wi,
                        const spectrum::ColourWeights& power, const Wavelengths& lambda, int bounces) {
    if (bounces > g.max_bounces || (g.kind == GatherPoint::kVolume) != volume_photon) return Rgb(0.0f);
    if (g.kind == GatherPoint::kLambert) return lambert_contribution(g, wi, power, lambda.lambdas());
    return contribution_evaluated(g, vp, wi, power, lambda);
}
// The same for a binned surface arrival (the BSDF only evaluated at its wavelengths' values); the
// colour is read only when the direction and bounces let the photon count.
inline Rgb contribution(const GatherPoint& g, const VisiblePoint& vp, const ArrivalDirection& d,
                        const ArrivalColour& c) {
    if (d.bounces > g.max_bounces || g.kind == GatherPoint::kVolume) return Rgb(0.0f);
    if (g.kind == GatherPoint::kLambert) return lambert_contribution(g, d.wi, c.power, c.lambda);
    return contribution_evaluated(g, vp, d.wi, c.power, Wavelengths::at_values(c.lambda));
}
}  // namespace

PhotonAccumulator::LocalSlot* PhotonAccumulator::local_slots() {
    if (!locals_) return nullptr;
    std::vector<LocalSlot>& v = locals_->per_thread.local();
    if (v.size() != count_) v.assign(count_, LocalSlot{});
    return v.data();
}

void PhotonAccumulator::add(LocalSlot* local, uint32_t i, const int64_t q[3], uint64_t m) {
    if (local) {
        LocalSlot& s = local[i];
        for (int k = 0; k < 3; ++k) s.phi[k] += q[k];
        s.m += m;
    } else {
        Slot& s = slots_[i];
        for (int k = 0; k < 3; ++k) s.phi[k].fetch_add(q[k], std::memory_order_relaxed);
        s.m.fetch_add(m, std::memory_order_relaxed);
    }
}

uint64_t PhotonAccumulator::photon_pass(const Prepared& P, const std::vector<VisiblePoint>& vps,
                                        const std::vector<PixelStats>& stats, photon::HitPointGrid& grid,
                                        uint64_t seed, uint64_t pass, uint64_t count) {
    const int max_depth = P.options.max_depth;
    tbb::task_group building;
    if (P.active_media() || trace_count_ > 0)  // volume photons and the trace search the grid
        build_grid(grid, vps, stats);
    else
        building.run([&] { build_grid(grid, vps, stats); });
    // Fixed point: 2^32 units per (total light power). Photon powers are of the order of the total
    // power times albedos, so contributions keep ~30 significant bits and sums cannot overflow.
    scale_ = 0x1p32 / std::max(double(P.lights.total_power().average()), 1e-30);
    gather_.resize(vps.size());
    tbb::parallel_for(size_t(0), vps.size(),
                      [&](size_t i) { gather_[i] = make_gather_point(vps[i], max_depth, P); });
    // Under MPI each rank traces its share of the photon indices; update() sums the ranks' integer
    // sums, so the result is the single process's exactly. Chunks bound the pending hits' memory.
    const auto [lo, hi] = dist::share(count);
    uint64_t rays = 0;
    try {
        for (uint64_t first = lo; first < hi && max_depth >= 1; first += kChunk) {
            const uint64_t n = std::min(kChunk, hi - first);
            rays += trace_chunk(P, vps, grid, seed, pass, first, n);
            building.wait();
            for (size_t l = 0; l < grid.level_count(); ++l) gather_level(vps, grid, l);
        }
    } catch (...) {
        building.wait();  // the build reads vps and stats and writes grid: let it finish first
        throw;
    }
    building.wait();
    return rays;
}

uint64_t PhotonAccumulator::trace_chunk(const Prepared& P, const std::vector<VisiblePoint>& vps,
                                        const photon::HitPointGrid& grid, uint64_t seed, uint64_t pass,
                                        uint64_t first, uint64_t count) {
    const photon::PhotonScene ps{P.scene, P.accel,          P.lights,
                                 P.bsdfs, P.active_media(), P.options.sharp_glossy};
    const photon::PhotonPathOptions popt{P.options.max_depth - 1};
    const bool packets = photon::packets_possible(ps);
    const uint64_t blocks = (count + kBlock - 1) / kBlock;
    if (pending_.size() < blocks) pending_.resize(blocks);
    std::atomic<uint64_t> total_rays{0};
    const double scale = scale_;
    // --trace-pixel: what the traced slots gather is recorded as the photon arrives (in the
    // photon's own order of hits), by a search of its own (path_recorder.h).
    const auto record = [&](uint64_t idx, Vec3 p, int volume_medium, Vec3 wi,
                            const spectrum::ColourWeights& power, const Wavelengths& lambda, int bounces) {
        const bool volume = volume_medium >= 0;
        grid.query(p, [&](uint32_t i) {
            if (size_t(i) - trace_first_ >= trace_count_ || (volume && vps[i].medium != volume_medium))
                return;
            const Rgb c = contribution(gather_[i], vps[i], volume, wi, power, lambda, bounces);
            if (!c.is_black() && c.is_finite()) trace_->photon(i, {idx, p, power.total(), wi, c});
        });
    };
    tbb::parallel_for(uint64_t(0), blocks, [&](uint64_t blk) {
        std::vector<PendingHit>& hits = pending_[blk].hits;
        std::vector<ArrivalColour>& colours = pending_[blk].colours;
        hits.clear();
        colours.clear();
        LocalSlot* local = nullptr;
        const uint64_t block_first = first + blk * kBlock;
        // Photon block_first + j's visitor (16 photons in flight where only surfaces stop them).
        const auto visitor_of = [&](uint64_t j) {
            const uint64_t idx = block_first + j;
            // Photons scattering in a medium (not straight from a light: single scattering is
            // sampled at the visible point) reach the volume points of that medium whose ball holds
            // them; few, so they search the grid one by one.
            const auto on_volume = [&, idx](const photon::PhotonVolumeHit& h) {
                if (h.bounces == 0) return;
                if (!local) local = local_slots();
                const spectrum::ColourWeights power = spectrum::colour_weights(h.power, h.lambda);
                grid.query(h.p, [&](uint32_t i) {
                    if (vps[i].medium != h.medium) return;
                    const Rgb c = contribution(gather_[i], vps[i], true, h.wi, power, h.lambda, h.bounces);
                    int64_t q[3];
                    if (quantize(c, scale, q)) add(local, i, q, 1);
                });
                if (trace_count_) record(idx, h.p, h.medium, h.wi, power, h.lambda, h.bounces);
            };
            // Surface photons wait for the binned gather.
            const auto on_surface = [&, idx](const photon::PhotonHit& h) {
                if (h.bounces == 0) return;  // direct light: shadow rays at the visible points
                hits.push_back({h.hit.p, 0, {h.wi, h.bounces}});
                colours.push_back({spectrum::colour_weights(h.power, h.lambda), h.lambda.lambdas()});
                if (trace_count_) record(idx, h.hit.p, -1, h.wi, colours.back().power, h.lambda, h.bounces);
            };
            return photon::Visitor{on_surface, on_volume};
        };
        const uint64_t rays =
            photon::trace_photons(ps, seed, pass, block_first, std::min(kBlock, first + count - block_first),
                                  popt, packets, visitor_of);
        total_rays.fetch_add(rays, std::memory_order_relaxed);
    });
    pending_blocks_ = blocks;
    return total_rays.load();
}

void PhotonAccumulator::gather_level(const std::vector<VisiblePoint>& vps, const photon::HitPointGrid& grid,
                                     size_t level) {
    // Bin the chunk's surface hits by their bucket in this level (a counting sort): positions in
    // three arrays (four distance tests per SSE instruction), the rest beside them.
    const uint32_t buckets = grid.bucket_count(level);
    bin_start_.assign(size_t(buckets) + 1, 0);
    tbb::parallel_for(size_t(0), pending_blocks_, [&](size_t blk) {
        for (PendingHit& h : pending_[blk].hits) h.bucket = grid.bucket_of(level, h.p);
    });
    for (size_t blk = 0; blk < pending_blocks_; ++blk)
        for (const PendingHit& h : pending_[blk].hits)
            if (h.bucket != photon::HitPointGrid::kNoBucket) ++bin_start_[h.bucket + 1];
    for (uint32_t b = 0; b < buckets; ++b) bin_start_[b + 1] += bin_start_[b];
    const size_t binned = bin_start_[buckets];
    for (auto* v : {&bin_x_, &bin_y_, &bin_z_}) v->resize(binned);
    bin_direction_.resize(binned);
    bin_colour_.resize(binned);
    {
        // Each hit's place in bucket order (serial: the order is the hits'), then the moves in
        // parallel (a hit's bucket field now holds its place).
        std::vector<uint32_t> fill(bin_start_.begin(), bin_start_.end() - 1);
        for (size_t blk = 0; blk < pending_blocks_; ++blk)
            for (PendingHit& h : pending_[blk].hits)
                if (h.bucket != photon::HitPointGrid::kNoBucket) h.bucket = fill[h.bucket]++;
        tbb::parallel_for(size_t(0), pending_blocks_, [&](size_t blk) {
            const PendingBlock& block = pending_[blk];
            for (size_t j = 0; j < block.hits.size(); ++j) {
                const PendingHit& h = block.hits[j];
                if (h.bucket == photon::HitPointGrid::kNoBucket) continue;
                const uint32_t to = h.bucket;
                bin_x_[to] = h.p.x, bin_y_[to] = h.p.y, bin_z_[to] = h.p.z;
                bin_direction_[to] = h.direction;
                bin_colour_[to] = block.colours[j];
            }
        });
    }
    // Each bucket's entries against its hits: a point's sums are added up in registers and
    // written once per bucket, and the bucket's entries are read once for all its hits.
    const double scale = scale_;
    tbb::parallel_for(
        tbb::blocked_range<uint32_t>(0, buckets, 256), [&](const tbb::blocked_range<uint32_t>& r) {
            LocalSlot* local = local_slots();
            const float *bx = bin_x_.data(), *by = bin_y_.data(), *bz = bin_z_.data();
            for (uint32_t b = r.begin(); b < r.end(); ++b) {
                const uint32_t h0 = bin_start_[b], h1 = bin_start_[b + 1];
                if (h0 == h1) continue;
                for (const auto *en = grid.bucket_begin(level, b), *end = grid.bucket_end(level, b);
                     en != end; ++en) {
                    const GatherPoint& g = gather_[en->index];
                    if (g.kind == GatherPoint::kVolume) continue;
                    int64_t sum[3] = {0, 0, 0};
                    uint64_t m = 0;
                    const auto match = [&](uint32_t h) __attribute__((always_inline)) {
                        const Rgb c = contribution(g, vps[en->index], bin_direction_[h], bin_colour_[h]);
                        int64_t q[3];
                        if (!quantize(c, scale, q)) return;
                        for (int k = 0; k < 3; ++k) sum[k] += q[k];
                        ++m;
                    };
                    // The distance test of HitPointGrid::query, operation for operation, four hits at
                    // a time: |p - e|² = (dx² + dy²) + dz² <= r².
                    const __m128 ex = _mm_set1_ps(en->x), ey = _mm_set1_ps(en->y), ez = _mm_set1_ps(en->z);
                    const __m128 er2 = _mm_set1_ps(en->r2);
                    uint32_t h = h0;
                    for (; h + 4 <= h1; h += 4) {
                        const __m128 dx = _mm_sub_ps(_mm_loadu_ps(bx + h), ex);
                        const __m128 dy = _mm_sub_ps(_mm_loadu_ps(by + h), ey);
                        const __m128 dz = _mm_sub_ps(_mm_loadu_ps(bz + h), ez);
                        const __m128 d2 = _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)),
                                                     _mm_mul_ps(dz, dz));
                        for (unsigned mask = unsigned(_mm_movemask_ps(_mm_cmple_ps(d2, er2))); mask != 0;
                             mask &= mask - 1)
                            match(h + uint32_t(std::countr_zero(mask)));
                    }
                    for (; h < h1; ++h) {
                        const float dx = bx[h] - en->x, dy = by[h] - en->y, dz = bz[h] - en->z;
                        if (dx * dx + dy * dy + dz * dz <= en->r2) match(h);
                    }
                    if (m > 0) add(local, en->index, sum, m);
                }
            }
        });
}

// Calls f(i, m, sum) with each point's photon count and fixed-point flux sums, clearing them.
// Under MPI the sums are those of every rank (exact: integers).
template <class F>
void PhotonAccumulator::drain(F&& f) {
    std::vector<LocalSlot*> locals;
    if (locals_)
        for (auto& v : locals_->per_thread)
            if (v.size() == count_) locals.push_back(v.data());
    // This rank's sums of point i, cleared.
    const auto take = [&](size_t i, uint64_t& m, int64_t sum[3]) {
        Slot& s = slots_[i];
        m = s.m.exchange(0, std::memory_order_relaxed);
        for (int k = 0; k < 3; ++k) sum[k] = s.phi[k].exchange(0, std::memory_order_relaxed);
        for (LocalSlot* l : locals) {
            for (int k = 0; k < 3; ++k) sum[k] += l[i].phi[k];
            m += l[i].m;
            l[i] = LocalSlot{};
        }
    };
    if (!dist::distributed()) {
        tbb::parallel_for(size_t(0), count_, [&](size_t i) {
            uint64_t m;
            int64_t sum[3];
            take(i, m, sum);
            f(i, m, sum);
        });
        return;
    }
    std::vector<int64_t>& all = reduced_;
    all.resize(count_ * 4);  // per point: Φ r, g, b, M
    tbb::parallel_for(size_t(0), count_, [&](size_t i) {
        uint64_t m;
        take(i, m, &all[4 * i]);
        all[4 * i + 3] = int64_t(m);
    });
    dist::sum(all.data(), all.size());
    tbb::parallel_for(size_t(0), count_, [&](size_t i) { f(i, uint64_t(all[4 * i + 3]), &all[4 * i]); });
}

void EyePassExchange::share(const scene::Scene& scene, const std::vector<film::Tile>& tiles, int width,
                            size_t per_pixel, std::vector<VisiblePoint>& vps,
                            std::vector<PixelStats>& slots) {
    if (!dist::distributed()) return;
    // Plain data (the Bsdf holds its parameters, and pointers to its material's spectra that
    // rebind() sets again in this process): copied as bytes.
    static_assert(std::is_trivially_copyable_v<VisiblePoint> && std::is_trivially_copyable_v<PixelStats>);
    constexpr size_t kPoint = sizeof(VisiblePoint) + sizeof(PixelStats);
    // One tile's points and statistics, row by row, appended to / read from `bytes`.
    const auto visit = [&](const film::Tile& tile, auto&& copy) {
        for (int y = tile.y0; y < tile.y1; ++y)
            for (int x = tile.x0; x < tile.x1; ++x) {
                const size_t base = (size_t(y) * size_t(width) + size_t(x)) * per_pixel;
                for (size_t s = base; s < base + per_pixel; ++s) copy(vps[s], slots[s]);
            }
    };
    std::string& mine = mine_;
    mine.clear();
    for (size_t t = 0; t < tiles.size(); ++t)
        if (dist::owns(t))
            visit(tiles[t], [&](const VisiblePoint& v, const PixelStats& st) {
                mine.append(reinterpret_cast<const char*>(&v), sizeof v);
                mine.append(reinterpret_cast<const char*>(&st), sizeof st);
            });
    dist::all_gather(mine, all_);  // rank 0 .. N-1, each its own in order
    const std::string& all = all_;
    size_t at = 0;
    const size_t n = size_t(dist::ranks());
    for (size_t r = 0; r < n; ++r)
        for (size_t t = r; t < tiles.size(); t += n)
            visit(tiles[t], [&](VisiblePoint& v, PixelStats& st) {
                if (at + kPoint > all.size())
                    throw std::runtime_error("sppm: the ranks' eye passes disagree in size");
                std::memcpy(static_cast<void*>(&v), all.data() + at, sizeof v);
                std::memcpy(static_cast<void*>(&st), all.data() + at + sizeof v, sizeof st);
                if (v.bsdf && v.material >= 0) v.bsdf->rebind(scene.materials[size_t(v.material)]);
                at += kPoint;
            });
}

void PhotonAccumulator::pilot(std::vector<PixelStats>& stats, const std::vector<VisiblePoint>& vps,
                              const PilotRadius& a) {
    drain([&](size_t i, uint64_t m, const int64_t*) {
        if (vps[i].volume())
            stats[i].r2 = pilot_r2_volume(a, stats[i].r2, m);
        else if (vps[i].bsdf)
            stats[i].r2 = pilot_r2(a, stats[i].r2, m);
    });
}

void PhotonAccumulator::update(std::vector<PixelStats>& stats, const std::vector<VisiblePoint>& vps,
                               float alpha, const std::vector<float>& open_fraction) {
    drain([&](size_t i, uint64_t m, const int64_t* sum) {
        if (m == 0 || !vps[i].present()) return;
        // β Φ_i: the flux the camera path carries to the pixel (Φ_i a colour, the camera path's
        // throughput at its wavelengths: spectrum::colour_through).
        double phi[3];
        const VisiblePoint& vp = vps[i];
        if (vp.beta.is_flat() && !vp.lambda.secondary_terminated()) {
            for (int k = 0; k < 3; ++k) phi[k] = double(vp.beta[0]) * (double(sum[k]) / scale_);
        } else {
            const Rgb c =
                spectrum::colour_through(vp.beta, vp.lambda,
                                         Rgb(float(double(sum[0]) / scale_), float(double(sum[1]) / scale_),
                                             float(double(sum[2]) / scale_)));
            for (int k = 0; k < 3; ++k) phi[k] = double(c[k]);
        }
        if (vps[i].volume()) {
            if (!open_fraction.empty())
                for (double& v : phi) v /= double(open_fraction[i]);
            progressive_update_volume(stats[i], m, phi, double(alpha));
        } else {
            progressive_update(stats[i], m, phi, double(alpha));
        }
    });
}

void record_eye_path(PathRecorder& trace, uint64_t sample, int64_t iteration, size_t slot, bool volume_slot,
                     const std::function<Rgb(VisiblePoint& vp)>& run) {
    VisiblePoint vp;
    {
        RecordingScope scope(&trace, sample, iteration);
        scope.done(run(vp));
    }
    if (vp.present())
        trace.visible_point(slot + (volume_slot && vp.volume() ? 1 : 0), vp.p, vp.medium, vp.beta);
}

void bound_radii_at_edges(const std::vector<VisiblePoint>& vps, std::vector<PixelStats>& stats,
                          const CameraModel::Footprint& footprint) {
    std::vector<size_t> surface;
    for (size_t i = 0; i < vps.size(); ++i)
        if (vps[i].bsdf && stats[i].r2 > 0) surface.push_back(i);
    std::vector<Vec3> p(surface.size()), n(surface.size());
    std::vector<double> r2(surface.size()), r2_min(surface.size());
    for (size_t k = 0; k < surface.size(); ++k) {
        const VisiblePoint& vp = vps[surface[k]];
        p[k] = vp.p;
        n[k] = vp.bsdf->geometric_normal();
        r2[k] = stats[surface[k]].r2;
        const double r_min = kPilotRadiusMinPixels * double(footprint.at(vp.path_length));
        r2_min[k] = r_min * r_min;
    }
    integrators::bound_radii_at_edges(p, n, r2, r2_min);
    for (size_t k = 0; k < surface.size(); ++k) stats[surface[k]].r2 = r2[k];
}

void build_grid(photon::HitPointGrid& grid, const std::vector<VisiblePoint>& vps,
                const std::vector<PixelStats>& stats) {
    std::vector<Vec3> pos(vps.size());
    std::vector<float> r2(vps.size(), 0.0f);
    for (size_t i = 0; i < vps.size(); ++i)
        if (vps[i].present()) {
            pos[i] = vps[i].p;
            r2[i] = float(stats[i].r2);
        }
    grid.build(pos, r2);
}

void photon_iteration(const Prepared& P, PhotonAccumulator& acc, const std::vector<VisiblePoint>& vps,
                      ProgressiveState& state, photon::HitPointGrid& grid, uint64_t pass, uint64_t photons,
                      float alpha, const PilotRadius* pilot) {
    RayCounts rays;
    rays.photon = acc.photon_pass(P, vps, state.slots, grid, P.options.seed, pass, photons);
    P.stats.add_rays(rays);
    if (pilot) {
        acc.pilot(state.slots, vps, *pilot);
        return;
    }
    // N ← N + αM, R² ← R² (N + αM)/(N + M), τ ← (τ + βΦ) R²_new/R²_old; a volume point's βΦ
    // counts over the open part of its ball (boundary bias of the 3D kernel, photon/open_ball.h).
    state.photons_emitted += photons;
    std::vector<float> open;
    if (P.active_media()) {
        open.assign(vps.size(), 1.0f);
        tbb::parallel_for(size_t(0), vps.size(), [&](size_t i) {
            if (vps[i].volume() && state.slots[i].r2 > 0)
                open[i] = photon::open_ball_fraction(P.accel, vps[i].p, float(std::sqrt(state.slots[i].r2)));
        });
    }
    acc.update(state.slots, vps, alpha, open);
}

void end_iteration(PathRecorder* trace, ProgressiveState& state, ProgressiveBudget& budget,
                   const std::function<void()>& resolve_film) {
    if (trace) trace->end_pass(state.photons_emitted, [&](size_t s) { return state.slots[s]; });
    budget.after_iteration(resolve_film);
}

RenderDone finish_progressive(const Prepared& P, const std::string& name, const ProgressiveState& state,
                              ProgressiveBudget& budget, const std::function<void()>& resolve_film) {
    resolve_film();
    const RenderDone done = budget.finish();
    P.stats.add_value(name, std::to_string(state.iterations) + " iterations, " +
                                std::to_string(state.photons_emitted) + " photons");
    P.stats.add_photons_emitted(state.photons_emitted);
    return done;
}

void resolve(const std::vector<PixelStats>& stats, int slots_per_pixel, double slot_weight,
             double direct_scale, uint64_t photons_emitted, film::Film& film, bool layers,
             const std::vector<uint8_t>& volume_slot) {
    const int w = film.width(), h = film.height();
    const double inv_photons = photons_emitted > 0 ? 1.0 / double(photons_emitted) : 0.0;
    // Layers are created here, before the parallel loop (Film::layer is not thread-safe).
    film::Layer* direct_layer = layers ? &film.layer("direct") : nullptr;
    film::Layer* indirect_layer = layers ? &film.layer("indirect") : nullptr;
    tbb::parallel_for(0, h, [&](int y) {
        for (int x = 0; x < w; ++x) {
            double sum[3] = {0, 0, 0}, direct[3] = {0, 0, 0}, indirect[3] = {0, 0, 0};
            for (int s = 0; s < slots_per_pixel; ++s) {
                const size_t i = (size_t(y) * size_t(w) + size_t(x)) * size_t(slots_per_pixel) + size_t(s);
                const PixelStats& st = stats[i];
                const double k = !volume_slot.empty() && volume_slot[i]
                                     ? volume_radiance_scale(st.r2, inv_photons)
                                     : radiance_scale(st.r2, inv_photons);  // eq. 12
                for (int c = 0; c < 3; ++c) {
                    const double d = st.direct[c] * direct_scale, l = st.tau[c] * k;
                    sum[c] += d + l;
                    direct[c] += d;
                    indirect[c] += l;
                }
            }
            const double inv = slot_weight;
            auto mean = [&](const double* v) {
                return Rgb(float(v[0] * inv), float(v[1] * inv), float(v[2] * inv));
            };
            film.set_pixel(x, y, mean(sum));
            if (direct_layer) {
                direct_layer->set(x, y, mean(direct));
                indirect_layer->set(x, y, mean(indirect));
            }
        }
    });
}

}  // namespace phos::integrators::sppm
