// Reading sparse density grids: OpenVDB (.vdb, converted to NanoVDB) and NanoVDB (.nvdb) files.
#pragma once

#include <string>

#include "scene/medium.h"

namespace phos::io {

// Reads the float grid `grid_name` of the volume file `path` (the extension decides: .vdb or .nvdb)
// as one NanoVDB float grid. Throws InputError naming the file when it cannot be opened or read,
// has no grid of that name (the message lists the grids it has) or the grid is not a float grid.
scene::SparseGrid read_volume_grid(const std::string& path, const std::string& grid_name = "density");

}  // namespace phos::io
