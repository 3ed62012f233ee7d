// Writes the volume target's seeds (fuzz/volume_fuzzer.cpp) into DIR: a small fog volume named
// "density" as zip- and blosc-compressed .nvdb files (uncompressed, a NanoVDB grid is over 300 kB:
// beyond -max_len), and one holding only another grid. Binary files are made here rather than kept
// in the repository. Usage: volume_seeds DIR (called by scripts/fuzz.sh).
#include <nanovdb/util/IO.h>
#include <nanovdb/util/OpenToNanoVDB.h>
#include <openvdb/openvdb.h>

#include <cstdio>
#include <filesystem>
#include <string>

namespace {

// Writes `grid` as `dir/name` with `codec` (skipped, said, for a codec this NanoVDB lacks).
void seed(const std::string& dir, const std::string& name, const openvdb::FloatGrid& grid,
          nanovdb::io::Codec codec) {
    try {
        nanovdb::io::writeGrid(dir + "/" + name, nanovdb::openToNanoVDB(grid), codec);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "volume_seeds: %s: %s\n", name.c_str(), e.what());
    }
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: volume_seeds DIR\n");
        return 2;
    }
    const std::string dir = argv[1];
    std::filesystem::create_directories(dir);
    openvdb::initialize();
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setName("density");
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(0.25));
    auto acc = grid->getAccessor();
    for (int z = 0; z < 3; ++z)
        for (int y = 0; y < 3; ++y)
            for (int x = 0; x < 3; ++x) acc.setValue(openvdb::Coord(x, y, z), 0.5f + float(x + y + z));
    seed(dir, "fog-zip.nvdb", *grid, nanovdb::io::Codec::ZIP);
    seed(dir, "fog-blosc.nvdb", *grid, nanovdb::io::Codec::BLOSC);
    auto other = grid->deepCopy();
    other->setName("temperature");
    seed(dir, "other-grid.nvdb", *other, nanovdb::io::Codec::ZIP);
    return 0;
}
