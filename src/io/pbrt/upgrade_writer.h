// `phos upgrade`: a pbrt file (pbrt-v3 or pbrt-v4, with everything it includes) written back as
// one pbrt-v4 file, each directive after the pbrt-v3 rules of upgrade_v3.h, as pbrt-v4's
// `pbrt --upgrade` writes it. Includes and imports are inlined; the files a directive names (meshes,
// images, spectra, grids) are written relative to the output file's folder, so the result renders
// from where it is written. Comments and layout are not kept.
#pragma once

#include <string>

namespace phos::io {

// The pbrt-v4 text of `input` (and its includes) for a file to be written at `output`. Throws
// ParseError on malformed input, as loading it would.
std::string upgrade_pbrt(const std::string& input, const std::string& output);

}  // namespace phos::io
