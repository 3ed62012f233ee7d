// Materials as plain data. One "layered" description covers both the .scn model (kd, ks with
// shininess, kt with index of refraction, glow emission) and the pbrt materials phos maps onto it;
// shading/ turns a Material into a BSDF.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "core/vec.h"
#include "scene/texture.h"
#include "spectrum/distribution.h"

namespace phos::scene {

class MeasuredBsdf;  // scene/measured_bsdf.h

struct Material {
    std::string name;

    // Lambertian reflection (albedo), optionally multiplied by a texture.
    Rgb diffuse{0.0f};
    int diffuse_texture = -1;

    // Glossy / specular reflection. shininess >= kMirrorShininess means an ideal mirror; below it,
    // an energy-normalised modified Phong lobe with exponent `shininess`.
    Rgb specular{0.0f};
    float shininess = 0.0f;
    // Conductor Fresnel for the specular lobe (pbrt "conductor" with eta/k): when set, the specular
    // reflectance is Fresnel(conductor_eta, conductor_k, cos) * specular instead of `specular`.
    bool conductor = false;
    Rgb conductor_eta{1.0f};
    Rgb conductor_k{0.0f};
    // Measured η and k over wavelength (pbrt's named metals, spectra): used instead of the RGB values
    // above (which then hold their colour) when set.
    std::optional<spectrum::Distribution> conductor_eta_spectrum, conductor_k_spectrum;
    // A conductor given by its normal-incidence reflectance r (pbrt-v4's conductor "reflectance"):
    // `specular` (times specular_texture) is r, and the Fresnel factor is that of eta = 1,
    // k = 2 sqrt(r) / sqrt(1 - r), which reflects r at normal incidence.
    bool conductor_from_reflectance = false;
    int specular_texture = -1;

    // Microfacet roughness (pbrt's materials): when `microfacet` is set, the specular lobe is a
    // Trowbridge-Reitz (GGX) microfacet reflection (times the conductor Fresnel, or `specular`)
    // and a rough dielectric uses the same distribution, with roughness `roughness_u` along dpdu
    // and `roughness_v` across (each a float texture when its index is >= 0), mapped to alpha by
    // alpha = sqrt(roughness) when `remap_roughness` (pbrt-v4's RoughnessToAlpha), else alpha =
    // roughness. Both alphas below 1e-3 make the lobe a delta (mirror / smooth glass). Without it,
    // `shininess` and `transmission_shininess` are Phong exponents (.scn, .scene).
    bool microfacet = false;
    float roughness_u = 0, roughness_v = 0;
    int roughness_u_texture = -1, roughness_v_texture = -1;
    bool remap_roughness = true;

    // Dielectric boundary: Fresnel reflection + refraction scaled by `transmission`, index `ior`.
    // Sharp when transmission_shininess >= kMirrorShininess, "frosted" (rough) below.
    Rgb transmission{0.0f};
    float ior = 1.0f;
    // A dispersive dielectric: the index over wavelength (Sellmeier, Cauchy, a named glass, a table);
    // `ior` then holds its value at the d line (587.6 nm). Paths that refract or reflect at it go
    // on with their hero wavelength alone.
    std::optional<spectrum::Distribution> ior_spectrum;
    float transmission_shininess = 1e6f;
    bool thin = false;  // thin dielectric sheet (pbrt thindielectric): no bending

    // Lambertian transmission (pbrt diffusetransmission), optionally multiplied by a texture.
    Rgb diffuse_transmission{0.0f};
    int diffuse_transmission_texture = -1;

    // Glow seen by camera/specular rays, not a light (.scn `e`, with --no-emission-lights; see scn_loader.h).
    Rgb emission{0.0f};
    // .scn ambient coefficient, used only with --ambient.
    Rgb ambient{0.0f};

    // pbrt's coateddiffuse and coatedconductor (shading/layered_bxdf.h): when `layered` is set the
    // material is a dielectric coat of index `coat_eta` and microfacet roughness roughness_u/_v
    // (with their textures and remap_roughness; smooth below alpha 1e-3) over a base, separated by
    // a slab of `layer_thickness` holding a medium of albedo `layer_albedo` (black: none) and
    // Henyey-Greenstein `layer_g`; `layer_max_depth` events, `layer_samples` walks per estimate.
    // The base is Lambertian with `diffuse` (times diffuse_texture), or with
    // `layered_conductor_base` a conductor: conductor_eta/_k (and their spectra), or
    // conductor_from_reflectance with `specular` (times specular_texture) as its reflectance, of
    // roughness base_roughness_u/_v (textures, the same remap). Its other lobes are unused.
    bool layered = false;
    float coat_eta = 1.5f;
    bool layered_conductor_base = false;
    float base_roughness_u = 0, base_roughness_v = 0;
    int base_roughness_u_texture = -1, base_roughness_v_texture = -1;
    float layer_thickness = 0.01f;
    Rgb layer_albedo{0.0f};
    int layer_albedo_texture = -1;  // multiplies layer_albedo when >= 0
    float layer_g = 0;
    int layer_max_depth = 10, layer_samples = 1;

    // pbrt "interface": the surface only bounds a medium and does not scatter light.
    bool interface_only = false;

    // pbrt "subsurface": the homogeneous medium (index into Scene::media) that a shape of this
    // material encloses under its dielectric boundary; the pbrt loader makes it the inside of each
    // such shape's MediumInterface. -1: none.
    int subsurface_medium = -1;

    // pbrt "mix": when mix_a >= 0 this material is, at each hit, one of materials mix_a and mix_b
    // (indices into Scene::materials), mix_b with probability `mix_amount` (times the float
    // texture mix_amount_texture when >= 0); the choice is a hash of the hit point, so every ray
    // and photon meeting that point sees the same material (scene/material_mix.h). Its own lobes
    // are unused.
    int mix_a = -1, mix_b = -1;
    float mix_amount = 0.5f;
    int mix_amount_texture = -1;
    bool is_mix() const { return mix_a >= 0; }

    // pbrt "measured" (shading/measured_bxdf.h): when set, the material is the tabulated BRDF of an
    // RGL .bsdf file (Dupuy & Jakob 2018) alone; its other lobes are unused.
    std::shared_ptr<const MeasuredBsdf> measured;

    // pbrt "hair" (Chiang et al. 2016, shading/hair_bxdf.h): when `hair`, the material is that fibre
    // BSDF alone, at the offset h = -1 + 2 v across the fibre (the hit's v: a curve's across
    // coordinate), with index hair_eta, roughnesses hair_beta_m / hair_beta_n and scale tilt
    // hair_alpha (degrees). Its absorption, as pbrt-v4's HairMaterial reads it: hair_sigma_a
    // (SigmaA); the colour hair_reflectance, times the texture hair_reflectance_texture when >= 0,
    // inverted per wavelength (Reflectance); or the melanin concentrations (Melanin).
    bool hair = false;
    enum class HairColour { SigmaA, Reflectance, Melanin } hair_colour = HairColour::Melanin;
    Rgb hair_sigma_a{0.0f}, hair_reflectance{0.0f};
    int hair_reflectance_texture = -1;
    float hair_eumelanin = 1.3f, hair_pheomelanin = 0;
    float hair_eta = 1.55f, hair_beta_m = 0.3f, hair_beta_n = 0.3f, hair_alpha = 2;

    int displacement_texture = -1;  // pbrt "displacement": float texture bump-mapping the shading normal
    std::shared_ptr<const TextureImage> normal_map;  // pbrt "normalmap": tangent-space normals (linear RGB)

    static constexpr float kMirrorShininess = 10000.0f;
};

}  // namespace phos::scene
