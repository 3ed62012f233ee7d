// Runtime participating media built from scene::Medium: the coefficients at a point and the
// majorant segments along a ray that delta and ratio tracking sample against (medium_tracking.h).
#pragma once

#include <memory>
#include <vector>

#include "core/transform.h"
#include "core/vec.h"
#include "scene/medium.h"
#include "scene/scene.h"
#include "shading/density_grid.h"
#include "shading/phase.h"
#include "spectrum/rgb_spectrum.h"
#include "spectrum/sampled_spectrum.h"

namespace phos::shading {

// Absorption and scattering coefficients (1/scene-unit) and emitted radiance at a point, at a
// path's wavelengths.
struct MediumCoefficients {
    Spectrum sigma_a, sigma_s, Le;
    Spectrum sigma_t() const { return sigma_a + sigma_s; }
};

class Medium {
public:
    explicit Medium(const scene::Medium& m);
    ~Medium();
    Medium(Medium&&) noexcept;

    bool homogeneous() const { return !grid_; }
    bool emissive() const { return !Le_.is_black(); }
    const PhaseFunction& phase() const { return phase_; }
    // Coefficients at world-space point p. The RGB coefficients are read as unbounded spectra, the
    // emission as an illuminant (spectrum/rgb_spectrum.h).
    MediumCoefficients at(Vec3 p, const Wavelengths& lambda) const;
    // Homogeneous media: sigma_t everywhere (the exact transmittance is exp(-sigma_t d)).
    Spectrum sigma_t(const Wavelengths& lambda) const {
        return sigma_a_s_.sample(lambda) + sigma_s_s_.sample(lambda);
    }
    // Its colour (the RGB the scene gives, scaled): for choices that do not depend on wavelength.
    Rgb sigma_t_rgb() const { return sigma_a_ + sigma_s_; }
    Rgb sigma_t_rgb(Vec3 p) const;
    Rgb sigma_s_rgb() const { return sigma_s_; }

    // Majorant segments along the world-space ray o + t d (d unit), t in [t0, t1): each next()
    // gives [ta, tb) and a scalar majorant (>= every channel of sigma_t there). Homogeneous media
    // give one segment; grids one per majorant cell (space outside the grid is skipped). The majorant
    // bounds sigma_t at every wavelength.
    class Majorants {
    public:
        bool next(float& ta, float& tb, float& sigma_maj);

    private:
        friend class Medium;
        bool single_ = true, done_ = false;
        float t0_ = 0, t1_ = 0, sigma_ = 0;
        MajorantGrid::Segments cells_;
    };
    Majorants majorants(Vec3 o, Vec3 d, float t0, float t1) const;

private:
    Rgb sigma_a_, sigma_s_, Le_;
    spectrum::RgbSpectrum sigma_a_s_, sigma_s_s_, Le_s_;
    float max_sigma_t_ = 0;  // the largest sigma_t over wavelengths at density 1
    PhaseFunction phase_;
    Transform to_medium_;
    std::unique_ptr<DensityGrid> grid_;
    std::unique_ptr<MajorantGrid> majorant_grid_;
    std::unique_ptr<DensityGrid> le_scale_;  // uniform grids: per-cell emission factors (pbrt "Lescale")
};

// The scene's media, indexed as scene::Scene::media (-1 = vacuum).
class MediaSet {
public:
    explicit MediaSet(const scene::Scene& scene);
    bool empty() const { return media_.empty(); }
    size_t size() const { return media_.size(); }
    const Medium& operator[](int i) const { return media_[size_t(i)]; }
    // True when the scene has at least one medium a ray can be in (lights, camera or surfaces name it).
    bool active() const { return active_; }

private:
    std::vector<Medium> media_;
    bool active_ = false;
};

}  // namespace phos::shading
