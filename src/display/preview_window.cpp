// The preview window's thread (see preview_window.h): GLFW window, one RGB8 texture drawn as a
// letterboxed quad with the legacy fixed pipeline (works on any GL, Mesa's software one included),
// tone-mapped on the CPU exactly as PNG output is (io/image/tonemap.h), so what the window shows is
// what `-o out.png` writes.
#include "display/preview_window.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <csignal>
#include <cstdlib>
#include <mutex>
#include <vector>

#include "core/format.h"
#include "core/interrupt.h"
#include "core/log.h"
#include "display/framebuffer.h"
#include "io/image/image_io.h"
#include "io/image/tonemap.h"

#ifdef PHOS_HAS_GLFW
#include <GLFW/glfw3.h>
#endif

namespace phos::display {

struct PreviewWindow::State {
    const LiveImage* image = nullptr;
    PreviewOptions options;
    std::atomic<bool> render_done{false};
    // options.hold, which the destructor may withdraw while the window's thread reads it.
    std::atomic<bool> hold{false};
    std::mutex mutex;
    std::condition_variable cv;
    int started = 0;  // 0 pending, 1 open, -1 failed
    std::string why;
    std::vector<int> keys;  // pressed since the last frame (the window thread only)
};

PreviewWindow::PreviewWindow() : state_(std::make_unique<State>()) {}

PreviewWindow::~PreviewWindow() {
    if (thread_.joinable()) {
        state_->hold = false;
        finish();
    }
}

#ifdef PHOS_HAS_GLFW

PreviewKey preview_key(int key) {
    switch (key) {
        case GLFW_KEY_EQUAL:
        case GLFW_KEY_KP_ADD:
        case GLFW_KEY_RIGHT_BRACKET:
            return PreviewKey::ExposureUp;
        case GLFW_KEY_MINUS:
        case GLFW_KEY_KP_SUBTRACT:
        case GLFW_KEY_LEFT_BRACKET:
            return PreviewKey::ExposureDown;
        case GLFW_KEY_L:
        case GLFW_KEY_TAB:
            return PreviewKey::NextLayer;
        case GLFW_KEY_S:
            return PreviewKey::Save;
        case GLFW_KEY_Q:
        case GLFW_KEY_ESCAPE:
            return PreviewKey::Quit;
        default:
            return PreviewKey::None;
    }
}

bool preview_available() { return true; }

namespace {

std::mutex g_error_mutex;
std::string g_error;

void on_glfw_error(int, const char* description) {
    std::lock_guard lock(g_error_mutex);
    g_error = description ? description : "unknown GLFW error";
}

std::string last_glfw_error() {
    std::lock_guard lock(g_error_mutex);
    return g_error.empty() ? "no display" : g_error;
}

// The window's size for a width x height image: shrunk to fit 1280 x 960, small images magnified
// by an integer factor (up to 4) so they stay visible.
void window_size(int w, int h, int& ww, int& wh) {
    double scale = std::min({1.0, 1280.0 / w, 960.0 / h});
    if (scale >= 1.0) scale = std::clamp(std::floor(std::min(512.0 / w, 512.0 / h)), 1.0, 4.0);
    ww = std::max(1, int(std::lround(w * scale)));
    wh = std::max(1, int(std::lround(h * scale)));
}

// Draws the texture letterboxed into the framebuffer.
void draw(GLFWwindow* window, GLuint texture, int w, int h) {
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(window, &fw, &fh);
    glViewport(0, 0, fw, fh);
    glClearColor(0.12f, 0.12f, 0.12f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    const double s = std::min(double(fw) / w, double(fh) / h);
    const float sx = float(w * s / fw), sy = float(h * s / fh);
    glEnable(GL_TEXTURE_2D);
    glBindTexture(GL_TEXTURE_2D, texture);
    glBegin(GL_QUADS);  // texture rows are top row first: t = 0 at the top
    glTexCoord2f(0, 1);
    glVertex2f(-sx, -sy);
    glTexCoord2f(1, 1);
    glVertex2f(sx, -sy);
    glTexCoord2f(1, 0);
    glVertex2f(sx, sy);
    glTexCoord2f(0, 0);
    glVertex2f(-sx, sy);
    glEnd();
    glDisable(GL_TEXTURE_2D);
}

Image window_pixels(GLFWwindow* window) {
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(window, &fw, &fh);
    return read_framebuffer(fw, fh);
}

void run_window(PreviewWindow::State& s);

}  // namespace

bool PreviewWindow::start(const LiveImage& image, const PreviewOptions& options, std::string& why) {
    state_->image = &image;
    state_->options = options;
    state_->hold = options.hold;
    thread_ = std::thread([this] { run_window(*state_); });
    std::unique_lock lock(state_->mutex);
    state_->cv.wait(lock, [&] { return state_->started != 0; });
    if (state_->started > 0) return true;
    why = state_->why;
    lock.unlock();
    thread_.join();
    return false;
}

void PreviewWindow::finish() {
    if (!thread_.joinable()) return;
    state_->render_done = true;
    glfwPostEmptyEvent();
    thread_.join();
}

namespace {

void run_window(PreviewWindow::State& s) {
    const auto report = [&](int started, const std::string& why) {
        std::lock_guard lock(s.mutex);
        s.started = started;
        s.why = why;
        s.cv.notify_all();
    };
    glfwSetErrorCallback(on_glfw_error);
    // Mesa's software OpenGL (llvmpipe: no GPU, Xvfb) rasterises on as many threads as there are
    // cores; one is plenty for a textured quad and leaves the cores to the render.
    ::setenv("LP_NUM_THREADS", "1", 0);
    if (!glfwInit()) return report(-1, last_glfw_error());
    const LiveImage& image = *s.image;
    const int w = image.width(), h = image.height();
    int ww = 0, wh = 0;
    window_size(w, h, ww, wh);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
    GLFWwindow* window = glfwCreateWindow(ww, wh, s.options.title.c_str(), nullptr, nullptr);
    if (!window) {
        const std::string why = last_glfw_error();
        glfwTerminate();
        return report(-1, why);
    }
    glfwMakeContextCurrent(window);
    glfwSwapInterval(0);
    glfwSetWindowUserPointer(window, &s);
    glfwSetKeyCallback(window, [](GLFWwindow* win, int key, int, int action, int) {
        if (action == GLFW_PRESS || action == GLFW_REPEAT)
            static_cast<PreviewWindow::State*>(glfwGetWindowUserPointer(win))->keys.push_back(key);
    });
    report(1, "");

    GLuint texture = 0;
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, w, h, 0, GL_RGB, GL_UNSIGNED_BYTE, nullptr);

    using clock = std::chrono::steady_clock;
    auto next_draw = clock::now();
    uint64_t shown = ~uint64_t(0);
    size_t layer = 0;
    float exposure = s.options.exposure;
    bool view_changed = true;
    int snapshots = 0;
    Image current(w, h);
    while (!glfwWindowShouldClose(window)) {
        const uint64_t version = image.version();
        if (s.render_done && !s.hold && version == shown) break;  // the final image is shown
        glfwWaitEventsTimeout(0.05);
        const std::vector<std::string> names = image.layer_names();
        for (int key : s.keys) {
            switch (preview_key(key)) {
                case PreviewKey::ExposureUp:
                    exposure += 0.5f, view_changed = true;
                    break;
                case PreviewKey::ExposureDown:
                    exposure -= 0.5f, view_changed = true;
                    break;
                case PreviewKey::NextLayer:
                    layer = (layer + 1) % names.size(), view_changed = true;
                    break;
                case PreviewKey::Save:
                    if (!s.options.snapshot_stem.empty()) {
                        const std::string path =
                            s.options.snapshot_stem + ".snapshot-" + std::to_string(++snapshots) + ".exr";
                        try {
                            io::write_image(path, current);
                            log::info("phos: preview: saved " + names[layer % names.size()] + " to " + path);
                        } catch (const std::exception& e) {
                            log::warn(std::string("preview: ") + e.what());
                        }
                    }
                    break;
                case PreviewKey::Quit:
                    if (!s.render_done)
                        interrupt::request(SIGINT);  // as Ctrl-C
                    else
                        glfwSetWindowShouldClose(window, GLFW_TRUE);
                    break;
                case PreviewKey::None:
                    break;
            }
        }
        s.keys.clear();
        const uint64_t now = image.version();
        if (now == shown && !view_changed) continue;
        // While the render runs, redraws are spaced so that the window takes at most ~2 % of one
        // core (and at most four a second): each is a copy, a tone map and an upload of what
        // changed, and with a software OpenGL the drawing itself takes CPU from the render.
        if (!view_changed && !s.render_done && clock::now() < next_draw) continue;
        const auto began = clock::now();
        layer %= names.size();
        if (view_changed) {  // another layer or exposure: everything
            const std::vector<Rgb> values = image.read(layer);
            for (size_t i = 0; i < values.size() && i < current.pixels.size(); ++i)
                current.pixels[i] = values[i];
            const std::vector<uint8_t> rgb = io::to_srgb8(current, exposure);
            glBindTexture(GL_TEXTURE_2D, texture);
            glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
        } else {  // only the blocks that changed since the last redraw
            glBindTexture(GL_TEXTURE_2D, texture);
            for (const Region& r : image.changed_since(shown)) {
                const std::vector<Rgb> values = image.read_region(layer, r);
                if (values.size() != size_t(r.width()) * size_t(r.height())) continue;
                Image part(r.width(), r.height());
                for (int y = 0; y < r.height(); ++y)
                    for (int x = 0; x < r.width(); ++x) {
                        const Rgb v = values[size_t(y) * size_t(r.width()) + size_t(x)];
                        part.pixels[size_t(y) * size_t(r.width()) + size_t(x)] = v;
                        current.pixels[size_t(r.y0 + y) * size_t(w) + size_t(r.x0 + x)] = v;
                    }
                const std::vector<uint8_t> rgb = io::to_srgb8(part, exposure);
                glTexSubImage2D(GL_TEXTURE_2D, 0, r.x0, r.y0, r.width(), r.height(), GL_RGB, GL_UNSIGNED_BYTE,
                                rgb.data());
            }
        }
        const std::string title =
            printf_string("%s  [%s, exposure %+.1f%s]", s.options.title.c_str(), names[layer].c_str(),
                          exposure, s.render_done ? ", done" : "");
        glfwSetWindowTitle(window, title.c_str());
        draw(window, texture, w, h);
        glfwSwapBuffers(window);
        shown = now;
        view_changed = false;
        next_draw = clock::now() +
                    std::max<clock::duration>(std::chrono::milliseconds(250), (clock::now() - began) * 50);
    }
    if (!s.options.screenshot_path.empty()) {
        draw(window, texture, w, h);
        try {
            io::write_image(s.options.screenshot_path, window_pixels(window));
        } catch (const std::exception& e) {
            log::warn(std::string("preview screenshot: ") + e.what());
        }
    }
    glDeleteTextures(1, &texture);
    glfwDestroyWindow(window);
    glfwTerminate();
}

}  // namespace

#else  // built without GLFW

PreviewKey preview_key(int) { return PreviewKey::None; }
bool preview_available() { return false; }

bool PreviewWindow::start(const LiveImage&, const PreviewOptions&, std::string& why) {
    why = "this phos was built without the preview window (install libglfw3-dev and rebuild)";
    return false;
}

void PreviewWindow::finish() {}

#endif

}  // namespace phos::display
