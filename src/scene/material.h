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

    // Lambertian transmission (pbrt diffusetransmission).
    Rgb diffuse_transmission{0.0f};

    // Glow seen by camera/specular rays, not a light (.scn `e`, with --no-emission-lights; see scn_loader.h).
    Rgb emission{0.0f};
    // .scn ambient coefficient, used only with --ambient.
    Rgb ambient{0.0f};

    // pbrt "interface": the surface only bounds a medium and does not scatter light.
    bool interface_only = false;

    int displacement_texture = -1;  // pbrt "displacement": float texture bump-mapping the shading normal
    std::shared_ptr<const TextureImage> normal_map;  // pbrt "normalmap": tangent-space normals (linear RGB)

    static constexpr float kMirrorShininess = 10000.0f;
};

}  // namespace phos::scene
