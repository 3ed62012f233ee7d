// Options shared by every integrator (image size, sampling budget, seed, depth, lens, shading
// switches, layers), filled from the command line and the scene file's render settings (the CLI
// wins). Their flags, defaults, ranges and help are in the option tables below (options.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/option_table.h"
#include "scene/pixel_filter.h"

namespace phos::render {

// The default --sharp-glossy exponent (see RenderOptions::sharp_glossy and docs/photon-mapping.md).
inline constexpr float kDefaultSharpGlossy = 10;
// The default --regularize exponent (see RenderOptions::regularize and docs/usage.md).
inline constexpr float kDefaultRegularize = 30;

// A render of part of the image (pbrt's Film "cropwindow" and "pixelbounds"; --crop-window,
// --pixel-bounds): the camera frames the full_width x full_height image and the render covers its
// pixels from (x0, y0) on, RenderOptions::width x height of them. full_width 0: the whole image.
struct CropWindow {
    int x0 = 0, y0 = 0;
    int full_width = 0, full_height = 0;
    bool active() const { return full_width > 0; }
};

struct RenderOptions {
    int width = 512;  // the image rendered (the crop's size when `crop` is active)
    int height = 512;
    int spp = 16;  // samples per pixel (iterations for progressive integrators)
    uint64_t seed = 0;
    int max_depth = 16;  // path segments from the camera
    // Glossy lobes at least as sharp as a modified-Phong lobe of this exponent are followed by
    // camera paths like mirrors and glass, and photons scattered by them stay caustic photons
    // (Bsdf::split_lobes); photonmap, ppm and sppm read it (integrators/transport_options.h).
    float sharp_glossy = kDefaultSharpGlossy;
    // Path regularisation (path): after a rough bounce, lobes sharper than a Phong lobe of exponent
    // regularize x (s + 1)^(1/3) at camera sample s are widened to it (Bsdf::regularized); 0 = off.
    float regularize = kDefaultRegularize;
    int dof_samples = 1;       // lens samples per pixel sample (--dof)
    float lens_radius = -1;    // --dof aperture radius; < 0: the scene camera's own lens
    float focal_distance = 1;  // --dof focal distance (with lens_radius >= 0)
    bool ambient =
        false;  // ka * ambient seen, like the glow e, by camera rays and after mirror/glass bounces
    bool background_light = false;  // the background lights diffuse surfaces too
    bool layers = false;            // --layers: integrators record their component layers
    std::vector<std::string> aovs;  // --aov: auxiliary images (albedo, normal, depth)
    // --filter, --filter-radius: the pixel filter replacing the scene's (unset: the scene's), and its
    // radius in pixels (0: the filter's own default, pbrt-v4's).
    std::optional<scene::PixelFilter::Kind> filter;
    float filter_radius = 0;
    // --crop-window x0 x1 y0 y1 (fractions of the image, as pbrt's cropwindow) or --pixel-bounds
    // x0 x1 y0 y1 (pixels, [x0, x1) x [y0, y1)); they replace the scene file's. The command resolves
    // them into `crop` and `width` x `height` before rendering (resolve_crop).
    std::optional<std::array<float, 4>> crop_window;
    std::optional<std::array<int, 4>> pixel_bounds;
    CropWindow crop;
};

// The part of a width x height image a crop window (fractions) or pixel bounds select, as pbrt-v4
// rounds them: pixels [ceil(W x0), ceil(W x1)) x [ceil(H y0), ceil(H y1)). Throws options::ValueError
// for an empty or out-of-image result.
CropWindow resolve_crop(int width, int height, const std::optional<std::array<float, 4>>& crop_window,
                        const std::optional<std::array<int, 4>>& pixel_bounds, int& crop_width,
                        int& crop_height);

// The pixel filter a render uses: the scene's, or the one --filter and --filter-radius give.
scene::PixelFilter effective_filter(const scene::PixelFilter& from_scene, const RenderOptions& options);

// The option tables over RenderOptions: "Image" (size, layers, AOVs) and "Sampling" (samples,
// seed, depth, lens, shading switches).
const options::Table& image_options();
const options::Table& sampling_options();

// The auxiliary images --aov accepts.
const std::vector<std::string>& aov_names();

}  // namespace phos::render
