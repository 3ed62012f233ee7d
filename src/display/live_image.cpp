// The shared converging image (see live_image.h).
#include "display/live_image.h"

#include <chrono>

namespace phos::display {

LiveImage::LiveImage(int width, int height) : width_(width), height_(height) {
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
    }
    changed_.notify_all();
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
