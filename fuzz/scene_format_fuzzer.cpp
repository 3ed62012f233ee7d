// libFuzzer harness for the dissertation's `.scene` / `.mesh` / `.mat` reader (io/scene_format):
// the input is the `.scene` file, optionally followed by "#@file NAME" sections (fuzz_support.h)
// holding `.mesh`, `.mat` or PLY files it names; fixtures (a.mesh, a.mat, t.mat, m.ply, m.off,
// m.obj, t.pfm, t.bmp) are always present.
#include "fuzz/fuzz_support.h"
#include "io/scene_format/scene_format_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static phos::fuzz::Scratch scratch;
    static const std::vector<std::pair<std::string, std::string>> fixtures = {
        {"a.mesh", "ply m.ply\nmaterial a.mat\nscale 2\nrotate 90 0 1 0\ntranslate 0 1 0\n"},
        {"a.mat", "diffuse 0.5 0.5 0.5\n"},
        {"t.mat", "diffuse 1 1 1\ntexture t.pfm\n"},
        {"g.mat", "transmission 1 1 1\nior 1.5\nabsorption 0.1 0.1 0.1\nscattering 0.2 0.2 0.2\nphase 0.3\n"},
        {"m.ply", phos::fuzz::fixture_ply()},
        {"m.off", phos::fuzz::fixture_off()},
        {"m.obj", phos::fuzz::fixture_obj()},
        {"m.mtl", phos::fuzz::fixture_mtl()},
        {"t.pfm", phos::fuzz::fixture_pfm()},
        {"t.bmp", phos::fuzz::fixture_bmp()},
    };
    const std::string path = scratch.prepare(fixtures, phos::fuzz::split_input(data, size), "main.scene");
    phos::fuzz::expect_reader_errors([&] { phos::io::load_scene_format(path); });
    return 0;
}
