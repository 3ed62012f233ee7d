// `phos diff`: compares a render with a reference using the bench metrics.
#include "app/lib/diff_command.h"

#include <cstdio>

#include "core/error.h"
#include "film/metrics.h"
#include "io/image/image_io.h"
#include "io/image/tonemap.h"

namespace phos::app {

Image displayed(const Image& image) {
    Image out = image;
    for (Rgb& p : out.pixels)
        for (int c = 0; c < 3; ++c) p[c] = io::linear_to_srgb(p[c]);
    return out;
}

void run_diff(const DiffCommand& cmd) {
    const Image img = io::read_image(cmd.image);
    const Image ref = io::read_image(cmd.reference);
    const bool same_size = img.width == ref.width && img.height == ref.height;
    if (same_size || cmd.block_correlation <= 0)
        std::printf("relMSE %.6g\nmean_ratio %.6g\n", film::rel_mse(img, ref), film::mean_ratio(img, ref));
    if (cmd.block_correlation > 0)
        std::printf("block_correlation %.6g\n",
                    film::block_correlation(displayed(img), displayed(ref), cmd.block_correlation));
    if (!cmd.window.empty()) {
        if (cmd.window.size() != 4) throw InputError("--window takes x0 x1 y0 y1");
        const auto& w = cmd.window;
        const double a = film::window_mean(img, w[0], w[1], w[2], w[3]);
        const double b = film::window_mean(ref, w[0], w[1], w[2], w[3]);
        std::printf("window_mean %.6g\nwindow_mean_reference %.6g\nwindow_ratio %.6g\n", a, b,
                    b > 0 ? a / b : 0.0);
    }
}

}  // namespace phos::app
