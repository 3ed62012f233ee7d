// Error metrics (see metrics.h). Sums in double, in pixel order, so results are reproducible.
#include "film/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"

namespace phos::film {
namespace {

std::string size_text(const Image& img) {
    return std::to_string(img.width) + "x" + std::to_string(img.height);
}

void check_same_size(const Image& image, const Image& reference) {
    if (image.width != reference.width || image.height != reference.height ||
        image.pixels.size() != reference.pixels.size())
        throw InputError("image size " + size_text(image) + " does not match reference size " +
                         size_text(reference));
}

}  // namespace

double rel_mse(const Image& image, const Image& reference) {
    check_same_size(image, reference);
    if (image.pixels.empty()) return 0.0;
    double sum = 0;
    for (size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double x = image.pixels[i][c], r = reference.pixels[i][c];
            sum += (x - r) * (x - r) / (r * r + 0.01);
        }
    return sum / (3.0 * double(image.pixels.size()));
}

double mean_value(const Image& image) {
    if (image.pixels.empty()) return 0.0;
    double sum = 0;
    for (const Rgb& p : image.pixels) sum += double(p.r) + double(p.g) + double(p.b);
    return sum / (3.0 * double(image.pixels.size()));
}

double mean_ratio(const Image& image, const Image& reference) {
    check_same_size(image, reference);
    const double m = mean_value(image), r = mean_value(reference);
    if (r == 0) return m == 0 ? 1.0 : std::numeric_limits<double>::infinity();
    return m / r;
}

double window_mean(const Image& image, int x0, int x1, int y0, int y1) {
    if (x0 < 0 || y0 < 0 || x1 > image.width || y1 > image.height || x0 >= x1 || y0 >= y1)
        throw InputError("window x[" + std::to_string(x0) + "," + std::to_string(x1) + ") y[" +
                         std::to_string(y0) + "," + std::to_string(y1) + ") is empty or outside the " +
                         size_text(image) + " image");
    double sum = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            const Rgb& p = image.at(x, y);
            sum += (double(p.r) + double(p.g) + double(p.b)) / 3.0;
        }
    return sum / (double(x1 - x0) * double(y1 - y0));
}

double speckle_fraction(const Image& image) {
    if (image.pixels.empty()) return 0.0;
    const int w = image.width, h = image.height;
    std::vector<float> lum(image.pixels.size());
    for (size_t i = 0; i < lum.size(); ++i) lum[i] = image.pixels[i].luminance();
    uint64_t speckles = 0;
    std::vector<float> window;
    window.reserve(25);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            window.clear();
            for (int j = std::max(0, y - 2); j <= std::min(h - 1, y + 2); ++j)
                for (int i = std::max(0, x - 2); i <= std::min(w - 1, x + 2); ++i)
                    window.push_back(lum[size_t(j) * size_t(w) + size_t(i)]);
            const auto mid = window.begin() + std::ptrdiff_t(window.size() / 2);
            std::nth_element(window.begin(), mid, window.end());
            const double l = lum[size_t(y) * size_t(w) + size_t(x)];
            if (l > kSpeckleRatio * double(*mid) + kSpeckleOffset) ++speckles;
        }
    return double(speckles) / double(lum.size());
}

namespace {

// Mean luminance of each whole block x block block of `image`, row by row.
std::vector<double> block_means(const Image& image, int block, int bx, int by) {
    std::vector<double> means(size_t(bx) * size_t(by), 0.0);
    for (int y = 0; y < by * block; ++y)
        for (int x = 0; x < bx * block; ++x)
            means[size_t(y / block) * size_t(bx) + size_t(x / block)] += double(image.at(x, y).luminance());
    for (double& m : means) m /= double(block) * double(block);
    return means;
}

}  // namespace

double block_correlation(const Image& a, const Image& b, int block) {
    const bool a_larger = a.width >= b.width;
    const Image& big = a_larger ? a : b;
    const Image& small = a_larger ? b : a;
    if (block < 1 || small.width < 1 || small.height < 1 || big.width % small.width != 0 ||
        big.height % small.height != 0 || big.width / small.width != big.height / small.height)
        throw InputError("image sizes " + size_text(a) + " and " + size_text(b) +
                         " are not integer multiples of each other");
    const int scale = big.width / small.width;
    const int bx = small.width / block, by = small.height / block;
    if (bx < 1 || by < 1)
        throw InputError("no whole " + std::to_string(block) + "x" + std::to_string(block) +
                         " block fits in " + size_text(small));
    const std::vector<double> s = block_means(small, block, bx, by),
                              g = block_means(big, block * scale, bx, by);
    const double n = double(s.size());
    double ms = 0, mg = 0;
    for (size_t i = 0; i < s.size(); ++i) ms += s[i], mg += g[i];
    ms /= n, mg /= n;
    double cov = 0, vs = 0, vg = 0;
    for (size_t i = 0; i < s.size(); ++i) {
        cov += (s[i] - ms) * (g[i] - mg);
        vs += (s[i] - ms) * (s[i] - ms);
        vg += (g[i] - mg) * (g[i] - mg);
    }
    if (!(vs > 0) || !(vg > 0)) return 0.0;
    return cov / std::sqrt(vs * vg);
}

}  // namespace phos::film
