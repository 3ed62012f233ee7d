// EmbreeScene: turns a scene::Scene into Embree 3 geometry (triangles, user-geometry analytic
// shapes, instances of per-object scenes) and converts Embree hits into SurfaceHit records.
#include "accel/embree_scene.h"

#include <embree3/rtcore.h>
#include <emmintrin.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <mutex>
#include <string>
#include <vector>

#include "accel/alpha_mask.h"
#include "accel/analytic.h"
#include "accel/bilinear_patch.h"
#include "accel/curves.h"
#include "core/error.h"
#include "core/frame.h"
#include "core/log.h"
#include "core/rng.h"
#include "scene/material_mix.h"

namespace phos::accel {

using detail::Affine;
using detail::Analytic;
using detail::CanonicalHit;
using detail::CurveGeom;
using detail::D3;

namespace {

// Unit roundoff of float; error bounds below are small multiples of it times coordinate magnitudes.
constexpr double kUlp = 0x1p-24;

// What mesh_local computes from a triangle's vertices (and uvs) alone, with the same operations:
// kept per triangle so that a hit only does the work that depends on where it landed.
struct TriangleFacts {
    D3 n;                       // unit counter-clockwise normal (flipped with MeshGeom::flip)
    D3 dpdu;                    // unit tangent, before the fallback for one along n
    double area2 = 0;           // |(p1 - p0) x (p2 - p0)|
    double error = 0;           // position error bound of a point on the triangle
    double edge_bound = 0;      // error x the longest edge: inset_point's test for "far from every edge"
    bool dpdu_along_n = false;  // |dpdu . n| >= 0.999: the hit takes a tangent from its normal instead
    // Without per-vertex normals (MeshGeom::normals empty), ng, ns and dpdu are the same for every
    // hit of a top-level triangle, and so is the BSDF's frame built from them (SurfaceHit::shading):
    // the hit's ng (= ns) and dpdu as finish_hit stores them, and that frame.
    Vec3 ng_float, dpdu_float;
    ShadingFrame shading;
};

struct MeshGeom {
    const float* vertices = nullptr;  // Embree's vertex buffer, 3 floats per vertex, geometry space
    const uint32_t* indices = nullptr;
    std::vector<Vec3> normals;  // unit per-vertex shading normals in geometry space, or empty
    const std::vector<Vec2>* uvs = nullptr;
    bool flip = false;  // reverse_orientation XOR transform swaps handedness
    const scene::Shape* source = nullptr;
    int shape = -1;
    std::vector<TriangleFacts> facts;  // per triangle, or empty (too many triangles to keep them)
    // Set for a mesh's exact bilinear patches (Embree user geometry, one primitive per patch; no
    // triangles, vertices or indices): hits go through patch_local.
    const struct PatchSet* patches = nullptr;
    D3 vertex(uint32_t i) const { return {vertices[3 * i], vertices[3 * i + 1], vertices[3 * i + 2]}; }
};

// The exact bilinear patches of one mesh (scene::TriangleMesh::patches).
struct PatchSet {
    std::vector<std::array<D3, 4>> corners;  // geometry space, pbrt's order p00 p10 p01 p11
    const uint32_t* indices = nullptr;       // 4 per patch into the mesh's vertices
    const std::vector<Vec2>* uvs = nullptr;  // the mesh's uvs (MeshGeom::uvs), or null
    const scene::Shape* source = nullptr;    // for its alpha mask
    bool alpha = false;                      // has_alpha(*source)
};

// What the alpha filter of a masked triangle mesh or curve set reads (Embree's user data of the
// geometry): the shape and how a hit's uv is found.
struct AlphaGeom {
    const scene::Shape* source = nullptr;
    const uint32_t* indices = nullptr;       // triangles: 3 per triangle
    const std::vector<Vec2>* uvs = nullptr;  // triangles: the mesh's uvs, or null
    const CurveGeom* curves = nullptr;       // curves: the curve set, else null
};

// The facts of triangle `prim` (defined with mesh_local below).
TriangleFacts triangle_facts(const MeshGeom& m, unsigned prim);

// What an Embree geomID stands for.
struct Geom {
    enum Kind { Mesh, Analytic, Instance, Curves } kind = Mesh;
    int index = 0;  // into Impl::meshes / analytics / instances / curves
};

struct InstanceData {
    int instance = -1, object = -1;
    Affine to_world, to_object;
    double norm = 1;        // ||M||, scales object-space error bounds to world
    double error_term = 0;  // extra error from Embree transforming rays into object space in float
};

// The intersect context extended with the exact canonical hit of the last accepted analytic
// intersection (Embree passes our context through to the callbacks unchanged).
// `hit` is indexed by the ray's id: 0 for single rays (one hit), the lane for packets
// (EmbreeScene::intersect16, sixteen), so a single-ray query sets up only one. `rays` are the
// world-space rays by the same index and `scene` the scene: what alpha masks decide with (a mask
// hashes the world ray, not Embree's copy of it in an instance's space).
struct QueryContext {
    RTCIntersectContext ctx;
    CanonicalHit* hit;
    const Ray* rays;
    const scene::Scene* scene;
};

// Salt of alpha_hash for candidate hit `root` (0: the first along the ray from its tnear) of
// primitive `prim` of geometry `geom` under instance `inst`.
inline uint64_t alpha_salt(unsigned geom, unsigned prim, unsigned inst, unsigned root) {
    return hash_combine(hash_combine(uint64_t(geom) << 32 | prim, inst), root);
}

// Whether a masked shape keeps the candidate hit at `uv` of lane `i` (see alpha_mask.h).
inline bool keeps(const QueryContext& qc, const scene::Shape& shape, Vec2 uv, RTCRayN* ray, unsigned N,
                  unsigned i, uint64_t salt) {
    const Ray& r = qc.rays[RTCRayN_id(ray, N, i) & 15u];
    return alpha_keeps(*qc.scene, shape, uv, r.origin, r.dir, salt);
}

// (Two-argument maxima: the initializer-list form is not inlined, 2 % of photon tracing.)
inline double max_abs(D3 v) { return std::max(std::fabs(v.x), std::max(std::fabs(v.y), std::fabs(v.z))); }
D3 normalized(D3 v) {
    const double l = std::sqrt(detail::dot(v, v));
    return l > 0 ? v * (1.0 / l) : v;
}

void analytic_bounds_cb(const RTCBoundsFunctionArguments* args) {
    const auto& a = *static_cast<const Analytic*>(args->geometryUserPtr);
    D3 lo, hi;
    detail::analytic_bounds(a, lo, hi);
    RTCBounds* b = args->bounds_o;
    b->lower_x = std::nextafter(float(lo.x), -kInf), b->upper_x = std::nextafter(float(hi.x), kInf);
    b->lower_y = std::nextafter(float(lo.y), -kInf), b->upper_y = std::nextafter(float(hi.y), kInf);
    b->lower_z = std::nextafter(float(lo.z), -kInf), b->upper_z = std::nextafter(float(hi.z), kInf);
}

// Transforms ray i into canonical space and intersects it; N is 1 for rtcIntersect1 but the
// packet layout is honoured anyway. A masked shape skips the hits its alpha drops and reports the
// next one (an analytic shape has at most two along a ray; `inst` is the instance, for the salt).
bool analytic_hit(const Analytic& a, const QueryContext& qc, RTCRayN* ray, unsigned N, unsigned i,
                  unsigned geom, unsigned inst, CanonicalHit& h) {
    const D3 o(RTCRayN_org_x(ray, N, i), RTCRayN_org_y(ray, N, i), RTCRayN_org_z(ray, N, i));
    const D3 d(RTCRayN_dir_x(ray, N, i), RTCRayN_dir_y(ray, N, i), RTCRayN_dir_z(ray, N, i));
    const D3 oc = a.to_canon.point(o), dc = a.to_canon.vector(d);
    double tmin = RTCRayN_tnear(ray, N, i);
    const double tmax = RTCRayN_tfar(ray, N, i);
    if (!detail::intersect_canonical(a, oc, dc, tmin, tmax, h)) return false;
    if (!has_alpha(*a.source)) return true;
    for (unsigned root = 0; root < 4; ++root) {
        const Vec2 uv = detail::analytic_surface(a, h, 0.0).uv;
        if (keeps(qc, *a.source, uv, ray, N, i, alpha_salt(geom, 0, inst, root))) return true;
        tmin = h.t;
        if (!detail::intersect_canonical(a, oc, dc, tmin, tmax, h) || !(h.t > tmin)) return false;
    }
    return false;
}

void analytic_intersect_cb(const RTCIntersectFunctionNArguments* args) {
    const auto& a = *static_cast<const Analytic*>(args->geometryUserPtr);
    auto* qc = reinterpret_cast<QueryContext*>(args->context);
    RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
    RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        CanonicalHit h;
        if (!analytic_hit(a, *qc, ray, args->N, i, args->geomID, args->context->instID[0], h)) continue;
        RTCRayN_tfar(ray, args->N, i) = float(h.t);
        // Embree wants some Ng; ours is recomputed exactly from the canonical hit afterwards.
        RTCHitN_Ng_x(hit, args->N, i) = -RTCRayN_dir_x(ray, args->N, i);
        RTCHitN_Ng_y(hit, args->N, i) = -RTCRayN_dir_y(ray, args->N, i);
        RTCHitN_Ng_z(hit, args->N, i) = -RTCRayN_dir_z(ray, args->N, i);
        RTCHitN_u(hit, args->N, i) = 0;
        RTCHitN_v(hit, args->N, i) = 0;
        RTCHitN_primID(hit, args->N, i) = args->primID;
        RTCHitN_geomID(hit, args->N, i) = args->geomID;
        RTCHitN_instID(hit, args->N, i, 0) = args->context->instID[0];
        // Each accepted hit is closer than all earlier ones, so the last one stored is the final
        // closest hit whenever that is an analytic shape.
        qc->hit[RTCRayN_id(ray, args->N, i) & 15u] = h;
    }
}

void analytic_occluded_cb(const RTCOccludedFunctionNArguments* args) {
    const auto& a = *static_cast<const Analytic*>(args->geometryUserPtr);
    const auto& qc = *reinterpret_cast<const QueryContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        CanonicalHit h;
        if (analytic_hit(a, qc, args->ray, args->N, i, args->geomID, args->context->instID[0], h))
            RTCRayN_tfar(args->ray, args->N, i) = -kInf;
    }
}

// Bilinear patches: the box of the four corners (a patch lies in their convex hull), and the
// exact double-precision hit (accel/bilinear_patch.h) whose (u, v) the canonical hit carries in
// p.x, p.y for finish_hit.
void patch_bounds_cb(const RTCBoundsFunctionArguments* args) {
    const auto& set = *static_cast<const PatchSet*>(args->geometryUserPtr);
    const std::array<D3, 4>& c = set.corners[args->primID];
    D3 lo = c[0], hi = c[0];
    for (const D3& p : c) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    RTCBounds* b = args->bounds_o;
    b->lower_x = std::nextafter(float(lo.x), -kInf), b->upper_x = std::nextafter(float(hi.x), kInf);
    b->lower_y = std::nextafter(float(lo.y), -kInf), b->upper_y = std::nextafter(float(hi.y), kInf);
    b->lower_z = std::nextafter(float(lo.z), -kInf), b->upper_z = std::nextafter(float(hi.z), kInf);
}

// The uv a hit at the patch's (u, v) reports (patch_local): the corners' uvs interpolated
// bilinearly, else (u, v).
Vec2 patch_uv(const PatchSet& set, unsigned prim, double u, double v) {
    u = std::clamp(u, 0.0, 1.0), v = std::clamp(v, 0.0, 1.0);
    if (!set.uvs) return {float(u), float(v)};
    const double w[4] = {(1 - u) * (1 - v), u * (1 - v), (1 - u) * v, u * v};
    const uint32_t* idx = set.indices + 4 * size_t(prim);
    const std::vector<Vec2>& t = *set.uvs;
    return t[idx[0]] * float(w[0]) + t[idx[1]] * float(w[1]) + t[idx[2]] * float(w[2]) +
           t[idx[3]] * float(w[3]);
}

// The patch's closest hit of ray i, skipping those a mask drops (at most two along a ray).
bool patch_hit(const PatchSet& set, const QueryContext& qc, unsigned prim, RTCRayN* ray, unsigned N,
               unsigned i, unsigned geom, unsigned inst, detail::PatchHit& h) {
    const D3 o(RTCRayN_org_x(ray, N, i), RTCRayN_org_y(ray, N, i), RTCRayN_org_z(ray, N, i));
    const D3 d(RTCRayN_dir_x(ray, N, i), RTCRayN_dir_y(ray, N, i), RTCRayN_dir_z(ray, N, i));
    double tmin = RTCRayN_tnear(ray, N, i);
    const double tmax = RTCRayN_tfar(ray, N, i);
    if (!detail::intersect_patch(set.corners[prim], o, d, tmin, tmax, h)) return false;
    if (!set.alpha) return true;
    for (unsigned root = 0; root < 4; ++root) {
        if (keeps(qc, *set.source, patch_uv(set, prim, h.u, h.v), ray, N, i,
                  alpha_salt(geom, prim, inst, root)))
            return true;
        tmin = h.t;
        if (!detail::intersect_patch(set.corners[prim], o, d, tmin, tmax, h) || !(h.t > tmin)) return false;
    }
    return false;
}

void patch_intersect_cb(const RTCIntersectFunctionNArguments* args) {
    const auto& set = *static_cast<const PatchSet*>(args->geometryUserPtr);
    auto* qc = reinterpret_cast<QueryContext*>(args->context);
    RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
    RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        detail::PatchHit h;
        if (!patch_hit(set, *qc, args->primID, ray, args->N, i, args->geomID, args->context->instID[0], h))
            continue;
        RTCRayN_tfar(ray, args->N, i) = float(h.t);
        RTCHitN_Ng_x(hit, args->N, i) = -RTCRayN_dir_x(ray, args->N, i);
        RTCHitN_Ng_y(hit, args->N, i) = -RTCRayN_dir_y(ray, args->N, i);
        RTCHitN_Ng_z(hit, args->N, i) = -RTCRayN_dir_z(ray, args->N, i);
        RTCHitN_u(hit, args->N, i) = float(h.u);
        RTCHitN_v(hit, args->N, i) = float(h.v);
        RTCHitN_primID(hit, args->N, i) = args->primID;
        RTCHitN_geomID(hit, args->N, i) = args->geomID;
        RTCHitN_instID(hit, args->N, i, 0) = args->context->instID[0];
        qc->hit[RTCRayN_id(ray, args->N, i) & 15u] = {h.t, D3(h.u, h.v, 0), 0};
    }
}

void patch_occluded_cb(const RTCOccludedFunctionNArguments* args) {
    const auto& set = *static_cast<const PatchSet*>(args->geometryUserPtr);
    const auto& qc = *reinterpret_cast<const QueryContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        detail::PatchHit h;
        if (patch_hit(set, qc, args->primID, args->ray, args->N, i, args->geomID, args->context->instID[0],
                      h))
            RTCRayN_tfar(args->ray, args->N, i) = -kInf;
    }
}

// Embree's barycentrics (u, v) of triangle `prim` clamped to the triangle (its robust test can
// report them a hair outside) as b, and the uv there: the mesh's uvs interpolated, else (b1, b2).
Vec2 triangle_uv(const uint32_t* indices, const std::vector<Vec2>* uvs, unsigned prim, float u, float v,
                 double b[3]) {
    double b1 = std::clamp(double(u), 0.0, 1.0), b2 = std::clamp(double(v), 0.0, 1.0);
    if (b1 + b2 > 1) {
        const double s = b1 + b2;
        b1 /= s, b2 /= s;
    }
    const double b0 = std::max(0.0, 1.0 - b1 - b2);
    b[0] = b0, b[1] = b1, b[2] = b2;
    if (!uvs) return {float(b1), float(b2)};
    const uint32_t i0 = indices[3 * prim], i1 = indices[3 * prim + 1], i2 = indices[3 * prim + 2];
    const Vec2 t0 = (*uvs)[i0], t1 = (*uvs)[i1], t2 = (*uvs)[i2];
    return t0 * float(b0) + t1 * float(b1) + t2 * float(b2);
}

// Embree's intersection and occlusion filter of a masked triangle mesh or curve set: lanes whose
// candidate hit the mask drops are invalidated, and Embree goes on to the next candidate. The uv
// is the one the hit reports (triangle_uv; for curves curve_surface's, from the ray as Embree
// hands it to the filter, in the geometry's space, with the candidate's t in tfar).
void alpha_filter_cb(const RTCFilterFunctionNArguments* args) {
    const auto& g = *static_cast<const AlphaGeom*>(args->geometryUserPtr);
    const auto& qc = *reinterpret_cast<const QueryContext*>(args->context);
    const unsigned N = args->N;
    for (unsigned i = 0; i < N; ++i) {
        if (args->valid[i] != -1) continue;
        const unsigned prim = RTCHitN_primID(args->hit, N, i);
        const float u = RTCHitN_u(args->hit, N, i), v = RTCHitN_v(args->hit, N, i);
        Vec2 uv;
        if (g.curves) {
            RTCRayN* r = args->ray;
            const D3 o(RTCRayN_org_x(r, N, i), RTCRayN_org_y(r, N, i), RTCRayN_org_z(r, N, i));
            const D3 d(RTCRayN_dir_x(r, N, i), RTCRayN_dir_y(r, N, i), RTCRayN_dir_z(r, N, i));
            const D3 ng(RTCHitN_Ng_x(args->hit, N, i), RTCHitN_Ng_y(args->hit, N, i),
                        RTCHitN_Ng_z(args->hit, N, i));
            uv = detail::curve_surface(*g.curves, prim, u, ng, o, d, RTCRayN_tfar(r, N, i)).uv;
        } else {
            double b[3];
            uv = triangle_uv(g.indices, g.uvs, prim, u, v, b);
        }
        const uint64_t salt =
            alpha_salt(RTCHitN_geomID(args->hit, N, i), prim, RTCHitN_instID(args->hit, N, i, 0), 0);
        if (!keeps(qc, *g.source, uv, args->ray, N, i, salt)) args->valid[i] = 0;
    }
}

// Installs alpha_filter_cb on a geometry of a masked shape (before it is committed).
void set_alpha_filter(RTCGeometry g, const AlphaGeom* data) {
    rtcSetGeometryUserData(g, const_cast<AlphaGeom*>(data));
    rtcSetGeometryIntersectFilterFunction(g, alpha_filter_cb);
    rtcSetGeometryOccludedFilterFunction(g, alpha_filter_cb);
}

std::string where(const scene::Shape& s) { return s.origin.empty() ? std::string("shape") : s.origin; }

}  // namespace

struct EmbreeScene::Impl {
    RTCDevice device = nullptr;
    // Whether intersect16 hands its rays to Embree's packet kernels. Embree's 16-wide kernels and
    // the kernels of the CPU's own best ISA give the single-ray kernels' hits to the bit; an ISA
    // capped below an AVX-512 CPU's (--embree-config isa=avx2) splits a 16-ray packet into 8-wide
    // kernels whose triangle hits differ from its single-ray ones in the last bits of t, p and uv.
    // There the lanes are traced one by one, so a hit never depends on the call that found it.
    bool packets = true;
    RTCScene top = nullptr;
    std::vector<RTCScene> object_scenes;
    // A vector: nothing keeps pointers to a mesh's record, and every hit indexes it (through a
    // deque that cost ~16 instructions per photon hit).
    std::vector<MeshGeom> meshes;
    // Triangles whose TriangleFacts are kept (152 bytes each): the first 2^20 of the scene's, so
    // that huge meshes do not double the accelerator's memory; the others compute them per hit.
    static constexpr size_t kMaxCachedTriangles = size_t(1) << 20;
    size_t cached_triangles = 0;
    // The meshes' bilinear patches (a deque: Embree keeps pointers to them).
    std::deque<PatchSet> patch_sets;
    std::deque<Analytic> analytics;  // a deque: Embree keeps pointers to the Analytic records
    // Masked triangle meshes' and curve sets' filter data, and the curve sets they point to
    // (deques: Embree keeps pointers to them).
    std::deque<AlphaGeom> alpha_geoms;
    std::deque<CurveGeom> alpha_curves;
    std::vector<InstanceData> instances;
    std::vector<CurveGeom> curves;                // pbrt curve shapes
    std::vector<Geom> top_geoms;                  // by geomID in `top`
    std::vector<std::vector<Geom>> object_geoms;  // by object, by geomID in its scene
    Bounds bounds;
    std::mutex error_mutex;
    std::string error;

    ~Impl() {
        if (top) rtcReleaseScene(top);
        for (RTCScene s : object_scenes)
            if (s) rtcReleaseScene(s);
        if (device) rtcReleaseDevice(device);
    }

    static void on_error(void* user, RTCError code, const char* str) {
        // Never throw through Embree's C frames: remember the message, the constructor throws.
        auto* self = static_cast<Impl*>(user);
        const std::string msg = "Embree error " + std::to_string(int(code)) + ": " + (str ? str : "");
        log::warn(msg);
        std::lock_guard<std::mutex> lock(self->error_mutex);
        if (self->error.empty()) self->error = msg;
    }

    void check() {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error.empty()) throw InputError(error);
    }

    RTCScene new_scene() {
        RTCScene s = rtcNewScene(device);
        rtcSetSceneFlags(s, RTC_SCENE_FLAG_ROBUST);
        rtcSetSceneBuildQuality(s, RTC_BUILD_QUALITY_HIGH);
        return s;
    }

    static void attach(RTCScene s, RTCGeometry g, std::vector<Geom>& ids, Geom what) {
        rtcCommitGeometry(g);
        const unsigned id = rtcAttachGeometry(s, g);
        rtcReleaseGeometry(g);
        if (ids.size() <= id) ids.resize(id + 1);
        ids[id] = what;
    }

    // A mesh's per-vertex shading normals (in geometry space) and uvs.
    static void vertex_attributes(MeshGeom& mg, const scene::Shape& shape, size_t nv) {
        const auto& mesh = shape.mesh;
        if (!mesh.normals.empty() && mesh.normals.size() != nv)
            log::warn(where(shape) + ": normal count differs from vertex count; normals ignored");
        else if (!mesh.normals.empty()) {
            // pbrt-v4: normals go through the normal transform and flip with ReverseOrientation.
            mg.normals.resize(nv);
            for (size_t i = 0; i < nv; ++i) {
                Vec3 n = shape.to_world.normal(mesh.normals[i]);
                const float l = length(n);
                n = l > 0 && std::isfinite(l) ? n / l : Vec3(0.0f);
                mg.normals[i] = shape.reverse_orientation ? -n : n;
            }
        }
        if (!mesh.uvs.empty() && mesh.uvs.size() != nv)
            log::warn(where(shape) + ": uv count differs from vertex count; uvs ignored");
        else if (!mesh.uvs.empty())
            mg.uvs = &mesh.uvs;
    }

    // Adds a mesh's exact bilinear patches as one user geometry.
    void add_patches(RTCScene s, std::vector<Geom>& ids, const scene::Shape& shape, int index) {
        const auto& mesh = shape.mesh;
        const size_t np = mesh.patch_count();
        PatchSet& set = patch_sets.emplace_back();
        set.indices = mesh.patches.data();
        set.source = &shape;
        set.alpha = has_alpha(shape);
        set.corners.resize(np);
        const Affine m = Affine::from(shape.to_world);
        for (size_t i = 0; i < np; ++i)
            for (size_t k = 0; k < 4; ++k)
                set.corners[i][k] = m.point(D3(mesh.positions[mesh.patches[4 * i + k]]));
        MeshGeom mg;
        mg.patches = &set;
        mg.flip = mesh.patches_flipped != (shape.reverse_orientation != shape.to_world.swaps_handedness());
        mg.source = &shape;
        mg.shape = index;
        vertex_attributes(mg, shape, mesh.positions.size());
        set.uvs = mg.uvs;
        RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryUserPrimitiveCount(g, unsigned(np));
        rtcSetGeometryUserData(g, &set);
        rtcSetGeometryBoundsFunction(g, patch_bounds_cb, nullptr);
        rtcSetGeometryIntersectFunction(g, patch_intersect_cb);
        rtcSetGeometryOccludedFunction(g, patch_occluded_cb);
        meshes.push_back(std::move(mg));
        attach(s, g, ids, {Geom::Mesh, int(meshes.size() - 1)});
    }

    // Adds a triangle mesh whose object-space vertices are `pos` and triangles `idx`.
    void add_triangles(RTCScene s, std::vector<Geom>& ids, const scene::Shape& shape, int index,
                       const std::vector<Vec3>& pos, const std::vector<uint32_t>& idx) {
        const size_t nv = pos.size(), nt = idx.size() / 3;
        RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vb = static_cast<float*>(
            rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nv));
        auto* ib = static_cast<uint32_t*>(
            rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), nt));
        if (!vb || !ib) {
            rtcReleaseGeometry(g);
            check();
            throw InputError(where(shape) + ": cannot allocate mesh buffers");
        }
        const Affine m = Affine::from(shape.to_world);
        for (size_t i = 0; i < nv; ++i) {
            const Vec3 w = m.point(D3(pos[i])).to_float();
            vb[3 * i] = w.x, vb[3 * i + 1] = w.y, vb[3 * i + 2] = w.z;
        }
        std::copy(idx.begin(), idx.begin() + std::ptrdiff_t(3 * nt), ib);

        MeshGeom mg;
        mg.vertices = vb;
        mg.indices = ib;
        mg.flip = shape.reverse_orientation != shape.to_world.swaps_handedness();
        mg.source = &shape;
        mg.shape = index;
        if (shape.kind == scene::Shape::Kind::Mesh) vertex_attributes(mg, shape, nv);
        if (has_alpha(shape))
            set_alpha_filter(g, &alpha_geoms.emplace_back(AlphaGeom{&shape, ib, mg.uvs, nullptr}));
        if (cached_triangles + nt <= kMaxCachedTriangles) {
            cached_triangles += nt;
            mg.facts.resize(nt);
            tbb::parallel_for(tbb::blocked_range<size_t>(0, nt, 4096),
                              [&](const tbb::blocked_range<size_t>& r) {
                                  for (size_t t = r.begin(); t < r.end(); ++t)
                                      mg.facts[t] = triangle_facts(mg, unsigned(t));
                              });
        }
        meshes.push_back(std::move(mg));
        attach(s, g, ids, {Geom::Mesh, int(meshes.size() - 1)});
    }

    void add_mesh(RTCScene s, std::vector<Geom>& ids, const scene::Shape& shape, int index) {
        const auto& mesh = shape.mesh;
        if (mesh.indices.size() % 3 != 0)
            throw InputError(where(shape) + ": mesh index count is not a multiple of 3");
        if (mesh.patches.size() % 4 != 0)
            throw InputError(where(shape) + ": bilinear patch index count is not a multiple of 4");
        if (mesh.positions.empty() || (mesh.indices.empty() && mesh.patches.empty())) {
            log::warn(where(shape) + ": empty mesh ignored");
            return;
        }
        for (uint32_t i : mesh.patches)
            if (i >= mesh.positions.size())
                throw InputError(where(shape) + ": patch vertex index " + std::to_string(i) +
                                 " out of range (" + std::to_string(mesh.positions.size()) + " vertices)");
        for (uint32_t i : mesh.indices)
            if (i >= mesh.positions.size())
                throw InputError(where(shape) + ": mesh vertex index " + std::to_string(i) +
                                 " out of range (" + std::to_string(mesh.positions.size()) + " vertices)");
        for (const Vec3& p : mesh.positions)
            if (!is_finite(p)) throw InputError(where(shape) + ": mesh has a non-finite vertex");
        if (!mesh.indices.empty()) add_triangles(s, ids, shape, index, mesh.positions, mesh.indices);
        if (!mesh.patches.empty()) add_patches(s, ids, shape, index);
    }

    // A box is 12 triangles, counter-clockwise seen from outside, so its normals point out.
    void add_box(RTCScene s, std::vector<Geom>& ids, const scene::Shape& shape, int index) {
        const Vec3 lo = min(shape.box_min, shape.box_max), hi = max(shape.box_min, shape.box_max);
        if (!is_finite(lo) || !is_finite(hi)) throw InputError(where(shape) + ": box with non-finite corner");
        std::vector<Vec3> pos(8);
        for (int c = 0; c < 8; ++c)
            pos[size_t(c)] = {c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z};
        std::vector<uint32_t> idx;
        for (int a = 0; a < 3; ++a) {
            const int b = (a + 1) % 3, c = (a + 2) % 3;
            for (int side = 0; side < 2; ++side) {
                // Corners of the face in the (b, c) plane, walked so that e_b x e_c = +e_a.
                uint32_t q[4];
                const int bc[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
                for (int k = 0; k < 4; ++k) q[k] = uint32_t((side << a) | (bc[k][0] << b) | (bc[k][1] << c));
                if (side == 0) std::swap(q[1], q[3]);  // outward is -e_a: walk the other way
                idx.insert(idx.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
            }
        }
        add_triangles(s, ids, shape, index, pos, idx);
    }

    void add_analytic(RTCScene s, std::vector<Geom>& ids, const scene::Shape& shape, int index) {
        Analytic a;
        const char* why = "";
        if (!detail::make_analytic(shape, index, a, why)) {
            log::warn(where(shape) + ": degenerate shape ignored (" + why + ")");
            return;
        }
        analytics.push_back(a);
        RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryUserPrimitiveCount(g, 1);
        rtcSetGeometryUserData(g, &analytics.back());
        rtcSetGeometryBoundsFunction(g, analytic_bounds_cb, nullptr);
        rtcSetGeometryIntersectFunction(g, analytic_intersect_cb);
        rtcSetGeometryOccludedFunction(g, analytic_occluded_cb);
        attach(s, g, ids, {Geom::Analytic, int(analytics.size() - 1)});
    }

    void add_curves(RTCScene s, std::vector<Geom>& ids, const scene::Shape& shape, int index) {
        CurveGeom c;
        std::string why;
        RTCGeometry g = detail::new_curve_geometry(device, shape, index, c, why);
        if (!g) {
            check();
            log::warn(where(shape) + ": curves ignored (" + why + ")");
            return;
        }
        curves.push_back(c);
        if (has_alpha(shape))
            set_alpha_filter(g, &alpha_geoms.emplace_back(
                                    AlphaGeom{&shape, nullptr, nullptr, &alpha_curves.emplace_back(c)}));
        attach(s, g, ids, {Geom::Curves, int(curves.size() - 1)});
    }

    void add_shape(RTCScene s, std::vector<Geom>& ids, const scene::Shape& shape, int index) {
        using Kind = scene::Shape::Kind;
        switch (shape.kind) {
            case Kind::Mesh:
                add_mesh(s, ids, shape, index);
                break;
            case Kind::Box:
                add_box(s, ids, shape, index);
                break;
            case Kind::Curves:
                add_curves(s, ids, shape, index);
                break;
            default:
                add_analytic(s, ids, shape, index);
                break;
        }
    }

    void add_instance(const scene::Scene& sc, int i) {
        const scene::Instance& inst = sc.instances[size_t(i)];
        if (inst.object < 0 || size_t(inst.object) >= sc.objects.size())
            throw InputError("instance " + std::to_string(i) + " refers to object " +
                             std::to_string(inst.object) + " which does not exist");
        RTCScene obj = object_scenes[size_t(inst.object)];
        if (!obj) return;  // an object with no usable geometry
        const Mat4& mm = inst.to_world.matrix();
        if (mm(3, 0) != 0 || mm(3, 1) != 0 || mm(3, 2) != 0 || mm(3, 3) != 1)
            throw InputError("instance " + std::to_string(i) + ": transform is not affine");
        InstanceData d;
        d.instance = i;
        d.object = inst.object;
        d.to_world = Affine::from(inst.to_world);
        if (!d.to_world.inverse(d.to_object))
            throw InputError("instance " + std::to_string(i) + ": singular transform");
        d.norm = d.to_world.norm();
        // Embree maps the ray origin into object space in float: an error of about
        // cond(M) * ulp * (|p| + |translation|) in world terms (the |p| part is added per hit).
        const double cond = d.norm * d.to_object.norm();
        const double tr = max_abs({d.to_world.m[0][3], d.to_world.m[1][3], d.to_world.m[2][3]});
        d.error_term = 16 * kUlp * cond * tr;
        instances.push_back(d);

        RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(g, obj);
        rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, mm.m.data());
        attach(top, g, top_geoms, {Geom::Instance, int(instances.size() - 1)});
    }
};

EmbreeScene::EmbreeScene(const scene::Scene& scene, const char* device_config)
    : scene_(scene), mixes_(scene::has_mix_materials(scene)), impl_(std::make_unique<Impl>()) {
    Impl& im = *impl_;
    im.device = rtcNewDevice(device_config);
    if (!im.device)
        throw InputError("cannot create the Embree device (error " +
                         std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
    rtcSetDeviceErrorFunction(im.device, &Impl::on_error, &im);
    im.packets = rtcGetDeviceProperty(im.device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) != 0 ||
                 !__builtin_cpu_supports("avx512f");

    // One scene per object first: instances need their scenes committed.
    im.object_scenes.assign(scene.objects.size(), nullptr);
    im.object_geoms.resize(scene.objects.size());
    for (size_t o = 0; o < scene.objects.size(); ++o) {
        RTCScene s = im.new_scene();
        const auto& shapes = scene.objects[o].shapes;
        for (size_t i = 0; i < shapes.size(); ++i) im.add_shape(s, im.object_geoms[o], shapes[i], int(i));
        if (im.object_geoms[o].empty()) {
            rtcReleaseScene(s);
            continue;
        }
        rtcCommitScene(s);
        im.object_scenes[o] = s;
    }
    im.check();

    im.top = im.new_scene();
    for (size_t i = 0; i < scene.shapes.size(); ++i)
        im.add_shape(im.top, im.top_geoms, scene.shapes[i], int(i));
    for (size_t i = 0; i < scene.instances.size(); ++i) im.add_instance(scene, int(i));
    rtcCommitScene(im.top);
    im.check();

    RTCBounds b;
    rtcGetSceneBounds(im.top, &b);
    if (b.lower_x <= b.upper_x && b.lower_y <= b.upper_y && b.lower_z <= b.upper_z) {
        im.bounds.lo = {b.lower_x, b.lower_y, b.lower_z};
        im.bounds.hi = {b.upper_x, b.upper_y, b.upper_z};
    }
}

EmbreeScene::~EmbreeScene() = default;

Bounds EmbreeScene::bounds() const { return impl_->bounds; }

namespace {

void init_ray(const Ray& ray, RTCRay& r) {
    r.org_x = ray.origin.x, r.org_y = ray.origin.y, r.org_z = ray.origin.z;
    r.dir_x = ray.dir.x, r.dir_y = ray.dir.y, r.dir_z = ray.dir.z;
    r.tnear = std::max(ray.tmin, 0.0f);
    r.tfar = ray.tmax;
    r.time = 0;
    r.mask = ~0u;
    r.id = 0;
    r.flags = 0;
}

// Lanes of a packet past its rays (EmbreeScene::intersect16).
constexpr Ray kEmptyRay{Vec3(0.0f), Vec3(0.0f), 0.0f, 0.0f};

// The largest ray coordinate Embree traces: its kernels assert (RayK::valid, FLT_LARGE there) that
// every origin and direction coordinate is at most this in magnitude and that neither end of the
// interval is NaN, and Debian's Embree keeps its assertions (an abort: a camera at 1e20 did it).
constexpr float kMaxRayCoordinate = 1.844e18f;
inline bool traceable(Vec3 v) {
    const auto ok = [](float x) { return std::fabs(x) <= kMaxRayCoordinate; };  // false for NaN
    return ok(v.x) && ok(v.y) && ok(v.z);
}

// Rays that fail this hit nothing: Embree could not trace them (see above), or their direction
// or interval is empty (tmax > tmin, both not NaN; init_ray clamps tmin to 0). intersect16
// checks its rays with the same comparisons four at a time.
inline bool usable(const Ray& ray) {
    return traceable(ray.origin) && traceable(ray.dir) && length_squared(ray.dir) > 0 &&
           ray.tmax > std::max(ray.tmin, 0.0f);
}

// Called for a ray that is not usable(): says once per process when the reason is its size (a
// scene or camera with coordinates beyond Embree's range), so that such a scene's black pixels are
// explained. Rays that are merely empty or NaN say nothing.
void note_unusable(const Ray& ray) {
    if (!is_finite(ray.origin) || !is_finite(ray.dir) || (traceable(ray.origin) && traceable(ray.dir)))
        return;
    log::warn_once("accel: ray beyond range",
                   "rays with coordinates beyond +-1.8e18 (the most Embree traces) hit nothing: the scene or "
                   "camera has coordinates that large");
}

// Local (geometry-space) surface data before the instance transform.
struct Local {
    D3 p, ng, ns, dpdu;
    Vec2 uv;
    double error = 0;
};

// The hit point moved at least `inset` away from every edge of the triangle (towards its
// interior) when that is a small move. Near an edge shared with another
// face, the rounding of p to float could otherwise put it on the wrong side of the neighbour's
// plane, and a ray spawned from there would slip out through the edge (a leak at box corners).
D3 inset_point(D3 p0, D3 p1, D3 p2, double b0, double b1, double b2, const TriangleFacts& t) {
    const D3 p = p0 * b0 + p1 * b1 + p2 * b2;
    // Fast path (almost every hit): the distance to each edge, b_i * area2 / len_i, exceeds inset.
    const double bmin = std::min({b0, b1, b2});
    const double area2 = t.area2, inset = t.error;
    if (bmin * area2 >= t.edge_bound) return p;
    if (!(area2 > 0)) return p;
    const D3 opposite[3] = {p2 - p1, p0 - p2, p1 - p0};
    double need[3], sum = 0;
    for (int i = 0; i < 3; ++i) {
        // Barycentric coordinate i at distance `inset` from the opposite edge: inset / altitude.
        need[i] = inset * std::sqrt(detail::dot(opposite[i], opposite[i])) / area2;
        sum += need[i];
    }
    if (!(sum < 1)) return p;  // smaller than the inset: leave it
    // Shrink the triangle about the point with barycentrics need/sum: every b_i >= need_i. Slivers
    // would move the point far along the surface; they keep the plain point.
    const double k = 1 - sum;
    const D3 q = p0 * (need[0] + k * b0) + p1 * (need[1] + k * b1) + p2 * (need[2] + k * b2);
    const D3 dq = q - p;
    return detail::dot(dq, dq) <= 16 * inset * inset ? q : p;
}

TriangleFacts triangle_facts(const MeshGeom& m, unsigned prim) {
    const uint32_t i0 = m.indices[3 * prim], i1 = m.indices[3 * prim + 1], i2 = m.indices[3 * prim + 2];
    const D3 p0 = m.vertex(i0), p1 = m.vertex(i1), p2 = m.vertex(i2);
    TriangleFacts t;
    const double mag = std::max({max_abs(p0), max_abs(p1), max_abs(p2)});
    t.error = 16 * kUlp * mag;
    const D3 cr = detail::cross(p1 - p0, p2 - p0);  // counter-clockwise = front
    t.area2 = std::sqrt(detail::dot(cr, cr));
    const D3 opposite[3] = {p2 - p1, p0 - p2, p1 - p0};
    double len2[3];
    for (int i = 0; i < 3; ++i) len2[i] = detail::dot(opposite[i], opposite[i]);
    t.edge_bound = t.error * std::sqrt(std::max({len2[0], len2[1], len2[2]}));
    t.n = t.area2 > 0 ? cr * (1.0 / t.area2) : cr;
    if (m.flip) t.n = t.n * -1.0;
    D3 dpdu;
    if (m.uvs) {
        const Vec2 t0 = (*m.uvs)[i0], t1 = (*m.uvs)[i1], t2 = (*m.uvs)[i2];
        const double du02 = double(t0.x) - t2.x, dv02 = double(t0.y) - t2.y;
        const double du12 = double(t1.x) - t2.x, dv12 = double(t1.y) - t2.y;
        const double det = du02 * dv12 - dv02 * du12;
        if (std::fabs(det) > 1e-12) dpdu = ((p0 - p2) * dv12 - (p1 - p2) * dv02) * (1.0 / det);
    } else {
        dpdu = p1 - p0;
    }
    t.dpdu = normalized(dpdu);
    // |dpdu . n| does not depend on n's sign (a hit with shading normals may flip n).
    t.dpdu_along_n = !(std::fabs(detail::dot(t.dpdu, t.n)) < 0.999);
    if (m.normals.empty()) {
        // What finish_hit stores in a hit on this triangle, and what the BSDF builds from it.
        t.ng_float = t.n.to_float();
        t.dpdu_float = t.dpdu_along_n ? Frame(t.ng_float).s : t.dpdu.to_float();
        t.shading = shading_frame(t.ng_float, t.ng_float, t.dpdu_float);
    }
    return t;
}

// The point of triangle `prim` at Embree's barycentrics (u, v) (clamped to the triangle, then
// inset_point), its barycentrics b and its uv.
D3 mesh_point(const MeshGeom& m, const TriangleFacts& t, unsigned prim, float u, float v, double b[3],
              Vec2& uv) {
    const uint32_t i0 = m.indices[3 * prim], i1 = m.indices[3 * prim + 1], i2 = m.indices[3 * prim + 2];
    const D3 p0 = m.vertex(i0), p1 = m.vertex(i1), p2 = m.vertex(i2);
    // Clamped to the triangle: p is then a convex combination of the vertices and cannot fall
    // outside a neighbouring face's plane at an axis-aligned edge or corner, where a spawned ray
    // would escape.
    uv = triangle_uv(m.indices, m.uvs, prim, u, v, b);
    return inset_point(p0, p1, p2, b[0], b[1], b[2], t);
}

Local mesh_local(const MeshGeom& m, unsigned prim, float u, float v) {
    TriangleFacts computed;
    const TriangleFacts& t = m.facts.empty() ? (computed = triangle_facts(m, prim)) : m.facts[prim];
    Local L;
    double b[3];
    L.error = t.error;
    L.p = mesh_point(m, t, prim, u, v, b, L.uv);
    L.ng = L.ns = t.n;
    const uint32_t i0 = m.indices[3 * prim], i1 = m.indices[3 * prim + 1], i2 = m.indices[3 * prim + 2];
    const double b0 = b[0], b1 = b[1], b2 = b[2];
    if (!m.normals.empty()) {
        const Vec3 ns = m.normals[i0] * float(b0) + m.normals[i1] * float(b1) + m.normals[i2] * float(b2);
        if (length_squared(ns) > 0) {
            L.ns = normalized(D3(ns));
            // pbrt: with shading normals the geometric normal follows them.
            if (detail::dot(L.ng, L.ns) < 0) L.ng = L.ng * -1.0;
        }
    }
    L.dpdu = t.dpdu;
    if (t.dpdu_along_n) {
        const Frame f(L.ng.to_float());
        L.dpdu = D3(f.s);
    }
    return L;
}

// A hit on bilinear patch `prim` at the exact (u, v) of `h` (its p.x, p.y), as pbrt-v4's
// BilinearPatch::InteractionFromIntersection: the point, n = dp/du x dp/dv (flipped with the mesh),
// uv and the tangent along the texture's u from the corners' uvs when given, shading normals
// interpolated bilinearly with the geometric normal turned to their side.
Local patch_local(const MeshGeom& m, unsigned prim, const CanonicalHit& h) {
    const std::array<D3, 4>& c = m.patches->corners[prim];
    const double u = std::clamp(h.p.x, 0.0, 1.0), v = std::clamp(h.p.y, 0.0, 1.0);
    const double w[4] = {(1 - u) * (1 - v), u * (1 - v), (1 - u) * v, u * v};
    Local L;
    L.p = c[0] * w[0] + c[1] * w[1] + c[2] * w[2] + c[3] * w[3];
    const D3 dpdu = (c[1] - c[0]) * (1 - v) + (c[3] - c[2]) * v;
    const D3 dpdv = (c[2] - c[0]) * (1 - u) + (c[3] - c[1]) * u;
    D3 n = normalized(detail::cross(dpdu, dpdv));
    if (!(detail::dot(n, n) > 0)) n = normalized(detail::cross(c[3] - c[0], c[2] - c[1]));  // a corner
    if (m.flip) n = n * -1.0;
    L.ng = L.ns = n;
    const uint32_t* idx = m.patches->indices + 4 * size_t(prim);
    D3 tangent = dpdu;
    if (m.uvs) {
        const std::vector<Vec2>& t = *m.uvs;
        const Vec2 t00 = t[idx[0]], t10 = t[idx[1]], t01 = t[idx[2]], t11 = t[idx[3]];
        L.uv = t00 * float(w[0]) + t10 * float(w[1]) + t01 * float(w[2]) + t11 * float(w[3]);
        // d(s, t)/du and d(s, t)/dv; dp/ds by the chain rule when that map is invertible.
        const double dsdu = (1 - v) * (double(t10.x) - t00.x) + v * (double(t11.x) - t01.x);
        const double dtdu = (1 - v) * (double(t10.y) - t00.y) + v * (double(t11.y) - t01.y);
        const double dsdv = (1 - u) * (double(t01.x) - t00.x) + u * (double(t11.x) - t10.x);
        const double dtdv = (1 - u) * (double(t01.y) - t00.y) + u * (double(t11.y) - t10.y);
        const double det = dsdu * dtdv - dtdu * dsdv;
        if (std::fabs(det) > 1e-12) tangent = (dpdu * dtdv - dpdv * dtdu) * (1.0 / det);
    } else {
        L.uv = {float(u), float(v)};
    }
    if (!m.normals.empty()) {
        const Vec3 ns = m.normals[idx[0]] * float(w[0]) + m.normals[idx[1]] * float(w[1]) +
                        m.normals[idx[2]] * float(w[2]) + m.normals[idx[3]] * float(w[3]);
        if (length_squared(ns) > 0) {
            L.ns = normalized(D3(ns));
            if (detail::dot(L.ng, L.ns) < 0) L.ng = L.ng * -1.0;  // pbrt: ng follows the shading normal
        }
    }
    L.dpdu = normalized(tangent);
    if (!(std::fabs(detail::dot(L.dpdu, L.ng)) < 0.999)) L.dpdu = D3(Frame(L.ng.to_float()).s);
    double mag = max_abs(L.p);
    for (const D3& q : c) mag = std::max(mag, max_abs(q));
    L.error = 32 * kUlp * mag;
    return L;
}

// `amplify` >= 1 accounts for the larger spawn offsets of instanced hits (see intersect).
Local analytic_local(const Analytic& a, const CanonicalHit& h, double amplify) {
    const D3 approx = a.to_space.point(h.p);
    const double error = 32 * kUlp * std::max(max_abs(approx), a.size);
    // The spawn offset is at most about sqrt(3) * error * amplify; in canonical units, times the
    // norm of the inverse map.
    const double inset = 4 * error * amplify * a.to_canon.norm();
    const detail::AnalyticSurface s = detail::analytic_surface(a, h, inset);
    Local L;
    L.p = s.p;
    L.ng = L.ns = s.n;
    L.dpdu = s.dpdu;
    L.uv = s.uv;
    L.error = error;
    return L;
}

}  // namespace

bool EmbreeScene::intersect(const Ray& ray, SurfaceHit& hit) const {
    if (!usable(ray)) {
        note_unusable(ray);
        return false;
    }
    CanonicalHit canonical;
    QueryContext qc{{}, &canonical, &ray, &scene_};
    rtcInitIntersectContext(&qc.ctx);
    RTCRayHit rh;
    init_ray(ray, rh.ray);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(impl_->top, &qc.ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    const Vec3 ng(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
    finish_hit({rh.hit.geomID, rh.hit.primID, rh.hit.instID[0], rh.hit.u, rh.hit.v, rh.ray.tfar, ng, &ray},
               canonical, hit);
    return true;
}

void EmbreeScene::intersect16(const Ray* rays, int n, SurfaceHit* hits, bool* found) const {
    if (!impl_->packets) {
        for (int k = 0; k < n; ++k) found[k] = intersect(rays[k], hits[k]);
        return;
    }
    alignas(64) RTCRayHit16 rh;
    alignas(64) int valid[16];
    // The analytic callbacks' exact hits, one per lane: a lane's entry is written before its hit
    // is read. The thread's own (no call here runs inside another), so that each call does not
    // construct sixteen of them (5 instructions per photon ray).
    thread_local CanonicalHit canonical[16];
    // (Lanes past n are never traced, so the callbacks read only rays[0, n).)
    QueryContext qc{{}, canonical, rays, &scene_};
    rtcInitIntersectContext(&qc.ctx);
    for (int k = 0; k < 16; ++k) {
        const Ray& r = k < n ? rays[k] : kEmptyRay;
        rh.ray.org_x[k] = r.origin.x, rh.ray.org_y[k] = r.origin.y, rh.ray.org_z[k] = r.origin.z;
        rh.ray.dir_x[k] = r.dir.x, rh.ray.dir_y[k] = r.dir.y, rh.ray.dir_z[k] = r.dir.z;
        rh.ray.tnear[k] = std::max(r.tmin, 0.0f), rh.ray.tfar[k] = r.tmax, rh.ray.time[k] = 0;  // as init_ray
        rh.ray.mask[k] = ~0u, rh.ray.flags[k] = 0;
        rh.ray.id[k] = unsigned(k);  // the analytic callbacks file their canonical hit by lane
        rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
    }
    // usable() of every lane, four lanes per SSE instruction (the same comparisons on the same
    // values). A lane left out still holds a well-formed empty ray: Embree's AVX2 kernels (the
    // packet split into two halves of 8) assert that every ray of a half is finite, left out or
    // not, and Debian's Embree keeps its assertions (an abort on CPUs without AVX-512).
    const __m128 largest = _mm_set1_ps(kMaxRayCoordinate),
                 abs_mask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
    const auto traceable = [&](const float* v) {
        return _mm_cmple_ps(_mm_and_ps(_mm_load_ps(v), abs_mask), largest);
    };
    bool any = false;
    for (int k = 0; k < 16; k += 4) {
        const __m128 dx = _mm_load_ps(rh.ray.dir_x + k), dy = _mm_load_ps(rh.ray.dir_y + k),
                     dz = _mm_load_ps(rh.ray.dir_z + k);
        const __m128 len2 =
            _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)), _mm_mul_ps(dz, dz));
        __m128 ok = _mm_and_ps(_mm_and_ps(traceable(rh.ray.org_x + k), traceable(rh.ray.org_y + k)),
                               traceable(rh.ray.org_z + k));
        ok = _mm_and_ps(ok, _mm_and_ps(_mm_and_ps(traceable(rh.ray.dir_x + k), traceable(rh.ray.dir_y + k)),
                                       traceable(rh.ray.dir_z + k)));
        ok = _mm_and_ps(ok, _mm_cmpgt_ps(len2, _mm_setzero_ps()));
        ok = _mm_and_ps(ok, _mm_cmpgt_ps(_mm_load_ps(rh.ray.tfar + k), _mm_load_ps(rh.ray.tnear + k)));
        _mm_store_si128(reinterpret_cast<__m128i*>(valid + k), _mm_castps_si128(ok));
        const int mask = _mm_movemask_ps(ok);
        any |= mask != 0;
        if (mask == 0xf) continue;
        for (int i = k; i < k + 4; ++i) {
            if (valid[i]) continue;
            if (i < n) note_unusable(rays[i]);
            rh.ray.org_x[i] = rh.ray.org_y[i] = rh.ray.org_z[i] = 0;
            rh.ray.dir_x[i] = rh.ray.dir_y[i] = rh.ray.dir_z[i] = 0;
            rh.ray.tnear[i] = rh.ray.tfar[i] = 0;
            rh.ray.mask[i] = 0;
        }
    }
    if (any) rtcIntersect16(valid, impl_->top, &qc.ctx, &rh);
    for (int k = 0; k < n; ++k) {
        found[k] = valid[k] != 0 && rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
        if (!found[k]) continue;
        const Vec3 ng(rh.hit.Ng_x[k], rh.hit.Ng_y[k], rh.hit.Ng_z[k]);
        finish_hit({rh.hit.geomID[k], rh.hit.primID[k], rh.hit.instID[0][k], rh.hit.u[k], rh.hit.v[k],
                    rh.ray.tfar[k], ng, &rays[k]},
                   canonical[k], hits[k]);
    }
}

void EmbreeScene::finish_hit(const RawHit& raw, const detail::CanonicalHit& canonical,
                             SurfaceHit& hit) const {
    const Impl& im = *impl_;
    const InstanceData* inst = nullptr;
    const Geom* g;
    if (raw.inst != RTC_INVALID_GEOMETRY_ID) {
        inst = &im.instances[size_t(im.top_geoms[raw.inst].index)];
        g = &im.object_geoms[size_t(inst->object)][raw.geom];
    } else {
        g = &im.top_geoms[raw.geom];
    }

    // What every hit records of its shape.
    const auto record_shape = [&](const scene::Shape& shape, int shape_index) {
        hit.t = raw.t;
        hit.shape = shape_index;
        hit.instance = inst ? inst->instance : -1;
        hit.material = shape.material;
        hit.area_light = shape.area_light;
        hit.media = shape.media;
    };
    Local L;
    const scene::Shape* shape;
    int shape_index;
    if (g->kind == Geom::Mesh) {
        const MeshGeom& m = im.meshes[size_t(g->index)];
        hit.primitive = int(raw.prim);
        // (Under an instance the world-space vectors differ per instance.)
        if (!inst && !m.facts.empty() && m.normals.empty()) {
            // A flat top-level triangle (most hits): what the lines below give, with the kept
            // float normal, tangent and frame instead of rounding them again.
            const TriangleFacts& t = m.facts[raw.prim];
            double b[3];
            const D3 p = mesh_point(m, t, raw.prim, raw.u, raw.v, b, hit.uv);
            hit.p = p.to_float();
            hit.ng = hit.ns = t.ng_float;
            hit.dpdu = t.dpdu_float;
            hit.shading = &t.shading;
            record_shape(*m.source, m.shape);
            hit.error = float(t.error + 2 * kUlp * max_abs(p)) * 1.0001f;
            return;
        }
        L = m.patches ? patch_local(m, raw.prim, canonical) : mesh_local(m, raw.prim, raw.u, raw.v);
        shape = m.source;
        shape_index = m.shape;
        hit.shading = nullptr;
    } else if (g->kind == Geom::Curves) {
        const CurveGeom& c = im.curves[size_t(g->index)];
        // The ray in the geometry's space (Embree's ng already is).
        D3 o(raw.ray->origin), d(raw.ray->dir);
        if (inst) o = inst->to_object.point(o), d = inst->to_object.vector(d);
        const detail::CurveSurface cs = detail::curve_surface(c, raw.prim, raw.u, D3(raw.ng), o, d, raw.t);
        L.p = cs.p;
        L.ng = L.ns = cs.n;
        L.dpdu = cs.dpdu;
        L.uv = cs.uv;
        L.error = cs.error;
        shape = c.source;
        shape_index = c.shape;
        hit.primitive = int(raw.prim);
        hit.shading = nullptr;
    } else {
        const Analytic& a = im.analytics[size_t(g->index)];
        L = analytic_local(a, canonical, inst ? 1 + inst->norm * inst->to_object.norm() : 1.0);
        shape = a.source;
        shape_index = a.shape;
        hit.primitive = 0;
        hit.shading = nullptr;
    }

    if (inst) {
        const D3 pw = inst->to_world.point(L.p);
        const double cond = inst->norm * inst->to_object.norm();
        L.error = L.error * inst->norm + inst->error_term + 16 * kUlp * cond * max_abs(pw);
        L.p = pw;
        // Normals by the inverse transpose; an instance transform never flips orientation (pbrt).
        L.ng = normalized(inst->to_object.transpose_vector(L.ng));
        L.ns = normalized(inst->to_object.transpose_vector(L.ns));
        L.dpdu = normalized(inst->to_world.vector(L.dpdu));
    }

    // ng, ns and dpdu are unit vectors in double here; rounding to float keeps them unit to 1e-7.
    hit.p = L.p.to_float();
    hit.ng = L.ng.to_float();
    hit.ns = L.ns.to_float();
    hit.uv = L.uv;
    hit.dpdu = L.dpdu.to_float();
    record_shape(*shape, shape_index);
    if (mixes_) hit.material = scene::resolve_material(scene_, hit.material, hit.p, hit.uv);
    // Also cover the rounding of p itself to float.
    hit.error = float(L.error + 2 * kUlp * max_abs(L.p)) * 1.0001f;
}

double EmbreeScene::triangle_constants_bytes(double triangles) {
    return std::min(triangles, double(Impl::kMaxCachedTriangles)) * double(sizeof(TriangleFacts));
}

bool EmbreeScene::occluded(const Ray& ray) const {
    if (!usable(ray)) {
        note_unusable(ray);
        return false;
    }
    CanonicalHit canonical;
    QueryContext qc{{}, &canonical, &ray, &scene_};
    rtcInitIntersectContext(&qc.ctx);
    RTCRay r;
    init_ray(ray, r);
    rtcOccluded1(impl_->top, &qc.ctx, &r);
    return r.tfar < 0;  // Embree sets tfar to -inf on any hit
}

}  // namespace phos::accel
