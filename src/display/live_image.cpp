// The shared converging image (see live_image.h).
#include "display/live_image.h"

#include <algorithm>
#include <chrono>

namespace phos::display {

LiveImage::LiveImage(int width, int height)
    : width_(width),
      height_(height),
      blocks_x_((width + kBlock - 1) / kBlock),
      blocks_y_((height + kBlock - 1) / kBlock),
      block_version_(size_t(blocks_x_) * size_t(blocks_y_), 0) {
    names_.push_back("image");
    values_.emplace_back(size_t(width) * size_t(height), Rgb(0.0f));
}

void LiveImage::add_layers(const film::Film& film) {
    for (const std::string& name : film.layer_names()) {
        bool known = false;
        for (const std::string& n : names_) known |= n == name;
        if (known) continue;
        names_.push_back(name);
        values_.emplace_back(size_t(width_) * size_t(height_), Rgb(0.0f));
    }
}

void LiveImage::update_tile(const film::Film& film, const film::Tile& tile) {
    // Read the film outside the lock (this tile is not written meanwhile), then copy in.
    const int w = tile.width(), h = tile.height();
    std::vector<Rgb> block;
    std::vector<std::string> names;
    {
        std::lock_guard lock(mutex_);
        names = names_;
    }
    block.reserve(size_t(w) * size_t(h) * names.size());
    for (size_t l = 0; l < names.size(); ++l) {
        const film::Layer* layer = l == 0 ? &film.main() : film.find_layer(names[l]);
        for (int y = tile.y0; y < tile.y1; ++y)
            for (int x = tile.x0; x < tile.x1; ++x) block.push_back(layer ? layer->value(x, y) : Rgb(0.0f));
    }
    {
        std::lock_guard lock(mutex_);
        size_t i = 0;
        for (size_t l = 0; l < names.size(); ++l)
            for (int y = tile.y0; y < tile.y1; ++y)
                for (int x = tile.x0; x < tile.x1; ++x)
                    values_[l][size_t(y) * size_t(width_) + size_t(x)] = block[i++];
        ++version_;
        mark(tile.x0, tile.y0, tile.x1, tile.y1);
    }
    changed_.notify_all();
}

void LiveImage::update_frame(const film::Film& film) {
    {
        std::lock_guard lock(mutex_);
        add_layers(film);
        for (size_t l = 0; l < names_.size(); ++l) {
            const film::Layer* layer = l == 0 ? &film.main() : film.find_layer(names_[l]);
            if (!layer) continue;
            for (int y = 0; y < height_; ++y)
                for (int x = 0; x < width_; ++x)
                    values_[l][size_t(y) * size_t(width_) + size_t(x)] = layer->value(x, y);
        }
        ++version_;
        mark(0, 0, width_, height_);
    }
    changed_.notify_all();
}

void LiveImage::mark(int x0, int y0, int x1, int y1) {
    for (int by = y0 / kBlock; by * kBlock < y1 && by < blocks_y_; ++by)
        for (int bx = x0 / kBlock; bx * kBlock < x1 && bx < blocks_x_; ++bx)
            block_version_[size_t(by) * size_t(blocks_x_) + size_t(bx)] = version_;
}

std::vector<Region> LiveImage::changed_since(uint64_t seen) const {
    std::lock_guard lock(mutex_);
    std::vector<Region> out;
    for (int by = 0; by < blocks_y_; ++by) {
        int first = -1, last = -1;
        for (int bx = 0; bx < blocks_x_; ++bx)
            if (seen == 0 || block_version_[size_t(by) * size_t(blocks_x_) + size_t(bx)] > seen) {
                if (first < 0) first = bx;
                last = bx;
            }
        if (first >= 0)
            out.push_back({first * kBlock, by * kBlock, std::min(width_, (last + 1) * kBlock),
                           std::min(height_, (by + 1) * kBlock)});
    }
    return out;
}

std::vector<Rgb> LiveImage::read_region(size_t layer, const Region& r) const {
    std::lock_guard lock(mutex_);
    std::vector<Rgb> out;
    if (layer >= values_.size()) return out;
    out.reserve(size_t(r.width()) * size_t(r.height()));
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x)
            out.push_back(values_[layer][size_t(y) * size_t(width_) + size_t(x)]);
    return out;
}

void LiveImage::finish() {
    {
        std::lock_guard lock(mutex_);
        finished_ = true;
        ++version_;
    }
    changed_.notify_all();
}

std::vector<std::string> LiveImage::layer_names() const {
    std::lock_guard lock(mutex_);
    return names_;
}

uint64_t LiveImage::version() const {
    std::lock_guard lock(mutex_);
    return version_;
}

bool LiveImage::finished() const {
    std::lock_guard lock(mutex_);
    return finished_;
}

std::vector<Rgb> LiveImage::read(size_t layer) const {
    std::lock_guard lock(mutex_);
    return layer < values_.size() ? values_[layer] : std::vector<Rgb>();
}

void LiveImage::wait(uint64_t seen, double seconds) const {
    std::unique_lock lock(mutex_);
    changed_.wait_for(lock, std::chrono::duration<double>(seconds),
                      [&] { return version_ != seen || finished_; });
}

}  // namespace phos::display
