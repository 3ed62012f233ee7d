// The photon viewer (see photon_viewer.h): an orbit camera around the points' bounds, matrices
// built here (no GLU) and loaded into the fixed pipeline, points and lines drawn from client-side
// vertex arrays, picking done on the CPU with the same matrices.
#include "display/photon_viewer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/format.h"
#include "core/log.h"
#include "display/framebuffer.h"
#include "io/image/image_io.h"
#include "io/image/tonemap.h"

#ifdef PHOS_HAS_GLFW
#include <GLFW/glfw3.h>
#endif

namespace phos::display {

Rgb group_colour(int g) {
    static const Rgb kColours[] = {{0.95f, 0.85f, 0.3f}, {0.3f, 0.8f, 1.0f},   {1.0f, 0.35f, 0.3f},
                                   {0.5f, 1.0f, 0.4f},   {0.85f, 0.45f, 1.0f}, {1.0f, 0.6f, 0.2f}};
    return kColours[size_t(g) % std::size(kColours)];
}

Rgb bounce_colour(int bounces) {
    static const Rgb kColours[] = {{1.0f, 1.0f, 1.0f},   {1.0f, 0.2f, 0.15f}, {1.0f, 0.55f, 0.1f},
                                   {0.95f, 0.9f, 0.15f}, {0.3f, 0.9f, 0.3f},  {0.2f, 0.85f, 0.9f},
                                   {0.25f, 0.4f, 1.0f},  {0.6f, 0.3f, 1.0f},  {1.0f, 0.25f, 0.85f}};
    if (bounces < 0) return Rgb(0.5f);
    return kColours[std::min<size_t>(size_t(bounces), std::size(kColours) - 1)];
}

#ifdef PHOS_HAS_GLFW

namespace {

using Mat4 = std::array<float, 16>;  // column-major, as OpenGL takes it

Mat4 multiply(const Mat4& a, const Mat4& b) {
    Mat4 r{};
    for (int c = 0; c < 4; ++c)
        for (int row = 0; row < 4; ++row)
            for (int k = 0; k < 4; ++k)
                r[size_t(c * 4 + row)] += a[size_t(k * 4 + row)] * b[size_t(c * 4 + k)];
    return r;
}

Mat4 perspective(float fovy, float aspect, float near, float far) {
    const float f = 1.0f / std::tan(fovy / 2);
    Mat4 m{};
    m[0] = f / aspect;
    m[5] = f;
    m[10] = (far + near) / (near - far);
    m[11] = -1;
    m[14] = 2 * far * near / (near - far);
    return m;
}

Mat4 look_at(Vec3 eye, Vec3 target, Vec3 up) {
    const Vec3 f = normalize(target - eye), s = normalize(cross(f, up)), u = cross(s, f);
    return {s.x, u.x, -f.x, 0, s.y,          u.y,          -f.y,        0,
            s.z, u.z, -f.z, 0, -dot(s, eye), -dot(u, eye), dot(f, eye), 1};
}

struct Camera {
    Vec3 target{0.0f};
    float yaw = 0.6f, pitch = 0.35f, distance = 1, fovy = 0.8f;
    Vec3 eye() const {
        return target + distance * Vec3(std::cos(pitch) * std::sin(yaw), std::sin(pitch),
                                        std::cos(pitch) * std::cos(yaw));
    }
};

struct Viewer {
    const ViewerScene* scene = nullptr;
    Camera camera, home;
    float extent = 1;
    std::vector<bool> shown;
    std::vector<bool> present;  // groups that have points
    int colouring = 0;          // ViewerColouring: 0 power, 1 map, 2 bounces
    int colourings = 2;         // 3 when the points have bounce counts
    float point_size = 2;
    bool dragging = false, panning = false, moved = false;
    double last_x = 0, last_y = 0, press_x = 0, press_y = 0;
    bool pick = false;
    bool dirty = true;
};

Mat4 view_projection(const Viewer& v, int fw, int fh) {
    const float near = std::max(1e-4f * v.extent, v.camera.distance - 4 * v.extent);
    const float far = v.camera.distance + 4 * v.extent;
    return multiply(
        perspective(v.camera.fovy, float(fw) / float(std::max(fh, 1)), std::max(near, 1e-4f * v.extent), far),
        look_at(v.camera.eye(), v.camera.target, {0, 1, 0}));
}

// The picked point: nearest to the cursor within 8 pixels, the closest to the camera among those.
long pick_point(const Viewer& v, const Mat4& m, int fw, int fh, double cx, double cy) {
    long best = -1;
    double best_d2 = 64, best_depth = std::numeric_limits<double>::max();
    const auto& pts = v.scene->points;
    for (size_t i = 0; i < pts.size(); ++i) {
        if (!v.shown[pts[i].group]) continue;
        const Vec3 p = pts[i].position;
        const float x = m[0] * p.x + m[4] * p.y + m[8] * p.z + m[12];
        const float y = m[1] * p.x + m[5] * p.y + m[9] * p.z + m[13];
        const float z = m[2] * p.x + m[6] * p.y + m[10] * p.z + m[14];
        const float w = m[3] * p.x + m[7] * p.y + m[11] * p.z + m[15];
        if (!(w > 0)) continue;
        const double sx = (x / w * 0.5 + 0.5) * fw, sy = (1 - (y / w * 0.5 + 0.5)) * fh;
        const double d2 = (sx - cx) * (sx - cx) + (sy - cy) * (sy - cy);
        if (d2 > 64) continue;
        const double depth = z / w;
        if (d2 < best_d2 - 1e-9 || (std::abs(d2 - best_d2) < 4 && depth < best_depth)) {
            best = long(i);
            best_d2 = std::min(best_d2, d2);
            best_depth = depth;
        }
    }
    return best;
}

void draw(GLFWwindow* window, const Viewer& v, const std::vector<float>& xyz, const std::vector<float>& rgb,
          const std::vector<float>& lines) {
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(window, &fw, &fh);
    glViewport(0, 0, fw, fh);
    glClearColor(0.08f, 0.08f, 0.09f, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    const Mat4 m = view_projection(v, fw, fh);
    glMatrixMode(GL_PROJECTION);
    glLoadMatrixf(m.data());
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glEnableClientState(GL_VERTEX_ARRAY);
    if (!lines.empty()) {
        glColor3f(0.35f, 0.35f, 0.4f);
        glVertexPointer(3, GL_FLOAT, 0, lines.data());
        glDrawArrays(GL_LINES, 0, GLsizei(lines.size() / 3));
    }
    glPointSize(v.point_size);
    glEnableClientState(GL_COLOR_ARRAY);
    // One draw per visible map (the arrays are grouped by map, see run_photon_viewer).
    size_t first = 0;
    const auto& pts = v.scene->points;
    while (first < pts.size()) {
        size_t last = first;
        while (last < pts.size() && pts[last].group == pts[first].group) ++last;
        if (v.shown[pts[first].group]) {
            glVertexPointer(3, GL_FLOAT, 0, xyz.data() + 3 * first);
            glColorPointer(3, GL_FLOAT, 0, rgb.data() + 3 * (size_t(v.colouring) * pts.size() + first));
            glDrawArrays(GL_POINTS, 0, GLsizei(last - first));
        }
        first = last;
    }
    glDisableClientState(GL_COLOR_ARRAY);
    glDisableClientState(GL_VERTEX_ARRAY);
}

// "TITLE  [colour power; maps global caustic; points 2 px]": the state the keys change.
std::string viewer_title(const std::string& title, const Viewer& v) {
    static const char* const kColourings[] = {"power", "map", "bounces"};
    std::string maps;
    for (size_t g = 0; g < v.scene->group_names.size(); ++g)
        if (v.shown[g] && g < v.present.size() && v.present[g]) maps += " " + v.scene->group_names[g];
    return title + "  [colour " + kColourings[v.colouring] + "; maps" + (maps.empty() ? " none" : maps) +
           printf_string("; points %d px]", int(v.point_size));
}

Image window_pixels(GLFWwindow* window) {
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(window, &fw, &fh);
    return read_framebuffer(fw, fh);
}

}  // namespace

bool run_photon_viewer(const ViewerScene& scene, const ViewerOptions& options, std::string& why) {
    static std::string glfw_error;
    glfwSetErrorCallback([](int, const char* d) { glfw_error = d ? d : "unknown GLFW error"; });
    if (!glfwInit()) {
        why = glfw_error.empty() ? "no display" : glfw_error;
        return false;
    }
    GLFWwindow* window = glfwCreateWindow(1024, 768, options.title.c_str(), nullptr, nullptr);
    if (!window) {
        why = glfw_error.empty() ? "cannot open a window" : glfw_error;
        glfwTerminate();
        return false;
    }
    glfwMakeContextCurrent(window);

    Viewer v;
    v.scene = &scene;
    v.point_size = options.point_size;
    v.shown.assign(std::max<size_t>(scene.group_names.size(), 1) + 256, true);
    v.present.assign(v.shown.size(), false);
    for (const ViewerPoint& p : scene.points) v.present[p.group] = true;
    // Bounds of the points and the geometry: the orbit's centre and distance.
    Vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    auto grow = [&](Vec3 p) {
        lo = Vec3(std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z));
        hi = Vec3(std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z));
    };
    for (const ViewerPoint& p : scene.points) grow(p.position);
    for (const Vec3& p : scene.lines) grow(p);
    if (!(lo.x <= hi.x)) lo = Vec3(-1.0f), hi = Vec3(1.0f);
    v.extent = std::max(0.5f * length(hi - lo), 1e-6f);
    v.camera.target = 0.5f * (lo + hi);
    v.camera.distance = v.extent / std::tan(v.camera.fovy / 2) * 1.1f;
    v.home = v.camera;

    // Vertex arrays: positions, then the colourings (power, map, bounces) one after the other.
    bool bounces = !scene.points.empty();
    for (const ViewerPoint& p : scene.points) bounces &= p.bounces >= 0;
    v.colourings = bounces ? 3 : 2;
    v.colouring = std::min(int(options.colouring), v.colourings - 1);
    std::vector<float> xyz, rgb(scene.points.size() * 3 * size_t(v.colourings)), lines;
    xyz.reserve(scene.points.size() * 3);
    for (size_t i = 0; i < scene.points.size(); ++i) {
        const ViewerPoint& p = scene.points[i];
        xyz.insert(xyz.end(), {p.position.x, p.position.y, p.position.z});
        const Rgb g = group_colour(p.group);
        for (int c = 0; c < 3; ++c) {
            rgb[3 * i + size_t(c)] = p.colour[c];
            rgb[3 * (scene.points.size() + i) + size_t(c)] = g[c];
            if (bounces) rgb[3 * (2 * scene.points.size() + i) + size_t(c)] = bounce_colour(p.bounces)[c];
        }
    }
    for (const Vec3& p : scene.lines) lines.insert(lines.end(), {p.x, p.y, p.z});

    glfwSetWindowUserPointer(window, &v);
    glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int) {
        if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
        Viewer& s = *static_cast<Viewer*>(glfwGetWindowUserPointer(w));
        if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9) {
            const size_t g = size_t(key - GLFW_KEY_1);
            if (g < s.scene->group_names.size()) s.shown[g] = !s.shown[g];
        } else if (key == GLFW_KEY_C) {
            s.colouring = (s.colouring + 1) % s.colourings;
        } else if (key == GLFW_KEY_EQUAL || key == GLFW_KEY_KP_ADD) {
            s.point_size = std::min(s.point_size + 1, 16.0f);
        } else if (key == GLFW_KEY_MINUS || key == GLFW_KEY_KP_SUBTRACT) {
            s.point_size = std::max(s.point_size - 1, 1.0f);
        } else if (key == GLFW_KEY_R) {
            s.camera = s.home;
        } else if (key == GLFW_KEY_Q || key == GLFW_KEY_ESCAPE) {
            glfwSetWindowShouldClose(w, GLFW_TRUE);
        }
        s.dirty = true;
    });
    glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int action, int) {
        Viewer& s = *static_cast<Viewer*>(glfwGetWindowUserPointer(w));
        double x, y;
        glfwGetCursorPos(w, &x, &y);
        if (action == GLFW_PRESS) {
            s.dragging = button == GLFW_MOUSE_BUTTON_LEFT;
            s.panning = !s.dragging;
            s.moved = false;
            s.last_x = s.press_x = x;
            s.last_y = s.press_y = y;
        } else {
            if (button == GLFW_MOUSE_BUTTON_LEFT && !s.moved) s.pick = true;
            s.dragging = s.panning = false;
        }
    });
    glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) {
        Viewer& s = *static_cast<Viewer*>(glfwGetWindowUserPointer(w));
        if (!s.dragging && !s.panning) return;
        const double dx = x - s.last_x, dy = y - s.last_y;
        s.last_x = x, s.last_y = y;
        if (std::abs(x - s.press_x) + std::abs(y - s.press_y) > 3) s.moved = true;
        if (s.dragging) {
            s.camera.yaw -= float(dx) * 0.008f;
            s.camera.pitch = std::clamp(s.camera.pitch + float(dy) * 0.008f, -1.55f, 1.55f);
        } else {
            const Vec3 f = normalize(s.camera.target - s.camera.eye());
            const Vec3 r = normalize(cross(f, Vec3(0, 1, 0))), u = cross(r, f);
            const float k = s.camera.distance * 0.0015f;
            s.camera.target = s.camera.target - r * (float(dx) * k) + u * (float(dy) * k);
        }
        s.dirty = true;
    });
    glfwSetScrollCallback(window, [](GLFWwindow* w, double, double dy) {
        Viewer& s = *static_cast<Viewer*>(glfwGetWindowUserPointer(w));
        s.camera.distance *= std::pow(0.9f, float(dy));
        s.dirty = true;
    });

    while (!glfwWindowShouldClose(window)) {
        if (v.dirty) {
            glfwSetWindowTitle(window, viewer_title(options.title, v).c_str());
            draw(window, v, xyz, rgb, lines);
            if (!options.screenshot_path.empty()) {
                try {
                    io::write_image(options.screenshot_path, window_pixels(window));
                } catch (const std::exception& e) {
                    log::warn(std::string("photon viewer screenshot: ") + e.what());
                }
                break;
            }
            glfwSwapBuffers(window);
            v.dirty = false;
        }
        glfwWaitEvents();
        if (v.pick) {
            v.pick = false;
            int fw = 0, fh = 0, ww = 0, wh = 0;
            glfwGetFramebufferSize(window, &fw, &fh);
            glfwGetWindowSize(window, &ww, &wh);
            const double sx = ww > 0 ? double(fw) / ww : 1, sy = wh > 0 ? double(fh) / wh : 1;
            const long i = pick_point(v, view_projection(v, fw, fh), fw, fh, v.press_x * sx, v.press_y * sy);
            if (i >= 0 && scene.describe)
                std::printf("%s\n", scene.describe(scene.points[size_t(i)].id).c_str());
            else if (i < 0)
                std::printf("no photon under the cursor\n");
            std::fflush(stdout);
        }
    }
    glfwDestroyWindow(window);
    glfwTerminate();
    return true;
}

#else  // built without GLFW

bool run_photon_viewer(const ViewerScene&, const ViewerOptions&, std::string& why) {
    why = "this phos was built without the viewer (install libglfw3-dev and rebuild)";
    return false;
}

#endif

}  // namespace phos::display
