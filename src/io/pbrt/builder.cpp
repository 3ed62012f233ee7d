// SceneBuilder core: graphics-state stack, transforms and coordinate systems, the rendering options
// (camera, film, sampler, integrator) and the load_pbrt entry point.
#include "io/pbrt/builder.h"

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "core/error.h"
#include "core/log.h"
#include "core/option_table.h"
#include "spectrum/color.h"

namespace phos::io {

scene::Scene load_pbrt(const std::string& path, const PbrtOptions& options) {
    pbrt::SceneBuilder builder(options, path);
    pbrt::parse_file(path, builder);
    scene::Scene s = builder.take_scene();
    s.source = path;
    // A pbrt file without an Integrator directive asks for pbrt-v4's default, volpath: phos's path.
    if (!s.settings.integrator) {
        s.settings.integrator = "path";
        s.settings.integrator_implied = true;
    }
    return s;
}

}  // namespace phos::io

namespace phos::io::pbrt {

namespace fs = std::filesystem;

SceneBuilder::SceneBuilder(const PbrtOptions& options, const std::string& main_file)
    : options_(options), main_dir_(fs::path(main_file).parent_path().string()) {}

void SceneBuilder::warn(const Loc& loc, const std::string& message) const {
    log::warn(loc.str() + ": " + message);
}

void SceneBuilder::warn_once(const std::string& key, const Loc& loc, const std::string& message) const {
    log::warn_once("pbrt:" + key, loc.str() + ": " + message);
}

void SceneBuilder::require_world(bool world, const std::string& directive, const Loc& loc) const {
    if (world && !world_) loc.fail(directive + " is only allowed after WorldBegin");
    if (!world && world_)
        loc.fail(directive + " is not allowed after WorldBegin (at " + world_loc_.str() + ")");
}

std::string SceneBuilder::resolve(const std::string& filename, const Loc& loc) const {
    const fs::path p(filename);
    if (p.is_absolute()) return filename;
    // The non-throwing overloads: a name the file system rejects (too long, say) is simply not found.
    std::error_code ec;
    const fs::path local = fs::path(loc.filename()).parent_path() / p;
    if (fs::exists(local, ec)) return local.string();
    const fs::path main = fs::path(main_dir_) / p;
    if (fs::exists(main, ec)) return main.string();
    return local.string();
}

int SceneBuilder::current_material() {
    if (gs_.material >= 0) return gs_.material;
    if (default_material_ < 0) {
        scene::Material m;  // pbrt-v4's default material: diffuse, reflectance 0.5
        m.name = "pbrt-default";
        m.diffuse = Rgb(0.5f);
        default_material_ = int(scene_.materials.size());
        scene_.materials.push_back(m);
    }
    return default_material_;
}

// ---- transforms ----

void SceneBuilder::set_ctm(const Transform& t, const Loc& loc) {
    for (float v : t.matrix().m)
        if (!std::isfinite(v)) loc.fail("transformation is not finite");
    gs_.ctm = t;
}

void SceneBuilder::identity(const Loc& loc) { set_ctm(Transform(), loc); }

void SceneBuilder::translate(Vec3 d, const Loc& loc) { set_ctm(gs_.ctm * Transform::translate(d), loc); }

void SceneBuilder::scale(Vec3 s, const Loc& loc) {
    if (s.x == 0 || s.y == 0 || s.z == 0) loc.fail("Scale by zero");
    set_ctm(gs_.ctm * Transform::scale(s), loc);
}

void SceneBuilder::rotate(float degrees, Vec3 axis, const Loc& loc) {
    if (!(length(axis) > 0)) loc.fail("Rotate about a zero-length axis");
    set_ctm(gs_.ctm * Transform::rotate(degrees, axis), loc);
}

void SceneBuilder::look_at(Vec3 eye, Vec3 target, Vec3 up, const Loc& loc) {
    try {
        set_ctm(gs_.ctm * Transform::look_at(eye, target, up), loc);
    } catch (const std::invalid_argument& e) {
        loc.fail(e.what());
    }
}

namespace {
// pbrt writes matrices column by column (translation in elements 12..14).
Transform from_pbrt_matrix(const float v[16], const Loc& loc) {
    Mat4 m;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) m(r, c) = v[c * 4 + r];
    Mat4 inv;
    if (!m.inverse(inv)) loc.fail("singular transformation matrix");
    return Transform(m, inv);
}
}  // namespace

void SceneBuilder::transform(const float m[16], const Loc& loc) { set_ctm(from_pbrt_matrix(m, loc), loc); }

void SceneBuilder::concat_transform(const float m[16], const Loc& loc) {
    set_ctm(gs_.ctm * from_pbrt_matrix(m, loc), loc);
}

void SceneBuilder::coordinate_system(const std::string& name, const Loc&) { coord_systems_[name] = gs_.ctm; }

void SceneBuilder::coord_sys_transform(const std::string& name, const Loc& loc) {
    const auto it = coord_systems_.find(name);
    if (it == coord_systems_.end()) loc.fail("CoordSysTransform: unknown coordinate system '" + name + "'");
    gs_.ctm = it->second;
}

void SceneBuilder::reverse_orientation(const Loc&) { gs_.reverse_orientation = !gs_.reverse_orientation; }

// ---- rendering options ----

void SceneBuilder::camera(const std::string& type, const ParamList& params, const Loc& loc) {
    require_world(false, "Camera", loc);
    CameraSpec c;
    c.type = type;
    c.loc = loc;
    c.medium = gs_.outside;
    const Transform world_to_camera = gs_.ctm;
    c.camera_to_world = world_to_camera.inverse();
    coord_systems_["camera"] = c.camera_to_world;
    const std::string d = "Camera \"" + type + "\"";
    if (type != "perspective" && type != "orthographic" && type != "spherical" && type != "realistic") {
        warn(loc,
             d + " is not supported; a perspective camera with the default 90 degree field of view is used");
        params.mark_all_used();
        c.type = "perspective";
    } else {
        if (type == "perspective") {
            c.fov_deg = params.get_float("fov", 90.0f);
            if (!(c.fov_deg > 0 && c.fov_deg < 180))
                params.find("fov")->loc.fail("fov must be in (0, 180) degrees");
        } else if (type == "spherical") {
            const std::string mapping = params.get_string("mapping", "equalarea");
            if (mapping != "equalarea" && mapping != "equirectangular")
                params.find("mapping")->loc.fail(d +
                                                 ": mapping must be \"equalarea\" or \"equirectangular\"");
            c.equirectangular = mapping == "equirectangular";
        } else if (type == "realistic") {
            realistic_lens(params, c, loc);
        }
        if (type == "perspective" || type == "orthographic") {
            c.lens_radius = params.get_float("lensradius", 0.0f);
            c.focal_distance = params.get_float("focaldistance", 1e6f);
        }
        if (c.lens_radius < 0) params.find("lensradius")->loc.fail("lensradius must not be negative");
        if (!(c.focal_distance > 0)) params.find("focaldistance")->loc.fail("focaldistance must be positive");
        const std::vector<float> sw =
            type != "realistic" ? params.get_floats("screenwindow") : std::vector<float>{};
        if (!sw.empty()) {
            if (sw.size() != 4 || !(sw[1] > sw[0]) || !(sw[3] > sw[2]))
                params.find("screenwindow")->loc.fail("screenwindow needs 4 values: xmin xmax ymin ymax");
            c.screen_window = sw;
        }
        // pbrt-v4's exposure time, a factor of the film's imaging ratio (no motion blur in phos).
        const float open = params.get_float("shutteropen", 0.0f),
                    close = params.get_float("shutterclose", 1.0f);
        c.exposure_time = close - open;
        if (!(c.exposure_time > 0)) {
            const Param* sp =
                params.has("shutterclose") ? params.find("shutterclose") : params.find("shutteropen");
            sp->loc.fail(d + ": shutterclose must be later than shutteropen (the shutter never opens)");
        }
        if (params.has("frameaspectratio")) {
            params.get_float("frameaspectratio", 1.0f);
            warn(params.find("frameaspectratio")->loc, d + ": parameter \"float frameaspectratio\" is not "
                                                           "supported (the film's aspect ratio is used)");
        }
    }
    done(params, d);
    camera_ = c;
}

void SceneBuilder::film(const std::string& type, const ParamList& params, const Loc& loc) {
    require_world(false, "Film", loc);
    const std::string d = "Film \"" + type + "\"";
    if (type != "rgb" && type != "gbuffer" && type != "spectral")
        warn(loc, d + " is not a pbrt-v4 film type; treated as \"rgb\"");
    if (type == "gbuffer") {
        // pbrt-v4 adds albedo, normal and depth channels to its EXR; phos writes them as images of
        // their own beside the image (OUT.albedo.exr...), as --aov does.
        scene_.settings.aovs = {"albedo", "normal", "depth"};
        log::info(loc.str() + ": note: " + d +
                  ": its albedo, normal and depth are written as images beside the image (as --aov "
                  "albedo,normal,depth)");
        params.get_string("coordinatesystem", "camera");  // phos's normals are in world space
    } else if (type == "spectral") {
        warn(loc, d + ": phos writes the RGB image; the per-wavelength channels are not written");
        for (const char* p : {"nbuckets", "lambdamin", "lambdamax"})
            if (params.has(p)) params.find(p);
    }
    const int w = params.get_int("xresolution", 1280), h = params.get_int("yresolution", 720);
    constexpr int kMax = scene::RenderSettings::kMaxResolution;
    if (w <= 0 || h <= 0 || w > kMax || h > kMax)
        loc.fail(d + ": resolution " + std::to_string(w) + " x " + std::to_string(h) + " is not in [1, " +
                 std::to_string(kMax) + "] on each side");
    scene_.settings.width = w;
    scene_.settings.height = h;
    const std::string out = params.get_string("filename", "");
    if (!out.empty()) scene_.settings.output = out;
    if (const Param* cp = params.find("cropwindow")) {
        const std::vector<float> c = params.get_floats("cropwindow");
        if (c.size() != 4 ||
            !(c[0] >= 0 && c[1] <= 1 && c[0] < c[1] && c[2] >= 0 && c[3] <= 1 && c[2] < c[3]))
            cp->loc.fail(d + ": cropwindow needs 4 values x0 x1 y0 y1 in [0, 1] with x0 < x1 and y0 < y1");
        scene_.settings.crop_window = std::array<float, 4>{c[0], c[1], c[2], c[3]};
    }
    if (const Param* bp = params.find("pixelbounds")) {
        const std::vector<int> b = params.get_ints("pixelbounds");
        if (b.size() != 4 ||
            !(b[0] >= 0 && b[1] <= w && b[0] < b[1] && b[2] >= 0 && b[3] <= h && b[2] < b[3]))
            bp->loc.fail(d + ": pixelbounds needs 4 values x0 x1 y0 y1 inside the " + std::to_string(w) +
                         " x " + std::to_string(h) + " image with x0 < x1 and y0 < y1");
        scene_.settings.pixel_bounds = std::array<int, 4>{b[0], b[1], b[2], b[3]};
        scene_.settings.crop_window.reset();  // pbrt-v4: pixelbounds win over cropwindow
    }
    // The sensor (pbrt-v4's PixelSensor): phos's film is the CIE 1931 observer. The imaging ratio
    // exposure time × ISO / 100 is completed by the camera's shutter times (end_of_files).
    film_iso_ = params.get_float("iso", 100.0f);
    film_diagonal_mm_ = params.get_float("diagonal", 35.0f);
    if (!(film_diagonal_mm_ > 0)) params.find("diagonal")->loc.fail(d + ": diagonal must be positive");
    if (!(film_iso_ > 0)) params.find("iso")->loc.fail(d + ": iso must be positive");
    float white_balance = params.get_float("whitebalance", 0.0f);
    if (!(white_balance == 0 || (white_balance >= 1000 && white_balance <= 40000)))
        params.find("whitebalance")
            ->loc.fail(d + ": whitebalance must be 0 (none) or a temperature in [1000, 40000] kelvin");
    const std::string sensor = params.get_string("sensor", "cie1931");
    if (sensor != "cie1931") {
        warn(params.find("sensor")->loc,
             d + ": sensor \"" + sensor + "\" is not supported; the CIE 1931 observer (\"cie1931\") is used");
        // pbrt-v4 white-balances a camera sensor for 6500 K unless told otherwise.
        if (white_balance == 0) white_balance = 6500;
    }
    scene_.film_response.white_balance_kelvin = white_balance;
    done(params, d);
}

void SceneBuilder::pixel_filter(const std::string& type, const ParamList& params, const Loc& loc) {
    require_world(false, "PixelFilter", loc);
    const std::string d = "PixelFilter \"" + type + "\"";
    using Kind = scene::PixelFilter::Kind;
    scene::PixelFilter f;
    if (type == "box")
        f.kind = Kind::Box;
    else if (type == "gaussian")
        f.kind = Kind::Gaussian;
    else if (type == "mitchell")
        f.kind = Kind::Mitchell;
    else if (type == "sinc" || type == "lanczos")
        f.kind = Kind::Lanczos;
    else if (type == "triangle")
        f.kind = Kind::Triangle;
    else
        loc.fail(
            d + ": unknown filter (pbrt-v4 has \"box\", \"gaussian\", \"mitchell\", \"sinc\", \"triangle\")");
    const Vec2 r = scene::PixelFilter::default_radius(f.kind);
    f.radius = {params.get_float("xradius", r.x), params.get_float("yradius", r.y)};
    for (const char* p : {"xradius", "yradius"})
        if (const Param* rp = params.find(p);
            rp && !(params.get_float(p, 1) > 0 && params.get_float(p, 1) <= 64))
            rp->loc.fail(d + ": \"" + std::string(p) + "\" must be in (0, 64] pixels");
    if (f.kind == Kind::Gaussian) {
        f.sigma = params.get_float("sigma", 0.5f);
        if (!(f.sigma > 0)) params.find("sigma")->loc.fail(d + ": sigma must be positive");
    } else if (f.kind == Kind::Mitchell) {
        f.b = params.get_float("B", 1.0f / 3.0f);
        f.c = params.get_float("C", 1.0f / 3.0f);
    } else if (f.kind == Kind::Lanczos) {
        f.tau = params.get_float("tau", 3.0f);
        if (!(f.tau > 0)) params.find("tau")->loc.fail(d + ": tau must be positive");
    }
    scene_.pixel_filter = f;
    filter_given_ = true;
    done(params, d);
}

void SceneBuilder::sampler(const std::string& type, const ParamList& params, const Loc& loc) {
    require_world(false, "Sampler", loc);
    const std::string d = "Sampler \"" + type + "\"";
    if (params.has("pixelsamples")) {
        const int spp = params.get_int("pixelsamples", 16);
        if (spp <= 0) params.find("pixelsamples")->loc.fail("pixelsamples must be positive");
        scene_.settings.spp = spp;
    }
    // phos has its own sample generator; the sampler's other settings do not apply.
    for (const char* p : {"seed", "randomization", "jitter", "xsamples", "ysamples", "dimensions"})
        if (params.has(p)) {
            params.find(p);
            warn(params.find(p)->loc,
                 d + ": parameter \"" + std::string(p) + "\" does not apply to phos (ignored)");
        }
    done(params, d);
}

namespace {
// pbrt-v4's integrators and the phos integrator that renders each; `same`: the same algorithm (the
// others are substitutes, with a warning). Any other renders with path, also with a warning.
struct PbrtIntegrator {
    const char* pbrt;
    const char* phos;
    bool same;
};
constexpr PbrtIntegrator kPbrtIntegrators[] = {
    {"path", "path", true},
    {"volpath", "path", true},  // phos's path tracer is its volumetric path tracer too
    {"sppm", "sppm", true},
    {"bdpt", "bdpt", true},
    {"mlt", "bdpt", false},  // Metropolis light transport explores bdpt's path space: the same image
};
}  // namespace

void SceneBuilder::integrator(const std::string& type, const ParamList& params, const Loc& loc) {
    require_world(false, "Integrator", loc);
    // pbrt-v3 SPPM's "numiterations" (upgrade_v3.h): the iterations, whatever the Sampler says.
    sppm_iterations_ = 0;
    if (const Param* n = type == "sppm" ? params.find("numiterations") : nullptr; n && n->type == "integer")
        sppm_iterations_ = int(n->numbers.at(0));
    // Parameters are kept as written; the renderer maps them onto its option tables by name
    // (maxdepth, radius, photonsperiteration, seed...) and warns about the ones it does not use.
    for (const Param& p : params.all()) {
        if (sppm_iterations_ > 0 && p.name == "numiterations") continue;
        scene::IntegratorParameter ip;
        ip.name = p.name;
        ip.type = p.type;
        for (double v : p.numbers) ip.values.push_back(options::format_number(v));
        for (const std::string& v : p.strings) ip.values.push_back(v);
        for (bool v : p.bools) ip.values.push_back(v ? "true" : "false");
        ip.file = p.loc.filename();
        ip.line = p.loc.line;
        ip.column = p.loc.col;
        if (p.loc.file) ip.included_from = p.loc.file->included_from;
        scene_.settings.integrator_parameters.push_back(std::move(ip));
    }
    params.mark_all_used();
    PbrtIntegrator match{"", "path", false};
    for (const PbrtIntegrator& i : kPbrtIntegrators)
        if (type == i.pbrt) match = i;
    scene_.settings.integrator = match.phos;
    if (!match.same) {
        scene_.settings.unavailable_integrator = type;
        scene_.settings.integrator_location = loc.str();
    }
}

void SceneBuilder::accelerator(const std::string& type, const ParamList& params, const Loc& loc) {
    require_world(false, "Accelerator", loc);
    params.mark_all_used();
    log::info(loc.str() + ": note: Accelerator \"" + type + "\" ignored (phos always uses Embree)");
}

void SceneBuilder::color_space(const std::string& name, const Loc& loc) {
    if (!spectrum::rgb_space_to_srgb(name, false))
        loc.fail("ColorSpace \"" + name +
                 "\": unknown (pbrt-v4 has \"srgb\", \"rec2020\", \"dci-p3\", \"aces2065-1\")");
    gs_.color_space = name;
}

void SceneBuilder::option(const Param& p, const Loc& loc) {
    const std::string d = "Option " + p.declaration();
    if (p.name == "seed") {
        // The render's seed: read like the Integrator's "seed" (the command line's --seed wins).
        if (p.type != "integer" || p.numbers.size() != 1 || p.numbers[0] < 0)
            p.loc.fail(d + ": takes one non-negative integer");
        scene::IntegratorParameter ip;
        ip.name = "seed";
        ip.type = "integer";
        ip.values = {options::format_number(p.numbers[0])};
        ip.file = p.loc.filename();
        ip.line = p.loc.line;
        ip.column = p.loc.col;
        if (p.loc.file) ip.included_from = p.loc.file->included_from;
        scene_.settings.integrator_parameters.push_back(std::move(ip));
    } else if (p.name == "rendercoordsys" || p.name == "pixelstats" || p.name == "wavefront" ||
               p.name == "disabletexturefiltering") {
        // Where pbrt renders (camera, camera-world or world space), its statistics images, its
        // GPU/wavefront mode and texture filtering: none of them changes phos's image.
        log::info(loc.str() + ": note: " + d + " does not change phos's image (ignored)");
    } else if (p.name == "displacementedgescale") {
        if (p.type != "float" || p.numbers.size() != 1 || !(p.numbers[0] > 0) || !std::isfinite(p.numbers[0]))
            p.loc.fail(d + ": takes one positive float");
        displacement_edge_scale_ = float(p.numbers[0]);
    } else if (p.name == "disablepixeljitter" || p.name == "disablewavelengthjitter" ||
               p.name == "forcediffuse") {
        warn(loc, d + " is not supported (ignored): phos renders as without it");
    } else {
        warn(loc, d + ": unknown option (ignored)");
    }
}

// ---- world structure ----

void SceneBuilder::world_begin(const Loc& loc) {
    if (world_) loc.fail("WorldBegin given twice (first at " + world_loc_.str() + ")");
    if (!stack_.empty())
        loc.fail("WorldBegin inside AttributeBegin (opened at " + stack_.back().loc.str() + ")");
    world_ = true;
    world_loc_ = loc;
    gs_.ctm = Transform();
    coord_systems_["world"] = gs_.ctm;
}

void SceneBuilder::attribute_begin(const Loc& loc) { stack_.push_back({gs_, loc, false}); }

void SceneBuilder::attribute_end(const Loc& loc) {
    if (stack_.empty()) loc.fail("AttributeEnd without matching AttributeBegin");
    if (stack_.back().transform_only)
        loc.fail("AttributeEnd closes the TransformBegin at " + stack_.back().loc.str());
    gs_ = stack_.back().state;
    stack_.pop_back();
}

void SceneBuilder::transform_begin(const Loc& loc) {
    warn_once("TransformBegin", loc,
              "TransformBegin/TransformEnd are deprecated in pbrt-v4 (handled as in pbrt-v3)");
    stack_.push_back({gs_, loc, true});
}

void SceneBuilder::transform_end(const Loc& loc) {
    if (stack_.empty()) loc.fail("TransformEnd without matching TransformBegin");
    if (!stack_.back().transform_only)
        loc.fail("TransformEnd closes the AttributeBegin at " + stack_.back().loc.str());
    gs_.ctm = stack_.back().state.ctm;
    stack_.pop_back();
}

void SceneBuilder::attribute(const std::string& target, const ParamList& params, const Loc& loc) {
    warn(loc, "Attribute \"" + target + "\" is not supported (its parameters are ignored)");
    params.mark_all_used();
}

void SceneBuilder::object_begin(const std::string& name, const Loc& loc) {
    require_world(true, "ObjectBegin", loc);
    if (object_ >= 0) loc.fail("ObjectBegin inside the object started at " + object_loc_.str());
    if (objects_.count(name)) loc.fail("object '" + name + "' defined twice");
    attribute_begin(loc);
    object_ = int(scene_.objects.size());
    object_loc_ = loc;
    objects_[name] = object_;
    scene_.objects.push_back({name, {}});
}

void SceneBuilder::object_end(const Loc& loc) {
    if (object_ < 0) loc.fail("ObjectEnd without matching ObjectBegin");
    object_ = -1;
    attribute_end(loc);
}

void SceneBuilder::object_instance(const std::string& name, const Loc& loc) {
    require_world(true, "ObjectInstance", loc);
    if (object_ >= 0) loc.fail("ObjectInstance inside an object definition is not allowed");
    const auto it = objects_.find(name);
    if (it == objects_.end()) loc.fail("ObjectInstance: unknown object '" + name + "'");
    scene_.instances.push_back({it->second, gs_.ctm});
}

void SceneBuilder::ignored_directive(const std::string& name, const Loc& loc) {
    warn(loc, name + " is not supported (ignored)");
}

void SceneBuilder::end_of_files(const Loc& loc) {
    if (object_ >= 0) object_loc_.fail("ObjectBegin without ObjectEnd");
    if (!stack_.empty())
        warn(stack_.back().loc, "AttributeBegin without AttributeEnd at the end of the input");
    if (!world_) warn(loc, "no WorldBegin in the scene");
    if (scene_.lights.empty() && skipped_light_)
        skipped_light_->fail(
            "none of the scene's lights can be used (this one is the first that cannot): its "
            "image would be black");
    if (sppm_iterations_ > 0) scene_.settings.spp = sppm_iterations_;
    // pbrt-v4's default pixel filter (for pbrt-v3 files too, as pbrt-v4 reads their upgrade).
    if (!filter_given_) {
        scene_.pixel_filter.kind = scene::PixelFilter::Kind::Gaussian;
        scene_.pixel_filter.radius = scene::PixelFilter::default_radius(scene_.pixel_filter.kind);
    }
    scene_.film_response.exposure = (camera_ ? camera_->exposure_time : 1.0f) * film_iso_ / 100;
    if (!camera_) return;  // the renderer frames the scene itself
    const CameraSpec& c = *camera_;
    scene::Camera cam;
    cam.eye = c.camera_to_world.point({0, 0, 0});
    cam.forward = normalize(c.camera_to_world.vector({0, 0, 1}));
    cam.up = normalize(c.camera_to_world.vector({0, 1, 0}));
    // pbrt's image x axis is camera +x; phos's is cross(forward, up).
    const Vec3 pbrt_right = c.camera_to_world.vector({1, 0, 0});
    cam.flip_x = dot(pbrt_right, cross(cam.forward, cam.up)) < 0;
    cam.lens_radius = c.lens_radius;
    cam.focal_distance = c.focal_distance;
    // pbrt's default screen window spans [-1, 1] along the shorter image axis.
    const int w = scene_.settings.width.value_or(1280), h = scene_.settings.height.value_or(720);
    float half_short = 1.0f;
    if (c.screen_window) {
        const std::vector<float>& sw = *c.screen_window;
        if (sw[0] != -sw[1] || sw[2] != -sw[3])
            warn(c.loc, "Camera: off-centre \"screenwindow\" is not supported; it is centred");
        half_short = w >= h ? 0.5f * (sw[3] - sw[2]) : 0.5f * (sw[1] - sw[0]);
    }
    if (c.type == "spherical") {
        cam.projection = scene::Camera::Projection::Spherical;
        cam.spherical_mapping = c.equirectangular ? scene::Camera::SphericalMapping::Equirectangular
                                                  : scene::Camera::SphericalMapping::EqualArea;
    } else if (c.type == "realistic") {
        cam.projection = scene::Camera::Projection::Realistic;
        cam.lens_elements = c.lens;
        cam.lens_focus_distance = c.focus_distance;
        cam.film_diagonal = film_diagonal_mm_ / 1000;
        cam.aperture = c.aperture;
    } else if (c.type == "orthographic") {
        cam.projection = scene::Camera::Projection::Orthographic;
        cam.ortho_half_size = half_short;
    } else {
        const float t = std::tan(0.5f * c.fov_deg * kPi / 180.0f) * half_short;
        cam.fov = 2.0f * std::atan(t);
    }
    scene_.camera = cam;
    scene_.camera_medium = c.medium;
}

}  // namespace phos::io::pbrt
