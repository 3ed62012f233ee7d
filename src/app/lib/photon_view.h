// What `phos photons --view` shows: the photon point cloud (photon_cloud.h) and the scene's
// geometry as line segments, turned into the viewer's neutral input (display/photon_viewer.h), with
// the text a picked photon prints.
#pragma once

#include <string>
#include <vector>

#include "display/photon_viewer.h"
#include "io/mesh/point_cloud.h"
#include "scene/scene.h"

namespace phos::app {

// The scene's shapes as line segments in world space (2 vertices each): mesh triangle edges,
// three great circles per sphere, box edges, disk rims, cylinder and cone outlines; instanced
// objects placed.
std::vector<Vec3> scene_lines(const scene::Scene& scene);

// The viewer's input from the cloud's columns (x y z, red green blue, map; the record printed on
// picking lists every column) and the scene's lines; `map_names` names the map ids.
display::ViewerScene viewer_scene(const io::PointCloud& cloud, const scene::Scene& scene,
                                  const std::vector<std::string>& map_names);

}  // namespace phos::app
