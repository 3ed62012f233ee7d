// Photon maps as a point cloud for `phos photons` (io/mesh/point_cloud.h): per photon its
// position, a displayable colour, the stored power, the incident direction, the surface normal and
// the map it belongs to, decoded from the 20-byte records with their own accessors.
#pragma once

#include <string>
#include <vector>

#include "integrators/photon_map.h"
#include "io/mesh/point_cloud.h"

namespace phos::app {

// The name `--maps` and the PLY comments use for map `kind` (photon::MapKind): global, caustic,
// indirect, volume, volume-caustic.
const char* photon_map_label(int kind);

// "global,caustic" -> the map kinds, in the order given, without repeats. Throws InputError naming
// an unknown map.
std::vector<int> parse_photon_maps(const std::string& list);

// The share of a map's photons whose colour is not clipped: each map's colours are its powers
// divided by this percentile of the photons' largest channel.
inline constexpr double kColourPercentile = 0.99;

// The photons of `kinds` (in that order; each map in k-d tree order) as columns x y z (float),
// red green blue (uchar: power / the map's kColourPercentile largest channel, scaled down to keep
// the hue where a channel exceeds 1, sRGB-encoded), power_r power_g power_b (float, W as stored),
// dx dy dz (unit vector towards where the photon came from), nx ny nz (the surface normal; 0 0 0
// for photons without one, in media), map (uchar, the MapKind) and, when the maps hold bounce
// counts (PhotonMaps::bounces), bounces (uchar), with comments saying so.
io::PointCloud photon_cloud(const integrators::PhotonMaps& maps, const std::vector<int>& kinds);

// The columns of the dissertation viewer's text format: position, power, direction.
const std::vector<std::string>& photon_text_columns();

}  // namespace phos::app
