// Image survey commands (see image_commands.h).
#include "app/lib/image_commands.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/lib/diff_command.h"
#include "core/error.h"
#include "film/metrics.h"
#include "io/image/image_io.h"

namespace phos::app {

ImageInfo image_info(const Image& image) {
    ImageInfo info;
    info.width = image.width;
    info.height = image.height;
    double sum = 0;
    uint64_t finite = 0, black = 0;
    for (const Rgb& p : image.pixels) {
        for (int c = 0; c < 3; ++c) {
            if (std::isfinite(p[c])) {
                sum += p[c];
                ++finite;
            } else {
                ++info.non_finite;
            }
        }
        if (p.r == 0 && p.g == 0 && p.b == 0) ++black;
    }
    info.mean = finite > 0 ? sum / double(finite) : 0.0;
    info.black_fraction = image.pixels.empty() ? 0.0 : double(black) / double(image.pixels.size());
    // Speckles as a viewer sees them: on the sRGB-encoded image, as the PNG shows it.
    info.speckle = film::speckle_fraction(displayed(image));
    info.speckle_linear = film::speckle_fraction(image);
    return info;
}

double window_luminance(const Image& image, int x0, int x1, int y0, int y1) {
    x0 = std::max(x0, 0), y0 = std::max(y0, 0);
    x1 = std::min(x1, image.width), y1 = std::min(y1, image.height);
    double sum = 0;
    int n = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            sum += double(image.at(x, y).luminance());
            ++n;
        }
    return n > 0 ? sum / n : 0.0;
}

void run_info(const std::vector<std::string>& paths, const std::vector<int>& windows) {
    for (const std::string& path : paths) {
        const Image image = io::read_image(path);
        const ImageInfo i = image_info(image);
        std::printf("%s %dx%d mean %.6g black %.4f nonfinite %llu speckle %.5f speckle_linear %.5f\n",
                    path.c_str(), i.width, i.height, i.mean, i.black_fraction,
                    static_cast<unsigned long long>(i.non_finite), i.speckle, i.speckle_linear);
        for (size_t w = 0; w + 3 < windows.size(); w += 4)
            std::printf("  window %d %d %d %d luminance %.6g\n", windows[w], windows[w + 1], windows[w + 2],
                        windows[w + 3],
                        window_luminance(image, windows[w], windows[w + 1], windows[w + 2], windows[w + 3]));
    }
}

Image montage(const std::vector<Image>& images, int cell) {
    const int n = int(images.size());
    const int cols = std::max(1, int(std::ceil(std::sqrt(double(n)))));
    const int rows = std::max(1, (n + cols - 1) / cols);
    Image out(cols * cell, rows * cell);
    for (int k = 0; k < n; ++k) {
        const Image& img = images[size_t(k)];
        if (img.width <= 0 || img.height <= 0) continue;
        const double scale = double(cell) / double(std::max(img.width, img.height));
        const int w = std::max(1, int(img.width * scale)), h = std::max(1, int(img.height * scale));
        const int x0 = (k % cols) * cell + (cell - w) / 2, y0 = (k / cols) * cell + (cell - h) / 2;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                // Box filter over the source pixels this cell pixel covers (non-finite ones skipped).
                const int sx0 = int(x / scale),
                          sx1 = std::max(sx0 + 1, std::min(img.width, int((x + 1) / scale)));
                const int sy0 = int(y / scale),
                          sy1 = std::max(sy0 + 1, std::min(img.height, int((y + 1) / scale)));
                Rgb sum(0.0f);
                int count = 0;
                for (int sy = sy0; sy < std::min(sy1, img.height); ++sy)
                    for (int sx = sx0; sx < std::min(sx1, img.width); ++sx) {
                        const Rgb& p = img.at(sx, sy);
                        if (!p.is_finite()) continue;
                        sum += p;
                        ++count;
                    }
                out.at(x0 + x, y0 + y) = count > 0 ? sum * (1.0f / float(count)) : Rgb(0.0f);
            }
    }
    return out;
}

void run_montage(const std::string& output, const std::vector<std::string>& inputs, int cell) {
    if (!io::is_writable_image_path(output))
        throw InputError("montage '" + output + "': unknown image format (use .exr, .pfm, .png or .bmp)");
    if (!(cell >= 8 && cell <= 4096))
        throw InputError("--cell: " + std::to_string(cell) + " is not in [8, 4096]");
    std::vector<Image> images;
    for (const std::string& path : inputs) images.push_back(io::read_image(path));
    io::write_image(output, montage(images, cell));
}

}  // namespace phos::app
