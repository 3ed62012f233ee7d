// The AOV pass (see aov.h): albedo through delta bounces, first-hit normal and depth.
#include "render/aov.h"

#include <algorithm>

#include "core/error.h"
#include "render/pixel_loop.h"
#include "shading/surface_walk.h"
#include "spectrum/color.h"

namespace phos::render {
namespace {

struct AovSample {
    Rgb albedo{0.0f};
    Vec3 normal{0.0f};
    float depth = 0;
    bool hit = false;
};

// The sum of the LobeAlbedos kinds in `mask` (sample_lobes mask bits).
Rgb albedo_of(const shading::Bsdf::LobeAlbedos& a, uint32_t mask) {
    Rgb r(0.0f);
    if (mask & shading::kDiffuse) r += a.diffuse;
    if (mask & shading::kGlossy) r += a.glossy;
    if (mask & shading::kSpecular) r += a.specular;
    if (mask & shading::kTransmission) r += a.transmission;
    return r;
}

AovSample trace(const Prepared& P, Ray ray, Sampler& sampler, RayCounts& rays, bool albedo) {
    AovSample out;
    // Colours seen through mirrors and glass: the throughput at a set of wavelengths, which meets
    // each albedo (a colour) as spectrum/color.h's colour_through says.
    Wavelengths lambda = Wavelengths::visible(sampler.next());
    Spectrum beta(1.0f);
    shading::SurfaceWalk walk(P.accel);
    for (int depth = 0;; ++depth) {
        accel::SurfaceHit hit;
        const shading::SurfaceWalk::Event event = walk.next(ray, hit);
        if (event == shading::SurfaceWalk::Event::Lost) break;
        if (event == shading::SurfaceWalk::Event::Escaped) {
            const Rgb L = P.scene.background + P.escaped_colour(normalize(ray.dir));
            out.albedo += spectrum::colour_through(
                beta, lambda,
                Rgb(std::clamp(L.r, 0.0f, 1.0f), std::clamp(L.g, 0.0f, 1.0f), std::clamp(L.b, 0.0f, 1.0f)));
            break;
        }
        const Vec3 wo = -normalize(ray.dir);
        const shading::Bsdf bsdf = P.bsdf(hit);
        if (depth == 0) {
            out.hit = true;
            out.depth = walk.distance();
            out.normal = dot(wo, bsdf.geometric_normal()) >= 0 ? bsdf.frame().n : -bsdf.frame().n;
            if (!albedo) break;
        }
        const shading::Bsdf::LobeSplit split = bsdf.split_lobes(wo);
        if (split.estimated)
            out.albedo +=
                spectrum::colour_through(beta, lambda, albedo_of(bsdf.lobe_albedos(wo), split.estimated));
        if (!split.followed || depth >= P.options.max_depth) break;
        const auto s = bsdf.sample_lobes(split.followed, wo, sampler.next(), sampler.next2(), lambda);
        if (!s || s->weight.is_black()) break;
        beta *= s->weight;
        if (s->dispersive) spectrum::terminate_secondary(lambda, beta);
        if (!beta.is_finite() || beta.max() < 1e-6f) break;
        ray = accel::spawn_ray(hit, s->wi);
        ++rays.bounce;
    }
    return out;
}

}  // namespace

void render_aovs(const Prepared& P, film::Film& film) {
    const std::vector<std::string>& valid = aov_names();
    film::Layer* albedo = nullptr;
    film::Layer* normal = nullptr;
    film::Layer* depth = nullptr;
    for (const std::string& name : P.options.aovs) {
        if (std::find(valid.begin(), valid.end(), name) == valid.end()) {
            std::string list;
            for (const std::string& v : valid) list += (list.empty() ? "" : ", ") + v;
            throw InputError("unknown auxiliary image '" + name + "' (known: " + list + ")");
        }
        // Layers are created before the parallel loop (creation is not thread-safe).
        film::Layer& layer = film.layer(name);
        (name == "albedo" ? albedo : name == "normal" ? normal : depth) = &layer;
    }
    if (!albedo && !normal && !depth) return;
    // The image's first samples, at most 64 per pixel (the features are first-hit quantities: more
    // only average the pixel's footprint further; a time budget would leave the count open).
    const int64_t n = int64_t(std::max(1, P.options.spp)) * std::max(1, P.options.dof_samples);
    const int samples = int(std::min<int64_t>(n, 64));
    for_each_sample(P, samples, [&](int x, int y, const Ray& ray, float, Sampler& sampler, RayCounts& rays) {
        const AovSample a = trace(P, ray, sampler, rays, albedo != nullptr);
        if (albedo) albedo->add(x, y, a.albedo);
        if (normal) normal->add(x, y, Rgb(a.normal.x, a.normal.y, a.normal.z));
        // Samples that hit nothing add weight 0: the mean is over the hits (0 where there are none).
        if (depth) depth->add(x, y, Rgb(a.depth), a.hit ? 1.0f : 0.0f);
    });
}

}  // namespace phos::render
