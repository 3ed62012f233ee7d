// Participating media as plain data (homogeneous and uniform density grids), and the inside/outside
// media of a surface.
#pragma once

#include <string>
#include <vector>

#include "core/transform.h"
#include "core/vec.h"

namespace phos::scene {

struct Medium {
    enum class Kind { Homogeneous, UniformGrid };
    std::string name;
    Kind kind = Kind::Homogeneous;
    Rgb sigma_a{0.0f};  // absorption, 1/scene-unit
    Rgb sigma_s{0.0f};  // scattering, 1/scene-unit
    float scale = 1.0f;
    float g = 0.0f;  // Henyey-Greenstein asymmetry
    Rgb emission{0.0f};
    // UniformGrid: density values nx*ny*nz over the box [p0, p1] in medium space.
    int nx = 0, ny = 0, nz = 0;
    std::vector<float> density;
    Vec3 p0{0.0f}, p1{1.0f};
    Transform to_world;
};

// Media on either side of a surface (-1 = none / vacuum; "inside" is opposite the normal).
struct MediumInterface {
    int inside = -1;
    int outside = -1;
};

}  // namespace phos::scene
