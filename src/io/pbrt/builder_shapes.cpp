// SceneBuilder: the Shape directive. Meshes (trianglemesh, bilinearmesh, plymesh) are baked into
// world space with pbrt's orientation rules resolved into the triangle winding; spheres, disks and
// cylinders keep the current transform as to_world. Area lights attach here.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/error.h"
#include "core/log.h"
#include "io/mesh/mesh_io.h"
#include "io/pbrt/builder.h"
#include "io/pbrt/curves.h"
#include "scene/bilinear_patch.h"
#include "scene/loop_subdivision.h"
#include "scene/mesh_displacement.h"
#include "scene/texture_eval.h"

namespace phos::io::pbrt {
namespace {

// Moves an object-space mesh into the space of `t` and orders each triangle counter-clockwise
// around pbrt's surface normal: the interpolated shading normal N when given (pbrt makes the
// geometric normal follow it), otherwise the winding normal flipped by ReverseOrientation XOR a
// handedness-swapping transform. N itself is flipped by ReverseOrientation, as pbrt does.
float bake_mesh(scene::TriangleMesh& mesh, const Transform& t, bool reverse) {
    for (Vec3& p : mesh.positions) p = t.point(p);
    for (Vec3& n : mesh.normals) {
        n = t.normal(n);
        const float len = length(n);
        if (len > 0) n = n / len;
        if (reverse) n = -n;
    }
    const bool flip = reverse != t.swaps_handedness();
    float area = 0;
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        uint32_t* tri = &mesh.indices[i];
        const Vec3 p0 = mesh.positions[tri[0]], p1 = mesh.positions[tri[1]], p2 = mesh.positions[tri[2]];
        const Vec3 ng = cross(p1 - p0, p2 - p0);
        area += 0.5f * length(ng);
        bool swap = flip;
        if (!mesh.normals.empty()) {
            const Vec3 ns = mesh.normals[tri[0]] + mesh.normals[tri[1]] + mesh.normals[tri[2]];
            swap = dot(ng, ns) < 0;
        }
        if (swap) std::swap(tri[1], tri[2]);
    }
    // Exact bilinear patches keep pbrt's corner order: their front is dp/du x dp/dv, flipped by the
    // same rule (or, with N, the side of the interpolated N, which the accelerator applies).
    mesh.patches_flipped = flip;
    for (size_t i = 0; i + 3 < mesh.patches.size(); i += 4) {
        const uint32_t* q = &mesh.patches[i];
        area += float(scene::patch_area(
            {mesh.positions[q[0]], mesh.positions[q[1]], mesh.positions[q[2]], mesh.positions[q[3]]}));
    }
    return area;
}

// Linear scale factor of a transform (cube root of |det|), for areas of transformed quadrics.
float linear_scale(const Transform& t) {
    const Vec3 x = t.vector({1, 0, 0}), y = t.vector({0, 1, 0}), z = t.vector({0, 0, 1});
    return std::cbrt(std::fabs(dot(x, cross(y, z))));
}

}  // namespace

void SceneBuilder::add_shape(scene::Shape shape, float area, const Loc& loc) {
    subsurface_interior(shape, loc);  // builder_subsurface.cpp
    if (object_ >= 0) {
        if (gs_.area_light)
            warn_once("instanced area light", loc,
                      "area lights inside ObjectBegin/ObjectEnd are not supported (the "
                      "shapes are kept, without emission)");
        scene_.objects[size_t(object_)].shapes.push_back(std::move(shape));
        return;
    }
    if (!gs_.area_light || shape.kind == scene::Shape::Kind::Curves) {
        scene_.shapes.push_back(std::move(shape));
        return;
    }
    const AreaLight& al = *gs_.area_light;
    Rgb L = al.L;
    std::optional<spectrum::Distribution> emission = al.spectrum;
    int texture = al.texture;
    // Meshes, spheres, disks and cylinders have pbrt's (u, v) for the image (shading/area_light.h).
    using K = scene::Shape::Kind;
    if (texture >= 0 && shape.kind != K::Mesh && shape.kind != K::Sphere && shape.kind != K::Disk &&
        shape.kind != K::Cylinder) {
        warn_once("area light image on an analytic shape", al.loc,
                  "image emission (\"filename\") is supported on meshes, spheres, disks and cylinders; "
                  "other shapes emit the image's mean radiance");
        L = L * al.image_mean;
        texture = -1;
    }
    if (al.power > 0) {
        // pbrt-v4: scale so that the emitted flux pi * area * L (twice if two-sided) equals `power`;
        // with an image, L is its mean luminance.
        const float k =
            kPi * area * (al.two_sided ? 2.0f : 1.0f) * (al.texture >= 0 ? al.image_luminance : 1.0f);
        if (!(k > 0)) loc.fail("area light with \"power\" on a shape of zero area");
        L = L * (al.power / k);
        if (emission) emission = emission->scaled(al.power / k);
    }
    // Not needed to render an area light, but filled as other loaders do: a representative point
    // and the mean emitting direction (area-weighted normal) for meshes.
    Vec3 position = shape.to_world.point(shape.center), direction{0, -1, 0};
    if (shape.kind == scene::Shape::Kind::Mesh && !shape.mesh.indices.empty()) {
        const scene::TriangleMesh& m = shape.mesh;
        Vec3 sum_n{0.0f}, sum_p{0.0f};
        for (size_t i = 0; i + 2 < m.indices.size(); i += 3) {
            const Vec3 p0 = m.positions[m.indices[i]], p1 = m.positions[m.indices[i + 1]],
                       p2 = m.positions[m.indices[i + 2]];
            const Vec3 n = cross(p1 - p0, p2 - p0);
            sum_n += n;
            sum_p += (p0 + p1 + p2) * (length(n) / 3.0f);
        }
        const float total = 2.0f * area;  // the weights |n| sum to twice the area
        if (total > 0) position = sum_p / total;
        if (length(sum_n) > 0) direction = normalize(sum_n);
    }
    const int index = scene_.add_area_light(std::move(shape), L, al.two_sided, std::move(emission));
    scene::Light& light = scene_.lights[size_t(index)];
    light.position = position;
    light.direction = direction;
    light.texture = texture;
    light.medium = gs_.outside;  // photons leave into the outside medium
    light.medium_declared = gs_.media_declared;
    light.origin = loc.str();  // the Shape that emits
}

// pbrt-v4's plymesh displacement: the object-space mesh refined until every edge is shorter than
// "edgelength" (default 1) measured in world space, each vertex moved along its normal by the
// float texture (or constant) "displacement" at its uv, the normals recomputed.
void SceneBuilder::displace(scene::TriangleMesh& mesh, const ParamList& params, const Param& dp,
                            const std::string& d) {
    // pbrt-v4 scales every edge length by Option "displacementedgescale".
    const float edge = params.get_float("edgelength", 1.0f) * displacement_edge_scale_;
    if (!(edge > 0) || !std::isfinite(edge))
        params.find("edgelength")->loc.fail(d + ": \"edgelength\" must be a positive length");
    int texture = -1;
    float constant = 0;
    if (dp.type == "texture") {
        const auto it = float_textures_.find(dp.strings[0]);
        if (it == float_textures_.end()) dp.loc.fail(d + ": unknown float texture \"" + dp.strings[0] + "\"");
        texture = it->second;
    } else {
        constant = params.get_float("displacement", 0.0f);
        if (!std::isfinite(constant)) dp.loc.fail(d + ": \"displacement\" is not finite");
    }
    const Transform& t = gs_.ctm;
    try {
        scene::displace_mesh(
            mesh, edge, [&](Vec3 a, Vec3 b) { return length(t.point(a) - t.point(b)); },
            [&](Vec3, Vec3, Vec2 uv) {
                return texture < 0 ? constant : scene::eval_texture(scene_, texture, uv).average();
            },
            size_t(1) << 25);
    } catch (const InputError& e) {
        dp.loc.fail(d + ": " + e.what());
    }
}

void SceneBuilder::shape(const std::string& type, const ParamList& params, const Loc& loc) {
    require_world(true, "Shape", loc);
    const std::string d = "Shape \"" + type + "\"";
    scene::Shape s;
    s.material = current_material();
    s.media = {gs_.inside, gs_.outside};
    s.origin = loc.filename() + ":" + std::to_string(loc.line);
    if (const Param* a = params.find("alpha")) {
        // pbrt-v4's cut-out: a float value in [0, 1] or a float texture (scene::Shape::alpha).
        if (a->type == "texture") {
            const auto it = float_textures_.find(a->strings[0]);
            if (it == float_textures_.end())
                a->loc.fail(d + ": unknown float texture \"" + a->strings[0] + "\"");
            s.alpha_texture = it->second;
        } else {
            s.alpha = params.get_float("alpha", 1.0f);
            if (!(s.alpha >= 0 && s.alpha <= 1)) a->loc.fail(d + ": \"alpha\" must be in [0, 1]");
        }
    }
    for (const char* p : {"emission", "displacement", "edgelength"})
        if (type == "plymesh" && std::string(p) != "emission")
            continue;  // plymesh reads them below
        else if (const Param* q = params.find(p))
            warn(q->loc, d + ": \"" + std::string(p) + "\" is not supported (ignored)");

    auto mesh_from_params = [&](bool bilinear) {
        const Param* pp = params.find("P");
        if (!pp) loc.fail(d + ": missing \"point3 P\"");
        scene::TriangleMesh m;
        m.positions = params.get_point3s("P");
        const size_t n = m.positions.size();
        const size_t per = bilinear ? 4 : 3;
        std::vector<int> idx = params.get_ints("indices");
        if (!params.has("indices")) {
            if (n != per)
                loc.fail(d + ": \"integer indices\" is required unless there are exactly " +
                         std::to_string(per) + " vertices");
            for (size_t i = 0; i < per; ++i) idx.push_back(int(i));
        }
        if (idx.empty() || idx.size() % per != 0)
            loc.fail(d + ": the number of indices (" + std::to_string(idx.size()) +
                     ") is not a positive multiple of " + std::to_string(per));
        for (int i : idx)
            if (i < 0 || size_t(i) >= n)
                loc.fail(d + ": vertex index " + std::to_string(i) + " out of range (" + std::to_string(n) +
                         " vertices in P)");
        m.normals = params.get_point3s("N");
        if (!m.normals.empty() && m.normals.size() != n)
            loc.fail(d + ": \"N\" has " + std::to_string(m.normals.size()) + " normals for " +
                     std::to_string(n) + " vertices");
        m.uvs = params.get_point2s("uv");
        if (m.uvs.empty()) m.uvs = params.get_point2s("st");
        if (!m.uvs.empty() && m.uvs.size() != n)
            loc.fail(d + ": \"uv\" has " + std::to_string(m.uvs.size()) + " entries for " +
                     std::to_string(n) + " vertices");
        for (const Vec3& p : m.positions)
            if (!is_finite(p)) pp->loc.fail(d + ": non-finite vertex position");
        if (const Param* q = params.find("S"))
            warn(q->loc, d + ": tangents \"S\" are not supported (ignored)");
        if (const Param* q = params.find("faceIndices")) q->used = true;  // only pbrt's ptex uses it
        if (!bilinear) {
            m.indices.assign(idx.begin(), idx.end());
        } else {
            // pbrt's patch vertex order is p00 p10 p01 p11. A planar patch is the quadrilateral of
            // its triangles (p00 p10 p11) and (p00 p11 p01), which keep the orientation of
            // dp/du x dp/dv; the others are intersected exactly as bilinear patches.
            for (size_t i = 0; i < idx.size(); i += 4) {
                const uint32_t a = uint32_t(idx[i]), b = uint32_t(idx[i + 1]), c = uint32_t(idx[i + 2]),
                               e = uint32_t(idx[i + 3]);
                if (scene::patch_is_planar({m.positions[a], m.positions[b], m.positions[c], m.positions[e]}))
                    m.indices.insert(m.indices.end(), {a, b, e, a, e, c});
                else
                    m.patches.insert(m.patches.end(), {a, b, c, e});
            }
        }
        return m;
    };

    float area = 0;
    const Transform& t = gs_.ctm;
    const float ls = linear_scale(t);
    if (type == "trianglemesh" || type == "bilinearmesh" || type == "plymesh") {
        s.kind = scene::Shape::Kind::Mesh;
        if (type == "plymesh") {
            const Param* fp = params.find("filename");
            if (!fp) loc.fail(d + ": missing \"string filename\"");
            const std::string path = resolve(params.get_string("filename", ""), fp->loc);
            std::error_code ec;
            if (!std::filesystem::exists(path, ec)) fp->loc.fail(d + ": cannot open '" + path + "'");
            try {
                s.mesh = read_ply(path);
            } catch (ParseError& e) {  // at the PLY file's own line; also where it is named
                fp->loc.add_to(e);
                throw;
            }
            if (const Param* dp = params.find("displacement")) displace(s.mesh, params, *dp, d);
        } else {
            s.mesh = mesh_from_params(type == "bilinearmesh");
        }
        area = bake_mesh(s.mesh, t, gs_.reverse_orientation);
        s.to_world = Transform();  // baked
    } else if (type == "sphere") {
        s.kind = scene::Shape::Kind::Sphere;
        s.radius = params.get_float("radius", 1.0f);
        if (!(s.radius > 0)) params.find("radius")->loc.fail(d + ": radius must be positive");
        // pbrt-v4 clamps: z range ordered and within [-r, r], phimax within [0, 360] degrees.
        const float zmin = params.get_float("zmin", -s.radius), zmax = params.get_float("zmax", s.radius);
        const float z_min = std::clamp(std::min(zmin, zmax), -s.radius, s.radius);
        const float z_max = std::clamp(std::max(zmin, zmax), -s.radius, s.radius);
        const float phi_deg = std::clamp(params.get_float("phimax", 360.0f), 0.0f, 360.0f);
        const float phi_max = phi_deg < 360.0f ? phi_deg * (kPi / 180.0f) : 2 * kPi;
        s.center = Vec3(0.0f);
        s.to_world = t;
        s.reverse_orientation = gs_.reverse_orientation;
        // pbrt's object space and (u, v): the pole along +z, phi from +x, v = 0 at the -z pole.
        s.axis = {0, 0, 1};
        s.pbrt_uv = true;
        area = 4 * kPi * s.radius * s.radius * ls * ls;
        if (z_min > -s.radius || z_max < s.radius || phi_deg < 360.0f) {
            if (!(z_max > z_min) || !(phi_max > 0)) {
                warn(loc, d + ": the partial sphere has no area (skipped)");
                done(params, d);
                return;
            }
            // pbrt's object space: the pole along +z, phi from +x (the frame of a +z axis).
            s.partial = true;
            s.axis = {0, 0, 1};
            s.z_min = z_min, s.z_max = z_max, s.phi_max = phi_max;
            area = phi_max * s.radius * (z_max - z_min) * ls * ls;
        }
    } else if (type == "disk") {
        s.kind = scene::Shape::Kind::Disk;
        s.radius = params.get_float("radius", 1.0f);
        s.inner_radius = params.get_float("innerradius", 0.0f);
        if (!(s.radius > 0)) params.find("radius")->loc.fail(d + ": radius must be positive");
        if (s.inner_radius < 0 || s.inner_radius >= s.radius)
            params.find("innerradius")->loc.fail(d + ": innerradius must be in [0, radius)");
        if (params.get_float("phimax", 360.0f) < 360.0f)
            warn(loc, d + ": partial disks (phimax) are unsupported; the full disk is used");
        s.center = {0, 0, params.get_float("height", 0.0f)};
        s.normal = {0, 0, 1};
        s.to_world = t;
        s.reverse_orientation = gs_.reverse_orientation;
        area = kPi * (s.radius * s.radius - s.inner_radius * s.inner_radius) * ls * ls;
    } else if (type == "cylinder") {
        s.kind = scene::Shape::Kind::Cylinder;
        s.radius = params.get_float("radius", 1.0f);
        const float zmin = params.get_float("zmin", -1.0f), zmax = params.get_float("zmax", 1.0f);
        if (!(s.radius > 0)) params.find("radius")->loc.fail(d + ": radius must be positive");
        if (!(zmax != zmin)) loc.fail(d + ": zmin and zmax must differ");
        if (params.get_float("phimax", 360.0f) < 360.0f)
            warn(loc, d + ": partial cylinders (phimax) are unsupported; the full cylinder is used");
        s.center = {0, 0, 0.5f * (zmin + zmax)};
        s.axis = {0, 0, 1};
        s.height = std::fabs(zmax - zmin);
        s.capped = false;
        s.to_world = t;
        s.reverse_orientation = gs_.reverse_orientation;
        area = 2 * kPi * s.radius * s.height * ls * ls;
    } else if (type == "loopsubdiv") {
        // pbrt-v4: subdivided at load into a triangle mesh with limit positions and normals.
        s.kind = scene::Shape::Kind::Mesh;
        const Param* pp = params.find("P");
        if (!pp) loc.fail(d + ": missing \"point3 P\"");
        if (!params.has("indices")) loc.fail(d + ": missing \"integer indices\"");
        const int levels = params.get_int("levels", 3);
        const Param* lp = params.find("levels");
        if (levels < 0) lp->loc.fail(d + ": \"levels\" must not be negative");
        const std::vector<int> idx = params.get_ints("indices");
        // 4^levels triangles per input triangle: refuse meshes that could not be held.
        if (levels > 12 || double(idx.size() / 3) * std::pow(4.0, levels) > double(1u << 28))
            (lp ? lp->loc : loc)
                .fail(d + ": " + std::to_string(idx.size() / 3) + " triangles subdivided " +
                      std::to_string(levels) + " times is too many triangles");
        std::vector<uint32_t> indices;
        indices.reserve(idx.size());
        for (int i : idx) {
            if (i < 0) params.find("indices")->loc.fail(d + ": negative vertex index " + std::to_string(i));
            indices.push_back(uint32_t(i));
        }
        const std::vector<Vec3> positions = params.get_point3s("P");
        for (const Vec3& p : positions)
            if (!is_finite(p)) pp->loc.fail(d + ": non-finite vertex position");
        try {
            s.mesh = scene::loop_subdivide(positions, indices, levels);
        } catch (const InputError& e) {
            params.find("indices")->loc.fail(d + ": " + e.what());
        }
        area = bake_mesh(s.mesh, t, gs_.reverse_orientation);
        s.to_world = Transform();  // baked
    } else if (type == "curve") {
        s.kind = scene::Shape::Kind::Curves;
        s.curves = read_curves(params, loc, d, [&](const Loc& l, const std::string& m) { warn(l, m); });
        s.to_world = t;
        s.reverse_orientation = gs_.reverse_orientation;
        if (gs_.area_light)
            warn_once("curve area light", loc,
                      "area lights on curves are not supported (pbrt-v4 cannot sample points on curves); "
                      "curves do not emit");
    } else {
        warn(loc, d + " is not supported (the shape is skipped)");
        params.mark_all_used();
        return;
    }
    done(params, d);
    add_shape(std::move(s), area, loc);
}

}  // namespace phos::io::pbrt
