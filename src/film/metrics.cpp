// Error metrics (see metrics.h). Sums in double, in pixel order, so results are reproducible.
#include "film/metrics.h"

#include <limits>
#include <string>

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

}  // namespace phos::film
