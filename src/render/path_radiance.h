// The radiance a camera path gathers, split into the components --layers writes. The integrator
// reports what its path finds and how it scatters; which component each contribution belongs to is
// decided here from those events (as Mitsuba's AOV integrator and pbrt's film keep such bookkeeping
// out of the estimator), and each contribution also goes to the --trace-pixel recorder.
#pragma once

#include <vector>

#include "core/rng.h"
#include "core/vec.h"
#include "shading/bsdf.h"
#include "spectrum/sampled_spectrum.h"

namespace phos::render {

// The components of the radiance along a camera ray, each a film layer with --layers, summing to
// the image. `Specular` holds everything that reached the camera after at least one mirror/glass
// (delta) bounce from it; the other three are what the first surface x seen directly sends:
// direct = its emission, light sampled at it and emission found by its BSDF samples (the light
// sampling's MIS partner), caustic = light reaching x through one or more delta bounces after it
// (x S+ L), indirect = the rest.
enum class Component { Direct, Caustic, Indirect, Specular };
// The film layer a component is written to: "direct", "caustic", "indirect", "specular".
const char* component_name(Component c);
// All four, in the order of their layers.
const std::vector<Component>& all_components();

struct RadianceParts {
    Rgb direct{0.0f}, caustic{0.0f}, indirect{0.0f}, specular{0.0f};
    Rgb total() const { return direct + caustic + indirect + specular; }
    Rgb& operator[](Component c);
};

// One camera path's radiance L, as colour, with `parts` (optional) its split into components and,
// while a pixel is traced, each contribution recorded with its term (path_recorder.h). The
// contributions are spectra at the path's wavelengths `lambda`, taken to colour as they are added
// (with `lambda` as it is then: after a dispersive interface the hero alone counts).
class PathRadiance {
public:
    explicit PathRadiance(const Wavelengths& lambda, RadianceParts* parts = nullptr)
        : lambda_(lambda), parts_(parts) {}
    // Emission the path found (an emitter it hit, emission in a medium, light escaping the scene),
    // the path's throughput included.
    void emission(const Spectrum& c);
    // The same for emission that is a colour already (the .scn glow: emission.h).
    void emission(Rgb c);
    // Light sampled at the path's current vertex (next-event estimation), throughput included.
    // `widened`: the vertex is a mirror or glass widened by path regularisation, so the light
    // counts as if it had come through the delta lobe (a caustic of x rather than indirect light).
    void light(const Spectrum& c, bool widened = false);
    // The path went on from its current vertex: through a delta lobe (mirror, glass) or not
    // (a diffuse or glossy lobe, a medium's phase function).
    void bounce(bool delta);
    Rgb total() const { return L_; }

private:
    // Where the path is: x is the first surface the camera sees directly.
    enum class Stage {
        Camera,         // the camera ray
        SpecularChain,  // after a delta bounce from the camera (whatever follows)
        FromX,          // the ray x's BSDF sampled from a non-delta lobe
        CausticChain,   // after x's non-delta bounce, delta bounces only
        Indirect,       // after two or more non-delta bounces
    };
    void add(Rgb c, Component part, bool emitted);

    Rgb L_{0.0f};
    const Wavelengths& lambda_;
    RadianceParts* parts_;
    Stage stage_ = Stage::Camera;
};

// The wavelengths of a camera path (hero wavelength at `u`, the others stratified from it:
// sampled_spectrum.h), recorded for --trace-pixel.
Wavelengths camera_wavelengths(float u);
// The same for a camera sample traced by the pixel loop: its pixel's stratified wavelength sample
// (pixel_loop.h's current_wavelength_sample) inside render_tile_samples, else `sampler`'s next value.
Wavelengths camera_wavelengths(Sampler& sampler);
// After BSDF sample `s` at a vertex of a camera path: a sample through a dispersive interface
// terminates the path's secondary wavelengths, and its throughput `beta` there.
void follow_dispersion(const shading::BsdfSample& s, Wavelengths& lambda, Spectrum& beta);

}  // namespace phos::render
