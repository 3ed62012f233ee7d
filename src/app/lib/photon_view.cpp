// Building the photon viewer's input (see photon_view.h).
#include "app/lib/photon_view.h"

#include <cmath>
#include <memory>

#include "core/error.h"
#include "core/format.h"

namespace phos::app {
namespace {

constexpr float kPi = 3.14159265358979f;

// A circle of `radius` around `centre` in the plane spanned by unit vectors a and b.
void circle(std::vector<Vec3>& out, const Transform& t, Vec3 centre, Vec3 a, Vec3 b, float radius) {
    constexpr int kSegments = 32;
    for (int i = 0; i < kSegments; ++i) {
        const float u0 = 2 * kPi * float(i) / kSegments, u1 = 2 * kPi * float(i + 1) / kSegments;
        out.push_back(t.point(centre + radius * (std::cos(u0) * a + std::sin(u0) * b)));
        out.push_back(t.point(centre + radius * (std::cos(u1) * a + std::sin(u1) * b)));
    }
}

// Two unit vectors perpendicular to unit n and to each other.
void basis(Vec3 n, Vec3& a, Vec3& b) {
    a = normalize(std::abs(n.x) > 0.9f ? cross(n, Vec3(0, 1, 0)) : cross(n, Vec3(1, 0, 0)));
    b = cross(n, a);
}

void shape_lines(std::vector<Vec3>& out, const scene::Shape& s, const Transform& placed) {
    const Transform t = placed * s.to_world;
    using Kind = scene::Shape::Kind;
    switch (s.kind) {
        case Kind::Mesh:
            for (size_t i = 0; i + 2 < s.mesh.indices.size(); i += 3)
                for (int e = 0; e < 3; ++e) {
                    out.push_back(t.point(s.mesh.positions[s.mesh.indices[i + size_t(e)]]));
                    out.push_back(t.point(s.mesh.positions[s.mesh.indices[i + size_t((e + 1) % 3)]]));
                }
            break;
        case Kind::Sphere:
            circle(out, t, s.center, {1, 0, 0}, {0, 1, 0}, s.radius);
            circle(out, t, s.center, {0, 1, 0}, {0, 0, 1}, s.radius);
            circle(out, t, s.center, {0, 0, 1}, {1, 0, 0}, s.radius);
            break;
        case Kind::Box: {
            const Vec3 lo = s.box_min, hi = s.box_max;
            auto corner = [&](int i) {
                return Vec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
            };
            for (int i = 0; i < 8; ++i)
                for (int bit : {1, 2, 4})
                    if (!(i & bit)) {
                        out.push_back(t.point(corner(i)));
                        out.push_back(t.point(corner(i | bit)));
                    }
            break;
        }
        case Kind::Disk: {
            Vec3 a, b;
            basis(normalize(s.normal), a, b);
            circle(out, t, s.center, a, b, s.radius);
            if (s.inner_radius > 0) circle(out, t, s.center, a, b, s.inner_radius);
            break;
        }
        case Kind::Cylinder:
        case Kind::Cone: {
            Vec3 a, b;
            const Vec3 axis = normalize(s.axis);
            basis(axis, a, b);
            const Vec3 base = s.center - 0.5f * s.height * axis, top = s.center + 0.5f * s.height * axis;
            circle(out, t, base, a, b, s.radius);
            const float top_radius = s.kind == Kind::Cylinder ? s.radius : 0.0f;
            if (top_radius > 0) circle(out, t, top, a, b, top_radius);
            for (int i = 0; i < 4; ++i) {
                const float u = 0.5f * kPi * float(i);
                const Vec3 r = std::cos(u) * a + std::sin(u) * b;
                out.push_back(t.point(base + s.radius * r));
                out.push_back(t.point(top + top_radius * r));
            }
            break;
        }
        case Kind::Curves:  // each segment's control polygon
            for (uint32_t first : s.curves.segments)
                for (uint32_t k = first; k < first + 3 && k + 1 < s.curves.points.size(); ++k) {
                    out.push_back(t.point(s.curves.points[k]));
                    out.push_back(t.point(s.curves.points[k + 1]));
                }
            break;
    }
}

const io::PointColumn& column(const io::PointCloud& cloud, const std::string& name) {
    for (const io::PointColumn& c : cloud.columns)
        if (c.name == name) return c;
    throw InputError("photon viewer: the point cloud has no column '" + name + "'");
}

}  // namespace

std::vector<Vec3> scene_lines(const scene::Scene& scene) {
    std::vector<Vec3> out;
    for (const scene::Shape& s : scene.shapes) shape_lines(out, s, Transform());
    for (const scene::Instance& inst : scene.instances)
        if (inst.object >= 0 && size_t(inst.object) < scene.objects.size())
            for (const scene::Shape& s : scene.objects[size_t(inst.object)].shapes)
                shape_lines(out, s, inst.to_world);
    return out;
}

display::ViewerScene viewer_scene(const io::PointCloud& cloud, const scene::Scene& scene,
                                  const std::vector<std::string>& map_names) {
    display::ViewerScene v;
    v.group_names = map_names;
    const io::PointColumn &x = column(cloud, "x"), &y = column(cloud, "y"), &z = column(cloud, "z");
    const io::PointColumn &r = column(cloud, "red"), &g = column(cloud, "green"), &b = column(cloud, "blue");
    const io::PointColumn& map = column(cloud, "map");
    const io::PointColumn* bounces = nullptr;
    for (const io::PointColumn& c : cloud.columns)
        if (c.name == "bounces") bounces = &c;
    v.points.resize(cloud.size());
    for (size_t i = 0; i < cloud.size(); ++i) {
        display::ViewerPoint& p = v.points[i];
        p.position = Vec3(x.floats[i], y.floats[i], z.floats[i]);
        p.colour = Rgb(float(r.bytes[i]) / 255.0f, float(g.bytes[i]) / 255.0f, float(b.bytes[i]) / 255.0f);
        p.group = map.bytes[i];
        if (bounces) p.bounces = bounces->bytes[i];
        p.id = uint32_t(i);
    }
    v.lines = scene_lines(scene);
    // The record of a picked photon: every column of the cloud, by name.
    auto shared = std::make_shared<io::PointCloud>(cloud);
    const std::vector<std::string> names = map_names;
    v.describe = [shared, names](uint32_t i) {
        std::string s = "photon " + std::to_string(i) + ":";
        for (const io::PointColumn& c : shared->columns) {
            s += c.is_float ? printf_string(" %s %.6g", c.name.c_str(), double(c.floats[i]))
                            : printf_string(" %s %d", c.name.c_str(), int(c.bytes[i]));
            if (c.name == "map" && c.bytes[i] < names.size()) s += " (" + names[c.bytes[i]] + ")";
        }
        return s;
    };
    return v;
}

}  // namespace phos::app
