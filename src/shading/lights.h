// Runtime lights built from scene::Light: sample_Li for direct lighting (next-event estimation),
// pdf_Li and Le for MIS when a BSDF-sampled ray hits an emitter, sample_Le and power() for photon
// emission. Area lights sample their shape (mesh triangles by area, disk, sphere...) in world space.
#pragma once

#include <memory>
#include <vector>

#include "accel/embree_scene.h"
#include "accel/ray.h"
#include "core/frame.h"
#include "core/vec.h"
#include "scene/scene.h"
#include "shading/distribution1d.h"
#include "spectrum/dense_spectrum.h"
#include "spectrum/distribution.h"
#include "spectrum/sampled_spectrum.h"

namespace phos::shading {

// The scene's bounding sphere: directional and infinite lights emit photons from a disk of this
// radius placed outside it, so every photon that can reach geometry is accounted for.
struct SceneSphere {
    Vec3 center{0.0f};
    float radius = 0;
    // Empty bounds give the unit sphere at the origin (nothing to hit, but no NaNs either).
    static SceneSphere from_bounds(const Bounds& bounds);
};

// The light space of a light's transform as an orthonormal frame: its linear part with the scale
// and shear removed (Gram-Schmidt on the images of x and y, keeping a mirror). Lights whose emission
// depends on direction (infinite maps, goniometric, projection) look directions up in it.
Frame light_frame(const Transform& to_world);

struct LightLiSample {
    Spectrum L;             // radiance arriving at the reference point along -wi (delta lights: I/d^2 or E)
    Vec3 wi;                // unit direction from the reference point towards the light
    float distance = kInf;  // to the sampled point on the light (kInf for directional / infinite)
    Vec3 p_light;           // the sampled point on the light (for shadow rays)
    Vec3 n_light;           // its normal (area lights)
    float pdf = 0;          // solid-angle pdf (1 for delta lights)
    bool delta = false;
};

struct LightLeSample {
    Ray ray;      // leaves the light (unit direction); tmin skips the emitting surface itself
    Vec3 n;       // surface normal at the origin (area lights), else the direction
    Spectrum Le;  // emitted radiance (area) or intensity (point/spot) along the ray
    float pdf_pos = 1, pdf_dir = 1;
    // Flux carried by this one sample: Le * |cos| / (pdf_pos * pdf_dir). Averaging over N samples
    // gives the light's power; a photon's power is weight / N (times 1/P(choose light)).
    Spectrum weight;
    bool back = false;  // a two-sided area light emitting from the back of its surface (n flipped)
};

// The media a light emits into (-1 = vacuum): `front` on the side of an area light's normal and
// for every other light, `back` behind a two-sided area light (light_media.h decides them).
struct LightMedia {
    int front = -1, back = -1;
};

struct LightOptions {
    bool legacy_attenuation = false;  // honour .scn (ca, la, qa) in sample_Li
};

// Spectra: every light emits the spectrum its scene::Light gives (scene::Light::spectrum, or its
// colour read as an illuminant RGB), evaluated at the path's wavelengths; power() is the RGB flux,
// which only chooses lights.
class Light {
public:
    explicit Light(const scene::Light& light);
    virtual ~Light() = default;
    virtual LightLiSample sample_Li(Vec3 ref, Vec2 u, const Wavelengths& lambda) const = 0;
    // Solid-angle pdf that sample_Li(ref) picks `p_light` (with normal n_light) in direction wi.
    virtual float pdf_Li(Vec3 ref, Vec3 wi, Vec3 p_light, Vec3 n_light) const = 0;
    // Area lights: radiance leaving an emitting surface point with normal n towards wo (unit, pointing
    // away from the surface).
    // Infinite lights: `n` is unused and `wo` is a direction pointing from the scene towards the sky;
    // the result is the radiance arriving from that direction. For a ray (origin o, direction d) that
    // escapes the scene, the radiance it brings back to o is Le({}, normalize(d)).
    // Delta lights: 0.
    virtual Spectrum Le(Vec3 n, Vec3 wo, const Wavelengths& lambda) const = 0;
    // Infinite lights: the radiance a ray leaving `origin` along unit `dir` brings back when it
    // escapes the scene. Le({}, dir) but for a light with a portal, which gives only what passes
    // through the portal from `origin` (pbrt-v4's PortalImageInfiniteLight::Le).
    virtual Spectrum escaped_Le(Vec3 origin, Vec3 dir, const Wavelengths& lambda) const {
        (void)origin;
        return Le({}, dir, lambda);
    }
    // Le at a surface point with parameterisation `uv` (SurfaceHit::uv): what an area light whose
    // emission varies over its surface (an image) gives; every other light ignores `uv`.
    virtual Spectrum surface_Le(Vec3 n, Vec2 uv, Vec3 wo, const Wavelengths& lambda) const {
        (void)uv;
        return Le(n, wo, lambda);
    }
    virtual LightLeSample sample_Le(Vec2 u_pos, Vec2 u_dir, const Wavelengths& lambda) const = 0;
    // The densities sample_Le has of emitting from a point with normal `n` in unit direction `w`
    // (the direction light travels): pdf_pos (area measure, 1 for point and spot lights; for
    // directional and infinite lights that of the disk photons start from) and pdf_dir (solid
    // angle; 1 for directional lights). For an area light `n` is its emitting surface normal; an
    // infinite light ignores it. Bidirectional methods weigh their strategies with these.
    virtual void pdf_Le(Vec3 n, Vec3 w, float& pdf_pos, float& pdf_dir) const = 0;
    virtual Rgb power() const = 0;
    virtual bool is_delta() const = 0;
    virtual bool is_infinite() const { return false; }

protected:
    // The light's emission spectrum (radiance, intensity or irradiance as the kind says) at `lambda`.
    Spectrum emission(const Wavelengths& lambda) const { return emission_.sample(lambda); }

private:
    spectrum::DenseSpectrum emission_;
};

// All lights of a scene, with a power-proportional distribution for choosing one. Light i is built
// from scene.lights[i]; area lights refer to top-level shapes (Scene::shapes; emitters inside
// instanced objects are not lights). Throws InputError for a bad shape or texture index. Warns
// (log::warn) about lights with zero power, and once per light about non-physical .scn attenuation
// when options.legacy_attenuation is off.
class LightSet {
public:
    LightSet(const scene::Scene& scene, const Bounds& scene_bounds, const LightOptions& options = {});
    ~LightSet();
    size_t size() const { return lights_.size(); }
    const Light& operator[](size_t i) const { return *lights_[i]; }
    // Picks a light with probability proportional to its power (average over channels).
    // Returns the index and sets `pmf`. Requires size() > 0.
    size_t choose(float u, float& pmf) const { return distribution_.sample_discrete(u, &pmf); }
    float pmf(size_t i) const;
    Rgb total_power() const;
    // Indices of infinite lights (seen by escaping rays).
    const std::vector<size_t>& infinite_lights() const { return infinite_; }
    // Where the lights sit (place_lights_in_media); every light is in vacuum until set.
    void set_media(std::vector<LightMedia> media) { media_ = std::move(media); }
    // The medium photons and light subpaths leaving light i along sample `s` start in.
    int emission_medium(size_t i, const LightLeSample& s) const {
        if (i >= media_.size()) return -1;
        return s.back ? media_[i].back : media_[i].front;
    }

private:
    std::vector<std::unique_ptr<Light>> lights_;
    Distribution1D distribution_;  // over lights_, by average power (uniform if all are zero)
    std::vector<size_t> infinite_;
    std::vector<LightMedia> media_;  // empty: all in vacuum
};

}  // namespace phos::shading
