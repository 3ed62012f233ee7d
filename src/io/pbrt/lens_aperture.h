// The shapes of a realistic camera's aperture stop (Camera "realistic" "aperture"): pbrt-v4's named
// diaphragms and images, as the transmission images scene::ApertureImage holds.
#pragma once

#include <optional>
#include <string>

#include "core/image.h"
#include "scene/camera.h"

namespace phos::io::pbrt {

// pbrt-v4's built-in diaphragms at 256 x 256: "gaussian" (exp(-r^2) - exp(-1) inside the unit
// circle), "square" (the middle half of each side), "pentagon" (a regular pentagon of radius 0.8)
// and "star" (a five-pointed star of outer radius 1), rasterised by winding number; nullopt for
// any other name.
std::optional<scene::ApertureImage> named_aperture(const std::string& name);
// An image's mean of R, G and B as the aperture, its top row along the stop's +y; nullopt when it
// is black everywhere (it would pass no light).
std::optional<scene::ApertureImage> aperture_from_image(const Image& image);

}  // namespace phos::io::pbrt
