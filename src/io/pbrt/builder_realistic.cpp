// SceneBuilder: Camera "realistic"'s own parameters as pbrt-v4's RealisticCamera::Create reads them
// (PBR 4th ed., sec. 5.4): the lens file, the aperture stop's diameter and shape, the focus distance.
#include <filesystem>

#include "core/error.h"
#include "io/image/image_io.h"
#include "io/pbrt/builder.h"
#include "io/pbrt/lens_aperture.h"
#include "io/pbrt/lens_file.h"

namespace phos::io::pbrt {

void SceneBuilder::realistic_lens(const ParamList& params, CameraSpec& c, const Loc& loc) const {
    const std::string d = "Camera \"realistic\"";
    const std::string name = params.get_string("lensfile", "");
    if (name.empty()) loc.fail(d + ": needs a \"lensfile\" (pbrt-v4's lens description)");
    const Loc& lens_loc = params.find("lensfile")->loc;
    const std::string path = resolve(name, lens_loc);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        lens_loc.fail(d + ": lens file '" + path + "' not found");
    try {
        c.lens = read_lens_file(path);
    } catch (ParseError& e) {  // at the lens file's own line; also where it is named
        lens_loc.add_to(e);
        throw;
    }
    // The stop's diameter is the scene's, at most the lens file's (pbrt-v4 clamps it with a warning).
    const float diameter = params.get_float("aperturediameter", 1.0f);
    if (!(diameter > 0)) params.find("aperturediameter")->loc.fail(d + ": aperturediameter must be positive");
    for (scene::LensElement& e : c.lens) {
        if (e.curvature_radius != 0) continue;
        const float radius = diameter / 2000;
        if (radius > e.aperture_radius)
            warn(params.has("aperturediameter") ? params.find("aperturediameter")->loc : loc,
                 d + ": aperturediameter " + std::to_string(diameter) +
                     " mm is larger than the lens file's aperture stop, " +
                     std::to_string(e.aperture_radius * 2000) + " mm, which is used");
        else
            e.aperture_radius = radius;
    }
    c.focus_distance = params.get_float("focusdistance", 10.0f);
    if (!(c.focus_distance > 0))
        params.find("focusdistance")->loc.fail(d + ": focusdistance must be positive");
    // The stop's shape: a named diaphragm or an image over the stop's bounding square.
    const std::string aperture = params.get_string("aperture", "");
    if (aperture.empty()) return;
    const Loc& aperture_loc = params.find("aperture")->loc;
    if (std::optional<scene::ApertureImage> named = named_aperture(aperture)) {
        c.aperture = std::move(*named);
        return;
    }
    const std::string image_path = resolve(aperture, aperture_loc);
    if (!std::filesystem::is_regular_file(image_path, ec))
        aperture_loc.fail(
            d + ": aperture '" + aperture +
            "' is neither \"gaussian\", \"square\", \"pentagon\" nor \"star\" nor an image file");
    Image image;
    try {
        image = read_image(image_path);
    } catch (const std::exception& e) {
        aperture_loc.fail(d + ": aperture image '" + image_path + "': " + e.what());
    }
    std::optional<scene::ApertureImage> shaped = aperture_from_image(image);
    if (!shaped) aperture_loc.fail(d + ": aperture image '" + image_path + "' is black: it passes no light");
    c.aperture = std::move(*shaped);
}

}  // namespace phos::io::pbrt
