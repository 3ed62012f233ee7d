// The CIE standard illuminants pbrt-v4 names besides D65 (which spectrum/color.h has at 1 nm):
// "stdillum-A" (incandescent, 2856 K), "stdillum-D50" (daylight), "stdillum-F1" to "stdillum-F12"
// (fluorescent lamps, their mercury lines included) and "illum-acesD60" (ACES' white): relative
// spectral power at evenly spaced wavelengths (standard_illuminants_data.cpp has the sources),
// linear between the samples. Emitters scale them to luminance 1 as pbrt-v4 does.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace phos::spectrum {

struct StandardIlluminant {
    std::string name;                 // "F11"
    float lambda_first, lambda_step;  // nm: value[i] is at lambda_first + i * lambda_step
    std::vector<float> value;

    std::vector<float> wavelengths() const;
};

const std::vector<StandardIlluminant>& standard_illuminants();
// "F11", or pbrt-v4's "stdillum-F11" / "illum-acesD60"; nullopt for an unknown name (and for D65).
std::optional<StandardIlluminant> standard_illuminant(const std::string& name);

}  // namespace phos::spectrum
