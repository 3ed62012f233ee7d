// `.mesh` files: the PLY geometry, its material and its transforms, applied in the order written
// after the PLY's own coordinates.
#include <algorithm>
#include <cctype>
#include <optional>

#include "core/error.h"
#include "core/log.h"
#include "core/spelling.h"
#include "core/transform.h"
#include "io/mesh/mesh_io.h"
#include "io/scene_format/reader.h"

namespace phos::io::scene_format {

namespace {
const std::vector<std::string> kMeshKeys = {"ply", "material", "translate", "scale", "rotate"};
}  // namespace

void Reader::read_mesh(const FileArg& f) {
    const auto [first_use, fresh] = meshes_.emplace(f.canonical.string(), where(f.token));
    if (!fresh)
        log::warn(where(f.token) + ": '" + f.token.text + "' is already placed (" + first_use->second +
                  "): its geometry is added twice at the same place");
    open(f);
    std::map<std::string, int> seen;
    std::optional<FileArg> ply;
    const MatFile* mat = nullptr;
    Token mat_token;
    Transform to_world;  // the transforms so far, the latest applied last
    for (const Line& l : file().lines) {
        const std::string& k = l.keyword.text;
        if (k == "ply") {
            reject_duplicate(l, seen);
            require_args(l, 1, "1 argument: file.ply");
            ply = file_argument(l, 0, "PLY file");
        } else if (k == "material") {
            reject_duplicate(l, seen);
            require_args(l, 1, "1 argument: file.mat");
            mat = &read_mat(file_argument(l, 0, "material file"));
            mat_token = l.args[0];
        } else if (k == "translate") {
            to_world = Transform::translate(vec3_at(numbers(l, 3, "x y z"), 0)) * to_world;
        } else if (k == "scale") {
            std::vector<double> v;
            if (l.args.size() == 1) {
                v = numbers(l, 1, "s");
                v = {v[0], v[0], v[0]};
            } else {
                v = numbers(l, 3, "sx sy sz");
            }
            for (size_t i = 0; i < l.args.size(); ++i)
                if (v[i] == 0) fail(l.args[i], "scale: a zero scale flattens the mesh");
            to_world = Transform::scale(vec3_at(v, 0)) * to_world;
        } else if (k == "rotate") {
            const std::vector<double> v = numbers(l, 4, "angle_degrees ax ay az");
            if (!(length(vec3_at(v, 1)) > 0)) fail(l.args[1], "rotate: the axis is zero");
            to_world = Transform::rotate(float(v[0]), vec3_at(v, 1)) * to_world;
        } else {
            const std::string guess = nearest_name(k, kMeshKeys);
            fail(l.keyword, "unknown key '" + k + "' in a .mesh file" +
                                (guess.empty() ? "" : "; did you mean '" + guess + "'?") +
                                " (keys: ply, material, translate, scale, rotate)");
        }
    }
    if (!ply) fail_at(file().end_line, file().end_col, "the mesh names no geometry: add 'ply file.ply'");
    if (!mat) fail_at(file().end_line, file().end_col, "the mesh names no material: add 'material file.mat'");

    std::string ext = ply->path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (ext != ".ply" && ext != ".obj" && ext != ".off")
        fail(ply->token, "ply: unknown mesh format '" + ext + "' (phos reads .ply, and also .obj and .off)");
    LoadedMesh loaded;
    try {
        loaded = io::read_mesh(ply->path.string());  // a ParseError names the PLY file's own line
    } catch (ParseError& e) {
        add_includers(e, ply->token);
        throw;
    } catch (const std::exception& e) {  // InputError, or a reader library's own exception
        fail(ply->token, "ply: cannot read '" + ply->token.text + "': " + e.what());
    }
    // The mesh readers have checked the indices and positions, at the mesh file's own lines.
    scene::TriangleMesh& m = loaded.mesh;
    if (mat->textured && m.uvs.size() != m.positions.size())
        fail(ply->token, "ply: '" + ply->token.text +
                             "' has no texture coordinates (vertex properties u v or s t), "
                             "but its material '" +
                             mat_token.text + "' has a texture");
    if (m.triangle_count() == 0) {
        log::warn(where(ply->token) + ": '" + ply->token.text + "' has no triangles; the mesh is skipped");
        close();
        return;
    }
    scene::Shape s;
    s.kind = scene::Shape::Kind::Mesh;
    s.mesh = std::move(m);
    s.to_world = to_world;
    close();
    // Messages about the object name the .scene line that placed it.
    add_object(std::move(s), *mat, f.token);
}

}  // namespace phos::io::scene_format
