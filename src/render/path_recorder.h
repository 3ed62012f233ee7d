// --trace-pixel: the record of every camera sample of one pixel, vertex by vertex (surface, event,
// sampled direction, throughput, light samples, photon-map lookups, what each vertex added), and
// for PPM / SPPM the visible points with the photons they gathered. Integrators report to the
// recorder active on their thread, `if (auto* r = recorder()) r->...`, which is set only while the
// traced pixel's samples run: when nothing is traced, recording costs one thread-local test.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "accel/ray.h"
#include "core/vec.h"
#include "shading/bsdf.h"
#include "shading/surface_walk.h"

namespace phos::render {

class Prepared;

// What happened at a vertex: the lobe sampled to go on (transmission: any refraction or diffuse
// transmission), scattering in a medium, an emitting surface where the path ends, or a ray that left
// the scene. A surface where the path ends without sampling (whitted and photonmap at diffuse
// surfaces, the maximum depth) is named by its BSDF's first lobe kind.
enum class TraceEvent { Diffuse, Glossy, Specular, Transmission, Medium, Emitter, Escaped };
const char* trace_event_name(TraceEvent e);

// What a contribution to the sample's radiance is: emission found (surfaces, media, the background
// seen by an escaping ray), light sampling (shadow rays, single scattering), a caustic-map estimate,
// indirect light (final gathering, the global / indirect / volume maps).
enum class TraceTerm { Emission, Light, Caustic, Indirect };
inline constexpr int kTraceTerms = 4;
const char* trace_term_name(TraceTerm t);

// One light sample (one shadow ray).
struct TracedLight {
    int light = -1;         // index in Scene::lights
    Vec3 from;              // the point it lights
    Vec3 direction;         // unit, towards the light
    float distance = kInf;  // to the sampled point on the light (kInf: a direction only)
    float pdf = 0;          // solid-angle density (1 for delta lights) times the light's selection pmf
    float mis_weight = 1;   // power-heuristic weight against BSDF / phase sampling
    int visible = -1;       // 1 unoccluded, 0 blocked, -1 no shadow ray (nothing to send)
    Spectrum transmittance{
        1.0f};  // through media along the shadow ray (1 without media), at the path's wavelengths
    // What it adds at its point: f L |cos| T w / pdf (phase instead of f |cos| in media), the path's
    // throughput not included; 0 when blocked. At the path's wavelengths.
    Spectrum contribution{0.0f};
};

// One photon density estimate.
struct TracedLookup {
    std::string map;  // "global", "caustic", "indirect", "irradiance cache", "volume", ...
    Vec3 position;
    uint32_t found = 0;  // photons in the estimate (0 for a march or beam estimate)
    float radius = 0;    // of the disc (0 when not a k-nearest estimate)
    Rgb estimate{0.0f};  // the estimate itself (throughput not included)
};

struct TracedVertex {
    TraceEvent event = TraceEvent::Diffuse;
    bool surface = false;  // position, normal, shape and material are those of a surface hit
    bool placed = false;   // has a position (a surface or a point in a medium)
    Vec3 position, normal;
    int shape = -1, instance = -1, material = -1, medium = -1, area_light = -1;
    std::string shape_name;  // the instanced object's name, else where the shape is defined
    std::string material_name;
    // The path's weight arriving here, which multiplies what the vertex adds (at the path's wavelengths).
    Spectrum throughput{1.0f};
    bool sampled = false;    // a direction was sampled here to continue the path
    Vec3 direction;          // the sampled direction (escaped: the ray's)
    float pdf = 0;           // its solid-angle density (delta lobes: the lobe's selection probability)
    Spectrum weight{0.0f};   // f |cos| / pdf of the sampled direction (media: 1)
    bool dispersed = false;  // the sample crossed a dispersive interface: the path kept its hero wavelength
    Rgb terms[kTraceTerms] = {};  // what the vertex added to the sample's radiance (colour), by TraceTerm
    std::vector<TracedLight> lights;
    std::vector<TracedLookup> lookups;
    bool empty() const;  // nothing added, no lights, no lookups
};

// A photon a PPM / SPPM visible point gathered in one pass.
struct TracedPhoton {
    uint64_t index = 0;  // in its pass
    Vec3 position;
    Rgb power;         // as the pass carries it: the photon's flux times the photons emitted
    Vec3 wi;           // unit, towards where the photon came from
    Rgb contribution;  // f(wo, wi) Φ (phase(wo, wi) Φ in media), the camera throughput not included
};

// One photon pass at a visible point and the statistics of its slot after the update
// (sppm_pixel_stats.h).
struct TracedPass {
    uint64_t iteration = 0;
    bool pilot = false;  // SPPM's pilot pass: its photons only choose the radius
    double radius = 0;   // the gathering radius during the pass
    std::vector<TracedPhoton> photons;
    double n = 0, r2 = 0, tau[3] = {0, 0, 0}, direct[3] = {0, 0, 0};
    uint64_t photons_emitted = 0;  // N_emitted after the pass
};

struct TracedVisiblePoint {
    size_t slot = 0;
    Vec3 position;
    int material = -1, medium = -1;
    std::string material_name;
    Spectrum throughput{0.0f};
    std::vector<TracedPass> passes;
};

// One camera sample (PPM: one hit point; SPPM: one iteration's eye path).
struct TracedPath {
    uint64_t sample = 0;
    int64_t iteration = -1;  // SPPM: the iteration
    TracedVertex camera;     // what the camera ray added before its first vertex (in media)
    std::vector<TracedVertex> vertices;
    Rgb contribution{0.0f};  // the sample's radiance (PPM / SPPM: emission and direct light)
    // The path's wavelengths (nm) and their densities as the path ended (0 for a secondary
    // wavelength a dispersive interface terminated).
    std::array<float, spectrum::kSpectrumSamples> lambda{}, lambda_pdf{};
    std::optional<TracedVisiblePoint> visible_point;
};

class PathRecorder {
public:
    PathRecorder(int x, int y) : x_(x), y_(y) {}
    int x() const { return x_; }
    int y() const { return y_; }
    const std::vector<TracedPath>& paths() const { return paths_; }

    void begin_path(uint64_t sample, int64_t iteration = -1);
    // The path's wavelengths (as they are now: call again after a termination).
    void wavelengths(const Wavelengths& lambda);
    void end_path(Rgb contribution) { paths_.back().contribution = contribution; }

    // The path's next event from SurfaceWalk::next: a surface, a scattering point in a medium, or
    // the ray leaving the scene (Lost and Absorbed record nothing). `throughput` arrives there.
    void vertex(const Prepared& P, shading::SurfaceWalk::Event event, const Ray& ray,
                const accel::SurfaceHit& hit, const shading::SurfaceWalk& walk, const Spectrum& throughput);
    // The path goes on from the last vertex by BSDF sample `s` / by phase sampling.
    void scattered(const shading::BsdfSample& s);
    void scattered_in_medium(Vec3 wi, float pdf);
    // What the last vertex (the camera ray before the first) adds to the sample's radiance.
    void add(TraceTerm term, Rgb c);
    void light(const TracedLight& l) { current().lights.push_back(l); }
    void lookup(TracedLookup l) { current().lookups.push_back(std::move(l)); }

    // PPM / SPPM. The last path ended at a visible point (in medium `medium`, or on the surface of
    // the path's last vertex when -1) stored in slot `slot`.
    void visible_point(size_t slot, Vec3 p, int medium, const Spectrum& throughput);
    // Starts a photon pass of `iteration` at every visible point still gathering, those of the
    // paths of the last path's iteration (SPPM: that iteration's eye path; PPM, whose paths have no
    // iteration: all), with the slot's current squared radius `r2(slot)`.
    template <class R2>
    void begin_pass(uint64_t iteration, bool pilot, R2&& r2);
    // A photon gathered by slot `slot` during the pass. Thread-safe (the photon pass is parallel).
    void photon(size_t slot, const TracedPhoton& p);
    // Ends the pass: the photons in index order, and the slots' statistics after the update.
    template <class Stats>
    void end_pass(uint64_t photons_emitted, Stats&& stats);

private:
    TracedVertex& current();
    std::vector<TracedVisiblePoint*> gathering();

    int x_, y_;
    std::vector<TracedPath> paths_;
    // Under MPI: every rank's photons of the pass (each rank traced a share of them). Collective.
    void gather_pending();
    std::mutex photons_mutex_;
    struct PendingPhoton {  // plain data, so the ranks can exchange them as bytes
        size_t slot;
        TracedPhoton photon;
    };
    std::vector<PendingPhoton> pending_;  // the current pass's photons
};

// The recorder active on this thread (null except while the traced pixel's samples run).
extern constinit thread_local PathRecorder* t_active_recorder;
inline PathRecorder* recorder() { return t_active_recorder; }

// Makes `r` (if not null) this thread's active recorder for the scope and records one camera path.
class RecordingScope {
public:
    RecordingScope(PathRecorder* r, uint64_t sample, int64_t iteration = -1) : r_(r) {
        if (!r_) return;
        r_->begin_path(sample, iteration);
        t_active_recorder = r_;
    }
    ~RecordingScope() {
        if (r_) t_active_recorder = nullptr;
    }
    // The sample's radiance.
    void done(Rgb contribution) {
        if (r_) r_->end_path(contribution);
    }
    RecordingScope(const RecordingScope&) = delete;
    RecordingScope& operator=(const RecordingScope&) = delete;

private:
    PathRecorder* r_;
};

// The pixel --trace-pixel asks for: the app installs its recorder around Integrator::render, and
// the integrators record that pixel's samples into it (null: nothing is traced).
PathRecorder* requested_trace();
class TraceRequest {
public:
    explicit TraceRequest(PathRecorder* r);
    ~TraceRequest();
    TraceRequest(const TraceRequest&) = delete;
    TraceRequest& operator=(const TraceRequest&) = delete;
};

// ---- implementation of the templates ----

template <class R2>
void PathRecorder::begin_pass(uint64_t iteration, bool pilot, R2&& r2) {
    for (TracedVisiblePoint* vp : gathering()) {
        TracedPass pass;
        pass.iteration = iteration;
        pass.pilot = pilot;
        pass.radius = std::sqrt(double(r2(vp->slot)));
        vp->passes.push_back(std::move(pass));
    }
}

template <class Stats>
void PathRecorder::end_pass(uint64_t photons_emitted, Stats&& stats) {
    gather_pending();
    std::stable_sort(pending_.begin(), pending_.end(),
                     [](const auto& a, const auto& b) { return a.photon.index < b.photon.index; });
    for (TracedVisiblePoint* vp : gathering()) {
        if (vp->passes.empty()) continue;
        TracedPass& pass = vp->passes.back();
        for (const auto& [slot, ph] : pending_)
            if (slot == vp->slot) pass.photons.push_back(ph);
        const auto& s = stats(vp->slot);
        pass.n = s.n;
        pass.r2 = s.r2;
        for (int c = 0; c < 3; ++c) pass.tau[c] = s.tau[c], pass.direct[c] = s.direct[c];
        pass.photons_emitted = photons_emitted;
    }
    pending_.clear();
}

}  // namespace phos::render
