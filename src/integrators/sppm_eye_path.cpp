// The eye path of PPM and SPPM: from the camera through mirrors and glass to the first
// non-specular surface, where a visible point is stored and direct light sampled (see sppm_core.h).
#include "core/error.h"
#include "integrators/direct_light.h"
#include "integrators/emission.h"
#include "integrators/sppm_core.h"
#include "shading/surface_walk.h"

namespace phos::integrators::sppm {

using shading::Bsdf;

Rgb trace_eye_path(const Prepared& P, accel::Ray ray, Sampler& sampler, int direct_samples, VisiblePoint& vp,
                   RayCounts& rays) {
    vp.bsdf.reset();
    Rgb L(0.0f), beta(1.0f);
    shading::SurfaceWalk walk(P.accel);  // its distance() is the visible point's path length
    for (int depth = 0;;) {
        accel::SurfaceHit hit;
        const shading::SurfaceWalk::Event event = walk.next(ray, hit);
        if (event == shading::SurfaceWalk::Event::Lost) break;
        if (event == shading::SurfaceWalk::Event::Escaped) {
            // Every vertex so far was specular, so escaped light is seen directly.
            L += beta * (P.scene.background + P.escaped(normalize(ray.dir)));
            break;
        }
        const Vec3 wo = -normalize(ray.dir);
        L += seen_emission(P, hit, wo, beta);
        if (depth == P.options.max_depth) break;
        const Bsdf bsdf = P.bsdf(hit);

        // Split the lobes into the non-specular part (a visible point) and the delta part (follow).
        const Bsdf::LobeSplit split = bsdf.split_lobes(wo);
        const float p_ns = split.p_non_delta;
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
            vp.path_length = walk.distance();
            vp.bsdf.emplace(bsdf);
            break;
        }
        const float u_lobe = sampler.next();
        const auto s = bsdf.sample_lobes(split.delta, wo, u_lobe, sampler.next2());
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
