// `phos photons SCENE --view`: a 3-D viewer of photon maps (GLFW + OpenGL, on the calling thread):
// the photons as points over the scene's geometry drawn as lines. Mouse: left drag orbits, right
// (or middle) drag pans, the wheel zooms, a click picks the nearest photon under the cursor and
// prints its record. Keys: 1-9 toggle each map, c cycles the colouring (power / map / bounce count
// when the points have one), + / - point size, r resets the view, q / Esc closes.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/vec.h"

namespace phos::display {

struct ViewerPoint {
    Vec3 position;
    Rgb colour;         // the power as a displayable colour (sRGB-encoded, 0-1)
    uint8_t group = 0;  // the map it belongs to (index into ViewerScene::group_names)
    int bounces = -1;   // scattering events before it was stored (-1: unknown)
    uint32_t id = 0;    // the caller's index, for describe()
};

struct ViewerScene {
    std::vector<ViewerPoint> points;
    std::vector<std::string> group_names;              // "global", "caustic", ...
    std::vector<Vec3> lines;                           // the scene's geometry, 2 vertices per segment
    std::function<std::string(uint32_t id)> describe;  // the record printed when a point is picked
};

enum class ViewerColouring { Power = 0, Map = 1, Bounces = 2 };

struct ViewerOptions {
    std::string title = "phos photons";
    float point_size = 2;
    ViewerColouring colouring = ViewerColouring::Power;  // the first colouring shown
    // Draw one frame, write the window's pixels here and close (for docs and tests).
    std::string screenshot_path;
};

// Opens the viewer and returns when it is closed: true, or false with the reason in `why` when
// there is no display (or no GLFW in this build).
bool run_photon_viewer(const ViewerScene& scene, const ViewerOptions& options, std::string& why);

// The colour of group `g` in the "map" colouring (distinct, saturated).
Rgb group_colour(int g);
// The colour of a bounce count in the "bounces" colouring: 0 (straight from a light) white, then
// red, orange, yellow, green, cyan, blue, violet for 1..7 bounces, 8 or more magenta; grey unknown.
Rgb bounce_colour(int bounces);

}  // namespace phos::display
