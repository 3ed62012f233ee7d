// The per-pixel first radius a pilot pass chooses, shared by SPPM (a pilot photon pass) and vcm (a
// pilot light pass): the disc that holds about k photons or light vertices, within bounds in pixel
// footprints, then bounded at geometric edges. phos's own rule, not in the papers
// (docs/progressive.md, docs/bidirectional.md).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/vec.h"

namespace phos::integrators {

// Bounds of the pilot's per-pixel radius in pixel footprints (the other defaults are in the option
// table, progressive_options.cpp).
constexpr double kPilotRadiusMinPixels = 1, kPilotRadiusMaxPixels = 8;

// Per-pixel initial radius from a pilot photon pass (SPPM, --radius-photons): the first
// iteration's photons only count how many fall in each visible point's largest allowed disc,
// R₀² max_scale (M_p; R₀ the automatic radius); the point's radius becomes the disc that would
// hold ~k photons, R² = R₀² max_scale clamp(k / M_p) within [min_scale, max_scale] R₀² (M_p = 0:
// R₀ kept). Counting in the largest disc keeps a dim point next to a caustic from choosing a disc
// that reaches into it. The pilot's photons are then discarded (N = τ = 0, not counted in
// N_emitted): the radius is independent of the photons the estimate uses, so choosing it adds no
// bias of its own (reusing them, with a radius picked so they number ~k, inflated sparse caustics
// by ~20 %). Bright caustics get small discs (less blur), dim diffuse regions large ones (less
// noise).
struct PilotRadius {
    double k = 0;                         // target photons per disc (0 = no pilot)
    double min_scale = 1, max_scale = 1;  // bounds on R²/R₀²
};

// The radius a point keeps after the pilot: r2 is the pilot's gathering disc (R₀² max_scale) and
// m the photons it held.
inline double pilot_r2(const PilotRadius& a, double r2, uint64_t m) {
    if (m == 0) return r2 / a.max_scale;
    return r2 * std::clamp(a.k / double(m), a.min_scale / a.max_scale, 1.0);
}
// The same for a volume point: a ball holds k photons at R² = R_p² (k / M_p)^(2/3).
inline double pilot_r2_volume(const PilotRadius& a, double r2, uint64_t m) {
    if (m == 0) return r2 / a.max_scale;
    return r2 * std::clamp(std::cbrt((a.k / double(m)) * (a.k / double(m))), a.min_scale / a.max_scale, 1.0);
}

// Edge-aware radii (after the pilot): a disc that reaches across a geometric edge averages
// photons from another surface, or from a strip the edge shadows (a contact, a corner, a light's
// rim), and the kernel's bias concentrates there (on cornell-diffuse the worst 1 % of pixels held
// 29 % of SPPM's error, nearly all of it bias, along such edges). So each surface point's r² is
// bounded by the squared distance to the nearest other point (within its disc) that lies on a
// surface turned more than acos(kEdgeNormalCos) away or off its tangent plane by more than
// kEdgePlaneSlope times the distance, but never below max(kEdgeMinShrink² r², r2_min[i]). The
// radius still shrinks as Hachisuka & Jensen's; only its start differs. Points with r2 <= 0 are
// left alone; n need not be oriented.
constexpr float kEdgeNormalCos = 0.9f, kEdgePlaneSlope = 0.1f;
constexpr double kEdgeMinShrink = 0.5;
void bound_radii_at_edges(const std::vector<Vec3>& p, const std::vector<Vec3>& n, std::vector<double>& r2,
                          const std::vector<double>& r2_min);

}  // namespace phos::integrators
