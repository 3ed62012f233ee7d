// Which closed boundary objects contain a point: the `.scene` format has no medium interfaces,
// so the medium around a nested object, the camera or a light is that of the innermost object
// containing it (or the scene's medium).
#pragma once

#include <vector>

#include "scene/shape.h"

namespace phos::io::scene_format {

// True when `p` lies inside the closed surface `shape` (sphere: distance; mesh: parity of the
// crossings of a ray from p, in world space).
bool contains(const scene::Shape& shape, Vec3 p);

// Among `candidates` (indices into `shapes`, except `skip`), the innermost one containing p (the
// smallest bounding box), or -1.
int innermost_container(const std::vector<scene::Shape>& shapes, const std::vector<int>& candidates, Vec3 p,
                        int skip = -1);

// A point on (or in) the shape, in world space, to test its own containment.
Vec3 reference_point(const scene::Shape& shape);

}  // namespace phos::io::scene_format
