// The film: per-pixel accumulation of weighted radiance samples with a box pixel filter (a sample
// counts only for the pixel it was taken in), plus named extra layers (direct, indirect, caustic...)
// that accumulate the same way. Each pixel must be written by one task at a time; no atomics.
#pragma once

#include <atomic>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/vec.h"

namespace phos::film {

// One accumulator of weighted sums per pixel. Double sums so that millions of samples (or many
// progressive passes) add up without float round-off.
class Layer {
public:
    Layer() = default;
    Layer(int width, int height);
    Layer(const Layer& other);
    Layer& operator=(const Layer& other);

    int width() const { return width_; }
    int height() const { return height_; }

    // Adds `weight * L` to pixel (x, y)'s sum and `weight` to its weight. A sample with a NaN or
    // infinite value or weight is rejected (counted, not added) and false returned, so one bad path
    // cannot poison a pixel. Samples outside the film are ignored (false, not counted).
    bool add(int x, int y, Rgb L, float weight = 1.0f);
    // Overwrites pixel (x, y) with `value` at weight 1 (for estimators that compute a final value).
    void set(int x, int y, Rgb value);
    // sum / weight, or black for a pixel that received no weight.
    Rgb value(int x, int y) const;
    double weight(int x, int y) const { return pixels_[index(x, y)].w; }
    Image image() const;

    void clear();
    // Samples rejected by add() for being NaN or infinite.
    uint64_t rejected() const { return rejected_.load(std::memory_order_relaxed); }

    // The raw sums, 4 doubles per pixel (r, g, b, weight) row by row, and their restoration (a
    // checkpoint; std::invalid_argument when the size does not match), with a rejected count.
    std::vector<double> sums() const;
    void set_sums(const std::vector<double>& sums, uint64_t rejected = 0);
    // The same for the rectangle [x0, x1) x [y0, y1) (inside the layer): its sums appended to `out`,
    // and overwritten from `sums` (4 doubles per pixel, row by row), e.g. a tile another process
    // rendered. add_rejected counts samples another process rejected.
    void append_region_sums(int x0, int y0, int x1, int y1, std::vector<double>& out) const;
    void set_region_sums(int x0, int y0, int x1, int y1, const double* sums);
    void add_rejected(uint64_t n) { rejected_.fetch_add(n, std::memory_order_relaxed); }

private:
    struct Pixel {
        double r = 0, g = 0, b = 0, w = 0;
    };
    size_t index(int x, int y) const { return size_t(y) * size_t(width_) + size_t(x); }
    bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < width_ && y < height_; }

    int width_ = 0, height_ = 0;
    std::vector<Pixel> pixels_;
    // Shared by all tasks writing this layer; bumped only for bad samples, so contention is nil.
    std::atomic<uint64_t> rejected_{0};
};

class Film {
public:
    Film() = default;
    Film(int width, int height);

    int width() const { return main_.width(); }
    int height() const { return main_.height(); }

    bool add_sample(int x, int y, Rgb L, float weight = 1.0f) { return main_.add(x, y, L, weight); }
    void set_pixel(int x, int y, Rgb value) { main_.set(x, y, value); }
    Image image() const { return main_.image(); }
    const Layer& main() const { return main_; }
    Layer& main() { return main_; }

    // The named layer, created empty (same size as the film) on first use. Creating a layer is not
    // thread-safe: name all layers before rendering in parallel; adding to existing ones is fine.
    Layer& layer(const std::string& name);
    // Null if no such layer.
    const Layer* find_layer(const std::string& name) const;
    std::vector<std::string> layer_names() const;  // sorted

    void clear();

    // NaN/inf samples rejected by the main image, for the -v report.
    uint64_t rejected_samples() const { return main_.rejected(); }

private:
    Layer main_;
    std::map<std::string, Layer> layers_;  // std::map: stable references and a fixed iteration order
};

}  // namespace phos::film
