// Wavefront OBJ reader (through tinyobjloader) and writer. Polygons are triangulated; OBJ's separate
// position/normal/uv indices are merged into the single index per vertex that TriangleMesh uses.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <sstream>
#include <tuple>

#include "core/error.h"
#include "core/log.h"
#include "io/gzip/gzip_file.h"
#include "io/mesh/mesh_io.h"

namespace phos::io {
namespace {

// tinyobjloader reports problems as free text, sometimes with "line N" in it; recover that number
// so the ParseError points at the offending line.
int line_in_message(const std::string& msg) {
    static const std::regex re(R"(line:?\s*(\d+))");
    std::smatch m;
    if (std::regex_search(msg, m, re)) return std::stoi(m[1].str());
    return 0;
}

// tinyobjloader 2.0 (Debian 12) converts the joint ids of its `vw` (skin weight) extension lines to
// int unchecked: undefined behaviour for a value such as 1e38. phos does not use skin weights, so
// those lines are blanked before parsing, their line breaks kept (\n, \r\n or \r, as tinyobjloader
// splits lines) so that line numbers in messages stay right.
std::string without_skin_weights(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (size_t i = 0; i < text.size();) {
        const size_t end = std::min(text.find_first_of("\r\n", i), text.size());
        size_t k = i;
        while (k < end && (text[k] == ' ' || text[k] == '\t')) ++k;
        const bool vw = end - k >= 3 && text[k] == 'v' && text[k + 1] == 'w' &&
                        (text[k + 2] == ' ' || text[k + 2] == '\t');
        if (!vw) out.append(text, i, end - i);
        if (end < text.size()) out.push_back(text[end]);
        i = end + 1;
    }
    return out;
}

std::string trim(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
    return s;
}

}  // namespace

LoadedMesh read_obj(const std::string& path) {
    std::string bytes;
    if (!read_maybe_gzip(path, bytes)) throw ParseError(path, 0, 0, "cannot open OBJ file");
    std::istringstream text(without_skin_weights(std::move(bytes)));
    // Material libraries are looked up beside the OBJ file, as tinyobjloader's own file loader does.
    const size_t slash = path.find_last_of('/');
    tinyobj::MaterialFileReader material_reader(slash == std::string::npos ? "" : path.substr(0, slash + 1));
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warning, error;
    const bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warning, &error, &text, &material_reader,
                                     /*triangulate=*/true, /*default_vcols_fallback=*/false);
    // Warnings come one per line; report each. tinyobjloader calls an out-of-range face index a
    // warning, but the face is unusable, so that one is an error here.
    std::istringstream warnings(warning);
    for (std::string w; std::getline(warnings, w);) {
        w = trim(w);
        if (w.empty()) continue;
        if (w.find("out of bounds") != std::string::npos) throw ParseError(path, line_in_message(w), 0, w);
        log::warn(path + ": " + w);
    }
    if (!ok || !error.empty()) {
        const std::string msg = trim(error);
        throw ParseError(path, line_in_message(msg), 0, msg.empty() ? "malformed OBJ file" : msg);
    }

    LoadedMesh out;
    for (const tinyobj::material_t& m : materials) out.material_names.push_back(m.name);

    // A single-index mesh can only carry normals/uvs if every corner has them.
    bool all_normals = true, all_uvs = true;
    size_t corners = 0;
    for (const tinyobj::shape_t& s : shapes)
        for (const tinyobj::index_t& i : s.mesh.indices) {
            all_normals &= i.normal_index >= 0;
            all_uvs &= i.texcoord_index >= 0;
            ++corners;
        }
    if (corners == 0) throw ParseError(path, 0, 0, "OBJ file has no faces");
    if (!all_normals && !attrib.normals.empty())
        log::warn(path + ": some faces have no normals; all vertex normals ignored");
    if (!all_uvs && !attrib.texcoords.empty())
        log::warn(path + ": some faces have no texture coordinates; all uvs ignored");

    std::map<std::tuple<int, int, int>, uint32_t> remap;
    scene::TriangleMesh& mesh = out.mesh;
    const size_t nv = attrib.vertices.size() / 3, nn = attrib.normals.size() / 3,
                 nt = attrib.texcoords.size() / 2;
    bool any_material = false;
    for (const tinyobj::shape_t& s : shapes) {
        const auto& idx = s.mesh.indices;
        for (size_t f = 0; f < s.mesh.num_face_vertices.size(); ++f) {
            if (s.mesh.num_face_vertices[f] != 3)
                throw ParseError(path, 0, 0, "face could not be triangulated in shape '" + s.name + "'");
            for (int k = 0; k < 3; ++k) {
                const tinyobj::index_t& i = idx[3 * f + size_t(k)];
                const int vn = all_normals ? i.normal_index : -1;
                const int vt = all_uvs ? i.texcoord_index : -1;
                if (i.vertex_index < 0 || size_t(i.vertex_index) >= nv || (vn >= 0 && size_t(vn) >= nn) ||
                    (vt >= 0 && size_t(vt) >= nt))
                    throw ParseError(path, 0, 0, "index out of range in shape '" + s.name + "'");
                const auto key = std::make_tuple(i.vertex_index, vn, vt);
                auto [it, inserted] = remap.try_emplace(key, uint32_t(mesh.positions.size()));
                if (inserted) {
                    const size_t v = size_t(i.vertex_index);
                    mesh.positions.push_back(
                        {attrib.vertices[3 * v], attrib.vertices[3 * v + 1], attrib.vertices[3 * v + 2]});
                    if (all_normals)
                        mesh.normals.push_back({attrib.normals[3 * size_t(vn)],
                                                attrib.normals[3 * size_t(vn) + 1],
                                                attrib.normals[3 * size_t(vn) + 2]});
                    if (all_uvs)
                        mesh.uvs.push_back(
                            {attrib.texcoords[2 * size_t(vt)], attrib.texcoords[2 * size_t(vt) + 1]});
                }
                mesh.indices.push_back(it->second);
            }
            int m = f < s.mesh.material_ids.size() ? s.mesh.material_ids[f] : -1;
            if (m >= int(out.material_names.size())) m = -1;
            any_material |= m >= 0;
            out.triangle_materials.push_back(m);
        }
    }
    if (!any_material) out.triangle_materials.clear();
    // The PLY and OFF readers reject non-finite numbers as they read them; tinyobjloader does not.
    for (const Vec3& p : mesh.positions)
        if (!is_finite(p)) throw ParseError(path, 0, 0, "a vertex position is not finite");
    return out;
}

}  // namespace phos::io
