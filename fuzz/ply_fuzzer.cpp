// libFuzzer harness for the PLY mesh reader (io/mesh): the input is the whole PLY file.
#include "fuzz/fuzz_support.h"
#include "io/mesh/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static phos::fuzz::Scratch scratch;
    const std::string path = scratch.write("m.ply", std::string(reinterpret_cast<const char*>(data), size));
    phos::fuzz::expect_reader_errors([&] {
        const phos::scene::TriangleMesh m = phos::io::read_ply(path);
        // What every caller relies on: indices in range, attributes absent or one per vertex.
        for (uint32_t i : m.indices)
            if (i >= m.positions.size()) phos::fuzz::invariant_failed("index out of range");
        if (m.indices.size() % 3 != 0) phos::fuzz::invariant_failed("partial triangle");
        if (!m.normals.empty() && m.normals.size() != m.positions.size())
            phos::fuzz::invariant_failed("normal count");
        if (!m.uvs.empty() && m.uvs.size() != m.positions.size()) phos::fuzz::invariant_failed("uv count");
    });
    return 0;
}
