// libFuzzer harness for compressed input (io/gzip): the input is a .ply.gz file, decompressed by
// the gzip reader and then read as PLY (the path .pbrt.gz includes and .ply.gz meshes take).
#include "fuzz/fuzz_support.h"
#include "io/mesh/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static phos::fuzz::Scratch scratch;
    const std::string path =
        scratch.write("m.ply.gz", std::string(reinterpret_cast<const char*>(data), size));
    phos::fuzz::expect_reader_errors([&] {
        const phos::scene::TriangleMesh m = phos::io::read_mesh(path).mesh;
        phos::fuzz::check_mesh(m);
    });
    return 0;
}
