// The pbrt-v4 writer behind `phos upgrade` (see upgrade_writer.h): a ParserTarget that prints each
// directive it receives (the parser has already applied the pbrt-v3 rules, upgrade_v3.h).
#include "io/pbrt/upgrade_writer.h"

#include <filesystem>
#include <sstream>

#include "core/option_table.h"
#include "io/pbrt/parser.h"
#include "io/pbrt/spectra.h"

namespace phos::io {
namespace pbrt {
namespace {

namespace fs = std::filesystem;

std::string pbrt_string(const std::string& s) {
    std::string q = "\"";
    for (const char c : s) {
        if (c == '"' || c == '\\') q += '\\';
        if (c == '\n') {
            q += "\\n";
            continue;
        }
        q += c;
    }
    return q + "\"";
}

// Numbers as the parser read them (doubles), and the floats it handed over (transforms) as the
// shortest text that reads back to the same float.
std::string num(double v) { return options::format_number(v); }
std::string num(float v) { return options::format_number(double(v), true); }

class UpgradeWriter final : public ParserTarget {
public:
    UpgradeWriter(const std::string& input, const std::string& output)
        : main_dir_(fs::path(input).parent_path()), out_dir_(fs::absolute(fs::path(output)).parent_path()) {}

    std::string text() const { return out_.str(); }

    void identity(const Loc&) override { line("Identity"); }
    void translate(Vec3 d, const Loc&) override { line("Translate " + vec(d)); }
    void scale(Vec3 s, const Loc&) override { line("Scale " + vec(s)); }
    void rotate(float degrees, Vec3 axis, const Loc&) override {
        line("Rotate " + num(degrees) + " " + vec(axis));
    }
    void look_at(Vec3 eye, Vec3 target, Vec3 up, const Loc&) override {
        line("LookAt " + vec(eye) + "  " + vec(target) + "  " + vec(up));
    }
    void transform(const float m[16], const Loc&) override { line("Transform " + matrix(m)); }
    void concat_transform(const float m[16], const Loc&) override { line("ConcatTransform " + matrix(m)); }
    void coordinate_system(const std::string& name, const Loc&) override {
        line("CoordinateSystem " + pbrt_string(name));
    }
    void coord_sys_transform(const std::string& name, const Loc&) override {
        line("CoordSysTransform " + pbrt_string(name));
    }
    void reverse_orientation(const Loc&) override { line("ReverseOrientation"); }

    void camera(const std::string& type, const ParamList& params, const Loc&) override {
        directive("Camera", type, params);
    }
    void film(const std::string& type, const ParamList& params, const Loc&) override {
        directive("Film", type, params, /*output_names=*/true);
    }
    void pixel_filter(const std::string& type, const ParamList& params, const Loc&) override {
        directive("PixelFilter", type, params);
    }
    void sampler(const std::string& type, const ParamList& params, const Loc&) override {
        directive("Sampler", type, params);
    }
    void integrator(const std::string& type, const ParamList& params_in, const Loc&) override {
        ParamList params = params_in;
        const std::optional<Param> iterations = params.take("numiterations");  // pbrt-v3 sppm (upgrade_v3.h)
        directive("Integrator", type, params);
        if (iterations && iterations->type == "integer")  // pbrt-v4's SPPM: the Sampler's pixel samples
            line("# pbrt-v3 sppm \"numiterations\" " + std::to_string(int(iterations->numbers.at(0))) +
                 ": give it as the Sampler's \"pixelsamples\"");
    }
    void accelerator(const std::string& type, const ParamList& params, const Loc&) override {
        directive("Accelerator", type, params);
    }
    void color_space(const std::string& name, const Loc&) override {
        line("ColorSpace " + pbrt_string(name));
    }
    void option(const Param& param, const Loc&) override { line("Option " + param_text(param, false)); }
    void make_named_medium(const std::string& name, const ParamList& params, const Loc&) override {
        directive("MakeNamedMedium", name, params);
    }
    void medium_interface(const std::string& inside, const std::string& outside, const Loc&) override {
        line("MediumInterface " + pbrt_string(inside) + " " + pbrt_string(outside));
    }

    void world_begin(const Loc&) override { line("WorldBegin"); }
    void attribute_begin(const Loc&) override { open_block("AttributeBegin"); }
    void attribute_end(const Loc&) override { close_block("AttributeEnd"); }
    void transform_begin(const Loc&) override { open_block("TransformBegin"); }
    void transform_end(const Loc&) override { close_block("TransformEnd"); }
    void attribute(const std::string& target, const ParamList& params, const Loc&) override {
        directive("Attribute", target, params);
    }
    bool applies_attributes() const override { return false; }  // written as given
    void texture(const std::string& name, const std::string& type, const std::string& cls,
                 const ParamList& params, const Loc&) override {
        line("Texture " + pbrt_string(name) + " " + pbrt_string(type) + " " + pbrt_string(cls) +
             params_text(params, false));
    }
    void material(const std::string& type, const ParamList& params, const Loc&) override {
        directive("Material", type, params);
    }
    void make_named_material(const std::string& name, const ParamList& params, const Loc&) override {
        directive("MakeNamedMaterial", name, params);
    }
    void named_material(const std::string& name, const Loc&) override {
        line("NamedMaterial " + pbrt_string(name));
    }
    void light_source(const std::string& type, const ParamList& params, const Loc&) override {
        directive("LightSource", type, params);
    }
    void area_light_source(const std::string& type, const ParamList& params, const Loc&) override {
        directive("AreaLightSource", type, params);
    }
    void shape(const std::string& type, const ParamList& params, const Loc&) override {
        directive("Shape", type, params);
    }
    void object_begin(const std::string& name, const Loc&) override {
        open_block("ObjectBegin " + pbrt_string(name));
    }
    void object_end(const Loc&) override { close_block("ObjectEnd"); }
    void object_instance(const std::string& name, const Loc&) override {
        line("ObjectInstance " + pbrt_string(name));
    }
    void ignored_directive(const std::string& name, const Loc&) override {
        line("# " + name + " (not kept)");
    }
    void end_of_files(const Loc&) override {}

private:
    std::ostringstream out_;
    fs::path main_dir_, out_dir_;
    int depth_ = 0;

    std::string indent(int extra) const { return std::string(size_t(4 * (depth_ + extra)), ' '); }
    void line(const std::string& s) { out_ << indent(0) << s << "\n"; }
    // A block's first and last lines: what is between them is indented one step more.
    void open_block(const std::string& s) {
        line(s);
        ++depth_;
    }
    void close_block(const std::string& s) {
        depth_ = depth_ > 0 ? depth_ - 1 : 0;
        line(s);
    }
    static std::string vec(Vec3 v) { return num(v.x) + " " + num(v.y) + " " + num(v.z); }
    static std::string matrix(const float m[16]) {
        std::string s = "[";
        for (int i = 0; i < 16; ++i) s += " " + num(m[i]);
        return s + " ]";
    }
    void directive(const std::string& name, const std::string& type, const ParamList& params,
                   bool output_names = false) {
        line(name + " " + pbrt_string(type) + params_text(params, output_names));
    }
    // A file a directive names, as written relative to the output file's folder (the input's rule:
    // relative to the naming file's folder, else the main file's).
    std::string moved_path(const std::string& name, const Loc& loc) const {
        const fs::path p(name);
        if (p.is_absolute()) return name;
        std::error_code ec;
        fs::path found = fs::path(loc.filename()).parent_path() / p;
        if (!fs::exists(found, ec) && fs::exists(main_dir_ / p, ec)) found = main_dir_ / p;
        const fs::path rel = fs::absolute(found, ec).lexically_normal().lexically_relative(out_dir_);
        return rel.empty() ? fs::absolute(found, ec).string() : rel.string();
    }
    std::string params_text(const ParamList& params, bool output_names) const {
        std::string s;
        for (const Param& p : params.all()) s += "\n" + indent(1) + param_text(p, output_names);
        return s;
    }
    std::string param_text(const Param& p, bool output_names) const {
        std::string s = "\"" + p.type + " " + p.name + "\" [";
        for (const double v : p.numbers) s += " " + num(v);
        for (const bool b : p.bools) s += b ? " true" : " false";
        for (const std::string& str : p.strings) {
            // Files named by the scene move with it; an output name (Film "filename") does not,
            // nor does a named spectrum.
            // A realistic camera's "aperture" is a file unless it names one of pbrt-v4's shapes.
            const bool named_stop =
                str == "gaussian" || str == "square" || str == "pentagon" || str == "star";
            const bool file =
                !output_names && ((p.type == "string" && (p.name == "filename" || p.name == "lensfile" ||
                                                          (p.name == "aperture" && !named_stop))) ||
                                  (p.type == "spectrum" && !named_spectrum_rgb(str, SpectrumUse::Albedo)));
            s += " " + pbrt_string(file ? moved_path(str, p.loc) : str);
        }
        return s + " ]";
    }
};

}  // namespace
}  // namespace pbrt

std::string upgrade_pbrt(const std::string& input, const std::string& output) {
    pbrt::UpgradeWriter writer(input, output);
    pbrt::parse_file(input, writer);
    return "# pbrt-v4 form of " + std::filesystem::path(input).filename().string() +
           ", written by phos upgrade\n" + writer.text();
}

}  // namespace phos::io
