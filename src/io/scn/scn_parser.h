// Internal to the `.scn` loader: the parser state (open files, group stack, per-file material
// numbering) and the helpers every command uses to read and validate its arguments.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "core/transform.h"
#include "io/scn/scn_loader.h"
#include "io/text/text_lexer.h"
#include "scene/scene.h"

namespace phos::io::scn {

using text::lex;
using text::LexedFile;
using text::NumberKind;
using text::parse_number;
using text::read_file_bytes;
using text::Token;

class Parser {
public:
    Parser(scene::Scene& scene, const ScnOptions& options) : scene_(scene), options_(options) {}

    // Reads the top-level file.
    void parse_top(const std::string& path);

private:
    // One file being read: its tokens and cursor, and its own material numbering.
    struct File {
        std::string name;  // as shown in messages
        std::filesystem::path dir;
        std::filesystem::path canonical;
        LexedFile lexed;
        size_t pos = 0;
        std::vector<int> materials;  // local index -> index into scene.materials
        size_t group_base = 0;       // group depth when this file started
        int id = 0;
    };
    // A `begin` ... `end` block.
    struct Group {
        Transform to_world;  // composed with all enclosing groups
        int material = -1;   // scene.materials index, -1 = the default material
        Token begin;
        int serial = 0;
    };
    // The numeric arguments of one command.
    struct Args {
        std::vector<double> v;
        std::vector<Token> tok;
        float f(size_t i) const { return float(v[i]); }
        Vec3 vec(size_t i) const { return {f(i), f(i + 1), f(i + 2)}; }
        Rgb rgb(size_t i) const { return {f(i), f(i + 1), f(i + 2)}; }
    };

    void parse_file(const std::filesystem::path& path, const std::string& name, const Token* included_by);
    void command(const Token& keyword);

    // --- argument reading (scn_parser.cpp) ---
    [[noreturn]] void fail(const Token& at, const std::string& message) const;
    const Token* next_token();
    // Reads exactly `n` numbers for `cmd`; `names` lists them for the message.
    Args numbers(const Token& cmd, int n, const char* names);
    // Reads a file-name token and resolves it against the current file's directory; the file must
    // exist. `what` names the argument ("mesh file").
    std::filesystem::path file_argument(const Token& cmd, const char* what, Token& token);
    // Material argument i of `a` -> scene.materials index (group default / default material for -1).
    int material(const Args& a, size_t i);
    int default_material();
    int emitter_material();
    void require_non_negative(const Args& a, size_t i, int count, const std::string& what) const;
    void require_positive(const Args& a, size_t i, const std::string& what) const;
    Vec3 direction(const Args& a, size_t i, const std::string& what) const;
    std::string where(const Token& t) const;
    const Transform& to_world() const;

    // --- commands (scn_commands.cpp) ---
    void cmd_camera(const Token& cmd);
    void cmd_material(const Token& cmd);
    void cmd_tri(const Token& cmd);
    void cmd_box(const Token& cmd);
    void cmd_sphere(const Token& cmd);
    void cmd_circle(const Token& cmd);
    void cmd_cylinder_or_cone(const Token& cmd, bool cone);
    void cmd_line(const Token& cmd);
    void cmd_mesh(const Token& cmd);
    void cmd_begin(const Token& cmd);
    void cmd_end(const Token& cmd);
    void cmd_include(const Token& cmd);
    void cmd_background_or_ambient(const Token& cmd, bool background);
    void cmd_dir_light(const Token& cmd);
    void cmd_point_or_spot_light(const Token& cmd, bool spot);
    void cmd_area_light(const Token& cmd);
    void cmd_rect_light(const Token& cmd);
    void attenuation(const Args& a, size_t i, const Token& cmd, scene::Light& light, bool area);
    int add_shape(scene::Shape shape, const Token& cmd);
    int load_texture(const std::filesystem::path& path, const Token& at);

    scene::Scene& scene_;
    ScnOptions options_;
    std::vector<File> files_;  // the include stack; back() is being read
    std::vector<Group> groups_;
    int next_file_id_ = 0;
    int next_group_serial_ = 1;
    int default_material_ = -1;
    int emitter_material_ = -1;
    std::map<std::string, int> texture_cache_;  // canonical path -> scene.textures index
    // Consecutive `tri`s with the same material in the same group and file go into one mesh.
    int merge_shape_ = -1;
    int merge_file_ = -1, merge_material_ = -1, merge_group_ = -1;
    bool camera_seen_ = false;
};

}  // namespace phos::io::scn
