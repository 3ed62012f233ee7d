// libFuzzer harness for the pbrt-v4 reader (io/pbrt): the input is the main scene file, optionally
// followed by "#@file NAME" sections (fuzz_support.h) that it can Include/Import or name as PLY
// meshes, images and spectra; fixtures (inc.pbrt, m.ply, t.pfm, t.bmp, s.spd) are always present.
#include "fuzz/fuzz_support.h"
#include "io/pbrt/pbrt_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static phos::fuzz::Scratch scratch;
    static const std::vector<std::pair<std::string, std::string>> fixtures = {
        {"inc.pbrt",
         "AttributeBegin\nMaterial \"diffuse\"\nShape \"sphere\" \"float radius\" 1\nAttributeEnd\n"},
        {"m.ply", phos::fuzz::fixture_ply()},
        {"t.pfm", phos::fuzz::fixture_pfm()},
        {"t.bmp", phos::fuzz::fixture_bmp()},
        {"s.spd", "400 0.5\n500 0.6\n700 0.7\n"},
    };
    const std::string path = scratch.prepare(fixtures, phos::fuzz::split_input(data, size), "main.pbrt");
    const bool strict = size > 0 && (data[size - 1] & 1);
    phos::fuzz::expect_reader_errors([&] {
        phos::io::PbrtOptions options;
        options.strict = strict;
        phos::io::load_pbrt(path, options);
    });
    return 0;
}
