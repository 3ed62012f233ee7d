// The eye path of PPM and SPPM: from the camera through mirrors and glass to the first
// non-specular surface, where a visible point is stored and direct light sampled (see sppm_core.h).
#include "core/error.h"
#include "integrators/direct_light.h"
#include "integrators/sppm_core.h"

namespace phos::integrators::sppm {

using shading::Bsdf;

Rgb trace_eye_path(const Prepared& P, accel::Ray ray, Sampler& sampler, int direct_samples, VisiblePoint& vp,
                   RayCounts& rays) {
    vp.bsdf.reset();
    const scene::Scene& scene = P.scene;
    Rgb L(0.0f), beta(1.0f);
    float length = 0;
    int crossings = 0;
    for (int depth = 0;;) {
        accel::SurfaceHit hit;
        if (!P.accel.intersect(ray, hit)) {
            // Every vertex so far was specular, so escaped light is seen directly.
            L += beta * (scene.background + P.escaped(normalize(ray.dir)));
            break;
        }
        length += hit.t * std::sqrt(dot(ray.dir, ray.dir));
        if (P.passes_through(hit)) {
            if (++crossings > 256) break;
            ray = accel::spawn_ray(hit, ray.dir);
            continue;
        }
        const Vec3 wo = -normalize(ray.dir);
        const scene::Material& mat = scene.materials[size_t(hit.material)];
        L += beta * (P.emitted(hit, wo) + mat.emission);
        if (depth == 0 && P.options.ambient) L += beta * mat.ambient * scene.ambient;
        if (depth == P.options.max_depth) break;
        const Bsdf bsdf = P.bsdf(hit);
        if (bsdf.flags() == 0) break;

        // Split the lobes into the non-specular part (a visible point) and the delta part (follow).
        float p_ns = 1;
        uint32_t delta_mask = 0;
        if (!bsdf.has_non_specular()) {
            p_ns = 0;
            delta_mask = ~0u;
        } else if (bsdf.flags() & shading::kSpecular) {
            const Bsdf::LobeAlbedos a = bsdf.lobe_albedos(wo);
            float ns = a.diffuse.average() + a.glossy.average(), d = a.specular.average();
            if (a.specular.average() > 0) delta_mask |= shading::kSpecular;
            if (a.transmission.average() > 0) {
                // The dielectric is delta when smooth, glossy when frosted: ask it.
                const auto s = bsdf.sample_lobes(shading::kTransmission, wo, 0.5f, {0.5f, 0.5f});
                if (s && s->is_specular()) {
                    d += a.transmission.average();
                    delta_mask |= shading::kTransmission;
                } else {
                    ns += a.transmission.average();
                }
            }
            p_ns = ns + d > 0 ? ns / (ns + d) : 1;
        }
        const float u = p_ns > 0 && p_ns < 1 ? sampler.next() : 0.5f;
        if (p_ns >= 1 || (p_ns > 0 && u < p_ns)) {
            const Rgb w = beta * (1 / p_ns);
            Rgb direct(0.0f);
            const int n = std::max(1, direct_samples);
            for (int k = 0; k < n; ++k) direct += sample_one_light(P, hit, bsdf, wo, sampler, rays, false);
            L += w * direct * (1.0f / float(n));
            vp.p = hit.p;
            vp.wo = wo;
            vp.beta = w;
            vp.depth = depth;
            vp.path_length = length;
            vp.bsdf.emplace(bsdf);
            break;
        }
        const float u_lobe = sampler.next();
        const auto s = bsdf.sample_lobes(delta_mask, wo, u_lobe, sampler.next2());
        if (!s || s->weight.is_black() || !s->weight.is_finite()) break;
        beta *= s->weight * (1 / (1 - p_ns));
        ray = accel::spawn_ray(hit, s->wi);
        ++rays.bounce;
        ++depth;
        if (!beta.is_finite() || beta.max() <= 0) break;
    }
    return L;
}

}  // namespace phos::integrators::sppm
