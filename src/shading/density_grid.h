// Density fields of heterogeneous media (pbrt's uniform grid, sparse NanoVDB grids) and the coarse
// majorant grid that bounds them for delta and ratio tracking.
#pragma once

#include <memory>
#include <vector>

#include "accel/embree_scene.h"
#include "core/vec.h"
#include "scene/medium.h"

namespace phos::shading {

// A scalar density in medium space: 0 outside bounds().
class DensityGrid {
public:
    virtual ~DensityGrid() = default;
    virtual float density(Vec3 p) const = 0;
    // Medium-space box outside which the density is 0 (never empty for a valid grid).
    virtual Bounds bounds() const = 0;
    // An upper bound of density(p) over every p in `box` (medium space), interpolation included.
    virtual float max_density(const Bounds& box) const = 0;
};

// The density grid of a UniformGrid or Sparse medium (nullptr for a homogeneous one). Throws
// InputError when the grid cannot be used (e.g. an empty sparse grid).
std::unique_ptr<DensityGrid> make_density_grid(const scene::Medium& medium);

// res^3 cells over a density grid's bounds, each holding the maximum density inside it (pbrt-v4's
// majorant grid), walked along a ray with a 3D DDA (Amanatides & Woo 1987).
class MajorantGrid {
public:
    explicit MajorantGrid(const DensityGrid& grid, int res = 16);

    // The cells a medium-space ray o + t d crosses for t in [t0, t1), in order. Each next() gives
    // one segment [ta, tb) and the maximum density over it; regions outside the grid's bounds are
    // skipped (their density is 0). Returns false when the range is exhausted.
    class Segments {
    public:
        bool next(float& ta, float& tb, float& max_density);

    private:
        friend class MajorantGrid;
        const MajorantGrid* grid_ = nullptr;
        float t_ = 0, t_end_ = 0;
        int cell_[3] = {0, 0, 0};
        int step_[3] = {0, 0, 0};
        int out_[3] = {0, 0, 0};
        float next_t_[3] = {0, 0, 0};
        float delta_t_[3] = {0, 0, 0};
        bool done_ = true;
        Vec3 o_, d_;  // the ray (plane crossings are computed from it, not accumulated)
    };
    Segments segments(Vec3 o, Vec3 d, float t0, float t1) const;

    int resolution() const { return res_; }
    float max_at(int x, int y, int z) const { return max_[size_t((z * res_ + y) * res_ + x)]; }
    const Bounds& bounds() const { return bounds_; }

private:
    int res_;
    Bounds bounds_;
    std::vector<float> max_;
};

}  // namespace phos::shading
