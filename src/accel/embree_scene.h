// The Embree 3 wrapper: builds a BVH from a scene::Scene (triangle meshes, exact analytic spheres,
// disks, cylinders, cones, boxes, instances) and answers closest-hit and occlusion queries.
#pragma once

#include <cstdint>
#include <memory>

#include "accel/ray.h"
#include "scene/scene.h"

namespace phos::accel {

struct Bounds {
    Vec3 lo{kInf}, hi{-kInf};
    bool empty() const { return lo.x > hi.x; }
    Vec3 center() const { return (lo + hi) * 0.5f; }
    Vec3 extent() const { return hi - lo; }
    void extend(Vec3 p) {
        lo = min(lo, p);
        hi = max(hi, p);
    }
};

class EmbreeScene {
public:
    // Keeps a reference to `scene`, which must outlive this object.
    explicit EmbreeScene(const scene::Scene& scene);
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    // Closest hit in (ray.tmin, ray.tmax); fills `hit` and returns true if there is one.
    bool intersect(const Ray& ray, SurfaceHit& hit) const;
    // True if anything lies in (ray.tmin, ray.tmax).
    bool occluded(const Ray& ray) const;
    // World-space bounds of all geometry.
    Bounds bounds() const;
    const scene::Scene& scene() const { return scene_; }

private:
    struct Impl;
    const scene::Scene& scene_;
    std::unique_ptr<Impl> impl_;
};

}  // namespace phos::accel
