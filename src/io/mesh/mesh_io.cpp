// Mesh-file dispatch: picks the reader from the file extension (case-insensitive; "name.ply.gz" by
// ".ply").
#include "io/mesh/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "core/error.h"

namespace phos::io {

LoadedMesh read_mesh(const std::string& path) {
    const auto lowered_extension = [](const std::filesystem::path& p) {
        std::string e = p.extension().string();
        std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
        return e;
    };
    std::string ext = lowered_extension(path);
    // A compressed mesh (mesh.ply.gz) is read by the reader of the extension before ".gz" (each
    // reader decompresses by the file's gzip magic).
    if (ext == ".gz") ext = lowered_extension(std::filesystem::path(path).stem());
    if (ext == ".off") {
        LoadedMesh m;
        m.mesh = read_off(path);
        return m;
    }
    if (ext == ".ply") {
        LoadedMesh m;
        m.mesh = read_ply(path);
        return m;
    }
    if (ext == ".obj") return read_obj(path);
    throw ParseError(path, 0, 0, "unknown mesh format '" + ext + "' (phos reads .off, .ply and .obj meshes)");
}

}  // namespace phos::io
