// Projection maps (Jensen 2001, sec. 5.2) for the caustic map: per light, the cells of its emission
// direction space from which a photon can reach a specular object (mirror, smooth or frosted glass),
// so caustic photons are emitted only there and weighted by the fraction of the light's emission
// those cells carry. The caustic map's power stays exact; no photons are spent on the (usually
// vast) part of the scene that can never give a caustic.
//
// The cells live in the light's primary sample space (the u_dir argument of Light::sample_Le), which
// works for every light whose direction depends on u_dir alone and whose origin lies in a small
// sphere: point and spot lights exactly, planar area lights conservatively (each cell tested against
// the specular objects' bounding spheres grown by the light's own radius). Lights where that does
// not hold (curved area lights, directional and infinite lights) keep their full emission (fraction
// 1): still exact, just without the speed-up.
#pragma once

#include <cstdint>
#include <vector>

#include "photon/photon_path.h"
#include "shading/distribution1d.h"

namespace phos::photon {

// True if the material has a lobe that starts or continues a caustic path (L S+ D): a delta lobe
// (mirror, smooth or thin glass) or a glossy lobe (Phong, frosted glass) at least as sharp as a
// Phong lobe of exponent `sharp_exponent` (shading::Bsdf::sharp_lobes).
bool is_caustic_caster(const scene::Material& m, float sharp_exponent);
// is_caustic_caster of each material of the scene, by index, a mix counting when either of its
// materials is one: built once per scene (a BSDF per material), looked up per shape.
std::vector<bool> caustic_caster_materials(const scene::Scene& scene, float sharp_exponent);
// True if some material of the scene is a caustic caster: only then can there be caustic photons.
bool has_caustic_casters(const scene::Scene& scene, float sharp_exponent);
// True if the material has a delta lobe (mirror or smooth glass): only then can the scene have
// L S+ D paths worth a caustic map.
bool has_delta_lobe(const scene::Material& m);
// has_delta_lobe of each material of the scene, by index, a mix counting when either of its
// materials has one.
std::vector<bool> delta_lobe_materials(const scene::Scene& scene);

struct BoundingSphere {
    Vec3 center{0.0f};
    float radius = 0;
};
// World-space bounding spheres of every shape (top-level and instanced) whose material is a
// caustic caster (at `sharp_exponent`).
std::vector<BoundingSphere> caustic_caster_bounds(const scene::Scene& scene, float sharp_exponent);

class ProjectionMap {
public:
    // resolution x resolution cells per light over u_dir in [0,1)^2.
    ProjectionMap(const PhotonScene& ps, int resolution = 64);

    // Fraction of the scene's emitted power that leaves through marked cells (0: no light can send
    // a photon towards a specular object, the caustic map stays empty).
    double fraction() const { return fraction_; }
    bool empty() const { return !(fraction_ > 0); }

    // Emits one photon through a marked cell: light chosen by power x fraction, a marked cell
    // uniformly, a uniform point in it. `power` = sample weight x fraction / pmf(light), so the
    // emitted photons' powers still average to the power reaching the marked directions.
    bool emit(const PhotonScene& ps, Sampler& sampler, const Wavelengths& lambda, Ray& ray, Spectrum& power,
              int& medium) const;

private:
    struct LightCells {
        std::vector<uint32_t> cells;  // marked cell indices (y * res + x); all of them when `full`
        float fraction = 0;
        bool full = false;
    };
    int res_;
    std::vector<LightCells> lights_;
    shading::Distribution1D choose_;  // over lights, by average power x fraction
    double fraction_ = 0;
};

}  // namespace phos::photon
