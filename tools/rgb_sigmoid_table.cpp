// rgb_sigmoid_table RES OUT: fits the sRGB-to-spectrum table (spectrum/rgb_sigmoid.h) at RES grid
// points per axis and writes it to OUT, the form data/rgb_sigmoid_srgb.bin takes (docs/spectral.md
// says how it was made). Prints the largest residual of any fit and the time taken.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "spectrum/rgb_sigmoid.h"

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: rgb_sigmoid_table RES OUT\n");
        return 2;
    }
    const int res = std::atoi(argv[1]);
    if (res < 2 || res > 256) {
        std::fprintf(stderr, "rgb_sigmoid_table: RES must be in [2, 256]\n");
        return 2;
    }
    const auto t0 = std::chrono::steady_clock::now();
    float worst = 0;
    const phos::spectrum::RgbSigmoidTable table = phos::spectrum::RgbSigmoidTable::fit(res, &worst);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const std::vector<uint8_t> bytes = table.bytes();
    std::ofstream out(argv[2], std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    if (!out) {
        std::fprintf(stderr, "rgb_sigmoid_table: cannot write %s\n", argv[2]);
        return 1;
    }
    std::printf("rgb_sigmoid_table: %d^3 x 3 fits in %.1f s, largest residual %.3g, %zu bytes\n", res,
                seconds, double(worst), bytes.size());
    return 0;
}
