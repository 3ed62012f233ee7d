// The ParserTarget that turns pbrt directives into a scene::Scene: graphics state and its stack,
// transforms and named coordinate systems, named materials/textures/media, object instancing.
// Implemented in builder.cpp (state, camera, options), builder_shapes.cpp, builder_materials.cpp
// (materials and textures) and builder_lights.cpp (lights and media).
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/transform.h"
#include "io/pbrt/parser.h"
#include "io/pbrt/pbrt_loader.h"
#include "io/pbrt/spectra.h"
#include "scene/scene.h"

namespace phos::io::pbrt {

class SceneBuilder : public ParserTarget {
public:
    SceneBuilder(const PbrtOptions& options, const std::string& main_file);

    // The finished scene (call after parse_file).
    scene::Scene take_scene() { return std::move(scene_); }

    void identity(const Loc& loc) override;
    void translate(Vec3 d, const Loc& loc) override;
    void scale(Vec3 s, const Loc& loc) override;
    void rotate(float degrees, Vec3 axis, const Loc& loc) override;
    void look_at(Vec3 eye, Vec3 target, Vec3 up, const Loc& loc) override;
    void transform(const float m[16], const Loc& loc) override;
    void concat_transform(const float m[16], const Loc& loc) override;
    void coordinate_system(const std::string& name, const Loc& loc) override;
    void coord_sys_transform(const std::string& name, const Loc& loc) override;
    void reverse_orientation(const Loc& loc) override;

    void camera(const std::string& type, const ParamList& params, const Loc& loc) override;
    void film(const std::string& type, const ParamList& params, const Loc& loc) override;
    void pixel_filter(const std::string& type, const ParamList& params, const Loc& loc) override;
    void sampler(const std::string& type, const ParamList& params, const Loc& loc) override;
    void integrator(const std::string& type, const ParamList& params, const Loc& loc) override;
    void accelerator(const std::string& type, const ParamList& params, const Loc& loc) override;
    void color_space(const std::string& name, const Loc& loc) override;
    void option(const Param& param, const Loc& loc) override;
    void make_named_medium(const std::string& name, const ParamList& params, const Loc& loc) override;
    void medium_interface(const std::string& inside, const std::string& outside, const Loc& loc) override;

    void world_begin(const Loc& loc) override;
    void attribute_begin(const Loc& loc) override;
    void attribute_end(const Loc& loc) override;
    void transform_begin(const Loc& loc) override;
    void transform_end(const Loc& loc) override;
    void attribute(const std::string& target, const ParamList& params, const Loc& loc) override;
    void texture(const std::string& name, const std::string& type, const std::string& tex_class,
                 const ParamList& params, const Loc& loc) override;
    void material(const std::string& type, const ParamList& params, const Loc& loc) override;
    void make_named_material(const std::string& name, const ParamList& params, const Loc& loc) override;
    void named_material(const std::string& name, const Loc& loc) override;
    void light_source(const std::string& type, const ParamList& params, const Loc& loc) override;
    void area_light_source(const std::string& type, const ParamList& params, const Loc& loc) override;
    void shape(const std::string& type, const ParamList& params, const Loc& loc) override;
    void object_begin(const std::string& name, const Loc& loc) override;
    void object_end(const Loc& loc) override;
    void object_instance(const std::string& name, const Loc& loc) override;
    void ignored_directive(const std::string& name, const Loc& loc) override;
    void end_of_files(const Loc& loc) override;

private:
    struct AreaLight {
        Rgb L{1.0f};
        std::optional<spectrum::Distribution> spectrum;  // L's spectrum when the file gives one
        bool two_sided = false;
        float power = -1;  // > 0: rescale L so the shape emits this flux
        // "filename": the radiance image (scene texture index, -1: none), its mean colour and
        // mean luminance (pbrt-v4 normalises "power" by the latter).
        int texture = -1;
        Rgb image_mean{1.0f};
        float image_luminance = 1;
        Loc loc;
    };
    struct GraphicsState {
        Transform ctm;
        bool reverse_orientation = false;
        int material = -1;  // index into scene_.materials; -1: pbrt's default (diffuse 0.5)
        std::optional<AreaLight> area_light;
        int inside = -1, outside = -1;     // media
        bool media_declared = false;       // a MediumInterface statement set them
        std::string color_space = "srgb";  // ColorSpace: how "rgb" values are read
    };
    struct StackEntry {
        GraphicsState state;
        Loc loc;
        bool transform_only = false;  // TransformBegin saves only the transform
    };
    struct CameraSpec {
        std::string type;
        Transform camera_to_world;
        float fov_deg = 90, lens_radius = 0, focal_distance = 1e6f;
        std::optional<std::vector<float>> screen_window;
        float exposure_time = 1;       // shutterclose - shutteropen
        bool equirectangular = false;  // spherical: the mapping (else equal-area)
        // realistic: the lens elements (metres, the stop narrowed to "aperturediameter") and
        // "focusdistance"
        std::vector<scene::LensElement> lens;
        float focus_distance = 10;
        scene::ApertureImage aperture;  // realistic: the stop's shape (empty: a circle)
        int medium = -1;
        Loc loc;
    };

    // Helpers shared by the builder files.
    void warn(const Loc& loc, const std::string& message) const;
    void warn_once(const std::string& key, const Loc& loc, const std::string& message) const;
    void done(const ParamList& params, const std::string& directive) const {
        params.report_unused(directive, options_.strict);
    }
    void require_world(bool world, const std::string& directive, const Loc& loc) const;
    std::string resolve(const std::string& filename, const Loc& loc) const;
    int current_material();
    void set_ctm(const Transform& t, const Loc& loc);
    // Camera "realistic": its lens file, aperture and focus into `c` (builder_realistic.cpp).
    void realistic_lens(const ParamList& params, CameraSpec& c, const Loc& loc) const;

    // Colours: an "rgb", "spectrum" or "blackbody" (or "float", as grey) parameter, or nullopt.
    // With `spectrum_out`, also the spectrum whose sRGB the colour is, for a blackbody, a named
    // illuminant (use Illuminant), a named metal or glass (other uses), an inline list or a file;
    // nullopt for RGB and float values.
    std::optional<Rgb> color(const ParamList& params, const std::string& name, SpectrumUse use,
                             std::optional<spectrum::Distribution>* spectrum_out = nullptr) const;
    // A colour that may instead name a texture ("texture reflectance" "wood"); sets *tex (or -1).
    Rgb color_or_texture(const ParamList& params, const std::string& name, Rgb def, int* tex, SpectrumUse use,
                         const std::string& directive);
    // A float that pbrt allows to be a texture; a texture is warned about and `def` used.
    float float_param(const ParamList& params, const std::string& name, float def,
                      const std::string& directive);
    int constant_texture(Rgb value);

    scene::Material make_material(const std::string& type, const ParamList& params, const Loc& loc,
                                  const std::string& directive);
    // A material's "displacement" and "normalmap" (pbrt-v4's bump and normal maps) into `m`;
    // located errors for an unknown texture or an unreadable image.
    void read_shading_detail(const ParamList& params, scene::Material& m, const std::string& directive);
    // pbrt-v4's "subsurface" material (builder_subsurface.cpp): its dielectric boundary into `m`
    // (eta and transmission; the caller reads the roughness) and a homogeneous medium for the
    // inside of its shapes, from a named measured medium, sigma_a/sigma_s or reflectance/mfp.
    void subsurface_material(const ParamList& params, scene::Material& m, const Loc& loc,
                             const std::string& directive);
    // A shape whose material is (or mixes in) a subsurface material encloses that material's medium.
    void subsurface_interior(scene::Shape& shape, const Loc& loc);
    void add_shape(scene::Shape shape, float area, const Loc& loc);
    // Applies a plymesh's "displacement" (the parameter `dp`) to its object-space mesh.
    void displace(scene::TriangleMesh& mesh, const ParamList& params, const Param& dp, const std::string& d);

    PbrtOptions options_;
    std::string main_dir_;
    scene::Scene scene_;
    GraphicsState gs_;
    std::vector<StackEntry> stack_;
    std::map<std::string, Transform> coord_systems_;
    std::map<std::string, int> named_materials_, float_textures_, spectrum_textures_, media_, objects_;
    // `measured` materials' files, read once per path.
    std::map<std::string, std::shared_ptr<const scene::MeasuredBsdf>> measured_files_;
    std::optional<CameraSpec> camera_;
    // pbrt-v3 SPPM's "numiterations" (0: not given): the iterations, whatever the Sampler says.
    int sppm_iterations_ = 0;
    bool filter_given_ = false;          // a PixelFilter directive was read (else pbrt-v4's Gaussian)
    float displacement_edge_scale_ = 1;  // Option "displacementedgescale"
    // The first light directive that could not be used: if no light could, the scene is refused
    // there (its image would be black) rather than rendered.
    std::optional<Loc> skipped_light_;
    float film_iso_ = 100;         // Film "iso": with the camera's exposure time, scene_.film_response
    float film_diagonal_mm_ = 35;  // Film "diagonal": the realistic camera's sensor size
    bool world_ = false;
    Loc world_loc_;
    int object_ = -1;  // index into scene_.objects while between ObjectBegin and ObjectEnd
    Loc object_loc_;
    int default_material_ = -1;
};

}  // namespace phos::io::pbrt
