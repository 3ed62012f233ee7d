// The option tables of RenderOptions (see options.h and core/option_table.h).
#include "render/options.h"

#include <cmath>

#include "scene/scene.h"

namespace phos::render {

using options::at_least;
using options::between;
using options::Effect;
using options::positive;
using options::ValueError;

namespace {
const options::Choices<scene::PixelFilter::Kind>& filter_choices() {
    using K = scene::PixelFilter::Kind;
    static const options::Choices<K> choices{{K::Box, "box"},
                                             {K::Gaussian, "gaussian"},
                                             {K::Mitchell, "mitchell"},
                                             {K::Lanczos, "sinc"},
                                             {K::Triangle, "triangle"}};
    return choices;
}
}  // namespace

scene::PixelFilter effective_filter(const scene::PixelFilter& from_scene, const RenderOptions& options) {
    scene::PixelFilter f = from_scene;
    if (options.filter && *options.filter != f.kind) {
        f = scene::PixelFilter{};
        f.kind = *options.filter;
        f.radius = scene::PixelFilter::default_radius(f.kind);
    }
    if (options.filter_radius > 0) f.radius = {options.filter_radius, options.filter_radius};
    return f;
}

CropWindow resolve_crop(int width, int height, const std::optional<std::array<float, 4>>& crop_window,
                        const std::optional<std::array<int, 4>>& pixel_bounds, int& crop_width,
                        int& crop_height) {
    crop_width = width;
    crop_height = height;
    if (!crop_window && !pixel_bounds) return {};
    std::array<int, 4> b{0, width, 0, height};
    if (pixel_bounds) {
        b = *pixel_bounds;
    } else {
        const std::array<float, 4>& c = *crop_window;
        for (const float v : c)
            if (!(v >= 0 && v <= 1)) throw ValueError("crop window values must be in [0, 1]");
        b = {int(std::ceil(double(width) * c[0])), int(std::ceil(double(width) * c[1])),
             int(std::ceil(double(height) * c[2])), int(std::ceil(double(height) * c[3]))};
    }
    if (b[0] < 0 || b[2] < 0 || b[1] > width || b[3] > height || b[1] <= b[0] || b[3] <= b[2])
        throw ValueError("pixel bounds [" + std::to_string(b[0]) + ", " + std::to_string(b[1]) + ") x [" +
                         std::to_string(b[2]) + ", " + std::to_string(b[3]) + ") select no pixel of the " +
                         std::to_string(width) + " x " + std::to_string(height) + " image");
    if (b[0] == 0 && b[2] == 0 && b[1] == width && b[3] == height) return {};
    crop_width = b[1] - b[0];
    crop_height = b[3] - b[2];
    return {b[0], b[2], width, height};
}

const std::vector<std::string>& aov_names() {
    static const std::vector<std::string> names{"albedo", "normal", "depth"};
    return names;
}

const options::Table& image_options() {
    static const options::Table table = [] {
        options::TableBuilder<RenderOptions> b("Image", "image size, component layers and auxiliary images");
        b.number("width", &RenderOptions::width, "W", between(1, scene::RenderSettings::kMaxResolution),
                 "image width in pixels; given alone, the height follows the scene's aspect ratio")
            .default_text = "the scene file's, else 512";
        b.number("height", &RenderOptions::height, "H", between(1, scene::RenderSettings::kMaxResolution),
                 "image height in pixels; given alone, the width follows the scene's aspect ratio")
            .default_text = "the scene file's, else 512";
        b.custom(
             "resolution", "W H", 2, "image size (the seed's -resolution)",
             [](RenderOptions& o, const std::vector<std::string>& v) {
                 const long long w = options::parse_integer(v.at(0)), h = options::parse_integer(v.at(1));
                 options::TableBuilder<RenderOptions>::check_range(
                     double(w), between(1, scene::RenderSettings::kMaxResolution));
                 options::TableBuilder<RenderOptions>::check_range(
                     double(h), between(1, scene::RenderSettings::kMaxResolution));
                 o.width = int(w);
                 o.height = int(h);
             },
             [](const RenderOptions& o) { return std::to_string(o.width) + " " + std::to_string(o.height); })
            .default_text = "the scene file's, else 512 512";
        b.flag("layers", &RenderOptions::layers,
               "also write the integrator's component layers as OUT.<layer>.<ext> (photonmap and path: "
               "direct, caustic, indirect, specular; whitted: direct, specular; ppm/sppm: direct, indirect)")
            .effect = Effect::None;
        auto& aov = b.custom(
            "aov", "NAMES", 1,
            "also write auxiliary images for denoisers as OUT.<name>.<ext>: a comma-separated list of "
            "albedo, "
            "normal, depth",
            [](RenderOptions& o, const std::vector<std::string>& v) {
                o.aovs.clear();
                const std::string& s = v.at(0);
                size_t at = 0;
                while (at <= s.size()) {
                    size_t end = s.find(',', at);
                    if (end == std::string::npos) end = s.size();
                    const std::string name = s.substr(at, end - at);
                    bool known = false;
                    for (const auto& n : aov_names()) known |= n == name;
                    if (!known) throw ValueError("'" + name + "' is not one of albedo, normal, depth");
                    bool dup = false;
                    for (const auto& n : o.aovs) dup |= n == name;
                    if (!dup) o.aovs.push_back(name);
                    at = end + 1;
                }
            },
            [](const RenderOptions& o) {
                std::string s;
                for (const auto& n : o.aovs) s += (s.empty() ? "" : ",") + n;
                return s;
            });
        aov.effect = Effect::None;
        aov.default_text = "none";
        aov.range_text = "albedo,normal,depth";
        auto& filter = b.custom(
            "filter", "NAME", 1,
            "pixel filter, sampled by filter importance sampling (as pbrt-v4): box (radius 0.5), gaussian "
            "(1.5, sigma 0.5), mitchell (2, B = C = 1/3), sinc (Lanczos, 4, tau 3), triangle (2)",
            [](RenderOptions& o, const std::vector<std::string>& v) {
                o.filter = options::parse_choice(filter_choices(), v.at(0));
            },
            [](const RenderOptions& o) {
                return o.filter ? options::choice_name(filter_choices(), *o.filter) : std::string("scene");
            });
        filter.default_text = "the scene file's (pbrt: its PixelFilter, else gaussian), else box";
        filter.range_text = options::choice_list(filter_choices());
        b.number("filter-radius", &RenderOptions::filter_radius, "R", between(0, 64),
                 "the pixel filter's radius in pixels (0: the filter's default; the scene's when it names "
                 "the same filter)")
            .default_text = "0";
        auto& crop = b.custom(
            "crop-window", "X0 X1 Y0 Y1", 4,
            "render only this part of the image, as fractions of its width and height (pbrt's cropwindow); "
            "the image written is that part",
            [](RenderOptions& o, const std::vector<std::string>& v) {
                std::array<float, 4> c{};
                for (size_t i = 0; i < 4; ++i) {
                    c[i] = float(options::parse_number(v.at(i)));
                    options::TableBuilder<RenderOptions>::check_range(double(c[i]), between(0, 1));
                }
                if (!(c[1] > c[0] && c[3] > c[2]))
                    throw ValueError("the window is empty (needs X0 < X1, Y0 < Y1)");
                o.crop_window = c;
                o.pixel_bounds.reset();
            },
            [](const RenderOptions& o) {
                if (!o.crop_window) return std::string("none");
                std::string s;
                for (const float v : *o.crop_window)
                    s += (s.empty() ? "" : " ") + options::format_number(v, true);
                return s;
            });
        crop.default_text = "the scene file's, else the whole image";
        auto& bounds = b.custom(
            "pixel-bounds", "X0 X1 Y0 Y1", 4,
            "render only pixels [X0, X1) x [Y0, Y1) of the image (pbrt's pixelbounds); the image written is "
            "that part",
            [](RenderOptions& o, const std::vector<std::string>& v) {
                std::array<int, 4> p{};
                for (size_t i = 0; i < 4; ++i) {
                    const long long n = options::parse_integer(v.at(i));
                    options::TableBuilder<RenderOptions>::check_range(
                        double(n), between(0, scene::RenderSettings::kMaxResolution));
                    p[i] = int(n);
                }
                if (!(p[1] > p[0] && p[3] > p[2]))
                    throw ValueError("the bounds are empty (needs X0 < X1, Y0 < Y1)");
                o.pixel_bounds = p;
                o.crop_window.reset();
            },
            [](const RenderOptions& o) {
                if (!o.pixel_bounds) return std::string("none");
                std::string s;
                for (const int v : *o.pixel_bounds) s += (s.empty() ? "" : " ") + std::to_string(v);
                return s;
            });
        bounds.default_text = "the scene file's, else the whole image";
        return b.build();
    }();
    return table;
}

const options::Table& sampling_options() {
    static const options::Table table = [] {
        options::TableBuilder<RenderOptions> b("Sampling",
                                               "samples, seed, path depth, lens and shading switches");
        auto& spp = b.number("spp", &RenderOptions::spp, "N", between(1, 1 << 20),
                             "samples per pixel (iterations for ppm/sppm)");
        spp.effect = Effect::Budget;
        spp.default_text = "the scene file's (for its own integrator), else 16";
        auto& aa = b.custom(
            "aa", "N", 1, "anti-aliasing level N: 4^N samples per pixel (the seed's -aa); replaces --spp",
            [](RenderOptions& o, const std::vector<std::string>& v) {
                const long long n = options::parse_integer(v.at(0));
                options::TableBuilder<RenderOptions>::check_range(double(n), between(0, 8));
                o.spp = 1 << (2 * n);
            },
            [](const RenderOptions& o) {
                int n = 0;
                while ((1 << (2 * (n + 1))) <= o.spp && n < 8) ++n;
                return std::to_string(n);
            });
        aa.effect = Effect::Budget;
        aa.default_text = "none (--spp)";
        aa.range_text = "[0, 8]";
        b.number("seed", &RenderOptions::seed, "S", at_least(0),
                 "random seed: the same scene, options and seed give a bit-identical image for any --threads")
            .pbrt = "seed";
        b.number("max-depth", &RenderOptions::max_depth, "N", between(0, 100000),
                 "maximum number of bounces from the camera (pbrt's maxdepth)")
            .pbrt = "maxdepth";
        auto& dof = b.custom(
            "dof", "SAMPLES DISTANCE RADIUS", 3,
            "thin-lens depth of field: lens samples per pixel sample, focal distance, aperture radius "
            "(replaces the scene camera's lens)",
            [](RenderOptions& o, const std::vector<std::string>& v) {
                const long long n = options::parse_integer(v.at(0));
                const double d = options::parse_number(v.at(1)), r = options::parse_number(v.at(2));
                using B = options::TableBuilder<RenderOptions>;
                try {
                    B::check_range(double(n), between(1, 4096));
                } catch (const ValueError& e) {
                    throw ValueError(std::string("SAMPLES ") + e.what());
                }
                if (!positive().contains(d)) throw ValueError("DISTANCE " + v[1] + " is not in (0, inf)");
                if (!at_least(0).contains(r)) throw ValueError("RADIUS " + v[2] + " is not in [0, inf)");
                o.dof_samples = int(n);
                o.focal_distance = float(d);
                o.lens_radius = float(r);
            },
            [](const RenderOptions& o) {
                return o.lens_radius < 0 ? std::string("off")
                                         : std::to_string(o.dof_samples) + " " +
                                               options::format_number(o.focal_distance, true) + " " +
                                               options::format_number(o.lens_radius, true);
            });
        dof.default_text = "the scene camera's lens";
        b.flag("ambient", &RenderOptions::ambient, ".scn: add the non-physical ka * ambient term");
        b.flag("background-light", &RenderOptions::background_light,
               "the background radiance also lights diffuse surfaces");
        return b.build();
    }();
    return table;
}

}  // namespace phos::render
