// The whole scene as plain data: what every loader produces and what the renderer consumes.
// Tests build scenes by hand through this struct, without any file.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "scene/camera.h"
#include "scene/light.h"
#include "scene/material.h"
#include "scene/medium.h"
#include "scene/pixel_filter.h"
#include "scene/shape.h"
#include "scene/texture.h"
#include "spectrum/distribution.h"

namespace phos::scene {

// A parameter of the scene file's integrator (pbrt `Integrator "sppm" "float radius" [0.1]`),
// kept as written: the renderer maps it onto its option tables by name (app/lib/render_command.cpp).
struct IntegratorParameter {
    std::string name, type;           // "radius", "float"
    std::vector<std::string> values;  // as text: numbers, "true"/"false", strings
    std::string file;                 // where it is written
    int line = 0, column = 0;
    std::vector<std::string> included_from;  // the Include lines that led to `file`, innermost first
};

// Render settings a scene file may carry (pbrt's Film/Sampler/Integrator); the CLI wins.
struct RenderSettings {
    static constexpr int kMaxResolution = 65536;  // pixels on a side, for files and --width/--height
    std::optional<int> width, height;
    std::optional<int> spp;
    std::optional<std::string> integrator;  // phos integrator name
    // The file names no integrator: `integrator` is its format's default (pbrt-v4's volpath: path),
    // which phos may replace by one fitted to the scene (app/lib/scene_defaults.h).
    bool integrator_implied = false;
    std::optional<std::string> output;  // image filename
    // pbrt's Film "cropwindow" (fractions x0 x1 y0 y1) or "pixelbounds" (pixels [x0, x1) x [y0, y1)):
    // only that part of the image is rendered and written.
    std::optional<std::array<float, 4>> crop_window;
    std::optional<std::array<int, 4>> pixel_bounds;
    // Auxiliary images the file asks for (pbrt's Film "gbuffer": albedo, normal, depth), written as
    // --aov writes them; the command line's --aov wins.
    std::vector<std::string> aovs;
    // When the file names an integrator phos does not have (pbrt "bdpt"): its name and where, so
    // the renderer can say which integrator it uses instead (unless --integrator chose one).
    std::string unavailable_integrator, integrator_location;
    std::vector<IntegratorParameter> integrator_parameters;
};

// How the film turns the light reaching it into the image, from pbrt-v4's film and camera
// settings: the image is multiplied by `exposure` (pbrt-v4's imaging ratio, exposure time × ISO /
// 100), and with `white_balance_kelvin` > 0 its linear sRGB is adapted from the white of an
// illuminant of that temperature to the sRGB white (spectrum::white_balance). The defaults leave
// the image as rendered.
struct FilmResponse {
    float white_balance_kelvin = 0;  // 0: no white balance
    float exposure = 1;
};

struct Scene {
    std::optional<Camera> camera;  // absent: the renderer frames the bounding box
    std::vector<Shape> shapes;
    std::vector<Object> objects;
    std::vector<Instance> instances;
    std::vector<Material> materials;
    std::vector<Light> lights;
    std::vector<Texture> textures;
    std::vector<Medium> media;
    int camera_medium = -1;
    Rgb background{0.0f};  // radiance of escaping camera / specular rays
    Rgb ambient{0.0f};     // .scn `ambient`, used only with --ambient
    RenderSettings settings;
    FilmResponse film_response;
    PixelFilter pixel_filter;  // how camera samples make pixels (the box of radius 1/2 by default)
    std::string source;        // the file it was loaded from

    // Adds an area light emitting radiance `L` from `shape` (appended); returns the light index.
    // `spectrum`: the radiance's spectrum when the file gives one (Light::spectrum), L its sRGB.
    int add_area_light(Shape shape, Rgb L, bool two_sided = false,
                       std::optional<spectrum::Distribution> spectrum = std::nullopt) {
        Light light;
        light.kind = Light::Kind::Area;
        light.color = L;
        light.spectrum = std::move(spectrum);
        light.two_sided = two_sided;
        light.shape = int(shapes.size());
        const int index = int(lights.size());
        shape.area_light = index;
        shapes.push_back(std::move(shape));
        lights.push_back(std::move(light));
        return index;
    }
};

}  // namespace phos::scene
