// Internal to the `.scene` loader: the reader's state (files being read, for cycles and messages;
// materials and textures shared by path) and the argument checks every command uses.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/text/text_lexer.h"
#include "scene/scene.h"

namespace phos::io::scene_format {

using text::Token;

inline Vec3 vec3_at(const std::vector<double>& v, size_t i) {
    return {float(v[i]), float(v[i + 1]), float(v[i + 2])};
}
inline Rgb rgb_at(const std::vector<double>& v, size_t i) {
    return {float(v[i]), float(v[i + 1]), float(v[i + 2])};
}

// One command: its keyword and its arguments, all on one line.
struct Line {
    Token keyword;
    std::vector<Token> args;
    int end_col = 1;  // just past the last token, for "expected 3 numbers, got 2"
};

// One `.mat` file as the scene uses it: a material, and the medium inside objects made of it.
struct MatFile {
    int material = -1;      // index into scene.materials
    int medium = -1;        // index into scene.media, -1 when the material has no interior medium
    bool boundary = false;  // bounds its interior (transmission, an interior medium or invisible)
    bool textured = false;
    Rgb emission{0.0f};  // radiance: objects made of it are area lights
};

class Reader {
public:
    explicit Reader(scene::Scene& scene) : scene_(scene) {}
    void read_scene(const std::string& path);

private:
    // A file being read: name for messages, directory for relative paths, its lines.
    struct File {
        std::string name;
        std::filesystem::path dir;
        std::filesystem::path canonical;
        std::vector<Line> lines;
        int end_line = 1, end_col = 1;
        std::string named_at;  // "file:line:col" of the argument that named it ("" for the .scene)
    };

    // A file named by an argument, resolved against the directory of the file that names it.
    struct FileArg {
        std::filesystem::path path;
        std::filesystem::path canonical;  // the key of the caches and of the cycle check
        std::string name;                 // as shown in messages
        Token token;
    };

    // --- files and arguments (reader.cpp) ---
    // Reads `f` into lines and makes it the current file (file_argument has checked it).
    void open(const FileArg& f);
    void close() { files_.pop_back(); }
    const File& file() const { return files_.back(); }
    [[noreturn]] void fail(const Token& at, const std::string& message) const;
    [[noreturn]] void fail_at(int line, int col, const std::string& message) const;
    // Where the files being read were named, innermost first (each error's "included from" lines).
    std::vector<std::string> include_chain() const;
    // Adds to an error from a file this one names at `at` (a PLY, a texture) where it was named.
    void add_includers(ParseError& e, const Token& at) const;
    std::string where(const Token& at) const;
    // Exactly `n` finite numbers, named by `names` in messages ("ex ey ez  lx ly lz  ux uy uz  d").
    std::vector<double> numbers(const Line& l, size_t n, const char* names) const;
    // Argument `i` of `l` as a file name, resolved; fails when the file does not exist, is a
    // directory or is already being read (a cycle).
    FileArg file_argument(const Line& l, size_t i, const char* what) const;
    void require_args(const Line& l, size_t n, const char* what) const;
    void require_non_negative(const Line& l, const std::vector<double>& v, size_t first, size_t count) const;
    void reject_duplicate(const Line& l, std::map<std::string, int>& seen) const;

    // --- the three kinds of file ---
    void scene_command(const Line& l);  // scene_file.cpp
    void cmd_camera(const Line& l);
    void cmd_light(const Line& l);
    void cmd_sphere(const Line& l);
    void cmd_medium(const Line& l);
    void read_mesh(const FileArg& f);           // mesh_file.cpp
    const MatFile& read_mat(const FileArg& f);  // mat_file.cpp
    int texture(const FileArg& f);
    void add_object(scene::Shape shape, const MatFile& mat, const Token& at);
    void finish();  // media on every boundary, the camera and the lights

    scene::Scene& scene_;
    std::vector<File> files_;                      // the stack: .scene, .mesh, .mat
    std::map<std::string, MatFile> mats_;          // canonical path -> material
    std::map<std::string, int> textures_;          // canonical path -> scene.textures index
    std::map<std::string, std::string> meshes_;    // canonical .mesh path -> where first used
    std::vector<std::pair<int, int>> boundaries_;  // (shape index, medium inside) of boundary shapes
    int scene_medium_ = -1;
    int emitter_material_ = -1;
    bool camera_seen_ = false;
};

}  // namespace phos::io::scene_format
