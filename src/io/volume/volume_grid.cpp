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
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <type_traits>
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

// The bytes of the file (of `file_bytes`) after the stream's position.
uint64_t bytes_left(std::istream& is, uint64_t file_bytes) {
    return file_bytes - std::min<uint64_t>(file_bytes, uint64_t(is.tellg()));
}

// A segment's header and grid descriptions, read as nanovdb::io::Segment::read does but with every
// size bounded by the file: a grid count, name or grid size the file cannot hold is an error (the
// NanoVDB reader trusts them: a name without its terminating NUL is read past its end).
struct SegmentInfo {
    nanovdb::io::Header header;
    std::vector<nanovdb::io::GridMetaData> meta;
};

bool read_segment(std::istream& is, uint64_t file_bytes, const std::string& path, SegmentInfo& seg) {
    is.read(reinterpret_cast<char*>(&seg.header), sizeof seg.header);
    if (is.gcount() == 0 && is.eof()) return false;  // no further segment
    if (!is) fail(path, "the file is truncated (a segment header)");
    if (seg.header.magic != NANOVDB_MAGIC_NUMBER) fail(path, "not a NanoVDB file (bad magic number)");
    if (seg.header.version.getMajor() != NANOVDB_MAJOR_VERSION_NUMBER)
        fail(path, "NanoVDB file version " + std::to_string(seg.header.version.getMajor()) +
                       " (this phos reads " + std::to_string(NANOVDB_MAJOR_VERSION_NUMBER) + ")");
    seg.meta.clear();
    for (uint32_t i = 0; i < seg.header.gridCount; ++i) {
        nanovdb::io::GridMetaData m;
        is.read(reinterpret_cast<char*>(static_cast<nanovdb::io::MetaData*>(&m)),
                sizeof(nanovdb::io::MetaData));
        if (!is) fail(path, "the file is truncated (a grid description)");
        if (m.nameSize == 0 || m.nameSize > bytes_left(is, file_bytes))
            fail(path, "a grid name's length is not what the file holds");
        std::string name(m.nameSize, '\0');
        is.read(name.data(), std::streamsize(name.size()));
        if (!is) fail(path, "the file is truncated (a grid name)");
        name.resize(std::strlen(name.c_str()));  // up to the first NUL (one is always there now)
        m.gridName = name;
        m.version = seg.header.version;
        // On disk a grid takes fileSize bytes; uncompressed that is its size, compressed at most
        // 1100 times less (zip and blosc cannot compress more than about 1000:1).
        if (m.fileSize > file_bytes ||
            m.gridSize < sizeof(nanovdb::GridData) + sizeof(nanovdb::TreeData<3>) ||
            (seg.header.codec == nanovdb::io::Codec::NONE ? m.gridSize != m.fileSize
                                                          : m.gridSize / 1100 > m.fileSize))
            fail(path, "grid \"" + name + "\" has sizes the file cannot hold");
        seg.meta.push_back(std::move(m));
    }
    return true;
}

// nanovdb::io::Internal::read with every compressed chunk's size bounded by the file (NanoVDB
// allocates whatever size the file claims) and every decompression checked: `residual` bytes of
// grid into `data`.
void read_grid_bytes(std::istream& is, char* data, uint64_t residual, nanovdb::io::Codec codec,
                     uint64_t file_bytes, const std::string& path) {
    const auto chunk_bytes = [&] {
        uint64_t size = 0;
        is.read(reinterpret_cast<char*>(&size), sizeof size);
        if (!is || size == 0 || size > bytes_left(is, file_bytes))
            fail(path, "a compressed block's size is not what the file holds");
        std::vector<char> chunk(size);
        is.read(chunk.data(), std::streamsize(size));
        if (!is) fail(path, "the file is truncated");
        return chunk;
    };
    switch (codec) {
        case nanovdb::io::Codec::NONE:
            is.read(data, std::streamsize(residual));
            if (!is || uint64_t(is.gcount()) != residual) fail(path, "the file is truncated");
            return;
        case nanovdb::io::Codec::ZIP: {
            const std::vector<char> chunk = chunk_bytes();
            uLongf n = uLongf(residual);
            if (uncompress(reinterpret_cast<Bytef*>(data), &n, reinterpret_cast<const Bytef*>(chunk.data()),
                           uLong(chunk.size())) != Z_OK ||
                n != residual)
                fail(path, "its zip-compressed grid does not decompress");
            return;
        }
        case nanovdb::io::Codec::BLOSC: {
#ifdef NANOVDB_USE_BLOSC
            while (residual > 0) {
                const std::vector<char> chunk = chunk_bytes();
                const uint64_t want = std::min<uint64_t>(residual, nanovdb::io::Internal::MAX_SIZE);
                size_t expected = 0, compressed = 0, block = 0;
                blosc_cbuffer_sizes(chunk.data(), &expected, &compressed, &block);
                if (chunk.size() < BLOSC_MIN_HEADER_LENGTH || compressed > chunk.size() || expected != want ||
                    blosc_decompress_ctx(chunk.data(), data, size_t(want), 1) != int(want))
                    fail(path, "its blosc-compressed grid does not decompress");
                data += want;
                residual -= want;
            }
            return;
#else
            fail(path, "its grid is blosc-compressed and this phos was built without blosc");
#endif
        }
        default:
            fail(path, "unknown compression codec " + std::to_string(int(codec)));
    }
}

// The tree's node tables lie inside the grid's `bytes`: checked before anything walks the tree
// (the checksum does).
bool tree_inside(const nanovdb::FloatGrid& grid, uint64_t bytes) {
    using Tree = nanovdb::FloatTree;
    const auto* tree = reinterpret_cast<const nanovdb::TreeData<3>*>(&grid.tree());
    const uint64_t tree_at =
        uint64_t(reinterpret_cast<const char*>(tree) - reinterpret_cast<const char*>(&grid));
    if (tree_at + sizeof(*tree) > bytes) return false;
    const uint64_t room = bytes - tree_at;
    for (const uint64_t at : tree->mNodeOffset)  // nodes are aligned (the tree itself is)
        if (at % NANOVDB_DATA_ALIGNMENT != 0) return false;
    const uint64_t node_bytes[3] = {sizeof(Tree::LeafNodeType), sizeof(Tree::Node1), sizeof(Tree::Node2)};
    for (int level = 0; level < 3; ++level) {
        const uint64_t at = tree->mNodeOffset[level], count = tree->mNodeCount[level];
        // A level with nodes starts after the tree's header (offset 0 means "no nodes" to NanoVDB).
        if (count > 0 && (at < sizeof(*tree) || at > room || count > (room - at) / node_bytes[level]))
            return false;
    }
    using RootData = Tree::RootType::DataType;
    const uint64_t root_at = tree->mNodeOffset[3];
    if (root_at < sizeof(*tree) || root_at > room || room - root_at < sizeof(RootData)) return false;
    const auto* root = reinterpret_cast<const RootData*>(reinterpret_cast<const char*>(tree) + root_at);
    return (room - root_at - sizeof(RootData)) / sizeof(RootData::Tile) >= root->mTableSize;
}

// The tree is a tree: every child (stored as a byte offset from its parent) is the start of a node
// of the level below, inside that level's node table, and every node of a level is the child of
// exactly one parent. So nothing that samples the grid leaves its buffer, and NanoVDB's node
// manager (used by the checksum), which lists nodes by walking from the root into arrays of the
// tables' sizes, stays inside them. (A checksum does not show this: a grid may have none.) Call
// after tree_inside.
bool is_tree(const nanovdb::FloatGrid& grid) {
    using Tree = nanovdb::FloatTree;
    const auto* tree = reinterpret_cast<const nanovdb::TreeData<3>*>(&grid.tree());
    const char* base = reinterpret_cast<const char*>(tree);
    std::vector<bool> seen[3];
    for (int level = 0; level < 3; ++level) seen[level].assign(tree->mNodeCount[level], false);
    // Marks the node at from + offset of `level`'s table (nodes of `size` bytes) as a child; false
    // when it is not one of the table's nodes or already has a parent.
    const auto take = [&](const void* from, int64_t offset, int level, uint64_t size) {
        const int64_t at = int64_t(static_cast<const char*>(from) - base) + offset;
        const int64_t table = int64_t(tree->mNodeOffset[level]);
        if (offset == 0 || at < table) return false;
        const uint64_t rel = uint64_t(at - table);
        if (rel % size != 0 || rel / size >= tree->mNodeCount[level] || seen[level][rel / size]) return false;
        seen[level][rel / size] = true;
        return true;
    };
    using RootData = Tree::RootType::DataType;
    const auto* root = reinterpret_cast<const RootData*>(base + tree->mNodeOffset[3]);
    for (uint32_t i = 0; i < root->mTableSize; ++i) {
        const RootData::Tile* t = root->tile(i);
        if (t->isChild() && !take(root, t->child, 2, sizeof(Tree::Node2))) return false;
    }
    // The children of the internal nodes of `level`.
    const auto take_children = [&](auto* node_type, int level, uint64_t child_size) {
        using Node = std::remove_pointer_t<decltype(node_type)>;
        using Data = typename Node::DataType;
        for (uint64_t k = 0; k < tree->mNodeCount[level]; ++k) {
            const auto* d = reinterpret_cast<const Data*>(base + tree->mNodeOffset[level] + k * sizeof(Node));
            for (auto it = d->mChildMask.beginOn(); it; ++it)
                if (!take(d, d->mTable[*it].child, level - 1, child_size)) return false;
        }
        return true;
    };
    if (!take_children(static_cast<const Tree::Node2*>(nullptr), 2, sizeof(Tree::Node1)) ||
        !take_children(static_cast<const Tree::Node1*>(nullptr), 1, sizeof(Tree::LeafNodeType)))
        return false;
    for (const std::vector<bool>& level : seen)  // every node has its parent
        if (std::find(level.begin(), level.end(), false) != level.end()) return false;
    return true;
}

// nanovdb::io::readGrid without its blind spots: sizes bounded by the file (read_segment,
// read_grid_bytes), a grid cut short by the end of the file is an error, the node tables must lie
// inside the grid and form a tree (is_tree), and the grid's checksum is verified.
scene::SparseGrid read_nvdb(const std::string& path, const std::string& name) {
    try {
        std::ifstream is(path, std::ios::binary);
        if (!is) fail(path, "cannot open it");
        std::error_code ec;
        const uint64_t file_bytes = std::filesystem::file_size(path, ec);
        if (ec) fail(path, "cannot open it");
        std::vector<std::string> names;
        SegmentInfo segment;
        while (read_segment(is, file_bytes, path, segment)) {
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
                read_grid_bytes(is, reinterpret_cast<char*>(handle.data()), m.gridSize, segment.header.codec,
                                file_bytes, path);
                // The grid's own header, read here: GridHandle::grid() follows the header's grid
                // index through the buffer, trusting it.
                const auto* grid = reinterpret_cast<const nanovdb::FloatGrid*>(handle.data());
                if (!grid->isValid() || grid->gridIndex() != 0 || grid->gridCount() == 0 ||
                    grid->gridType() != nanovdb::GridType::Float || grid->gridSize() > m.gridSize ||
                    !tree_inside(*grid, grid->gridSize()) || !is_tree(*grid))
                    fail(path, "grid \"" + name + "\" is not a valid NanoVDB float grid");
                // (NanoVDB's node manager, which the full checksum uses, cannot take a level without
                // nodes: such a grid, e.g. an empty one, has its header checked only.)
                const auto* tree = reinterpret_cast<const nanovdb::TreeData<3>*>(&grid->tree());
                const bool all_levels =
                    tree->mNodeCount[0] > 0 && tree->mNodeCount[1] > 0 && tree->mNodeCount[2] > 0;
                if (!nanovdb::validateChecksum(
                        *grid, all_levels ? nanovdb::ChecksumMode::Full : nanovdb::ChecksumMode::Partial))
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
