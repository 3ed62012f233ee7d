// Volume grids: .vdb through OpenVDB, converted with nanovdb::openToNanoVDB; .nvdb through
// nanovdb::io. The NanoVDB GridHandle stays alive behind SparseGrid::buffer (aliasing shared_ptr).
#include "io/volume/volume_grid.h"

#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/GridChecksum.h>
#include <nanovdb/util/GridHandle.h>
#include <nanovdb/util/HostBuffer.h>
#include <nanovdb/util/IO.h>
#include <nanovdb/util/OpenToNanoVDB.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <vector>

#include "core/error.h"

namespace phos::io {
namespace {

using Handle = nanovdb::GridHandle<nanovdb::HostBuffer>;

[[noreturn]] void fail(const std::string& path, const std::string& message) {
    throw InputError("volume file '" + path + "': " + message);
}

std::string list(const std::vector<std::string>& names) {
    if (names.empty()) return "it has no grids";
    std::string s = "it has ";
    for (size_t i = 0; i < names.size(); ++i) s += (i ? ", \"" : "\"") + names[i] + "\"";
    return s;
}

std::string type_name(nanovdb::GridType t) {
    const int i = int(t);
    if (i >= 0 && i < int(nanovdb::GridType::End)) return nanovdb::toStr(t);
    return "unknown";
}

// Wraps a handle holding one float grid into a SparseGrid that keeps it alive.
scene::SparseGrid wrap(Handle&& handle, const std::string& path, const std::string& name) {
    const nanovdb::FloatGrid* grid = handle.grid<float>();
    if (!grid) {
        const std::string t =
            handle.gridMetaData() ? type_name(handle.gridMetaData()->gridType()) : "unknown";
        fail(path, "grid \"" + name + "\" is a " + t + " grid, not a float grid");
    }
    if (reinterpret_cast<uintptr_t>(grid) % NANOVDB_DATA_ALIGNMENT != 0)
        fail(path, "grid \"" + name + "\" is not aligned in memory");
    const size_t bytes = size_t(grid->gridSize());
    auto owner = std::make_shared<Handle>(std::move(handle));
    scene::SparseGrid g;
    g.buffer = std::shared_ptr<const void>(owner, static_cast<const void*>(grid));
    g.bytes = bytes;
    g.file = path;
    return g;
}

scene::SparseGrid read_vdb(const std::string& path, const std::string& name) {
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
    openvdb::FloatGrid::Ptr grid;
    try {
        openvdb::io::File file(path);
        file.open(false);  // no delayed loading: read everything now, while the file is ours
        std::vector<std::string> names;
        for (auto it = file.beginName(); it != file.endName(); ++it) names.push_back(it.gridName());
        if (std::find(names.begin(), names.end(), name) == names.end()) {
            file.close();
            fail(path, "no grid named \"" + name + "\" (" + list(names) + ")");
        }
        openvdb::GridBase::Ptr base = file.readGrid(name);
        file.close();
        grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
        if (!grid) fail(path, "grid \"" + name + "\" is a " + base->valueType() + " grid, not a float grid");
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        fail(path, std::string("cannot read it as an OpenVDB file: ") + e.what());
    }
    try {
        Handle handle = nanovdb::openToNanoVDB<nanovdb::HostBuffer>(*grid);
        return wrap(std::move(handle), path, name);
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        fail(path, "cannot convert grid \"" + name + "\" to NanoVDB: " + e.what());
    }
}

// nanovdb::io::readGrid without its blind spot: an uncompressed grid cut short by the end of the
// file is an error here, and the grid's checksum is verified.
scene::SparseGrid read_nvdb(const std::string& path, const std::string& name) {
    try {
        std::ifstream is(path, std::ios::binary);
        if (!is) fail(path, "cannot open it");
        std::vector<std::string> names;
        nanovdb::io::Segment segment;
        while (segment.read(is)) {
            std::streamoff skip = 0;
            for (const auto& m : segment.meta) {
                names.push_back(m.gridName);
                if (m.gridName != name) {
                    skip += std::streamoff(m.fileSize);
                    continue;
                }
                if (m.gridType != nanovdb::GridType::Float)
                    fail(path,
                         "grid \"" + name + "\" is a " + type_name(m.gridType) + " grid, not a float grid");
                is.seekg(skip, std::ios_base::cur);
                Handle handle(nanovdb::HostBuffer::create(m.gridSize));
                if (segment.header.codec == nanovdb::io::Codec::NONE) {
                    is.read(reinterpret_cast<char*>(handle.data()), std::streamsize(m.gridSize));
                    if (!is || uint64_t(is.gcount()) != m.gridSize) fail(path, "the file is truncated");
                } else {
                    nanovdb::io::Internal::read(is, handle, segment.header.codec);
                    if (!is) fail(path, "the file is truncated");
                }
                const nanovdb::FloatGrid* grid = handle.grid<float>();
                if (!grid || grid->gridSize() > m.gridSize)
                    fail(path, "grid \"" + name + "\" is not a valid NanoVDB float grid");
                if (!nanovdb::validateChecksum(*grid, nanovdb::ChecksumMode::Full))
                    fail(path, "grid \"" + name + "\" fails its checksum (the file is corrupt)");
                return wrap(std::move(handle), path, name);
            }
            is.seekg(skip, std::ios_base::cur);
            if (!is) break;
        }
        fail(path, "no grid named \"" + name + "\" (" + list(names) + ")");
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        fail(path, std::string("cannot read it as a NanoVDB file: ") + e.what());
    }
}

}  // namespace

scene::SparseGrid read_volume_grid(const std::string& path, const std::string& grid_name) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (ext != ".vdb" && ext != ".nvdb") fail(path, "unknown extension (expected .vdb or .nvdb)");
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec) || !std::ifstream(path, std::ios::binary).is_open())
        fail(path, "cannot open it");
    return ext == ".vdb" ? read_vdb(path, grid_name) : read_nvdb(path, grid_name);
}

}  // namespace phos::io
