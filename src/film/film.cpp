// Film and layer accumulation (see film.h).
#include "film/film.h"

#include <cmath>
#include <stdexcept>

namespace phos::film {

Layer::Layer(int width, int height) {
    if (width < 0 || height < 0) throw std::invalid_argument("film size must not be negative");
    width_ = width;
    height_ = height;
    pixels_.resize(size_t(width) * size_t(height));
}

Layer::Layer(const Layer& other)
    : width_(other.width_), height_(other.height_), pixels_(other.pixels_), rejected_(other.rejected()) {}

Layer& Layer::operator=(const Layer& other) {
    width_ = other.width_;
    height_ = other.height_;
    pixels_ = other.pixels_;
    rejected_.store(other.rejected(), std::memory_order_relaxed);
    return *this;
}

bool Layer::add(int x, int y, Rgb L, float weight) {
    if (!inside(x, y)) return false;
    if (!L.is_finite() || !std::isfinite(weight)) {
        rejected_.fetch_add(1, std::memory_order_relaxed);
        return false;
    }
    Pixel& p = pixels_[index(x, y)];
    p.r += double(weight) * L.r;
    p.g += double(weight) * L.g;
    p.b += double(weight) * L.b;
    p.w += weight;
    return true;
}

void Layer::set(int x, int y, Rgb value) {
    if (!inside(x, y)) return;
    pixels_[index(x, y)] = Pixel{value.r, value.g, value.b, 1.0};
}

Rgb Layer::value(int x, int y) const {
    const Pixel& p = pixels_[index(x, y)];
    if (p.w == 0) return Rgb(0.0f);
    return Rgb(float(p.r / p.w), float(p.g / p.w), float(p.b / p.w));
}

Image Layer::image() const {
    Image img(width_, height_);
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) img.at(x, y) = value(x, y);
    return img;
}

std::vector<double> Layer::sums() const {
    std::vector<double> out;
    out.reserve(pixels_.size() * 4);
    for (const Pixel& p : pixels_) out.insert(out.end(), {p.r, p.g, p.b, p.w});
    return out;
}

void Layer::set_sums(const std::vector<double>& sums, uint64_t rejected) {
    if (sums.size() != pixels_.size() * 4) throw std::invalid_argument("Layer::set_sums: size mismatch");
    for (size_t i = 0; i < pixels_.size(); ++i)
        pixels_[i] = {sums[4 * i], sums[4 * i + 1], sums[4 * i + 2], sums[4 * i + 3]};
    rejected_.store(rejected, std::memory_order_relaxed);
}

void Layer::append_region_sums(int x0, int y0, int x1, int y1, std::vector<double>& out) const {
    if (!(0 <= x0 && x0 <= x1 && x1 <= width_ && 0 <= y0 && y0 <= y1 && y1 <= height_))
        throw std::invalid_argument("Layer::append_region_sums: outside the layer");
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            const Pixel& p = pixels_[index(x, y)];
            out.insert(out.end(), {p.r, p.g, p.b, p.w});
        }
}

void Layer::set_region_sums(int x0, int y0, int x1, int y1, const double* sums) {
    if (!(0 <= x0 && x0 <= x1 && x1 <= width_ && 0 <= y0 && y0 <= y1 && y1 <= height_))
        throw std::invalid_argument("Layer::set_region_sums: outside the layer");
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x, sums += 4) pixels_[index(x, y)] = {sums[0], sums[1], sums[2], sums[3]};
}

void Layer::clear() {
    for (Pixel& p : pixels_) p = Pixel{};
    rejected_.store(0, std::memory_order_relaxed);
}

Film::Film(int width, int height) : main_(width, height) {}

Layer& Film::layer(const std::string& name) {
    auto it = layers_.find(name);
    if (it == layers_.end()) it = layers_.emplace(name, Layer(width(), height())).first;
    return it->second;
}

const Layer* Film::find_layer(const std::string& name) const {
    const auto it = layers_.find(name);
    return it == layers_.end() ? nullptr : &it->second;
}

std::vector<std::string> Film::layer_names() const {
    std::vector<std::string> names;
    for (const auto& [name, layer] : layers_) names.push_back(name);
    return names;
}

void Film::clear() {
    main_.clear();
    for (auto& [name, layer] : layers_) layer.clear();
}

}  // namespace phos::film
