// SceneBuilder: LightSource, AreaLightSource, MakeNamedMedium and MediumInterface. Emission follows
// pbrt-v4's conventions: RGB values are radiance/intensity as given, other spectra are normalised to
// luminance 1, then `scale` and any `power`/`illuminance` normalisation apply.
#include <cmath>
#include <map>

#include "core/equal_area.h"
#include "core/error.h"
#include "core/log.h"
#include "io/image/image_io.h"
#include "io/pbrt/builder.h"
#include "io/pbrt/measured_media.h"
#include "io/text/image_texture.h"
#include "io/volume/volume_grid.h"

namespace phos::io::pbrt {
void SceneBuilder::light_source(const std::string& type, const ParamList& params, const Loc& loc) {
    require_world(true, "LightSource", loc);
    const std::string d = "LightSource \"" + type + "\"";
    if (object_ >= 0) {
        warn(loc, d + ": lights inside ObjectBegin/ObjectEnd are not supported (skipped)");
        if (!skipped_light_) skipped_light_ = loc;
        params.mark_all_used();
        return;
    }
    const Transform& t = gs_.ctm;
    scene::Light light;
    light.to_world = t;
    const float scale = params.get_float("scale", 1.0f);
    // The emission (times `scale`), and its spectrum when the file gives one; times(k) scales both.
    std::optional<spectrum::Distribution> emission;
    auto emitted = [&](const char* name) {
        const Rgb c = color(params, name, SpectrumUse::Illuminant, &emission).value_or(Rgb(1.0f)) * scale;
        if (emission) emission = emission->scaled(scale);
        return c;
    };
    auto times = [&](float k) {
        light.color = light.color * k;
        if (emission) emission = emission->scaled(k);
    };
    // A light's image (pbrt-v4 decodes 8-bit images from sRGB) as a scene texture; its index.
    auto image_texture = [&](const Param& fp) {
        const std::string path = resolve(params.get_string("filename", ""), fp.loc);
        Image img;
        try {
            img = read_image(path, true);
        } catch (const std::exception& ex) {
            fp.loc.fail(d + ": " + std::string(ex.what()));
        }
        for (const Rgb& c : img.pixels)
            if (!c.is_finite()) fp.loc.fail(d + ": the image has pixels that are not finite");
        scene::Texture tex;
        tex.kind = scene::Texture::Kind::Image;
        tex.image = text::to_texture_image(std::move(img));
        tex.filename = path;
        scene_.textures.push_back(std::move(tex));
        return int(scene_.textures.size()) - 1;
    };
    // pbrt-v3's goniometric "mapname": a lat-long image looked up (bilinearly, repeating, as
    // pbrt-v3's MIPMap at level 0) at s = phi / 2 pi, t = theta / pi of the direction in the light's
    // y/z-swapped space (theta from its +z, row 0 at the top), resampled at load into the equal-area
    // square that pbrt-v4 indexes with the same swapped direction: N x N pixels, N^2 >= 2 W H.
    auto latlong_to_equal_area = [&](const Param& mp, const std::string& name, const std::string& what) {
        Image img;
        try {
            img = read_image(resolve(name, mp.loc), true);
        } catch (const std::exception& ex) {
            mp.loc.fail(what + ": " + std::string(ex.what()));
        }
        if (img.width <= 0 || img.height <= 0) mp.loc.fail(what + ": the image has no pixels");
        for (const Rgb& c : img.pixels)
            if (!c.is_finite()) mp.loc.fail(what + ": the image has pixels that are not finite");
        const int w = img.width, h = img.height;
        auto texel = [&](int x, int y) {
            x = ((x % w) + w) % w;
            y = ((y % h) + h) % h;
            return img.pixels[size_t(y) * size_t(w) + size_t(x)];
        };
        const int n = std::min(2048, int(std::ceil(std::sqrt(2.0 * double(w) * double(h)))));
        auto map = std::make_shared<scene::TextureImage>();
        map->width = map->height = n;
        map->texels.resize(size_t(n) * size_t(n));
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const Vec3 v =
                    equal_area_square_to_sphere({(float(x) + 0.5f) / float(n), (float(y) + 0.5f) / float(n)});
                const float theta = std::acos(std::clamp(v.z, -1.0f, 1.0f));
                float phi = std::atan2(v.y, v.x);
                if (phi < 0) phi += 2 * kPi;
                const float fx = phi / (2 * kPi) * float(w) - 0.5f, fy = theta / kPi * float(h) - 0.5f;
                const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
                const float dx = fx - float(x0), dy = fy - float(y0);
                map->texels[size_t(y) * size_t(n) + size_t(x)] =
                    texel(x0, y0) * ((1 - dx) * (1 - dy)) + texel(x0 + 1, y0) * (dx * (1 - dy)) +
                    texel(x0, y0 + 1) * ((1 - dx) * dy) + texel(x0 + 1, y0 + 1) * (dx * dy);
            }
        scene::Texture tex;
        tex.kind = scene::Texture::Kind::Image;
        tex.image = std::move(map);
        tex.filename = name;
        scene_.textures.push_back(std::move(tex));
        return int(scene_.textures.size()) - 1;
    };
    auto required_image = [&]() -> const Param& {
        const Param* fp = params.find("filename");
        if (!fp) loc.fail(d + ": missing \"string filename\"");
        return *fp;
    };
    auto positive = [&](const char* name) {
        const float v = params.get_float(name, -1.0f);
        if (params.has(name) && !(v > 0))
            params.find(name)->loc.fail(d + ": \"" + std::string(name) + "\" must be positive");
        return v;
    };

    if (type == "point") {
        light.kind = scene::Light::Kind::Point;
        light.color = emitted("I");
        const float power = positive("power");
        if (power > 0) times(power / (4 * kPi));
        light.position = t.point(params.get_point3("from", {0, 0, 0}));
    } else if (type == "spot") {
        light.kind = scene::Light::Kind::Spot;
        light.color = emitted("I");
        const Vec3 from = params.get_point3("from", {0, 0, 0}), to = params.get_point3("to", {0, 0, 1});
        if (!(length(to - from) > 0)) loc.fail(d + ": \"from\" and \"to\" coincide");
        const float cone = params.get_float("coneangle", 30.0f),
                    delta = params.get_float("conedeltaangle", 5.0f);
        if (!(cone > 0 && cone <= 180)) loc.fail(d + ": coneangle must be in (0, 180]");
        light.position = t.point(from);
        light.direction = normalize(t.vector(to - from));
        light.cutoff = cone * kPi / 180.0f;
        light.falloff_start = std::clamp(cone - delta, 0.0f, cone) * kPi / 180.0f;
        light.dropoff = 0;
        const float power = positive("power");
        if (power > 0) {
            const float c0 = std::cos(light.falloff_start), c1 = std::cos(light.cutoff);
            times(power / (2 * kPi * ((1 - c0) + 0.5f * (c0 - c1))));
        }
    } else if (type == "distant") {
        light.kind = scene::Light::Kind::Directional;
        light.color = emitted("L");
        const Vec3 from = params.get_point3("from", {0, 0, 0}), to = params.get_point3("to", {0, 0, 1});
        if (!(length(to - from) > 0)) loc.fail(d + ": \"from\" and \"to\" coincide");
        light.direction = normalize(t.vector(to - from));
        const float e = positive("illuminance");
        if (e > 0) times(e);
    } else if (type == "infinite") {
        light.kind = scene::Light::Kind::Infinite;
        const Param* fp = params.find("filename");
        if (fp && params.has("L")) loc.fail(d + ": give either \"L\" or \"filename\", not both");
        if (const Param* pp = params.find("portal")) {
            // pbrt-v4: four points in world space (not the current transform) making a rectangle;
            // its frame's z, (p3 - p0) x (p1 - p0), is the side the light shines from.
            // pbrt-v4 only warns when the points are not a rectangle: phos refuses them.
            const std::vector<Vec3> p = params.get_point3s("portal");
            if (p.size() != 4) pp->loc.fail(d + ": \"portal\" takes four points");
            const Vec3 p01 = p[1] - p[0], p12 = p[2] - p[1], p32 = p[2] - p[3], p03 = p[3] - p[0];
            if (!(length(p01) > 0 && length(p12) > 0 && length(p32) > 0 && length(p03) > 0))
                pp->loc.fail(d + ": the portal has coincident points");
            const Vec3 a = normalize(p01), b = normalize(p12), c = normalize(p32), e03 = normalize(p03);
            if (std::fabs(dot(a, c) - 1) > 0.001f || std::fabs(dot(b, e03) - 1) > 0.001f)
                pp->loc.fail(d + ": the portal's opposite edges are not parallel");
            if (std::fabs(dot(a, b)) > 0.001f || std::fabs(dot(b, c)) > 0.001f ||
                std::fabs(dot(c, e03)) > 0.001f || std::fabs(dot(e03, a)) > 0.001f)
                pp->loc.fail(d + ": the portal's edges are not perpendicular");
            light.portal = p;
        }
        const float e = positive("illuminance");
        if (!fp) {
            light.color = emitted("L");
            // A uniform environment of radiance L gives illuminance pi * L on an upward surface.
            if (e > 0) times(e / kPi);
            if (emission && !light.portal.empty())
                warn(params.find("L")->loc,
                     d + ": a portal light reads a spectral \"L\" as its RGB (as pbrt-v4)");
        } else {
            light.texture = image_texture(*fp);
            light.color = Rgb(scale);
            const scene::TextureImage& img = *scene_.textures[size_t(light.texture)].image;
            light.equal_area = img.width == img.height;
            if (!light.equal_area) {
                if (e > 0)
                    warn(loc,
                         d + ": \"illuminance\" with a latitude-longitude map is not supported (ignored)");
                warn(fp->loc, d + ": a non-square map is read as a latitude-longitude map (pbrt-v4 expects "
                                  "equal-area square maps)");
            } else if (e > 0) {
                // pbrt-v4's illuminance of the map's upper hemisphere, summed over the pixel centres
                // with z > 0 as pbrt-v4 sums it (2 pi / N per pixel, where a pixel spans 4 pi / N).
                const int n = img.width;
                double k_e = 0;
                for (int y = 0; y < n; ++y)
                    for (int x = 0; x < n; ++x) {
                        const Vec3 w = equal_area_square_to_sphere(
                            {(float(x) + 0.5f) / float(n), (float(y) + 0.5f) / float(n)});
                        if (w.z > 0) k_e += double(img.at(x, y).luminance()) * w.z;
                    }
                k_e *= 2 * double(kPi) / (double(n) * double(n));
                if (!(k_e > 0))
                    params.find("illuminance")->loc.fail(d + ": the map's upper hemisphere is black");
                times(float(e / k_e));
            }
        }
    } else if (type == "goniometric") {
        light.kind = scene::Light::Kind::Goniometric;
        light.color = emitted("I");
        if (const Param* mp = params.find("mapname")) {
            // pbrt-v3 (its "mapname", which the v3 upgrade keeps): a lat-long map.
            if (params.has("filename")) loc.fail(d + ": give either \"filename\" or \"mapname\", not both");
            light.texture = latlong_to_equal_area(*mp, params.get_string("mapname", ""), d);
        } else {
            light.texture = image_texture(required_image());
        }
        const scene::TextureImage& img = *scene_.textures[size_t(light.texture)].image;
        if (img.width != img.height)
            required_image().loc.fail(d + ": the image is " + std::to_string(img.width) + " x " +
                                      std::to_string(img.height) + "; pbrt-v4 takes a square equal-area map");
        const float power = positive("power");
        if (power > 0) {
            // pbrt-v4: the flux of the map read as grey (its channels' average) is 4 pi mean.
            double sum = 0;
            for (const Rgb& c : img.texels) sum += c.average();
            const double k_e = 4 * double(kPi) * sum / double(img.texels.size());
            if (!(k_e > 0)) params.find("power")->loc.fail(d + ": \"power\" with a black image");
            times(float(power / k_e));
        }
        // pbrt-v4 looks the map up with y and z swapped in the light's space.
        Mat4 swap_yz;
        swap_yz(1, 1) = swap_yz(2, 2) = 0;
        swap_yz(1, 2) = swap_yz(2, 1) = 1;
        light.to_world = t * Transform(swap_yz, swap_yz);
        light.position = t.point({0, 0, 0});
    } else if (type == "projection") {
        light.kind = scene::Light::Kind::Projection;
        // pbrt-v4 reads no "I" (pbrt-v3 did): an "I" multiplies the image as pbrt-v3's did.
        light.color = emitted("I");
        light.texture = image_texture(required_image());
        const scene::TextureImage& img = *scene_.textures[size_t(light.texture)].image;
        const float fov = params.get_float("fov", 90.0f);
        if (!(fov > 0 && fov < 180)) params.find("fov")->loc.fail(d + ": fov must be in (0, 180)");
        light.fov = fov * kPi / 180.0f;
        const float power = positive("power");
        if (power > 0) {
            // pbrt-v4: the luminance flux of the image, each pixel's solid angle A cos^3 / pixels at
            // its centre, A the image's area on the plane at distance 1.
            const float aspect = float(img.width) / float(img.height), tan_half = std::tan(0.5f * light.fov);
            const float half_w = aspect > 1 ? aspect : 1, half_h = aspect > 1 ? 1 : 1 / aspect;
            const double area = 4.0 * double(half_w) * half_h * tan_half * tan_half;
            double sum = 0;
            for (int y = 0; y < img.height; ++y)
                for (int x = 0; x < img.width; ++x) {
                    const float px = (-half_w + 2 * half_w * (float(x) + 0.5f) / float(img.width)) * tan_half;
                    const float py =
                        (-half_h + 2 * half_h * (float(y) + 0.5f) / float(img.height)) * tan_half;
                    const double c = 1 / std::sqrt(1.0 + double(px) * px + double(py) * py);
                    sum += double(img.at(x, y).luminance()) * c * c * c;
                }
            const double k_e = area * sum / (double(img.width) * double(img.height));
            if (!(k_e > 0)) params.find("power")->loc.fail(d + ": \"power\" with a black image");
            times(float(power / k_e));
        }
        // pbrt-v4 flips y in the light's space, so that the image's top row lands on +y.
        light.to_world = t * Transform::scale({1, -1, 1});
        light.position = t.point({0, 0, 0});
    } else {
        warn(loc, d + " is not supported (the light is skipped)");
        if (!skipped_light_) skipped_light_ = loc;
        params.mark_all_used();
        return;
    }
    if (!light.color.is_finite()) loc.fail(d + ": emission is not finite");
    done(params, d);
    light.spectrum = std::move(emission);
    light.medium = gs_.outside;  // pbrt-v4: a light sits in the current outside medium
    light.medium_declared = gs_.media_declared;
    light.origin = loc.str();
    scene_.lights.push_back(std::move(light));
}

void SceneBuilder::area_light_source(const std::string& type, const ParamList& params, const Loc& loc) {
    require_world(true, "AreaLightSource", loc);
    const std::string d = "AreaLightSource \"" + type + "\"";
    if (type != "diffuse") {
        warn(loc, d + " is not supported (the shapes that follow do not emit)");
        if (!skipped_light_) skipped_light_ = loc;
        params.mark_all_used();
        gs_.area_light.reset();
        return;
    }
    AreaLight al;
    al.loc = loc;
    const float scale = params.get_float("scale", 1.0f);
    al.L = color(params, "L", SpectrumUse::Illuminant, &al.spectrum).value_or(Rgb(1.0f)) * scale;
    if (al.spectrum) al.spectrum = al.spectrum->scaled(scale);
    al.two_sided = params.get_bool("twosided", false);
    al.power = params.get_float("power", -1.0f);
    if (params.has("power") && !(al.power > 0))
        params.find("power")->loc.fail(d + ": \"power\" must be positive");
    if (const Param* fp = params.find("filename")) {
        // pbrt-v4: the image replaces L (both is an error); `scale` multiplies it.
        if (params.has("L")) loc.fail(d + ": give either \"L\" or \"filename\", not both");
        const std::string path = resolve(params.get_string("filename", ""), fp->loc);
        Image img;
        try {
            img = read_image(path, true);
        } catch (const std::exception& ex) {
            fp->loc.fail(d + ": " + std::string(ex.what()));
        }
        Rgb sum(0.0f);
        for (const Rgb& c : img.pixels) {
            if (!c.is_finite()) fp->loc.fail(d + ": the image has pixels that are not finite");
            sum += Rgb(std::max(c.r, 0.0f), std::max(c.g, 0.0f), std::max(c.b, 0.0f));
        }
        al.image_mean = sum / float(std::max<size_t>(img.pixels.size(), 1));
        al.image_luminance = al.image_mean.luminance();
        if (al.power > 0 && !(al.image_luminance > 0)) fp->loc.fail(d + ": \"power\" with a black image");
        scene::Texture tex;
        tex.kind = scene::Texture::Kind::Image;
        tex.image = text::to_texture_image(std::move(img));
        tex.filename = path;
        scene_.textures.push_back(std::move(tex));
        al.texture = int(scene_.textures.size()) - 1;
        al.L = Rgb(scale);
        al.spectrum.reset();
    }
    if (!al.L.is_finite()) loc.fail(d + ": emission is not finite");
    done(params, d);
    gs_.area_light = al;
}

void SceneBuilder::make_named_medium(const std::string& name, const ParamList& params, const Loc& loc) {
    if (media_.count(name)) loc.fail("medium \"" + name + "\" defined twice");
    if (!params.has("type")) loc.fail("MakeNamedMedium \"" + name + "\": missing \"string type\"");
    const std::string type = params.get_string("type", "");
    const std::string d = "MakeNamedMedium \"" + name + "\" (" + type + ")";
    const bool sparse = type == "nanovdb" || type == "openvdb";
    if (type != "homogeneous" && type != "uniformgrid" && !sparse) {
        warn(loc, d + ": medium type \"" + type + "\" is not supported; the medium is treated as vacuum");
        params.mark_all_used();
        media_[name] = -1;
        return;
    }
    scene::Medium m;
    m.name = name;
    m.to_world = gs_.ctm;
    m.sigma_a = Rgb(0.0011f, 0.0024f, 0.014f);  // pbrt's defaults (whole milk)
    m.sigma_s = Rgb(2.55f, 3.21f, 3.77f);
    const std::string preset = params.get_string("preset", "");
    if (!preset.empty()) {
        const auto it = measured_media().find(preset);
        if (it == measured_media().end())
            params.find("preset")->loc.fail(d + ": unknown medium preset \"" + preset + "\"");
        m.sigma_a = it->second.sigma_a;
        m.sigma_s = it->second.sigma_prime_s;
    }
    if (auto a = color(params, "sigma_a", SpectrumUse::Unbounded)) m.sigma_a = *a;
    if (auto s = color(params, "sigma_s", SpectrumUse::Unbounded)) m.sigma_s = *s;
    m.scale = params.get_float("scale", 1.0f);
    m.g = params.get_float("g", 0.0f);
    if (!(m.g > -1 && m.g < 1)) params.find("g")->loc.fail(d + ": g must be in (-1, 1)");
    if (m.sigma_a.r < 0 || m.sigma_a.g < 0 || m.sigma_a.b < 0 || m.sigma_s.r < 0 || m.sigma_s.g < 0 ||
        m.sigma_s.b < 0 || m.scale < 0)
        loc.fail(d + ": coefficients must not be negative");
    // Emission sigma_a Le: "Lescale" is one factor, or (uniformgrid) one per density cell.
    std::vector<float> le_scale = params.get_floats("Lescale");
    const Param* le_param = params.find("Le");
    if (auto le = color(params, "Le", SpectrumUse::Illuminant)) m.emission = *le;
    if (le_scale.size() == 1) {
        m.emission = m.emission * le_scale[0];
        le_scale.clear();
    }
    if (type == "uniformgrid") {
        m.kind = scene::Medium::Kind::UniformGrid;
        m.nx = params.get_int("nx", 1), m.ny = params.get_int("ny", 1), m.nz = params.get_int("nz", 1);
        if (m.nx <= 0 || m.ny <= 0 || m.nz <= 0) loc.fail(d + ": nx, ny and nz must be positive");
        m.density = params.get_floats("density");
        if (m.density.size() != size_t(m.nx) * size_t(m.ny) * size_t(m.nz))
            loc.fail(d + ": \"density\" has " + std::to_string(m.density.size()) +
                     " values, nx*ny*nz = " + std::to_string(size_t(m.nx) * size_t(m.ny) * size_t(m.nz)));
        m.p0 = params.get_point3("p0", {0, 0, 0});
        m.p1 = params.get_point3("p1", {1, 1, 1});
        if (!(m.p0.x < m.p1.x && m.p0.y < m.p1.y && m.p0.z < m.p1.z)) {
            const Param* bp = params.has("p1") ? params.find("p1") : params.find("p0");
            (bp ? bp->loc : loc).fail(d + ": p0 must be less than p1 in x, y and z");
        }
        if (const Param* tp = params.find("temperature"))
            warn(tp->loc, d + ": \"temperature\" grids are not supported");
        if (!le_scale.empty()) {
            if (le_scale.size() != m.density.size())
                params.find("Lescale")->loc.fail(d + ": \"Lescale\" has " + std::to_string(le_scale.size()) +
                                                 " values, nx*ny*nz = " + std::to_string(m.density.size()));
            m.emission_scale = std::move(le_scale);
        }
    } else if (!le_scale.empty()) {
        params.find("Lescale")->loc.fail(d + ": \"Lescale\" takes one value here");
    }
    if (sparse) {
        // pbrt-v4's nanovdb media emit only from a temperature grid.
        if (le_param)
            warn(le_param->loc, d + ": \"Le\" is ignored by nanovdb media (pbrt-v4 reads emission from "
                                    "a \"temperature\" grid, which phos does not support)");
        m.emission = Rgb(0.0f);
        const Param* fp = params.find("filename");
        if (!fp) loc.fail(d + ": missing \"string filename\"");
        m.kind = scene::Medium::Kind::Sparse;
        try {
            m.sparse = io::read_volume_grid(resolve(params.get_string("filename", ""), fp->loc), "density");
        } catch (const InputError& e) {
            fp->loc.fail(d + ": " + e.what());
        }
        if (const Param* tp = params.find("temperature"))
            warn(tp->loc, d + ": \"temperature\" grids are not supported");
        // pbrt-v4's nanovdb parameters phos reads no further: accepted without a warning.
        for (const char* ignored : {"temperaturecutoff", "temperaturescale"}) params.find(ignored);
    }
    done(params, d);
    media_[name] = int(scene_.media.size());
    scene_.media.push_back(std::move(m));
}

void SceneBuilder::medium_interface(const std::string& inside, const std::string& outside, const Loc& loc) {
    auto lookup = [&](const std::string& n) {
        if (n.empty()) return -1;
        const auto it = media_.find(n);
        if (it == media_.end()) loc.fail("MediumInterface: unknown medium \"" + n + "\"");
        return it->second;
    };
    gs_.inside = lookup(inside);
    gs_.outside = lookup(outside);
    gs_.media_declared = true;
}

}  // namespace phos::io::pbrt
