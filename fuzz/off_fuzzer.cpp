// libFuzzer harness for the OFF mesh reader (io/mesh): the input is the whole OFF file.
#include "fuzz/fuzz_support.h"
#include "io/mesh/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static phos::fuzz::Scratch scratch;
    const std::string path = scratch.write("m.off", std::string(reinterpret_cast<const char*>(data), size));
    phos::fuzz::expect_reader_errors([&] {
        const phos::scene::TriangleMesh m = phos::io::read_off(path);
        phos::fuzz::check_mesh(m);
    });
    return 0;
}
