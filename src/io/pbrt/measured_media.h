// pbrt-v4's named measured scattering properties (its GetMediumScatteringProperties: Jensen et al.
// 2001 and Narasimhan et al. 2006): what a `subsurface` material's `name` and a homogeneous
// medium's `preset` select.
#pragma once

#include <map>
#include <string>

#include "core/vec.h"

namespace phos::io::pbrt {

// The reduced scattering coefficient sigma_s' and the absorption coefficient sigma_a, RGB, in
// 1/mm; pbrt-v4 uses them unconverted as 1/scene-unit, sigma_s' as sigma_s with g = 0.
struct MeasuredMedium {
    Rgb sigma_prime_s, sigma_a;
};

// Every named medium by its pbrt name.
const std::map<std::string, MeasuredMedium>& measured_media();

}  // namespace phos::io::pbrt
