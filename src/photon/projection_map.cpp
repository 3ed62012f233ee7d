// Projection maps for caustic photons (see projection_map.h).
#include "photon/projection_map.h"

#include <algorithm>
#include <cmath>

#include "shading/bsdf.h"

namespace phos::photon {
namespace {

// Object-space bounding box of a shape (analytic shapes conservatively).
Bounds object_bounds(const scene::Shape& s) {
    Bounds b;
    using K = scene::Shape::Kind;
    switch (s.kind) {
        case K::Mesh:
            for (const Vec3& p : s.mesh.positions) b.extend(p);
            break;
        case K::Box:
            b.extend(s.box_min);
            b.extend(s.box_max);
            break;
        case K::Sphere:
        case K::Disk:
            b.extend(s.center - Vec3(s.radius));
            b.extend(s.center + Vec3(s.radius));
            break;
        case K::Cylinder:
        case K::Cone: {
            const float e = s.radius + 0.5f * s.height;
            b.extend(s.center - Vec3(e));
            b.extend(s.center + Vec3(e));
            break;
        }
        case K::Curves: {
            // A segment lies in the hull of its control points; the tube adds its radius.
            float r = 0;
            for (float x : s.curves.radii) r = std::max(r, std::fabs(x));
            for (const Vec3& p : s.curves.points) {
                b.extend(p - Vec3(r));
                b.extend(p + Vec3(r));
            }
            break;
        }
    }
    return b;
}

// Bounding sphere of a shape under the world transform t: exact for spheres, vertex-based for
// meshes, the box corners for the other shapes.
BoundingSphere world_sphere(const scene::Shape& s, const Transform& t) {
    if (s.kind == scene::Shape::Kind::Sphere) {
        const Vec3 c[3] = {t.vector({1, 0, 0}), t.vector({0, 1, 0}), t.vector({0, 0, 1})};
        const float l[3] = {length(c[0]), length(c[1]), length(c[2])};
        // Largest stretch: the largest column for a rotation x scale, the Frobenius norm otherwise.
        const float tol = 1e-4f * (l[0] * l[1] + l[1] * l[2] + l[0] * l[2]);
        const bool orthogonal = std::fabs(dot(c[0], c[1])) <= tol && std::fabs(dot(c[1], c[2])) <= tol &&
                                std::fabs(dot(c[0], c[2])) <= tol;
        const float stretch = orthogonal ? std::max(l[0], std::max(l[1], l[2]))
                                         : std::sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
        return {t.point(s.center), s.radius * stretch * 1.001f + 1e-6f};
    }
    std::vector<Vec3> pts;
    if (s.kind == scene::Shape::Kind::Mesh) {
        pts.reserve(s.mesh.positions.size());
        for (const Vec3& p : s.mesh.positions) pts.push_back(t.point(p));
    } else {
        const Bounds b = object_bounds(s);
        for (int i = 0; i < 8; ++i)
            pts.push_back(
                t.point(Vec3(i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z)));
    }
    Bounds w;
    for (const Vec3& p : pts) w.extend(p);
    if (w.empty()) return {Vec3(0.0f), -1};
    const Vec3 c = w.center();
    float r2 = 0;
    for (const Vec3& p : pts) r2 = std::max(r2, length_squared(p - c));
    return {c, std::sqrt(r2) * 1.001f + 1e-6f};
}

BoundingSphere sphere_of(const Bounds& b) { return {b.center(), 0.5f * length(b.extent()) * 1.001f + 1e-6f}; }

float angle_between(Vec3 a, Vec3 b) {  // unit vectors; atan2 form is accurate at small angles
    return std::atan2(length(cross(a, b)), dot(a, b));
}

bool same(Vec3 a, Vec3 b, float tol) { return length(a - b) <= tol; }

}  // namespace

// Both ask the material's BSDF (before textures: a textured roughness counts as its untextured
// value, 0 unless given, so such a surface counts as a caster).
bool has_delta_lobe(const scene::Material& m) {
    if (m.interface_only) return false;
    return shading::Bsdf::of_material(m, {}).flags() & shading::kSpecular;
}

bool is_caustic_caster(const scene::Material& m, float sharp_exponent) {
    if (m.interface_only) return false;
    return shading::Bsdf::of_material(m, {}).has_followed(sharp_exponent);
}

namespace {

// `of_plain` of each material, a mix taking the "or" of its two materials' (nested mixes
// followed; a mix's indices are checked, so a cycle or a bad index counts as false).
template <class OfPlain>
std::vector<bool> per_material(const scene::Scene& scene, OfPlain of_plain) {
    const size_t n = scene.materials.size();
    std::vector<bool> plain(n);
    for (size_t i = 0; i < n; ++i) plain[i] = !scene.materials[i].is_mix() && of_plain(scene.materials[i]);
    auto resolve = [&](auto&& self, int index, int depth) -> bool {
        if (index < 0 || size_t(index) >= n || depth > 64) return false;
        const scene::Material& m = scene.materials[size_t(index)];
        if (!m.is_mix()) return plain[size_t(index)];
        return self(self, m.mix_a, depth + 1) || self(self, m.mix_b, depth + 1);
    };
    std::vector<bool> out(n);
    for (size_t i = 0; i < n; ++i) out[i] = resolve(resolve, int(i), 0);
    return out;
}

bool material_flag(const std::vector<bool>& table, int material) {
    return material >= 0 && size_t(material) < table.size() && table[size_t(material)];
}

}  // namespace

std::vector<bool> caustic_caster_materials(const scene::Scene& scene, float sharp_exponent) {
    return per_material(scene,
                        [&](const scene::Material& m) { return is_caustic_caster(m, sharp_exponent); });
}

std::vector<bool> delta_lobe_materials(const scene::Scene& scene) {
    return per_material(scene, [](const scene::Material& m) { return has_delta_lobe(m); });
}

bool has_caustic_casters(const scene::Scene& scene, float sharp_exponent) {
    return std::any_of(scene.materials.begin(), scene.materials.end(),
                       [&](const scene::Material& m) { return is_caustic_caster(m, sharp_exponent); });
}

std::vector<BoundingSphere> caustic_caster_bounds(const scene::Scene& scene, float sharp_exponent) {
    const std::vector<bool> casters = caustic_caster_materials(scene, sharp_exponent);
    auto caster = [&](const scene::Shape& s) { return material_flag(casters, s.material); };
    std::vector<BoundingSphere> out;
    auto add = [&](const BoundingSphere& b) {
        if (b.radius >= 0) out.push_back(b);
    };
    for (const scene::Shape& s : scene.shapes)
        if (caster(s)) add(world_sphere(s, s.to_world));
    for (const scene::Instance& inst : scene.instances) {
        if (inst.object < 0 || size_t(inst.object) >= scene.objects.size()) continue;
        for (const scene::Shape& s : scene.objects[size_t(inst.object)].shapes)
            if (caster(s)) add(world_sphere(s, inst.to_world * s.to_world));
    }
    return out;
}

ProjectionMap::ProjectionMap(const PhotonScene& ps, int resolution) : res_(std::max(resolution, 1)) {
    const std::vector<BoundingSphere> casters = caustic_caster_bounds(ps.scene, ps.sharp_exponent);
    const int R = res_;
    // Where a light's rays go does not depend on wavelength: the probes take any wavelengths.
    const Wavelengths probe_wavelengths = Wavelengths::visible(0.5f);
    const uint32_t n_cells = uint32_t(R) * uint32_t(R);
    const float below_one = std::nextafter(1.0f, 0.0f);
    std::vector<float> weights;
    double total_power = 0, marked_power = 0;
    for (size_t li = 0; li < ps.lights.size(); ++li) {
        const shading::Light& L = ps.lights[li];
        LightCells lc;
        const double power = std::max(0.0f, L.power().average());
        if (!casters.empty()) {
            // The light must emit from a small region with directions set by u_dir alone: probe a
            // lattice of u_pos for a few u_dir values.
            const Vec2 dir_probes[3] = {{0.13f, 0.21f}, {0.71f, 0.87f}, {0.42f, 0.58f}};
            constexpr int P = 17;
            Bounds origins;
            bool separable = !L.is_infinite();
            Vec3 ref_dir[3];
            for (int k = 0; k < 3; ++k)
                ref_dir[k] = L.sample_Le({0.5f, 0.5f}, dir_probes[k], probe_wavelengths).ray.dir;
            for (int y = 0; y < P && separable; ++y)
                for (int x = 0; x < P && separable; ++x) {
                    const Vec2 up(std::min(float(x) / (P - 1), below_one),
                                  std::min(float(y) / (P - 1), below_one));
                    for (int k = 0; k < 3; ++k) {
                        const shading::LightLeSample s = L.sample_Le(up, dir_probes[k], probe_wavelengths);
                        if (!same(s.ray.dir, ref_dir[k], 1e-4f)) separable = false;
                        origins.extend(s.ray.origin);
                    }
                }
            if (separable && !origins.empty()) {
                // 10 % margin: the lattice need not hit the light's extreme points exactly.
                BoundingSphere light = sphere_of(origins);
                light.radius *= 1.1f;
                const Vec2 up_ref(0.5f, 0.5f);
                constexpr int M = 5;  // probes per cell side
                Vec3 d[M * M];
                for (uint32_t c = 0; c < n_cells; ++c) {
                    const float x0 = float(c % uint32_t(R)) / float(R),
                                y0 = float(c / uint32_t(R)) / float(R);
                    const float span = 1.0f / float(R) - 1e-6f;
                    Vec3 axis(0.0f);
                    for (int j = 0; j < M; ++j)
                        for (int i = 0; i < M; ++i) {
                            const Vec2 ud(std::min(x0 + span * float(i) / (M - 1), below_one),
                                          std::min(y0 + span * float(j) / (M - 1), below_one));
                            d[j * M + i] = normalize(L.sample_Le(up_ref, ud, probe_wavelengths).ray.dir);
                            axis += d[j * M + i];
                        }
                    if (!(length_squared(axis) > 0)) {
                        lc.cells.push_back(c);  // degenerate cell: keep it (conservative)
                        continue;
                    }
                    axis = normalize(axis);
                    // Half-angle of the cell's cone: farthest probe from the axis plus the largest
                    // gap between neighbouring probes (every direction of the cell lies within
                    // that gap of some probe).
                    float half = 0, gap = 0;
                    for (int j = 0; j < M; ++j)
                        for (int i = 0; i < M; ++i) {
                            const Vec3 v = d[j * M + i];
                            half = std::max(half, angle_between(axis, v));
                            if (i + 1 < M) gap = std::max(gap, angle_between(v, d[j * M + i + 1]));
                            if (j + 1 < M) gap = std::max(gap, angle_between(v, d[(j + 1) * M + i]));
                        }
                    half += gap;
                    bool hit = false;
                    for (const BoundingSphere& b : casters) {
                        const Vec3 to = b.center - light.center;
                        const float dist = length(to), r = b.radius + light.radius;
                        if (dist <= r || angle_between(axis, to / dist) <= half + std::asin(r / dist)) {
                            hit = true;
                            break;
                        }
                    }
                    if (hit) lc.cells.push_back(c);
                }
                lc.fraction = float(lc.cells.size()) / float(n_cells);
            } else {
                lc.full = true;
                lc.fraction = 1;
                lc.cells.resize(n_cells);
                for (uint32_t c = 0; c < n_cells; ++c) lc.cells[c] = c;
            }
        }
        total_power += power;
        marked_power += power * lc.fraction;
        weights.push_back(float(power * lc.fraction));
        lights_.push_back(std::move(lc));
    }
    fraction_ = total_power > 0 ? marked_power / total_power : 0;
    if (fraction_ > 0) choose_ = shading::Distribution1D(weights);
}

bool ProjectionMap::emit(const PhotonScene& ps, Sampler& sampler, const Wavelengths& lambda, Ray& ray,
                         Spectrum& power, int& medium) const {
    if (empty()) return false;
    float pmf = 0;
    const size_t li = choose_.sample_discrete(sampler.next(), &pmf);
    const LightCells& lc = lights_[li];
    if (!(pmf > 0) || lc.cells.empty()) return false;
    const uint32_t c = lc.cells[sampler.next_index(uint32_t(lc.cells.size()))];
    const Vec2 j = sampler.next2();
    const Vec2 u_pos = sampler.next2();
    const float below_one = std::nextafter(1.0f, 0.0f);
    const Vec2 u_dir(std::min((float(c % uint32_t(res_)) + j.x) / float(res_), below_one),
                     std::min((float(c / uint32_t(res_)) + j.y) / float(res_), below_one));
    const shading::LightLeSample s = ps.lights[li].sample_Le(u_pos, u_dir, lambda);
    if (s.weight.is_black() || !s.weight.is_finite()) return false;
    ray = s.ray;
    power = s.weight * (lc.fraction / pmf);
    medium = ps.lights.emission_medium(li, s);
    return true;
}

namespace detail {
bool emit_projected(const ProjectionMap& map, const PhotonScene& ps, Sampler& sampler,
                    const Wavelengths& lambda, Ray& ray, Spectrum& power, int& medium) {
    return map.emit(ps, sampler, lambda, ray, power, medium);
}
}  // namespace detail

}  // namespace phos::photon
