// The `.scene` commands: objects (mesh, sphere), camera, point and rectangular area lights given
// by flux, resolution, sky and the scene's medium; and, once all is read, the media on either side
// of every boundary (docs/formats/scene.md).
#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/log.h"
#include "core/spelling.h"
#include "io/scene_format/containment.h"
#include "io/scene_format/reader.h"

namespace phos::io::scene_format {

namespace {

const std::vector<std::string> kCommands = {"mesh",       "sphere", "camera", "light",
                                            "resolution", "sky",    "medium"};

}  // namespace

void Reader::scene_command(const Line& l) {
    const std::string& k = l.keyword.text;
    if (k == "mesh") {
        require_args(l, 1, "1 argument: file.mesh");
        read_mesh(file_argument(l, 0, "mesh file"));
    } else if (k == "sphere") {
        cmd_sphere(l);
    } else if (k == "camera") {
        cmd_camera(l);
    } else if (k == "light") {
        cmd_light(l);
    } else if (k == "resolution") {
        const std::vector<double> v = numbers(l, 2, "w h");
        for (size_t i = 0; i < 2; ++i)
            if (!(v[i] >= 1 && v[i] <= scene::RenderSettings::kMaxResolution && v[i] == std::floor(v[i])))
                fail(l.args[i], "resolution: expected a whole number of pixels in [1, " +
                                    std::to_string(scene::RenderSettings::kMaxResolution) + "], got '" +
                                    l.args[i].text + "'");
        if (scene_.settings.width) log::warn(where(l.keyword) + ": a second resolution replaces the first");
        scene_.settings.width = int(v[0]);
        scene_.settings.height = int(v[1]);
    } else if (k == "sky") {
        const std::vector<double> v = numbers(l, 3, "r g b");
        require_non_negative(l, v, 0, 3);
        for (const scene::Light& light : scene_.lights)
            if (light.kind == scene::Light::Kind::Infinite)
                fail(l.keyword, "sky: the scene already has a sky");
        if (v[0] + v[1] + v[2] > 0) {
            // Radiance of every ray that escapes: a constant environment light, which also lights the
            // scene and emits photons.
            scene::Light sky;
            sky.kind = scene::Light::Kind::Infinite;
            sky.color = rgb_at(v, 0);
            scene_.lights.push_back(sky);
        }
    } else if (k == "medium") {
        cmd_medium(l);
    } else {
        const std::string guess = nearest_name(k, kCommands);
        fail(l.keyword,
             "unknown command '" + k + "'" + (guess.empty() ? "" : "; did you mean '" + guess + "'?") +
                 " (commands: mesh, sphere, camera, light point, light area, resolution, sky, medium)");
    }
}

void Reader::cmd_sphere(const Line& l) {
    require_args(l, 5, "5 arguments: r cx cy cz file.mat");
    const Line numeric{l.keyword, {l.args.begin(), l.args.begin() + 4}, l.args[3].col + 1};
    const std::vector<double> v = numbers(numeric, 4, "r cx cy cz");
    if (!(v[0] > 0)) fail(l.args[0], "sphere: the radius must be positive, got '" + l.args[0].text + "'");
    const MatFile& mat = read_mat(file_argument(l, 4, "material file"));
    scene::Shape s;
    s.kind = scene::Shape::Kind::Sphere;
    s.center = vec3_at(v, 1);
    s.radius = float(v[0]);
    add_object(std::move(s), mat, l.keyword);
}

void Reader::cmd_camera(const Line& l) {
    const std::vector<double> v = numbers(l, 10, "ex ey ez  lx ly lz  ux uy uz  d");
    const Vec3 eye = vec3_at(v, 0), look = vec3_at(v, 3), up = vec3_at(v, 6);
    if (!(length(look - eye) > 1e-6f)) fail(l.args[3], "camera: the look-at point is the eye");
    if (!(length(up) > 0)) fail(l.args[6], "camera: the up vector is zero");
    if (length(cross(normalize(look - eye), normalize(up))) < 1e-6f)
        fail(l.args[6], "camera: the up vector is parallel to the viewing direction");
    if (!(v[9] > 0))
        fail(l.args[9], "camera: d (the distance to an image plane of height 2) must be positive, got '" +
                            l.args[9].text + "'");
    if (camera_seen_) log::warn(where(l.keyword) + ": a second camera replaces the first");
    camera_seen_ = true;
    scene::Camera c;
    c.eye = eye;
    c.forward = look - eye;
    c.up = up;
    c.fov = float(2 * std::atan(1 / v[9]));  // vertical: the image plane at distance d has height 2
    c.fov_vertical = true;
    scene_.camera = c;
}

void Reader::cmd_light(const Line& l) {
    if (l.args.empty()) fail_at(l.keyword.line, l.end_col, "light: expected a type, 'point' or 'area'");
    const Token type = l.args[0];
    const Line rest{type, {l.args.begin() + 1, l.args.end()}, l.end_col};
    scene::Light light;
    light.medium = -1;  // set by finish(): lights sit in the scene's medium
    light.origin = where(l.keyword);
    if (type.text == "point") {
        const std::vector<double> v = numbers(rest, 6, "px py pz  r g b");
        require_non_negative(rest, v, 3, 3);
        light.kind = scene::Light::Kind::Point;
        light.position = vec3_at(v, 0);
        light.color = rgb_at(v, 3) * (1.0f / (4.0f * kPi));  // flux -> intensity of an isotropic source
        scene_.lights.push_back(light);
    } else if (type.text == "area") {
        const std::vector<double> v = numbers(rest, 11, "px py pz  nx ny nz  r g b  w h");
        const Vec3 n = vec3_at(v, 3);
        if (!(length(n) > 0)) fail(rest.args[3], "light area: the normal is zero");
        require_non_negative(rest, v, 6, 3);
        for (size_t i = 9; i < 11; ++i)
            if (!(v[i] > 0))
                fail(rest.args[i], std::string("light area: the ") + (i == 9 ? "width" : "height") +
                                       " must be positive, got '" + rest.args[i].text + "'");
        // Width along world x projected onto the light's plane (z when n is along x), height along
        // n x width; corners counter-clockwise seen from n.
        const Vec3 nn = normalize(n);
        Vec3 wdir = Vec3(1, 0, 0) - nn * nn.x;
        if (length(wdir) < 1e-4f) wdir = Vec3(0, 0, 1) - nn * nn.z;
        wdir = normalize(wdir);
        const Vec3 hdir = cross(nn, wdir);
        const float w = float(v[9]), h = float(v[10]);
        const Vec3 c = vec3_at(v, 0), hw = wdir * (0.5f * w), hh = hdir * (0.5f * h);
        scene::Shape s;
        s.kind = scene::Shape::Kind::Mesh;
        s.mesh.positions = {c - hw - hh, c + hw - hh, c + hw + hh, c - hw + hh};
        s.mesh.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        s.mesh.indices = {0, 1, 2, 0, 2, 3};
        if (emitter_material_ < 0) {
            // The light's surface emits but does not reflect.
            scene::Material m;
            m.name = "area light (black)";
            emitter_material_ = int(scene_.materials.size());
            scene_.materials.push_back(m);
        }
        s.material = emitter_material_;
        s.origin = where(l.keyword);
        // Flux of a one-sided Lambertian emitter: Phi = pi * A * L.
        const Rgb L = rgb_at(v, 6) * float(1.0 / (double(kPi) * v[9] * v[10]));
        const int index = scene_.add_area_light(std::move(s), L);
        scene_.lights[size_t(index)].position = c;
        scene_.lights[size_t(index)].direction = nn;
        scene_.lights[size_t(index)].origin = where(l.keyword);
    } else {
        fail(type, "light: unknown type '" + type.text + "' (point or area)");
    }
}

void Reader::cmd_medium(const Line& l) {
    require_args(l, 1, "1 argument: file.mat");
    if (scene_medium_ >= 0) fail(l.keyword, "medium: the scene already has a medium");
    const MatFile& mat = read_mat(file_argument(l, 0, "material file"));
    if (mat.medium < 0) {
        log::warn(where(l.keyword) + ": medium: '" + l.args[0].text +
                  "' has no absorption or scattering; the scene stays clear");
        return;
    }
    const scene::Material& m = scene_.materials[size_t(mat.material)];
    if (!m.interface_only || mat.textured || !mat.emission.is_black())
        log::warn(where(l.keyword) + ": medium: only the absorption, scattering and phase of '" +
                  l.args[0].text + "' fill the scene; its surface terms are ignored here");
    scene_medium_ = mat.medium;
}

void Reader::add_object(scene::Shape shape, const MatFile& mat, const Token& at) {
    shape.material = mat.material;
    shape.origin = where(at);
    const int index = int(scene_.shapes.size());
    if (!mat.emission.is_black())
        scene_.lights[size_t(scene_.add_area_light(std::move(shape), mat.emission))].origin = where(at);
    else
        scene_.shapes.push_back(std::move(shape));
    if (mat.boundary) boundaries_.emplace_back(index, mat.medium);
}

void Reader::finish() {
    // A boundary has its material's medium (or none) inside; outside, the medium of the innermost
    // boundary containing it, else the scene's. Other surfaces are no transition: rays keep the
    // medium they travel in. The camera and the lights sit in the medium around them.
    std::vector<int> bounds;
    for (const auto& [shape, inside] : boundaries_) {
        bounds.push_back(shape);
        scene_.shapes[size_t(shape)].media.inside = inside;
    }
    const auto medium_at = [&](Vec3 p, int skip) {
        const int c = innermost_container(scene_.shapes, bounds, p, skip);
        return c < 0 ? scene_medium_ : scene_.shapes[size_t(c)].media.inside;
    };
    for (int shape : bounds)
        scene_.shapes[size_t(shape)].media.outside =
            medium_at(reference_point(scene_.shapes[size_t(shape)]), shape);
    scene_.camera_medium = scene_.camera ? medium_at(scene_.camera->eye, -1) : scene_medium_;
    for (scene::Light& light : scene_.lights) {
        light.medium_declared = true;  // the containment rule places every light
        if (light.kind == scene::Light::Kind::Point) light.medium = medium_at(light.position, -1);
        if (light.kind == scene::Light::Kind::Area) {
            const scene::Shape& s = scene_.shapes[size_t(light.shape)];
            Vec3 c = s.center;
            if (s.kind == scene::Shape::Kind::Mesh) {
                c = Vec3(0.0f);
                for (const Vec3& p : s.mesh.positions) c += s.to_world.point(p);
                c = c * (1.0f / float(std::max<size_t>(s.mesh.positions.size(), 1)));
            }
            light.medium = medium_at(c, light.shape);
        }
    }
}

}  // namespace phos::io::scene_format
