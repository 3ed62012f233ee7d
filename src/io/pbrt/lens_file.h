// pbrt-v4's lens description files (Camera "realistic" "lensfile"): the lens elements they list,
// front to rear, read with errors located at the lens file's line and column.
#pragma once

#include <string>
#include <vector>

#include "scene/camera.h"

namespace phos::io::pbrt {

// Parses a lens description: numbers separated by white space, '#' to the end of a line a
// comment, four per element (curvature radius, thickness, index of refraction, aperture diameter;
// lengths in millimetres, a radius of 0 the aperture stop, an index of 0 air), front element first.
// Returns the elements in metres, pbrt-v4's scene unit (aperture radius = diameter / 2). Throws
// ParseError naming `file`, the line and the column of the fault.
std::vector<scene::LensElement> parse_lens_file(const std::string& file, const std::string& text);
// Reads and parses the file at `path`; throws ParseError when it cannot be read.
std::vector<scene::LensElement> read_lens_file(const std::string& path);

}  // namespace phos::io::pbrt
