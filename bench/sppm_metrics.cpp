// Prints relMSE, mean ratio and (optionally) a window mean of an image against a reference, as
// bench/README.md defines them; used by bench/sppm_equal_time.sh.
// Usage: sppm_metrics IMAGE REFERENCE [X0 X1 Y0 Y1]
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "film/metrics.h"
#include "io/image/image_io.h"

int main(int argc, char** argv) {
    if (argc != 3 && argc != 7) {
        std::fprintf(stderr, "usage: sppm_metrics IMAGE REFERENCE [X0 X1 Y0 Y1]\n");
        return 2;
    }
    try {
        const phos::Image img = phos::io::read_image(argv[1]);
        const phos::Image ref = phos::io::read_image(argv[2]);
        std::printf("%9.5f %7.4f", phos::film::rel_mse(img, ref), phos::film::mean_ratio(img, ref));
        if (argc == 7) {
            const int x0 = std::atoi(argv[3]), x1 = std::atoi(argv[4]), y0 = std::atoi(argv[5]),
                      y1 = std::atoi(argv[6]);
            std::printf(" %8.3f", phos::film::window_mean(img, x0, x1, y0, y1));
        } else {
            std::printf(" %8s", "-");
        }
        std::printf("\n");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "sppm_metrics: %s\n", e.what());
        return 2;
    }
    return 0;
}
