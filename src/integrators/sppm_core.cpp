// Shared machinery of PPM and SPPM (see sppm_core.h).
#include "integrators/sppm_core.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

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
#include "integrators/progressive_budget.h"
#include "photon/photon_path.h"
#include "shading/phase.h"

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
        g.kd_pi.r = P.media[vp.medium].phase().g;
        return g;
    }
    if (!vp.bsdf) return g;
    const Bsdf& b = *vp.bsdf;
    const float s = dot(vp.wo, b.geometric_normal()) >= 0 ? 1.0f : -1.0f;
    g.ng = b.geometric_normal() * s;
    g.ns = b.frame().n * s;
    g.max_bounces = max_depth - 1 - vp.depth;
    g.kind = b.is_lambertian() ? GatherPoint::kLambert : GatherPoint::kSurface;
    g.kd_pi = b.diffuse_albedo() * float(1 / M_PI);
    return g;
}
}  // namespace

uint64_t PhotonAccumulator::photon_pass(const Prepared& P, const std::vector<VisiblePoint>& vps,
                                        const photon::HitPointGrid& grid, uint64_t seed, uint64_t pass,
                                        uint64_t count) {
    const int max_depth = P.options.max_depth;
    if (max_depth < 1 || grid.entry_count() == 0) return 0;
    // Fixed point: 2^32 units per (total light power). Photon powers are of the order of the total
    // power times albedos, so contributions keep ~30 significant bits and sums cannot overflow.
    scale_ = 0x1p32 / std::max(double(P.lights.total_power().average()), 1e-30);
    gather_.resize(vps.size());
    tbb::parallel_for(size_t(0), vps.size(),
                      [&](size_t i) { gather_[i] = make_gather_point(vps[i], max_depth, P); });
    const photon::PhotonScene ps{P.scene, P.accel, P.lights, P.bsdf_options, P.active_media()};
    const photon::PhotonPathOptions popt{max_depth - 1};
    constexpr uint64_t kBlock = 4096;
    // Under MPI each rank traces its share of the photon indices; update() sums the ranks' integer
    // sums, so the result is the single process's exactly.
    const auto [lo, hi] = dist::share(count);
    const uint64_t blocks = (hi - lo + kBlock - 1) / kBlock;
    std::atomic<uint64_t> total_rays{0};
    const double scale = scale_;
    tbb::parallel_for(uint64_t(0), blocks, [&](uint64_t blk) {
        LocalSlot* local = nullptr;
        if (locals_) {
            std::vector<LocalSlot>& v = locals_->per_thread.local();
            if (v.size() != count_) v.assign(count_, LocalSlot{});
            local = v.data();
        }
        uint64_t rays = 0;
        const uint64_t end = std::min(hi, lo + (blk + 1) * kBlock);
        // Adds contribution c of a photon to point i's sums.
        const auto add = [&](uint32_t i, const Rgb& c) {
            if (c.is_black() || !c.is_finite()) return;
            int64_t q[3];
            for (int k = 0; k < 3; ++k) q[k] = int64_t(std::min(double(c[k]) * scale, 0x1p52) + 0.5);
            if (local) {
                LocalSlot& s = local[i];
                for (int k = 0; k < 3; ++k) s.phi[k] += q[k];
                ++s.m;
            } else {
                Slot& s = slots_[i];
                for (int k = 0; k < 3; ++k) s.phi[k].fetch_add(q[k], std::memory_order_relaxed);
                s.m.fetch_add(1, std::memory_order_relaxed);
            }
        };
        // --trace-pixel: what the traced slots gather is recorded too (path_recorder.h).
        const auto record = [&](uint32_t i, uint64_t idx, Vec3 p, Rgb power, Vec3 wi, const Rgb& c) {
            if (size_t(i) - trace_first_ >= trace_count_ || c.is_black() || !c.is_finite()) return;
            trace_->photon(i, {idx, p, power, wi, c});
        };
        for (uint64_t idx = lo + blk * kBlock; idx < end; ++idx) {
            // Photons scattering in a medium (not straight from a light: single scattering is
            // sampled at the visible point) reach the volume points whose ball holds them.
            const auto on_volume = [&](const photon::PhotonVolumeHit& h) {
                if (h.bounces == 0) return;
                grid.query(h.p, [&](uint32_t i) {
                    const GatherPoint& g = gather_[i];
                    if (g.kind != GatherPoint::kVolume || h.bounces > g.max_bounces) return;
                    const Rgb c = h.power * shading::henyey_greenstein(dot(-vps[i].wo, h.wi), g.kd_pi.r);
                    add(i, c);
                    record(i, idx, h.p, h.power, h.wi, c);
                });
            };
            const auto on_surface = [&](const photon::PhotonHit& h) {
                if (h.bounces == 0) return;  // direct light: shadow rays at the visible points
                grid.query(h.hit.p, [&](uint32_t i) {
                    const GatherPoint& g = gather_[i];
                    if (g.kind == GatherPoint::kVolume || h.bounces > g.max_bounces) return;
                    Rgb c;
                    if (g.kind == GatherPoint::kLambert) {
                        // Bsdf::eval of a Lambert lobe: kd/π for wi on wo's side of ng and ns.
                        if (!(dot(h.wi, g.ng) > 0 && dot(h.wi, g.ns) > 0)) return;
                        c = g.kd_pi * h.power;
                    } else {
                        const VisiblePoint& vp = vps[i];
                        c = vp.bsdf->eval(vp.wo, h.wi) * h.power;
                    }
                    add(i, c);
                    record(i, idx, h.hit.p, h.power, h.wi, c);
                });
            };
            rays += photon::trace_photon(ps, seed, pass, idx, popt, photon::Visitor{on_surface, on_volume});
        }
        total_rays.fetch_add(rays, std::memory_order_relaxed);
    });
    return total_rays.load();
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

void EyePassExchange::share(const std::vector<film::Tile>& tiles, int width, size_t per_pixel,
                            std::vector<VisiblePoint>& vps, std::vector<PixelStats>& slots) {
    if (!dist::distributed()) return;
    // Plain data (the Bsdf holds its parameters, no pointers): copied as bytes.
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
                               float alpha) {
    drain([&](size_t i, uint64_t m, const int64_t* sum) {
        if (m == 0 || !vps[i].present()) return;
        const Rgb& beta = vps[i].beta;
        double phi[3];  // β Φ_i: the flux the camera path carries to the pixel
        for (int k = 0; k < 3; ++k) phi[k] = double(beta[k]) * (double(sum[k]) / scale_);
        if (vps[i].volume())
            progressive_update_volume(stats[i], m, phi, double(alpha));
        else
            progressive_update(stats[i], m, phi, double(alpha));
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
