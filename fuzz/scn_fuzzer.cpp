// libFuzzer harness for the `.scn` reader (io/scn): the input is the scene file, optionally followed
// by "#@file NAME" sections (fuzz_support.h) that it can `include` or name as meshes and textures;
// small valid fixtures (inc.scn, m.off, m.ply, m.obj, t.pfm, t.bmp) are always present too.
#include "fuzz/fuzz_support.h"
#include "io/scn/scn_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static phos::fuzz::Scratch scratch;
    static const std::vector<std::pair<std::string, std::string>> fixtures = {
        {"inc.scn", "material 0 0 0 0.5 0.5 0.5 0 0 0 0 0 0 0 0 0 10 1 0\nsphere 0 0 0 0 1\n"},
        {"m.off", phos::fuzz::fixture_off()},
        {"m.ply", phos::fuzz::fixture_ply()},
        {"m.obj", phos::fuzz::fixture_obj()},
        {"m.mtl", phos::fuzz::fixture_mtl()},
        {"t.pfm", phos::fuzz::fixture_pfm()},
        {"t.bmp", phos::fuzz::fixture_bmp()},
    };
    const std::string path = scratch.prepare(fixtures, phos::fuzz::split_input(data, size), "main.scn");
    // Both material readings and the default-light path.
    const bool raw = size > 0 && (data[size - 1] & 1);
    phos::fuzz::expect_reader_errors([&] {
        phos::io::ScnOptions options;
        options.raw_materials = raw;
        options.no_default_lights = raw;
        phos::io::load_scn(path, options);
    });
    return 0;
}
