// libFuzzer harness for the NanoVDB volume-file reader (io/volume: .nvdb segments, grid
// descriptions, zip / blosc / uncompressed grids, node tables and checksum, read by phos). The input
// is the .nvdb file; the grid asked for is "density". A grid that is returned must be a NanoVDB
// float grid of the size the reader reports. (.vdb files go through OpenVDB 10.0's own reader, whose
// blosc-chunk bug makes absurd allocations on the first truncated file: std::bad_alloc, which phos
// reports as a bad file, but an abort under AddressSanitizer; docs/testing.md.)
#include <nanovdb/NanoVDB.h>

#include "fuzz/fuzz_support.h"
#include "io/volume/volume_grid.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static phos::fuzz::Scratch scratch;
    const std::string path =
        scratch.write("volume.nvdb", std::string(reinterpret_cast<const char*>(data), size));
    phos::fuzz::expect_reader_errors([&] {
        const phos::scene::SparseGrid g = phos::io::read_volume_grid(path, "density");
        if (!g.buffer || g.bytes == 0) phos::fuzz::invariant_failed("an empty grid was returned");
        const auto* grid = static_cast<const nanovdb::FloatGrid*>(g.buffer.get());
        if (!grid->isValid() || grid->gridSize() != g.bytes || grid->gridType() != nanovdb::GridType::Float)
            phos::fuzz::invariant_failed("the grid returned is not the float grid of the size reported");
    });
    return 0;
}
