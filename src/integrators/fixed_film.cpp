// The fixed-point image sums of bdpt and vcm (see fixed_film.h).
#include "integrators/fixed_film.h"

#include <algorithm>
#include <cmath>

#include "core/byte_buffer.h"
#include "dist/ranks.h"

namespace phos::integrators::vcm {

namespace {

constexpr double kFixedScale = 1073741824.0;  // 2^30: the sums' fixed point

}  // namespace

FixedFilm::FixedFilm(int width, int height, bool layers)
    : width_(width),
      height_(height),
      pixels_(size_t(width) * size_t(height)),
      planes_(layers ? 1 + kParts : 1),
      sums_(pixels_ * 3 * planes_) {}

void FixedFilm::resume(const ProgressiveState& state, const std::string& what) {
    if (state.payload.empty()) return;
    ByteReader r(state.payload, what);
    const std::vector<int64_t> v = r.get_vector<int64_t>();
    if (v.size() != pixels_ * 3 * planes_ || !r.at_end()) r.fail("size does not match the image");
    if (dist::root())  // the other ranks start from 0: sum_over_ranks adds the saved sums once
        for (size_t i = 0; i < v.size() && i < sums_.size(); ++i) sums_[i].store(v[i]);
    if (dist::distributed()) total_ = v;
}

void FixedFilm::add(size_t pixel, Rgb v, Part part) {
    if (!v.is_finite()) {
        rejected_.fetch_add(1, std::memory_order_relaxed);
        return;
    }
    for (int c = 0; c < 3; ++c) {
        const double x = std::clamp(double(v[c]) * kFixedScale, -4.6e18, 4.6e18);
        const auto q = int64_t(std::llround(x));
        if (q == 0) continue;
        sums_[pixel * 3 + size_t(c)].fetch_add(q, std::memory_order_relaxed);
        if (planes_ > 1)
            sums_[((1 + size_t(part)) * pixels_ + pixel) * 3 + size_t(c)].fetch_add(
                q, std::memory_order_relaxed);
    }
}

std::vector<int64_t> FixedFilm::values() const {
    std::vector<int64_t> v(sums_.size());
    for (size_t i = 0; i < v.size(); ++i) v[i] = sums_[i].load();
    return v;
}

void FixedFilm::sum_over_ranks() {
    if (!dist::distributed()) return;
    total_ = values();
    dist::sum(total_.data(), total_.size());
}

void FixedFilm::resolve(film::Film& film, uint64_t iterations) const {
    const std::vector<int64_t> local = total_.empty() ? values() : std::vector<int64_t>{};
    const std::vector<int64_t>& v = total_.empty() ? local : total_;
    const double scale = iterations > 0 ? 1 / (kFixedScale * double(iterations)) : 0;
    const auto mean = [&](size_t plane, size_t i) {
        Rgb r;
        for (int c = 0; c < 3; ++c) r[c] = float(double(v[(plane * pixels_ + i) * 3 + size_t(c)]) * scale);
        return r;
    };
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) {
            const size_t i = size_t(y) * size_t(width_) + size_t(x);
            film.set_pixel(x, y, mean(0, i));
            if (planes_ > 1)
                for (int k = 0; k < kParts; ++k)
                    film.layer(component_name(Component(k))).set(x, y, mean(1 + size_t(k), i));
        }
}

RenderBudget FixedFilm::saving_sums(const RenderBudget& budget) const {
    RenderBudget saving = budget;
    saving.observers.on_checkpoint = [this, &budget](const ProgressiveState& s) {
        if (!budget.observers.on_checkpoint) return;
        ProgressiveState saved = s;
        ByteWriter w(saved.payload);
        w.put_vector(total_.empty() ? values() : total_);
        budget.observers.on_checkpoint(saved);
    };
    return saving;
}

}  // namespace phos::integrators::vcm
