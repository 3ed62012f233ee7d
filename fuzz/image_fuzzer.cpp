// libFuzzer harness for the image readers (io/image: OpenEXR, PFM, and stb_image for PNG, JPEG,
// TGA, BMP and Radiance HDR). read_image picks the decoder by extension, so the input's first byte
// chooses the file name's extension (low 3 bits) and the sRGB flag (top bit); the rest is the file.
#include "core/image.h"
#include "fuzz/fuzz_support.h"
#include "io/image/image_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static phos::fuzz::Scratch scratch;
    static const char* const kExtensions[8] = {".exr", ".pfm", ".png", ".jpg",
                                               ".tga", ".bmp", ".hdr", ".jpeg"};
    if (size < 1) return 0;
    const std::string path = scratch.write(std::string("image") + kExtensions[data[0] & 7],
                                           std::string(reinterpret_cast<const char*>(data + 1), size - 1));
    const bool srgb = (data[0] & 0x80) != 0;
    phos::fuzz::expect_reader_errors([&] {
        const phos::Image image = phos::io::read_image(path, srgb);
        if (image.width <= 0 || image.height <= 0 ||
            image.pixels.size() != size_t(image.width) * size_t(image.height))
            phos::fuzz::invariant_failed("image size");
    });
    return 0;
}
