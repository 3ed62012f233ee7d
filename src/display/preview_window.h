// `phos render --preview`: a window (GLFW + OpenGL) showing the image as it converges, on its own
// thread. It redraws only when the image or the view changed, at most about 20 times a second.
// Keys: + / - exposure, l (or Tab) cycles the layers (image, then the film's layers and AOVs), s
// saves the shown layer as EXR beside the output, q / Esc ends the render cleanly (as Ctrl-C
// does: the image so far is written). Closing the window stops showing; the render goes on.
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <thread>

#include "display/live_image.h"

namespace phos::display {

struct PreviewOptions {
    std::string title = "phos";
    float exposure = 0;           // stops
    bool hold = false;            // --preview-hold: stay open after the render until closed
    std::string snapshot_stem;    // `s` writes STEM.snapshot-N.exr
    std::string screenshot_path;  // --preview-screenshot: the window's pixels when it closes
};

// What a key does (exposed for tests).
enum class PreviewKey { None, ExposureUp, ExposureDown, NextLayer, Save, Quit };
PreviewKey preview_key(int glfw_key);

// Whether this phos was built with the preview window (GLFW found at build time).
bool preview_available();

class PreviewWindow {
public:
    PreviewWindow();
    ~PreviewWindow();
    PreviewWindow(const PreviewWindow&) = delete;
    PreviewWindow& operator=(const PreviewWindow&) = delete;

    // Opens the window on its own thread. False, with the reason in `why`, when there is no
    // display (or no GLFW in this build): the caller warns once and renders on.
    bool start(const LiveImage& image, const PreviewOptions& options, std::string& why);
    // The render is over: with `hold`, returns when the user closes the window; otherwise closes it
    // after showing the final image.
    void finish();

    struct State;  // shared with the window's thread (preview_window.cpp)

private:
    std::unique_ptr<State> state_;
    std::thread thread_;
};

}  // namespace phos::display
