// The --trace-pixel recorder (see path_recorder.h).
#include "render/path_recorder.h"

#include "dist/ranks.h"
#include "render/prepared.h"

namespace phos::render {

constinit thread_local PathRecorder* t_active_recorder = nullptr;

namespace {
// Set by the app's thread before Integrator::render and read by the render's own thread.
PathRecorder* g_requested = nullptr;

// The event a surface stands for when the path samples nothing there: its emission, else its
// BSDF's first lobe kind.
TraceEvent surface_event(const Prepared& P, const accel::SurfaceHit& hit) {
    const scene::Material& m = P.scene.materials[size_t(hit.material)];
    if (hit.area_light >= 0 || m.emission.max() > 0) return TraceEvent::Emitter;
    const uint32_t f = P.bsdf(hit).flags();
    if (f & shading::kDiffuse) return TraceEvent::Diffuse;
    if (f & shading::kGlossy) return TraceEvent::Glossy;
    if (f & shading::kTransmission) return TraceEvent::Transmission;
    if (f & shading::kSpecular) return TraceEvent::Specular;
    return TraceEvent::Diffuse;
}

// The instanced object's name, else where the shape is written ("file:line").
std::string shape_name(const scene::Scene& scene, const accel::SurfaceHit& hit) {
    if (hit.instance >= 0) {
        const scene::Object& o = scene.objects[size_t(scene.instances[size_t(hit.instance)].object)];
        return o.name.empty() ? o.shapes[size_t(hit.shape)].origin : o.name;
    }
    return hit.shape >= 0 ? scene.shapes[size_t(hit.shape)].origin : std::string();
}
}  // namespace

const char* trace_event_name(TraceEvent e) {
    switch (e) {
        case TraceEvent::Diffuse:
            return "diffuse";
        case TraceEvent::Glossy:
            return "glossy";
        case TraceEvent::Specular:
            return "specular";
        case TraceEvent::Transmission:
            return "transmission";
        case TraceEvent::Medium:
            return "medium";
        case TraceEvent::Emitter:
            return "emitter";
        case TraceEvent::Escaped:
            break;
    }
    return "escaped";
}

const char* trace_term_name(TraceTerm t) {
    switch (t) {
        case TraceTerm::Emission:
            return "emission";
        case TraceTerm::Light:
            return "light";
        case TraceTerm::Caustic:
            return "caustic";
        case TraceTerm::Indirect:
            break;
    }
    return "indirect";
}

bool TracedVertex::empty() const {
    for (const Rgb& t : terms)
        if (!t.is_black()) return false;
    return lights.empty() && lookups.empty();
}

void PathRecorder::begin_path(uint64_t sample, int64_t iteration) {
    TracedPath& p = paths_.emplace_back();
    p.sample = sample;
    p.iteration = iteration;
}

TracedVertex& PathRecorder::current() {
    TracedPath& p = paths_.back();
    return p.vertices.empty() ? p.camera : p.vertices.back();
}

void PathRecorder::vertex(const Prepared& P, shading::SurfaceWalk::Event event, const Ray& ray,
                          const accel::SurfaceHit& hit, const shading::SurfaceWalk& walk,
                          const Spectrum& throughput) {
    using Event = shading::SurfaceWalk::Event;
    if (event == Event::Lost || event == Event::Absorbed) return;
    TracedVertex v;
    v.throughput = throughput;
    v.medium = walk.medium();
    if (event == Event::Escaped) {
        v.event = TraceEvent::Escaped;
        v.direction = normalize(ray.dir);
    } else if (event == Event::Medium) {
        v.event = TraceEvent::Medium;
        v.placed = true;
        v.position = walk.medium_point();
    } else {
        const scene::Scene& scene = P.scene;
        v.event = surface_event(P, hit);
        v.surface = v.placed = true;
        v.position = hit.p;
        v.normal = hit.ns;
        v.shape = hit.shape;
        v.instance = hit.instance;
        v.shape_name = shape_name(scene, hit);
        v.material = hit.material;
        v.material_name = scene.materials[size_t(hit.material)].name;
        v.area_light = hit.area_light;
    }
    paths_.back().vertices.push_back(std::move(v));
}

void PathRecorder::scattered(const shading::BsdfSample& s) {
    TracedVertex& v = current();
    v.event = (s.flags & shading::kTransmission) ? TraceEvent::Transmission
              : (s.flags & shading::kSpecular)   ? TraceEvent::Specular
              : (s.flags & shading::kGlossy)     ? TraceEvent::Glossy
                                                 : TraceEvent::Diffuse;
    v.sampled = true;
    v.direction = s.wi;
    v.pdf = s.pdf;
    v.weight = s.weight;
    v.dispersed = s.dispersive;
}

void PathRecorder::wavelengths(const Wavelengths& lambda) {
    TracedPath& p = paths_.back();
    for (int i = 0; i < spectrum::kSpectrumSamples; ++i) {
        p.lambda[size_t(i)] = lambda[i];
        p.lambda_pdf[size_t(i)] = lambda.pdf(i);
    }
}

void PathRecorder::scattered_in_medium(Vec3 wi, float pdf) {
    TracedVertex& v = current();
    v.sampled = true;
    v.direction = wi;
    v.pdf = pdf;
    v.weight = Spectrum(1.0f);
}

void PathRecorder::add(TraceTerm term, Rgb c) { current().terms[int(term)] += c; }

void PathRecorder::visible_point(size_t slot, Vec3 p, int medium, const Spectrum& throughput) {
    TracedPath& path = paths_.back();
    TracedVisiblePoint& vp = path.visible_point.emplace();
    vp.slot = slot;
    vp.position = p;
    vp.medium = medium;
    if (medium < 0 && !path.vertices.empty() && path.vertices.back().surface) {
        vp.material = path.vertices.back().material;
        vp.material_name = path.vertices.back().material_name;
    }
    vp.throughput = throughput;
}

std::vector<TracedVisiblePoint*> PathRecorder::gathering() {
    std::vector<TracedVisiblePoint*> out;
    if (paths_.empty()) return out;
    const int64_t it = paths_.back().iteration;
    for (TracedPath& p : paths_)
        if (p.iteration == it && p.visible_point) out.push_back(&*p.visible_point);
    return out;
}

void PathRecorder::photon(size_t slot, const TracedPhoton& p) {
    const std::lock_guard<std::mutex> lock(photons_mutex_);
    pending_.push_back({slot, p});
}

PathRecorder* requested_trace() { return g_requested; }

TraceRequest::TraceRequest(PathRecorder* r) { g_requested = r; }
TraceRequest::~TraceRequest() { g_requested = nullptr; }

void PathRecorder::gather_pending() {
    if (!dist::distributed()) return;
    pending_ = dist::all_gather(std::span<const PendingPhoton>(pending_));
}

}  // namespace phos::render
