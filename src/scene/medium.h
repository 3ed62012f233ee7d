// Participating media as plain data (homogeneous, uniform density grids and sparse VDB grids), and
// the inside/outside media of a surface.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/transform.h"
#include "core/vec.h"

namespace phos::scene {

// A sparse density grid read from an OpenVDB (.vdb) or NanoVDB (.nvdb) file, held as one NanoVDB
// float grid (a position-independent, 32-byte-aligned buffer; io/volume builds it, the shading
// layer reads it). The grid's own index-to-world map defines medium space.
struct SparseGrid {
    std::shared_ptr<const void> buffer;  // the NanoVDB grid (nanovdb::FloatGrid), aligned
    size_t bytes = 0;
    std::string file;  // where it was read from (for messages)
};

struct Medium {
    enum class Kind { Homogeneous, UniformGrid, Sparse };
    std::string name;
    Kind kind = Kind::Homogeneous;
    Rgb sigma_a{0.0f};   // absorption, 1/scene-unit (density 1)
    Rgb sigma_s{0.0f};   // scattering, 1/scene-unit (density 1)
    float scale = 1.0f;  // multiplies sigma_a and sigma_s
    float g = 0.0f;      // Henyey-Greenstein asymmetry, in (-1, 1)
    Rgb emission{0.0f};  // radiance emitted per unit absorption (homogeneous and uniform-grid media)
    // UniformGrid: per-cell factors on `emission` (pbrt "Lescale" with nx*ny*nz values), on the
    // density's cells and reconstructed the same way; empty = 1 everywhere.
    std::vector<float> emission_scale;
    // UniformGrid: density values nx*ny*nz (x fastest) over the box [p0, p1] in medium space,
    // reconstructed trilinearly between cell centres as pbrt-v4 does.
    int nx = 0, ny = 0, nz = 0;
    std::vector<float> density;
    Vec3 p0{0.0f}, p1{1.0f};
    // Sparse: the density grid; its world-space voxel transform is baked into the NanoVDB grid's own
    // map, and to_world places it in the scene.
    SparseGrid sparse;
    Transform to_world;  // medium space -> world
};

// Media on either side of a surface (-1 = none / vacuum; "inside" is opposite the normal). A
// surface whose two sides name the same medium (both -1 by default) is not a medium transition:
// rays keep whatever medium they travel in when they cross or bounce off it (pbrt-v4's rule).
struct MediumInterface {
    int inside = -1;
    int outside = -1;
    bool is_transition() const { return inside != outside; }
};

}  // namespace phos::scene
