// The render's memory model (see memory_estimate.h). Sizes of phos's own records come from
// sizeof; the rest (the process base, Embree's BVH, what the allocator keeps of freed photon
// batches, the hit-point grid) was measured as VmRSS sampled through renders of this code on
// x86-64 Linux with glibc (docs/usage.md, "Memory").
#include "integrators/memory_estimate.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <set>

#include "accel/embree_scene.h"
#include "core/memory.h"
#include "dist/ranks.h"
#include "integrators/bidirectional_path.h"
#include "integrators/camera_subpath.h"
#include "integrators/sppm_core.h"
#include "photon/beam_bvh.h"
#include "photon/photon.h"
#include "photon/projection_map.h"
#include "photon/tracer.h"
#include "photon/volume_cache.h"

namespace phos::integrators {
namespace {

using photon::Photon;

// The process before any scene: binary, libraries, TBB workers, the Embree device (VmHWM of a
// 16x16 path render of a 12-triangle box: 40 MB, for 1 to 8 threads).
constexpr double kBase = 40e6;
// Under mpirun: OpenMPI 4.1's libraries, plugins and shared-memory segments (VmHWM of that render
// as 2 ranks: 53 MB against 43.6 MB alone).
constexpr double kMpiBase = 10e6;

// Embree 3 (accel/embree_scene.cpp: RTC_BUILD_QUALITY_HIGH, robust scenes), per triangle beyond
// its copy of the vertices (12 B, and 12 B of transformed normals when the mesh has them) and
// indices (12 B): 92 B at the peak while the BVH builds, 56 B kept (1 M and 2 M triangle meshes).
constexpr double kBvhBuildPerTriangle = 92;
constexpr double kBvhPerTriangle = 56;
constexpr double kPerGeometry = 1024;  // an analytic shape's or an instance's Embree geometry

// Photon tracing (photon/tracer.cpp) writes each stored photon once into its map's final array
// (power rescaled in place at the end); the batches in flight hold their photons again with their
// direction and emission index until committed. Up to photon::batches_in_flight(threads) batches
// of TraceOptions::batch_size emissions are in flight, and every map of the stream stores into
// them (the surplus is cut when committed): with volume maps, each batch fills the surface maps
// too. The slices are kept until the stream ends (measured: 1 M to 6 M photons on
// cornell-diffuse, fog-caustic's volume maps).
constexpr double kTracedPerPhoton = sizeof(Photon);
constexpr double kBatchPerPhoton = sizeof(Photon) + sizeof(Vec3) + sizeof(uint32_t);  // photon, wi, emission
// Stored photons per emitted one, for the batches in flight and when only --photons bounds a map
// (1.6 measured on cornell-diffuse's global map: diffuse scenes store one photon per bounce).
constexpr double kStoredPerEmitted = 1.6;
// The photons the batches in flight store with `threads` threads per rank.
double in_flight_photons(int threads) {
    return kStoredPerEmitted * double(photon::batches_in_flight(threads) * photon::TraceOptions{}.batch_size);
}
// The k-d tree build (photon/kdtree.cpp) permutes the traced array in place: nothing per photon
// beyond it. The irradiance cache's points (one per stride photons) are built in place too.
// Beam estimate of the volume maps: a 40-byte sphere per photon and the BVH's nodes (about one
// 32-byte node per 4 photons with 16-sphere leaves).
constexpr double kBeamPerPhoton = sizeof(photon::PhotonSphere) + sizeof(photon::BeamBvh::Node) / 4.0;

// Film: 4 doubles per pixel and layer (film/film.h); creating a layer copies it once. Writing
// adds the float image and the encoder's buffers (measured: 12.5 B per pixel for EXR, 15 for PNG).
constexpr double kFilmPerPixel = 32;
constexpr double kWritePerPixel = 16;

// Progressive photon mapping per hit-point slot (sppm_core.h): the per-thread fixed-point sums
// (PhotonAccumulator::LocalSlot) or the shared atomic ones, 32 bytes each; the hit-point grid's
// entries (20 B, a point in ~4 cells), buckets (2 to 4 per point) and the positions and radii it
// is built from (measured 555 B per pixel in all for sppm at 500² to 2000² with 2 threads).
constexpr double kAccumulatorSlot = 32;
constexpr double kGridPerPoint = 4 * 20 + 12 + sizeof(Vec3) + sizeof(float);

uint64_t bytes(double b) { return b > 0 ? uint64_t(b) : 0; }

// The threads the render will run on: --threads, at most the arena's.
int render_threads(const MemoryEstimateInputs& in) {
    const int arena = tbb::this_task_arena::max_concurrency();
    return in.threads > 0 ? std::min(in.threads, arena) : arena;
}

// One phase of the render and what it holds.
struct Phase {
    std::string name;
    std::vector<MemoryItem> items;
    void add(const std::string& item, double b) {
        if (b <= 0) return;
        for (MemoryItem& i : items)
            if (i.name == item) {
                i.bytes += bytes(b);
                return;
            }
        items.push_back({item, bytes(b)});
    }
    uint64_t total() const {
        uint64_t t = 0;
        for (const MemoryItem& i : items) t += i.bytes;
        return t;
    }
};

// The loaded scene's arrays and what Embree builds from them.
struct SceneMemory {
    double scene = 0;             // meshes, textures, density grids as loaded
    double geometry = 0;          // Embree's vertex, index and normal copies; shading's grid copies
    double triangles = 0;         // for the BVH
    double other_geometries = 0;  // analytic shapes, instances
};

void add_shape(const scene::Shape& s, SceneMemory& m) {
    using Kind = scene::Shape::Kind;
    if (s.kind == Kind::Mesh) {
        const scene::TriangleMesh& mesh = s.mesh;
        m.scene += double(mesh.positions.capacity() * sizeof(Vec3) + mesh.normals.capacity() * sizeof(Vec3) +
                          mesh.uvs.capacity() * sizeof(Vec2) + mesh.indices.capacity() * sizeof(uint32_t));
        m.geometry += double(mesh.positions.size() * sizeof(Vec3) + mesh.indices.size() * sizeof(uint32_t) +
                             mesh.normals.size() * sizeof(Vec3));
        m.triangles += double(mesh.triangle_count());
    } else if (s.kind == Kind::Box) {
        m.geometry += 8 * sizeof(Vec3) + 36 * sizeof(uint32_t);
        m.triangles += 12;
    } else {
        m.other_geometries += 1;
    }
}

SceneMemory scene_memory(const scene::Scene& scene) {
    SceneMemory m;
    for (const scene::Shape& s : scene.shapes) add_shape(s, m);
    for (const scene::Object& o : scene.objects)
        for (const scene::Shape& s : o.shapes) add_shape(s, m);
    m.other_geometries += double(scene.instances.size());
    std::set<const void*> seen;  // images and grids may be shared
    for (const scene::Texture& t : scene.textures)
        if (t.image && seen.insert(t.image.get()).second)
            m.scene += double(t.image->texels.capacity() * sizeof(Rgb));
    for (const scene::Medium& md : scene.media) {
        const double grid = double((md.density.capacity() + md.emission_scale.capacity()) * sizeof(float));
        m.scene += grid;
        m.geometry += grid;  // shading/density_grid.cpp keeps its own copy of a uniform grid
        if (md.sparse.buffer && seen.insert(md.sparse.buffer.get()).second)
            m.scene += double(md.sparse.bytes);
    }
    return m;
}

// Whether rays can travel in a medium (shading::MediaSet::active).
bool media_active(const scene::Scene& scene) {
    const auto valid = [&](int i) { return i >= 0 && size_t(i) < scene.media.size(); };
    bool active = valid(scene.camera_medium);
    for (const scene::Light& l : scene.lights) active |= valid(l.medium);
    for (const scene::Shape& s : scene.shapes) active |= valid(s.media.inside) || valid(s.media.outside);
    for (const scene::Object& o : scene.objects)
        for (const scene::Shape& s : o.shapes) active |= valid(s.media.inside) || valid(s.media.outside);
    return active;
}

// Photons a map will store: its budget, else what --photons emissions leave in it.
double stored_photons(const PhotonMapSettings& s, uint64_t emit) {
    return s.photons > 0 ? double(s.photons) : kStoredPerEmitted * double(emit);
}

// The photon mapper's phases (integrators/photon_map.cpp, build_maps): tracing, the k-d tree
// builds (one map at a time, while the traced arrays of the others exist), then the maps with
// their caches and beam BVHs through the render pass.
void photon_map_phases(const scene::Scene& scene, const PhotonMapOptions& o, float sharp_exponent,
                       int threads, const Phase& common, std::vector<Phase>& phases) {
    const double in_flight = in_flight_photons(threads);
    const bool delta = photon::has_caustic_casters(scene, sharp_exponent);
    const bool media = media_active(scene) && !o.photon_viz;
    const bool global = o.photon_viz || (o.indirect_light && !o.fast_global);
    const double n[photon::kMapCount] = {
        global ? stored_photons(o.global, o.photons) : 0,
        !o.photon_viz && o.caustics && delta ? stored_photons(o.caustic, o.photons) : 0,
        !o.photon_viz && o.indirect_light && o.fast_global ? stored_photons(o.indirect, o.photons) : 0,
        media && o.indirect_light ? stored_photons(o.volume, o.photons) : 0,
        media && o.caustics && delta ? stored_photons(o.volume_caustic, o.photons) : 0};
    double total = 0;
    for (double x : n) total += x;
    const double volume = n[photon::kVolumeMap] + n[photon::kVolumeCausticMap];
    // The most photons in flight: in the main stream (global, indirect, volume maps; volume
    // photons are rare, so the batches in flight fill up with surface photons) or the caustic
    // stream (caustic maps, through projection maps); never more than the maps store.
    const double surface = n[photon::kGlobalMap] + n[photon::kIndirectMap];
    const double main_stream =
        n[photon::kVolumeMap] > 0 && surface > 0 ? in_flight : surface + n[photon::kVolumeMap];
    const double caustic_stream = n[photon::kCausticMap] + n[photon::kVolumeCausticMap];
    const double retained = kBatchPerPhoton * std::min(std::max(main_stream, caustic_stream), in_flight);
    const double stride = std::max<uint32_t>(o.cache_stride, 1);

    Phase trace = common;
    trace.name = "photon tracing";
    trace.add("photon maps", kTracedPerPhoton * total + retained);
    phases.push_back(trace);

    Phase build = common;
    build.name = "photon map build";
    build.add("photon maps", sizeof(Photon) * total + retained);
    phases.push_back(build);

    Phase render = common;
    render.name = "render";
    render.add("photon maps", sizeof(Photon) * total + retained);
    if (o.volume_estimate == VolumeEstimate::Beam) render.add("beam BVH", kBeamPerPhoton * volume);
    // Cache points as photons (their k-d tree built in place), volume cache points with their
    // moments.
    if (o.irradiance_cache && global && !o.photon_viz)
        render.add("irradiance cache", sizeof(Photon) * n[photon::kGlobalMap] / stride);
    if (o.irradiance_cache && media && o.indirect_light)
        render.add("irradiance cache",
                   (sizeof(Photon) + sizeof(photon::VolumeMoments)) * n[photon::kVolumeMap] / stride);
    phases.push_back(render);
}

// PPM and SPPM (sppm_core.h): per hit-point slot the visible point, its statistics, the gather
// record, the fixed-point sums and the grid. `hit_points`: PPM's --ppm-eye-samples per pixel, else
// SPPM's one visible point per pixel.
void progressive_phase(const scene::Scene& scene, const MemoryEstimateInputs& in, bool hit_points,
                       const Phase& common, std::vector<Phase>& phases) {
    const RenderOptions& ro = in.render;
    const double pixels = double(ro.width) * double(ro.height);
    const bool media = media_active(scene);
    const int eye = hit_points ? std::max(1, in.progressive.eye_samples) : 1;
    const double slots = hit_points ? pixels * eye : pixels * (media ? 2 : 1);
    // PhotonAccumulator: per-thread copies when they take at most 1 GiB for every thread of the
    // arena, else shared atomics; the copies are made by the threads that run photon passes.
    const int arena = tbb::this_task_arena::max_concurrency();
    const int workers = render_threads(in);
    const bool per_thread = slots * kAccumulatorSlot * arena <= double(1u << 30);
    Phase p = common;
    p.name = "render";
    p.add("visible points", slots * (sizeof(VisiblePoint) + sizeof(sppm::GatherPoint) + 1));
    p.add("pixel statistics", slots * sizeof(sppm::PixelStats));
    p.add("photon sums", slots * kAccumulatorSlot * (1 + (per_thread ? workers : 0)));
    // One visible point per pixel and eye sample (with media, in one of the pixel's two slots).
    p.add("hit-point grid", pixels * eye * kGridPerPoint);
    p.add("pending photon hits", sppm::PhotonAccumulator::pending_bytes(in.progressive.photons_per_iter));
    if (in.checkpoint) p.add("checkpoint", slots * sizeof(sppm::PixelStats));
    // Under MPI: the eye-pass exchange's buffers (every slot's point and statistics, and this
    // rank's share again) and the summed photon sums, kept for the whole render.
    if (dist::distributed())
        p.add("rank exchange",
              slots * (double(sizeof(VisiblePoint) + sizeof(sppm::PixelStats)) * (1 + 1.0 / dist::ranks()) +
                       kAccumulatorSlot));
    phases.push_back(p);
}

// bdpt and vcm (bdpt.h, vcm.h): the fixed-point sums (image and layers, 24 bytes per pixel each), and for
// vcm the iteration's light subpaths: the vertices of one per pixel (kLightVerticesPerPath on
// average, measured 3.3 on the bench scenes at the default depth), the mergeable ones of all
// (kMergeableVerticesPerPath, measured 2.0: surfaces at least two segments from the light) packed
// twice (in their batches, then in grid order) and the grid over them.
constexpr double kLightVerticesPerPath = 4, kMergeableVerticesPerPath = 2.5;
constexpr double kMergeVertexBytes = double(sizeof(vcm::MergeVertex)), kVertexGridPerPoint = 12 + 4 + 8;
void bidirectional_phase(const MemoryEstimateInputs& in, bool light_vertices, const Phase& common,
                         std::vector<Phase>& phases) {
    const RenderOptions& ro = in.render;
    const double pixels = double(ro.width) * double(ro.height);
    Phase p = common;
    p.name = "render";
    const double planes = ro.layers ? 5 : 1;
    p.add("fixed-point sums", pixels * 24 * planes);
    if (light_vertices) {
        // --vcm-light-paths 0 (automatic) takes 2 per pixel, or more where the pilot finds fewer
        // mergeable vertices per subpath (about 3 per pixel then, vcm_pilot.cpp): 2 bounds both.
        const int k = in.progressive.vcm_light_paths > 0 ? in.progressive.vcm_light_paths : 2;
        const double paths = pixels * double(k);
        const double vertices = paths * kMergeableVerticesPerPath;
        // Subpath j < pixels keeps its vertices (and their range, 8 bytes); every subpath its
        // mergeable ones, in its batch and again in the grid's order.
        p.add("light vertices", pixels * (kLightVerticesPerPath * sizeof(vcm::VertexCore) + 8));
        if (in.progressive.vcm_mode == VcmMode::Ppm || in.progressive.vcm_mode == VcmMode::Vcm)
            p.add("merging",
                  vertices * (2 * kMergeVertexBytes + kVertexGridPerPoint) + pixels * sizeof(float));
    }
    if (in.checkpoint) p.add("checkpoint", 2 * pixels * 24 * planes);
    phases.push_back(p);
}

}  // namespace

std::string MemoryEstimate::breakdown(size_t max_items) const {
    std::string s;
    for (size_t i = 0; i < items.size() && i < max_items; ++i)
        s += (i ? ", " : "") + items[i].name + " " + memory::format_bytes(items[i].bytes);
    return s;
}

MemoryEstimate estimate_memory(const scene::Scene& scene, const MemoryEstimateInputs& in) {
    const RenderOptions& ro = in.render;
    const double pixels = double(ro.width) * double(ro.height);
    const SceneMemory sm = scene_memory(scene);
    std::vector<Phase> phases;

    Phase base;
    base.add("base", kBase);
    if (dist::distributed()) base.add("MPI", kMpiBase);
    base.add("scene", sm.scene);
    base.add("accelerator", sm.geometry + kPerGeometry * sm.other_geometries);

    Phase prepare = base;
    prepare.name = "BVH build";
    prepare.add("accelerator", kBvhBuildPerTriangle * sm.triangles +
                                   accel::EmbreeScene::triangle_constants_bytes(sm.triangles));
    phases.push_back(prepare);

    // From the render on: the BVH, and the film with its layers and AOVs.
    Phase common = base;
    common.add("accelerator",
               kBvhPerTriangle * sm.triangles + accel::EmbreeScene::triangle_constants_bytes(sm.triangles));
    const IntegratorInfo& info = integrator(in.integrator);
    const size_t layers = ro.layers ? info.layers.size() : 0;
    const size_t extra = layers + ro.aovs.size();
    const double film = kFilmPerPixel * pixels * double(1 + extra + (extra > 0 ? 1 : 0));
    common.add("film", film);
    switch (info.memory) {
        case RenderMemory::PhotonMaps:
            photon_map_phases(scene, in.photon_map, ro.sharp_glossy, render_threads(in), common, phases);
            break;
        case RenderMemory::FixedSums:
        case RenderMemory::LightVertices:
            bidirectional_phase(in, info.memory == RenderMemory::LightVertices, common, phases);
            break;
        case RenderMemory::HitPoints:
        case RenderMemory::VisiblePoints:
            progressive_phase(scene, in, info.memory == RenderMemory::HitPoints, common, phases);
            break;
        case RenderMemory::Film: {
            Phase render = common;
            render.name = "render";
            if (in.checkpoint) render.add("checkpoint", 2 * film);  // the film's sums, then encoded
            phases.push_back(render);
        }
    }
    Phase write = common;
    write.name = "writing the image";
    write.add("film", kWritePerPixel * pixels);
    phases.push_back(write);

    const Phase* peak = &phases.front();
    for (const Phase& p : phases)
        if (p.total() > peak->total()) peak = &p;
    MemoryEstimate e;
    e.total = peak->total();
    e.phase = peak->name;
    e.items = peak->items;
    std::stable_sort(e.items.begin(), e.items.end(),
                     [](const MemoryItem& a, const MemoryItem& b) { return a.bytes > b.bytes; });
    return e;
}

}  // namespace phos::integrators
