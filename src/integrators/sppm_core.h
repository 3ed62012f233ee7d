// The parts PPM and SPPM share: the photon pass that splats photons into the hit points' integer
// accumulators, the per-point update (whose equations, Hachisuka & Jensen 2009 eq. 9-12, are in
// sppm_pixel_stats.h), the photon half and the end of an iteration, the final pixel estimate. The
// eye path to a visible point is in eye_path.h, the pilot's radius rule in pilot_radius.h; the
// iteration loop itself is in ppm.cpp and sppm.cpp, with progressive_budget.h keeping its count,
// time, previews and checkpoints.
//
// Determinism: Φ_i and M_i are sums in 64-bit fixed point (integer atomics), exact and
// order-independent, so the result is bit-identical for any thread count.
#pragma once

#include <immintrin.h>

#include <algorithm>
#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/rng.h"
#include "film/film.h"
#include "film/tiles.h"
#include "integrators/eye_path.h"
#include "integrators/pilot_radius.h"
#include "integrators/progressive_options.h"
#include "integrators/sppm_pixel_stats.h"
#include "photon/hitpoint_grid.h"
#include "render/path_recorder.h"
#include "render/prepared.h"
#include "render/progressive_budget.h"
#include "render/progressive_checkpoint.h"
#include "render/render_budget.h"
#include "shading/bsdf.h"
#include "spectrum/color.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)
}  // namespace phos::integrators

namespace phos::integrators::sppm {

// The automatic or explicit initial radius of a visible point, before any photon pass: `radius`
// (--radius) when > 0, else `radius_pixels` pixel footprints at the point's path length.
struct InitialRadius {
    float radius;
    float radius_pixels;
    CameraModel::Footprint footprint;  // the camera's pixel footprint (camera.h)
    double r2(const VisiblePoint& vp) const {
        float r = radius > 0 ? radius : radius_pixels * footprint.at(vp.path_length);
        // A ball around a volume point holds far fewer photons than a disc of the same radius on
        // a surface (photons in thin media are sparse): it starts kVolumeRadiusScale times wider.
        if (vp.volume()) r *= kVolumeRadiusScale;
        return double(r) * double(r);
    }
    static constexpr float kVolumeRadiusScale = 4.0f;
};

// What the photon pass reads of a visible point, compact (44 bytes) so the per-photon loop touches
// one cache line per matched point instead of a whole VisiblePoint with its Bsdf.
struct GatherPoint {
    Vec3 ng;                   // geometric normal turned to wo's side (zero: no visible point)
    int max_bounces = -1;      // photons that bounced more often would make the path exceed max_depth
    Vec3 ns;                   // shading normal turned like ng
    uint32_t kind = 0;         // kSurface, kLambert (one Lambert lobe: f = kd / π above ng and ns), kVolume
    spectrum::RgbSpectrum kd;  // kd of a Lambert-only point
    float g = 0;               // the phase function's g of a volume point
    static constexpr uint32_t kSurface = 0, kLambert = 1, kVolume = 2;
};

// What the gather reads of a photon's surface hit, in two parts: the direction and bounces (16
// bytes, read for every hit within a point's radius) and the colour (one 64-byte cache line,
// read when those let the photon count).
struct ArrivalDirection {
    Vec3 wi;
    int bounces;
};
struct alignas(64) ArrivalColour {
    spectrum::ColourWeights power;  // the photon's power, wavelength by wavelength, as colour
    std::array<float, spectrum::kSpectrumSamples> lambda;  // the photon's wavelengths
};

// Per-hit-point photon statistics of one iteration, summed in 64-bit fixed point: per-thread
// arrays reduced in update() (no atomics in the photon loop), or integer atomics when per-thread
// copies would take too much memory. Integer sums are exact, so both are order-independent.
class PhotonAccumulator {
public:
    explicit PhotonAccumulator(size_t slots);
    ~PhotonAccumulator();
    // Traces photons [0, count) of pass `pass` on all cores, adding f(wo, wi) × power to each hit
    // point within its radius (photons straight from a light excluded: direct light is computed by
    // shadow rays); photons scattering in media add phase(wo, wi) × power to the volume points
    // whose ball holds them. Builds `grid` over the points with their radii in `stats` first
    // (build_grid), or while the first photons are traced where tracing does not read it (no
    // media, no --trace-pixel): the build is serial. Returns the number of photon rays traced.
    uint64_t photon_pass(const Prepared& P, const std::vector<VisiblePoint>& vps,
                         const std::vector<PixelStats>& stats, photon::HitPointGrid& grid, uint64_t seed,
                         uint64_t pass, uint64_t count);
    // Applies progressive_update (eq. 9-11; the 3D form for volume points) to `stats` (one per
    // visible point) with each point's M_i and β Φ_i, and clears the sums. A volume point's Φ_i is
    // divided by `open_fraction[i]`, the share of its ball photons can reach (photon/open_ball.h;
    // empty: 1 everywhere).
    void update(std::vector<PixelStats>& stats, const std::vector<VisiblePoint>& vps, float alpha,
                const std::vector<float>& open_fraction);
    // The pilot pass instead of update(): sets each visible point's r2 (the pilot's gathering disc)
    // by pilot_r2 from the photon count alone and clears the sums; N and τ stay 0 (see PilotRadius).
    void pilot(std::vector<PixelStats>& stats, const std::vector<VisiblePoint>& vps, const PilotRadius& a);
    // Memory the pending surface hits of a photon pass take (the memory check's estimate): a chunk
    // of at most kChunk photons, about 0.9 hits each after the first on cornell-diffuse (2
    // assumed), each held pending and again binned.
    static double pending_bytes(uint64_t photons_per_pass) {
        return double(std::min(photons_per_pass, kChunk)) * 2 *
               double(sizeof(PendingHit) + sizeof(ArrivalColour) + 3 * sizeof(float) +
                      sizeof(ArrivalDirection) + sizeof(ArrivalColour));
    }
    // --trace-pixel: the photons slots [first, first + count) gather also go to `trace`.
    void record(PathRecorder* trace, size_t first, size_t count) {
        trace_ = trace;
        trace_first_ = first;
        trace_count_ = trace ? count : 0;
    }

private:
    template <class F>
    void drain(F&& f);  // defined in sppm_core.cpp, its only user
    struct Slot {
        std::atomic<int64_t> phi[3];
        std::atomic<uint64_t> m;
    };
    struct LocalSlot {
        int64_t phi[3] = {0, 0, 0};
        uint64_t m = 0;
    };
    // A photon's surface hit after at least one bounce, waiting for the binned gather.
    struct PendingHit {
        Vec3 p;
        uint32_t bucket = 0;  // in the grid level being gathered
        ArrivalDirection direction;
    };
    // A block's pending hits: what binning reads (32 bytes a hit) apart from the colours it moves.
    struct PendingBlock {
        std::vector<PendingHit> hits;
        std::vector<ArrivalColour> colours;
    };
    // Photons are traced in chunks (bounding the pending hits' memory), in blocks of kBlock.
    static constexpr uint64_t kChunk = uint64_t(1) << 19, kBlock = 4096;
    // Traces photons [first, first + count) of the pass: surface hits go to pending_ (per block),
    // volume hits are added at once. Returns the rays traced.
    uint64_t trace_chunk(const Prepared& P, const std::vector<VisiblePoint>& vps,
                         const photon::HitPointGrid& grid, uint64_t seed, uint64_t pass, uint64_t first,
                         uint64_t count);
    // Adds the pending hits to the points of one grid level they reach, bucket by bucket.
    void gather_level(const std::vector<VisiblePoint>& vps, const photon::HitPointGrid& grid, size_t level);
    LocalSlot* local_slots();  // this thread's sums, or null (atomics)
    void add(LocalSlot* local, uint32_t i, const int64_t q[3], uint64_t m);
    // c in fixed point (what one photon adds); false when c is black or not finite.
    // (A photon's colour can have a negative component: a spectrum outside the sRGB gamut.)
    static bool quantize(const Rgb& c, double scale, int64_t q[3]) {
        if (c.is_black() || !c.is_finite()) return false;
        // Rounded to nearest (ties to even) by the conversion instruction itself.
        for (int k = 0; k < 3; ++k)
            q[k] = _mm_cvtsd_si64(_mm_set_sd(std::clamp(double(c[k]) * scale, -0x1p52, 0x1p52)));
        return true;
    }
    std::vector<PendingBlock> pending_;  // per block of the chunk
    size_t pending_blocks_ = 0;
    // The chunk's hits in bucket order: positions (one array per axis) and the rest.
    std::vector<float> bin_x_, bin_y_, bin_z_;
    std::vector<ArrivalDirection> bin_direction_;
    std::vector<ArrivalColour> bin_colour_;
    std::vector<uint32_t> bin_start_;  // bucket b's hits: [bin_start_[b], bin_start_[b + 1]) in each
    struct Locals;                     // per-thread LocalSlot arrays (tbb::enumerable_thread_specific)
    std::unique_ptr<Slot[]> slots_;
    std::unique_ptr<Locals> locals_;  // null: atomics
    std::vector<GatherPoint> gather_;
    std::vector<int64_t> reduced_;  // under MPI: per point Φ r, g, b, M, summed over the ranks
    size_t count_;
    double scale_ = 1;  // fixed-point units per unit of flux contribution
    PathRecorder* trace_ = nullptr;
    size_t trace_first_ = 0, trace_count_ = 0;
};

// --trace-pixel (path_recorder.h): runs an eye path again through `run` (which fills the visible
// point) with `trace` recording it as camera sample `sample` (SPPM: of iteration `iteration`), and
// records its visible point, stored in slot `slot`, or `slot + 1` for a volume point when
// `volume_slot` (SPPM with media).
void record_eye_path(PathRecorder& trace, uint64_t sample, int64_t iteration, size_t slot, bool volume_slot,
                     const std::function<Rgb(VisiblePoint& vp)>& run);

// Under MPI (dist/ranks.h) each rank runs the eye pass for the tiles it owns; share() gives every
// rank every pixel's visible points and statistics from the tile's owner (one all-gather), so that
// all ranks go on with the same state. No-op with one rank. Its buffers (272 bytes a pixel) live
// as long as the render: allocating them each iteration cost each rank 5 % in page faults.
class EyePassExchange {
public:
    void share(const scene::Scene& scene, const std::vector<film::Tile>& tiles, int width, size_t per_pixel,
               std::vector<VisiblePoint>& vps, std::vector<PixelStats>& slots);

private:
    std::string mine_, all_;
};

// Edge-aware radii (pilot_radius.h) over the surface visible points' r2 in `stats`, with r2_min one
// pixel footprint (the pilot's smallest radius, kPilotRadiusMinPixels) at each point's distance.
void bound_radii_at_edges(const std::vector<VisiblePoint>& vps, std::vector<PixelStats>& stats,
                          const CameraModel::Footprint& footprint);

// Builds the grid over the visible points with their current radii.
void build_grid(photon::HitPointGrid& grid, const std::vector<VisiblePoint>& vps,
                const std::vector<PixelStats>& stats);

// The photon half of iteration `pass` of PPM or SPPM: the photon pass (its `photons` photons within
// each visible point's radius in state.slots add M_i and β Φ_i), then the progressive update of
// every slot (eq. 9-11), whose photons join N_emitted; with `pilot` (SPPM's first iteration), the
// pilot's radii instead (PhotonAccumulator::pilot), its photons dropped.
void photon_iteration(const Prepared& P, PhotonAccumulator& acc, const std::vector<VisiblePoint>& vps,
                      ProgressiveState& state, photon::HitPointGrid& grid, uint64_t pass, uint64_t photons,
                      float alpha, const PilotRadius* pilot = nullptr);
// The end of a PPM or SPPM iteration: --trace-pixel's record of the pass (the slots after the
// update), then the budget's count, checkpoint and preview (`resolve_film` fills the film).
void end_iteration(PathRecorder* trace, ProgressiveState& state, ProgressiveBudget& budget,
                   const std::function<void()>& resolve_film);
// The end of a PPM or SPPM render: the final image, the budget's finish, and the -v line
// "`name`: N iterations, M photons".
RenderDone finish_progressive(const Prepared& P, const std::string& name, const ProgressiveState& state,
                              ProgressiveBudget& budget, const std::function<void()>& resolve_film);

// Final radiance of each pixel: slot_weight × the sum over its `slots_per_pixel` slots of
// direct × direct_scale + τ / (π R² N_emitted) (eq. 12; τ / (4/3 π R³ N_emitted) for the slots
// `volume_slot` marks). With `layers`, also the film layers "direct" (the first term) and
// "indirect" (the photon estimate), which sum to the image.
void resolve(const std::vector<PixelStats>& stats, int slots_per_pixel, double slot_weight,
             double direct_scale, uint64_t photons_emitted, film::Film& film, bool layers,
             const std::vector<uint8_t>& volume_slot);

}  // namespace phos::integrators::sppm
