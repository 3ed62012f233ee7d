// libFuzzer harness for the OBJ mesh reader (io/mesh, through tinyobjloader): the input is the OBJ
// file, optionally followed by "#@file NAME" sections (fuzz_support.h), e.g. the `.mtl` file its
// `mtllib` names; the fixture m.mtl is always present.
#include "fuzz/fuzz_support.h"
#include "io/mesh/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static phos::fuzz::Scratch scratch;
    static const std::vector<std::pair<std::string, std::string>> fixtures = {
        {"m.mtl", phos::fuzz::fixture_mtl()}};
    const std::string path = scratch.prepare(fixtures, phos::fuzz::split_input(data, size), "main.obj");
    phos::fuzz::expect_reader_errors([&] {
        const phos::io::LoadedMesh l = phos::io::read_obj(path);
        const phos::scene::TriangleMesh& m = l.mesh;
        phos::fuzz::check_mesh(m);
        if (!l.triangle_materials.empty() && l.triangle_materials.size() != m.triangle_count())
            phos::fuzz::invariant_failed("material count");
        for (int k : l.triangle_materials)
            if (k < -1 || k >= int(l.material_names.size())) phos::fuzz::invariant_failed("material index");
    });
    return 0;
}
