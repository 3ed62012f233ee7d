// The sRGB table phos renders with (RgbSigmoidTable::srgb): data/rgb_sigmoid_srgb.bin, made by
// tools/rgb_sigmoid_table at 32 points per axis (docs/spectral.md), embedded in the library.
#include "spectrum/rgb_sigmoid.h"

// The file's bytes between phos_rgb_sigmoid_srgb and phos_rgb_sigmoid_srgb_end (PHOS_DATA_DIR is
// the repository's data/ folder, set by CMakeLists.txt).
asm(".section .rodata\n"
    ".balign 16\n"
    ".global phos_rgb_sigmoid_srgb\n"
    "phos_rgb_sigmoid_srgb:\n"
    ".incbin \"" PHOS_DATA_DIR
    "/rgb_sigmoid_srgb.bin\"\n"
    ".global phos_rgb_sigmoid_srgb_end\n"
    "phos_rgb_sigmoid_srgb_end:\n"
    ".previous\n");
extern "C" const uint8_t phos_rgb_sigmoid_srgb[];
extern "C" const uint8_t phos_rgb_sigmoid_srgb_end[];

namespace phos::spectrum {

const RgbSigmoidTable& RgbSigmoidTable::srgb() {
    static const RgbSigmoidTable table =
        from_bytes(phos_rgb_sigmoid_srgb, size_t(phos_rgb_sigmoid_srgb_end - phos_rgb_sigmoid_srgb));
    return table;
}

}  // namespace phos::spectrum
