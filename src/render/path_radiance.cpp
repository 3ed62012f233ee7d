// A camera path's radiance and its components (see path_radiance.h).
#include "render/path_radiance.h"

#include "render/path_recorder.h"
#include "render/pixel_loop.h"
#include "spectrum/color.h"

namespace phos::render {

const char* component_name(Component c) {
    switch (c) {
        case Component::Direct:
            return "direct";
        case Component::Caustic:
            return "caustic";
        case Component::Indirect:
            return "indirect";
        case Component::Specular:
            break;
    }
    return "specular";
}

const std::vector<Component>& all_components() {
    static const std::vector<Component> all{Component::Direct, Component::Caustic, Component::Indirect,
                                            Component::Specular};
    return all;
}

Rgb& RadianceParts::operator[](Component c) {
    switch (c) {
        case Component::Direct:
            return direct;
        case Component::Caustic:
            return caustic;
        case Component::Indirect:
            return indirect;
        case Component::Specular:
            break;
    }
    return specular;
}

void PathRadiance::add(Rgb c, Component part, bool emitted) {
    L_ += c;
    if (parts_) (*parts_)[part] += c;
    if (auto* r = recorder()) r->add(emitted ? TraceTerm::Emission : TraceTerm::Light, c);
}

void PathRadiance::emission(const Spectrum& s) { emission(spectrum::to_srgb(s, lambda_)); }

void PathRadiance::emission(Rgb c) {
    switch (stage_) {
        case Stage::Camera:
        case Stage::FromX:
            return add(c, Component::Direct, true);
        case Stage::SpecularChain:
            return add(c, Component::Specular, true);
        case Stage::CausticChain:
            return add(c, Component::Caustic, true);
        case Stage::Indirect:
            break;
    }
    add(c, Component::Indirect, true);
}

void PathRadiance::light(const Spectrum& s, bool widened) {
    const Rgb c = spectrum::to_srgb(s, lambda_);
    if (stage_ == Stage::Camera) return add(c, Component::Direct, false);
    if (stage_ == Stage::SpecularChain) return add(c, Component::Specular, false);
    if (widened && (stage_ == Stage::FromX || stage_ == Stage::CausticChain))
        return add(c, Component::Caustic, false);
    add(c, Component::Indirect, false);
}

Wavelengths camera_wavelengths(float u) {
    const Wavelengths lambda = Wavelengths::visible(u);
    if (auto* r = recorder()) r->wavelengths(lambda);
    return lambda;
}

Wavelengths camera_wavelengths(Sampler& sampler) {
    const float u = current_wavelength_sample();
    return camera_wavelengths(u >= 0 ? u : sampler.next());
}

void follow_dispersion(const shading::BsdfSample& s, Wavelengths& lambda, Spectrum& beta) {
    if (!s.dispersive || lambda.secondary_terminated()) return;
    spectrum::terminate_secondary(lambda, beta);
    if (auto* r = recorder()) r->wavelengths(lambda);
}

void PathRadiance::bounce(bool delta) {
    switch (stage_) {
        case Stage::Camera:
            stage_ = delta ? Stage::SpecularChain : Stage::FromX;
            return;
        case Stage::FromX:
        case Stage::CausticChain:
            stage_ = delta ? Stage::CausticChain : Stage::Indirect;
            return;
        case Stage::SpecularChain:
        case Stage::Indirect:
            break;
    }
}

}  // namespace phos::render
