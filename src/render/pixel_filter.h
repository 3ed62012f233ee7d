// Filter importance sampling (Ernst et al. 2006; pbrt-v4's FilterSampler): a camera sample's
// position in its pixel is drawn with density proportional to |f| of the pixel filter, and the
// sample carries the weight f / (pdf ∫f), so the mean of weight × radiance over a pixel's samples
// is the filter-weighted pixel value ∫ f(p - c) L(p) dp / ∫ f. Each sample still belongs to one
// pixel: no sample is shared, so the pixel loop stays one task per pixel and bit-identical over
// threads. Light paths that reach the camera (bdpt, vcm) land on a film position and are shared
// out to every pixel whose filter covers it with splat_weight.
//
// Every filter pbrt-v4 offers is separable, f(x, y) = f1(x) f1(y): each axis is sampled from a
// fine piecewise-constant table of |f1| (a cell's value bounds |f1| on it, so the density is
// positive wherever f1 is not zero and the estimate is unbiased). For positive filters the weight
// is within a fraction of a percent of 1; for Mitchell and Lanczos it is negative where f is.
#pragma once

#include <vector>

#include "core/vec.h"
#include "scene/pixel_filter.h"

namespace phos::render {

class PixelFilterSampler {
public:
    explicit PixelFilterSampler(const scene::PixelFilter& filter = {});

    // A camera sample: its position relative to the pixel's corner (in [0.5 - r, 0.5 + r] per axis)
    // and its weight (mean 1 over u). The box of radius 1/2 returns u itself and weight 1 exactly.
    struct FilmSample {
        Vec2 position;
        float weight = 1;
    };
    FilmSample sample(Vec2 u) const;

    // The filter at offset d from a pixel's centre (pixels), normalised to unit integral.
    float splat_weight(Vec2 d) const;
    // f itself at offset d (the filter as pbrt-v4 defines it, not normalised).
    float evaluate(Vec2 d) const { return axis_[0].f(d.x) * axis_[1].f(d.y); }
    // ∫ f over its support (numerically, to about 1e-7 relative).
    float integral() const { return axis_[0].integral * axis_[1].integral; }
    Vec2 radius() const { return filter_.radius; }
    // Samples count only for the pixel they were taken in (splats go to one pixel, unweighted).
    bool is_pixel_box() const { return filter_.is_pixel_box(); }
    const scene::PixelFilter& filter() const { return filter_; }

private:
    struct Axis {
        scene::PixelFilter shape;  // kind and parameters (its radius along this axis is r)
        float r = 0.5f;
        double integral = 1;
        std::vector<float> cdf;  // cells + 1 entries, cdf[0] = 0, cdf.back() = 1
        std::vector<float> pdf;  // per cell, a density over [-r, r]
        float f(float x) const;
        // x in [-r, r] and f1(x) / pdf(x).
        void sample(float u, float& x, float& ratio) const;
    };
    scene::PixelFilter filter_;
    Axis axis_[2];
};

}  // namespace phos::render
