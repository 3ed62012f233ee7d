// The `.scn` commands: each reads its fixed arguments, validates them, and appends its camera,
// material, shape or light to the scene with phos's physically based reading (docs/formats/scn.md).
#include <cctype>
#include <cmath>

#include "core/error.h"
#include "core/format.h"
#include "core/log.h"
#include "io/mesh/mesh_io.h"
#include "io/scn/scn_parser.h"
#include "io/text/image_texture.h"

namespace phos::io::scn {
namespace fs = std::filesystem;

namespace {

// Length of the cross product of two vectors given as doubles (exact enough to tell a thin but
// real triangle from collinear points typed into a file).
double cross_length(const double* a, const double* b) {
    const double x = a[1] * b[2] - a[2] * b[1];
    const double y = a[2] * b[0] - a[0] * b[2];
    const double z = a[0] * b[1] - a[1] * b[0];
    return std::sqrt(x * x + y * y + z * z);
}

}  // namespace

int Parser::add_shape(scene::Shape shape, const Token& cmd) {
    shape.to_world = to_world();
    shape.origin = where(cmd);
    scene_.shapes.push_back(std::move(shape));
    return int(scene_.shapes.size()) - 1;
}

void Parser::cmd_camera(const Token& cmd) {
    const Args a = numbers(cmd, 12, "ex ey ez  tx ty tz  ux uy uz  fov  near far");
    const Vec3 t = direction(a, 3, "camera: the view direction");
    const Vec3 u = direction(a, 6, "camera: the up direction");
    if (length(cross(t, u)) < 1e-6f)
        fail(a.tok[6], "camera: the up direction is parallel to the view direction");
    const double half_fov = a.v[9];
    if (!(half_fov > 0 && half_fov < double(kPi) / 2))
        fail(a.tok[9], "camera: fov is the half angle in radians and must be in (0, pi/2), got '" +
                           a.tok[9].text + "'");
    if (a.v[10] < 0) fail(a.tok[10], "camera: near must not be negative, got '" + a.tok[10].text + "'");
    if (!(a.v[11] > a.v[10])) fail(a.tok[11], "camera: far must be greater than near");
    if (camera_seen_) log::warn(where(cmd) + ": a second camera replaces the first");
    camera_seen_ = true;

    // A camera inside a group is moved with it, like lights.
    const Transform& xf = to_world();
    scene::Camera c;
    c.eye = xf.point(a.vec(0));
    c.forward = xf.vector(a.vec(3));
    c.up = xf.vector(a.vec(6));
    c.fov = float(2 * half_fov);  // the file gives the half angle, Camera holds the full one
    c.near_clip = a.f(10);
    c.far_clip = a.f(11);
    scene_.camera = c;
}

void Parser::cmd_material(const Token& cmd) {
    const Args a = numbers(cmd, 17, "ka kd ks kt e as r g b, then n ir");
    const char* names[] = {"material: ka", "material: kd", "material: ks", "material: kt", "material: e"};
    for (int k = 0; k < 5; ++k) require_non_negative(a, size_t(3 * k), 3, names[k]);
    require_non_negative(a, 15, 1, "material: shininess n");
    require_positive(a, 16, "material: index of refraction ir");

    scene::Material m;
    m.name = where(cmd);
    m.ambient = a.rgb(0);
    m.diffuse = a.rgb(3);
    m.specular = a.rgb(6);
    m.transmission = a.rgb(9);
    m.emission = a.rgb(12);
    m.shininess = a.f(15);
    m.transmission_shininess = a.f(15);
    m.ior = a.f(16);

    // The texture argument: `0` or a file name.
    const Token* t = next_token();
    if (!t) {
        const File& f = files_.back();
        throw ParseError(f.name, f.lexed.end_line, f.lexed.end_col,
                         "material: expected a texture file name or 0, got end of file");
    }
    double zero = 1;
    const bool no_texture = parse_number(t->text, zero) == NumberKind::Number && zero == 0;  // "0", "0.0"
    if (!no_texture) {
        --files_.back().pos;  // let file_argument read (and locate) it
        Token tok;
        const fs::path p = file_argument(cmd, "texture file name (or 0)", tok);
        m.diffuse_texture = load_texture(p, tok);
    }

    // A material whose lobes sum to more than 1 in a channel creates light: path tracing diverges
    // and photon maps wash out. By default the three lobes of such a channel are scaled by the same
    // factor 1 / (kd + ks + kt) (the seed's -real); --raw-materials keeps them as written.
    const Rgb sum = m.diffuse + m.specular + m.transmission;
    if (sum.max() > 1) {
        const std::string what = where(cmd) + ": material " + std::to_string(files_.back().materials.size()) +
                                 " reflects more light than it receives (kd + ks + kt = " +
                                 printf_string("%g %g %g", sum.r, sum.g, sum.b) + ")";
        if (options_.raw_materials) {
            log::warn(what + "; kept as written (--raw-materials): photon survival is clamped to 1");
        } else {
            Rgb factor(1.0f);
            for (int c = 0; c < 3; ++c)
                if (sum[c] > 1) {
                    factor[c] = 1.0f / sum[c];
                    m.diffuse[c] *= factor[c];
                    m.specular[c] *= factor[c];
                    m.transmission[c] *= factor[c];
                }
            log::warn(what + "; scaled by " + printf_string("%g %g %g", factor.r, factor.g, factor.b) +
                      " per channel (--raw-materials keeps it as written)");
        }
    }
    files_.back().materials.push_back(int(scene_.materials.size()));
    scene_.materials.push_back(std::move(m));
}

int Parser::load_texture(const fs::path& path, const Token& at) {
    std::error_code ec;
    fs::path canonical = fs::weakly_canonical(path, ec);
    const std::string key = ec ? path.string() : canonical.string();
    if (const auto it = texture_cache_.find(key); it != texture_cache_.end()) return it->second;
    scene::Texture tex;
    try {
        tex = text::read_image_texture(path.string());
    } catch (ParseError& e) {
        e.add_included_from(files_.back().name, at.line, at.col);
        throw;
    } catch (const std::exception& e) {  // InputError, or a decoder library's own exception
        fail(at, std::string("material: cannot read texture '") + at.text + "': " + e.what());
    }
    const int index = int(scene_.textures.size());
    scene_.textures.push_back(std::move(tex));
    texture_cache_[key] = index;
    return index;
}

void Parser::cmd_tri(const Token& cmd) {
    const Args a = numbers(cmd, 10, "material x1 y1 z1 x2 y2 z2 x3 y3 z3");
    const int mat = material(a, 0);
    const double e1[3] = {a.v[4] - a.v[1], a.v[5] - a.v[2], a.v[6] - a.v[3]};
    const double e2[3] = {a.v[7] - a.v[1], a.v[8] - a.v[2], a.v[9] - a.v[3]};
    const double e3[3] = {a.v[7] - a.v[4], a.v[8] - a.v[5], a.v[9] - a.v[6]};
    const auto len2 = [](const double* e) { return e[0] * e[0] + e[1] * e[1] + e[2] * e[2]; };
    const double longest = std::max(len2(e1), std::max(len2(e2), len2(e3)));
    // Twice the area, relative to the longest edge squared: zero for coincident or collinear points.
    if (!(cross_length(e1, e2) > 1e-12 * longest) || longest == 0)
        fail(cmd, "tri: degenerate triangle (zero area: its vertices coincide or are collinear)");

    const int group = groups_.empty() ? 0 : groups_.back().serial;
    const int file = files_.back().id;
    const bool merge = merge_shape_ >= 0 && merge_shape_ == int(scene_.shapes.size()) - 1 &&
                       merge_file_ == file && merge_material_ == mat && merge_group_ == group;
    if (!merge) {
        scene::Shape s;
        s.kind = scene::Shape::Kind::Mesh;
        s.material = mat;
        merge_shape_ = add_shape(std::move(s), cmd);
        merge_file_ = file, merge_material_ = mat, merge_group_ = group;
    }
    scene::Shape& s = scene_.shapes[size_t(merge_shape_)];
    auto& mesh = s.mesh;
    const uint32_t base = uint32_t(mesh.positions.size());
    for (int k = 0; k < 3; ++k) mesh.positions.push_back(a.vec(size_t(1 + 3 * k)));
    for (uint32_t k = 0; k < 3; ++k) mesh.indices.push_back(base + k);
    if (merge) {
        // "file:first-last" names the run of `tri` lines merged into this mesh.
        // The file name may itself contain '-': look for it only after the last ':'.
        const std::string first = s.origin.substr(0, s.origin.find('-', s.origin.rfind(':')));
        s.origin = first + "-" + std::to_string(cmd.line);
    }
}

void Parser::cmd_box(const Token& cmd) {
    const Args a = numbers(cmd, 7, "material x1 y1 z1 x2 y2 z2");
    scene::Shape s;
    s.kind = scene::Shape::Kind::Box;
    s.material = material(a, 0);
    const char* axis = "xyz";
    for (size_t k = 0; k < 3; ++k)
        if (a.v[1 + k] == a.v[4 + k])
            fail(a.tok[4 + k], std::string("box: zero size along ") + axis[k] + " (both corners have " +
                                   axis[k] + " = " + a.tok[4 + k].text + ")");
    s.box_min = min(a.vec(1), a.vec(4));
    s.box_max = max(a.vec(1), a.vec(4));
    add_shape(std::move(s), cmd);
}

void Parser::cmd_sphere(const Token& cmd) {
    const Args a = numbers(cmd, 5, "material cx cy cz r");
    scene::Shape s;
    s.kind = scene::Shape::Kind::Sphere;
    s.material = material(a, 0);
    require_positive(a, 4, "sphere: radius");
    s.center = a.vec(1);
    s.radius = a.f(4);
    add_shape(std::move(s), cmd);
}

void Parser::cmd_circle(const Token& cmd) {
    const Args a = numbers(cmd, 8, "material cx cy cz nx ny nz r");
    scene::Shape s;
    s.kind = scene::Shape::Kind::Disk;
    s.material = material(a, 0);
    s.normal = direction(a, 4, "circle: normal");
    require_positive(a, 7, "circle: radius");
    s.center = a.vec(1);
    s.radius = a.f(7);
    add_shape(std::move(s), cmd);
}

void Parser::cmd_cylinder_or_cone(const Token& cmd, bool cone) {
    const Args a = numbers(cmd, 6, "material cx cy cz r h");
    scene::Shape s;
    s.kind = cone ? scene::Shape::Kind::Cone : scene::Shape::Kind::Cylinder;
    s.material = material(a, 0);
    require_positive(a, 4, cmd.text + ": radius");
    require_positive(a, 5, cmd.text + ": height");
    // Centred at c along +y; a cone's base is at c - h/2 y and its apex at c + h/2 y.
    s.center = a.vec(1);
    s.axis = {0, 1, 0};
    s.radius = a.f(4);
    s.height = a.f(5);
    s.capped = true;
    add_shape(std::move(s), cmd);
}

void Parser::cmd_line(const Token& cmd) {
    const Args a = numbers(cmd, 7, "material x1 y1 z1 x2 y2 z2");
    scene::Shape s;
    s.kind = scene::Shape::Kind::Cylinder;
    s.material = material(a, 0);
    const Vec3 p1 = a.vec(1), p2 = a.vec(4);
    const float len = length(p2 - p1);
    if (!(len > 0)) fail(a.tok[4], "line: the two end points coincide");
    // A segment has no thickness; it is drawn as a capped cylinder 1/200 of its length wide.
    s.center = (p1 + p2) * 0.5f;
    s.axis = (p2 - p1) / len;
    s.height = len;
    s.radius = 0.005f * len;
    s.capped = true;
    add_shape(std::move(s), cmd);
}

void Parser::cmd_mesh(const Token& cmd) {
    const Args a = numbers(cmd, 1, "material");
    const int mat = material(a, 0);
    Token tok;
    const fs::path p = file_argument(cmd, "mesh file name", tok);
    std::string ext = p.extension().string();
    for (char& ch : ext) ch = char(std::tolower(static_cast<unsigned char>(ch)));
    if (ext != ".off" && ext != ".ply" && ext != ".obj")
        fail(tok, "mesh: unknown mesh format '" + ext + "' (phos reads .off, .ply and .obj meshes)");
    LoadedMesh loaded;
    try {
        loaded = read_mesh(p.string());  // a ParseError names the mesh file's own line
    } catch (ParseError& e) {
        e.add_included_from(files_.back().name, tok.line, tok.col);  // and this command's
        throw;
    } catch (const std::exception& e) {  // InputError, or a reader library's own exception
        fail(tok, std::string("mesh: cannot read '") + tok.text + "': " + e.what());
    }
    // The mesh readers have checked the indices and positions, at the mesh file's own lines.
    if (loaded.mesh.triangle_count() == 0) {
        log::warn(where(cmd) + ": mesh '" + tok.text + "' has no triangles; skipped");
        return;
    }
    scene::Shape s;
    s.kind = scene::Shape::Kind::Mesh;
    s.material = mat;  // per-face OBJ materials are not used: the .scn command names one material
    s.mesh = std::move(loaded.mesh);
    add_shape(std::move(s), cmd);
}

void Parser::cmd_begin(const Token& cmd) {
    const Args a = numbers(cmd, 17, "material a00 a01 a02 a03 ... a33");
    Group g;
    if (a.v[0] == -1)
        g.material = groups_.empty() ? -1 : groups_.back().material;
    else
        g.material = material(a, 0);
    Mat4 m;
    for (size_t k = 0; k < 16; ++k) m.m[k] = a.f(1 + k);
    for (size_t k = 12; k < 16; ++k)
        if (a.v[1 + k] != (k == 15 ? 1.0 : 0.0))
            fail(a.tok[1 + k], "begin: the matrix's last row must be 0 0 0 1 (an affine transform)");
    Mat4 inv;
    if (!m.inverse(inv)) fail(cmd, "begin: the group matrix is singular (not invertible)");
    g.to_world = to_world() * Transform(m, inv);
    g.begin = cmd;
    g.serial = next_group_serial_++;
    groups_.push_back(std::move(g));
}

void Parser::cmd_end(const Token& cmd) {
    if (groups_.size() <= files_.back().group_base) fail(cmd, "end without a matching begin");
    groups_.pop_back();
}

void Parser::cmd_include(const Token& cmd) {
    Token tok;
    const fs::path p = file_argument(cmd, "scene file name", tok);
    parse_file(p, p.string(), &tok);
}

void Parser::cmd_background_or_ambient(const Token& cmd, bool background) {
    const Args a = numbers(cmd, 3, "r g b");
    require_non_negative(a, 0, 3, cmd.text + " colour");
    (background ? scene_.background : scene_.ambient) = a.rgb(0);
}

void Parser::attenuation(const Args& a, size_t i, const Token& cmd, scene::Light& light, bool area) {
    require_non_negative(a, i, 3, cmd.text + ": attenuation constant");
    if (a.v[i] == 0 && a.v[i + 1] == 0 && a.v[i + 2] == 0)
        fail(a.tok[i], cmd.text + ": attenuation constants ca la qa are all zero");
    light.attenuation = a.vec(i);
    if (light.attenuation != Vec3(0, 0, 1) && !options_.legacy_attenuation)
        log::warn(where(cmd) + ": " + cmd.text +
                  " attenuation (ca la qa = " + printf_string("%g %g %g", a.v[i], a.v[i + 1], a.v[i + 2]) +
                  ") is not physical; phos uses the physical fall-off (" + (area ? "solid angle" : "1/d^2") +
                  "); --legacy-attenuation applies it to direct light");
}

void Parser::cmd_dir_light(const Token& cmd) {
    const Args a = numbers(cmd, 6, "r g b  dx dy dz");
    require_non_negative(a, 0, 3, "dir_light: colour");
    scene::Light l;
    l.kind = scene::Light::Kind::Directional;
    l.color = a.rgb(0);
    l.direction = normalize(to_world().vector(direction(a, 3, "dir_light: direction")));
    scene_.lights.push_back(l);
}

void Parser::cmd_point_or_spot_light(const Token& cmd, bool spot) {
    const Args a = spot ? numbers(cmd, 14, "r g b  px py pz  dx dy dz  ca la qa  cutoff dropoff")
                        : numbers(cmd, 9, "r g b  px py pz  ca la qa");
    require_non_negative(a, 0, 3, cmd.text + ": colour");
    scene::Light l;
    l.kind = spot ? scene::Light::Kind::Spot : scene::Light::Kind::Point;
    l.color = a.rgb(0);
    l.position = to_world().point(a.vec(3));
    if (spot) {
        l.direction = normalize(to_world().vector(direction(a, 6, "spot_light: direction")));
        const double cutoff = a.v[12];
        if (!(cutoff > 0 && cutoff <= double(kPi)))
            fail(a.tok[12], "spot_light: cutoff is a half angle in radians and must be in (0, pi], got '" +
                                a.tok[12].text + "'");
        require_non_negative(a, 13, 1, "spot_light: dropoff");
        l.cutoff = float(cutoff);
        l.dropoff = a.f(13);
    }
    attenuation(a, spot ? 9 : 6, cmd, l, false);
    scene_.lights.push_back(l);
}

void Parser::cmd_area_light(const Token& cmd) {
    const Args a = numbers(cmd, 13, "r g b  px py pz  dx dy dz  radius  ca la qa");
    require_non_negative(a, 0, 3, "area_light: colour");
    scene::Shape s;
    s.kind = scene::Shape::Kind::Disk;
    s.center = a.vec(3);
    s.normal = direction(a, 6, "area_light: direction");
    require_positive(a, 9, "area_light: radius");
    s.radius = a.f(9);
    s.material = emitter_material();
    s.to_world = to_world();
    s.origin = where(cmd);
    scene::Light l;
    attenuation(a, 10, cmd, l, true);
    const int index = scene_.add_area_light(std::move(s), a.rgb(0));
    scene::Light& added = scene_.lights[size_t(index)];
    added.attenuation = l.attenuation;
    added.position = to_world().point(a.vec(3));
    added.direction = normalize(to_world().normal(scene_.shapes.back().normal));
}

void Parser::cmd_rect_light(const Token& cmd) {
    const Args a = numbers(cmd, 17, "r g b  cx cy cz  a1x a1y a1z  a2x a2y a2z  len1 len2  ca la qa");
    require_non_negative(a, 0, 3, "rect_light: colour");
    const Vec3 a1 = direction(a, 6, "rect_light: side a1");
    const Vec3 a2 = direction(a, 9, "rect_light: side a2");
    if (length(cross(a1, a2)) < 1e-6f) fail(a.tok[9], "rect_light: sides a1 and a2 are parallel");
    require_positive(a, 12, "rect_light: len1");
    require_positive(a, 13, "rect_light: len2");
    scene::Light l;
    attenuation(a, 14, cmd, l, true);

    // Corners counter-clockwise seen from a1 x a2, so both triangles' normals point that way.
    const Vec3 c = a.vec(3), h1 = a1 * (0.5f * a.f(12)), h2 = a2 * (0.5f * a.f(13));
    scene::Shape s;
    s.kind = scene::Shape::Kind::Mesh;
    s.mesh.positions = {c - h1 - h2, c + h1 - h2, c + h1 + h2, c - h1 + h2};
    s.mesh.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    s.mesh.indices = {0, 1, 2, 0, 2, 3};
    s.material = emitter_material();
    s.to_world = to_world();
    s.origin = where(cmd);
    const int index = scene_.add_area_light(std::move(s), a.rgb(0));
    scene::Light& added = scene_.lights[size_t(index)];
    added.attenuation = l.attenuation;
    added.position = to_world().point(c);
    added.direction = normalize(to_world().normal(cross(a1, a2)));
}

}  // namespace phos::io::scn
