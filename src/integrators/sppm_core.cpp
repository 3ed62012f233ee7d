// Shared machinery of PPM and SPPM (see sppm_core.h).
#include "integrators/sppm_core.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <cmath>

#include "core/error.h"
#include "integrators/direct_light.h"
#include "photon/photon_path.h"

namespace phos::integrators::sppm {

using shading::Bsdf;

film::ProgressiveState start_state(const Prepared& P, const ProgressiveOptions& opt, const char* integrator,
                                   uint32_t slots_per_pixel) {
    const RenderOptions& ro = P.options;
    film::ProgressiveState state = opt.identity;
    state.integrator = integrator;
    state.width = uint32_t(ro.width);
    state.height = uint32_t(ro.height);
    state.slots_per_pixel = slots_per_pixel;
    state.seed = ro.seed;
    if (opt.resume) {
        film::check_resumable(*opt.resume, state, opt.resume_path);
        state = *opt.resume;
    } else {
        state.slots.assign(size_t(ro.width) * size_t(ro.height) * slots_per_pixel, {});
    }
    state.target_iterations = uint64_t(std::max(1, ro.spp));
    if (!(opt.alpha > 0 && opt.alpha <= 1)) throw InputError("--alpha must be in (0, 1]");
    return state;
}

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
GatherPoint make_gather_point(const VisiblePoint& vp, int max_depth) {
    GatherPoint g;
    if (!vp.bsdf) return g;
    const Bsdf& b = *vp.bsdf;
    const float s = dot(vp.wo, b.geometric_normal()) >= 0 ? 1.0f : -1.0f;
    g.ng = b.geometric_normal() * s;
    g.ns = b.frame().n * s;
    g.max_bounces = max_depth - 1 - vp.depth;
    g.lambert = b.is_lambertian() ? 1 : 0;
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
                      [&](size_t i) { gather_[i] = make_gather_point(vps[i], max_depth); });
    const photon::PhotonScene ps{P.scene, P.accel, P.lights, P.bsdf_options};
    const photon::PhotonPathOptions popt{max_depth - 1};
    constexpr uint64_t kBlock = 4096;
    const uint64_t blocks = (count + kBlock - 1) / kBlock;
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
        const uint64_t end = std::min(count, (blk + 1) * kBlock);
        for (uint64_t idx = blk * kBlock; idx < end; ++idx) {
            rays += photon::trace_photon(ps, seed, pass, idx, popt, [&](const photon::PhotonHit& h) {
                if (h.bounces == 0) return;  // direct light: shadow rays at the visible points
                grid.query(h.hit.p, [&](uint32_t i) {
                    const GatherPoint& g = gather_[i];
                    if (h.bounces > g.max_bounces) return;
                    Rgb c;
                    if (g.lambert) {
                        // Bsdf::eval of a Lambert lobe: kd/π for wi on wo's side of ng and ns.
                        if (!(dot(h.wi, g.ng) > 0 && dot(h.wi, g.ns) > 0)) return;
                        c = g.kd_pi * h.power;
                    } else {
                        const VisiblePoint& vp = vps[i];
                        c = vp.bsdf->eval(vp.wo, h.wi) * h.power;
                    }
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
                });
            });
        }
        total_rays.fetch_add(rays, std::memory_order_relaxed);
    });
    return total_rays.load();
}

// Calls f(i, m, sum) with each point's photon count and fixed-point flux sums, clearing them.
template <class F>
void PhotonAccumulator::drain(F&& f) {
    std::vector<LocalSlot*> locals;
    if (locals_)
        for (auto& v : locals_->per_thread)
            if (v.size() == count_) locals.push_back(v.data());
    tbb::parallel_for(size_t(0), count_, [&](size_t i) {
        Slot& s = slots_[i];
        uint64_t m = s.m.exchange(0, std::memory_order_relaxed);
        int64_t sum[3];
        for (int k = 0; k < 3; ++k) sum[k] = s.phi[k].exchange(0, std::memory_order_relaxed);
        for (LocalSlot* l : locals) {
            for (int k = 0; k < 3; ++k) sum[k] += l[i].phi[k];
            m += l[i].m;
            l[i] = LocalSlot{};
        }
        f(i, m, sum);
    });
}

void PhotonAccumulator::pilot(std::vector<film::SlotStats>& stats, const std::vector<VisiblePoint>& vps,
                              const PilotRadius& a) {
    drain([&](size_t i, uint64_t m, const int64_t*) {
        if (vps[i].bsdf) stats[i].r2 = pilot_r2(a, stats[i].r2, m);
    });
}

void PhotonAccumulator::update(std::vector<film::SlotStats>& stats, const std::vector<VisiblePoint>& vps,
                               float alpha) {
    drain([&](size_t i, uint64_t m, const int64_t* sum) {
        if (m == 0 || !vps[i].bsdf) return;
        double phi[3];
        for (int k = 0; k < 3; ++k) phi[k] = double(sum[k]) / scale_;
        film::SlotStats& st = stats[i];
        const double n_new = st.n + double(alpha) * double(m);
        const double r2_new = st.r2 * n_new / (st.n + double(m));
        const double shrink = r2_new / st.r2;
        const Rgb& beta = vps[i].beta;
        for (int k = 0; k < 3; ++k) st.tau[k] = (st.tau[k] + double(beta[k]) * phi[k]) * shrink;
        st.n = n_new;
        st.r2 = r2_new;
    });
}

void build_grid(photon::HitPointGrid& grid, const std::vector<VisiblePoint>& vps,
                const std::vector<film::SlotStats>& stats) {
    std::vector<Vec3> pos(vps.size());
    std::vector<float> r2(vps.size(), 0.0f);
    for (size_t i = 0; i < vps.size(); ++i)
        if (vps[i].bsdf) {
            pos[i] = vps[i].p;
            r2[i] = float(stats[i].r2);
        }
    grid.build(pos, r2);
}

void resolve(const std::vector<film::SlotStats>& stats, int slots_per_pixel, double direct_scale,
             uint64_t photons_emitted, film::Film& film) {
    const int w = film.width(), h = film.height();
    const double inv_photons = photons_emitted > 0 ? 1.0 / double(photons_emitted) : 0.0;
    tbb::parallel_for(0, h, [&](int y) {
        for (int x = 0; x < w; ++x) {
            double sum[3] = {0, 0, 0};
            for (int s = 0; s < slots_per_pixel; ++s) {
                const film::SlotStats& st =
                    stats[(size_t(y) * size_t(w) + size_t(x)) * size_t(slots_per_pixel) + size_t(s)];
                const double k = st.r2 > 0 ? inv_photons / (M_PI * st.r2) : 0.0;
                for (int c = 0; c < 3; ++c) sum[c] += st.direct[c] * direct_scale + st.tau[c] * k;
            }
            const double inv = 1.0 / slots_per_pixel;
            film.set_pixel(x, y, Rgb(float(sum[0] * inv), float(sum[1] * inv), float(sum[2] * inv)));
        }
    });
}

void run_loop(const Prepared& P, const ProgressiveOptions& opt, film::ProgressiveState& state,
              film::Film& film, Progress& progress, const std::function<void(uint64_t)>& iterate,
              const std::function<void(film::Film&)>& resolve_fn) {
    using clock = std::chrono::steady_clock;
    const auto t0 = opt.clock_start.value_or(clock::now());
    auto last_preview = clock::now();
    const uint64_t target = uint64_t(std::max(1, P.options.spp));
    uint64_t last_checkpoint = state.iterations;
    progress.start(state.integrator, target > state.iterations ? target - state.iterations : 0);
    while (state.iterations < target) {
        iterate(state.iterations);
        ++state.iterations;
        progress.advance();
        if (opt.on_checkpoint && opt.checkpoint_every > 0 &&
            state.iterations % uint64_t(opt.checkpoint_every) == 0) {
            opt.on_checkpoint(state);
            last_checkpoint = state.iterations;
        }
        const auto now = clock::now();
        if (opt.time > 0 && std::chrono::duration<double>(now - t0).count() >= opt.time) break;
        if (opt.on_preview && opt.write_every > 0 &&
            std::chrono::duration<double>(now - last_preview).count() >= opt.write_every) {
            resolve_fn(film);
            opt.on_preview(film);
            last_preview = clock::now();
        }
    }
    progress.finish();
    resolve_fn(film);
    if (opt.on_checkpoint && last_checkpoint != state.iterations) opt.on_checkpoint(state);
    if (opt.iterations_done) *opt.iterations_done = state.iterations;
}

}  // namespace phos::integrators::sppm
