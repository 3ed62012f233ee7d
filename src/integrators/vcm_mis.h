// Multiple importance sampling of bidirectional path tracing and vertex connection and merging,
// computed recursively along each subpath: Georgiev, Křivánek, Davidovič & Slusallek 2012, "Light
// transport simulation with vertex connection and merging", and Georgiev's technical report
// "Implementing vertex connection and merging" (2012), whose quantities dVCM, dVC, dVM these are.
// "[tr (n)]" below is the report's equation n, numbered as SmallVCM (Davidovič's implementation
// with the report) cites it. Every weight of a full path x_0 ... x_k is 1 / sum_j (p_j / p_current)^2
// (the power heuristic) over the strategies j that can make it; the ratios factor into what each
// subpath accumulated so far, so every strategy's weight costs O(1): the weight is
// 1 / (w_light + 1 + w_camera), each side's partial sum from its own subpath [tr (37)].
//
// Notation: pdfs are solid-angle densities of the BSDF (or phase function, or light emission) in
// the direction travelled (dir) and in the opposite one (rev); cos is |cos| with the shading normal
// (1 at a vertex in a medium); eta = pi r^2 N_light (the merging kernel's area times the light
// paths of an iteration: eta_VCM of [tr (20)] with n_VC = 1, n_VM = N_light). With the light
// paths' count equal to the camera samples' (one light path per pixel sample) the camera terms need
// no further factor. Per subpath, after vertex i:
//   start on a light:  dVCM = p_direct_A / p_emit,  dVC = cos_light / p_emit,  dVM = dVC / eta
//                      [tr (31)-(33)]; dVC = dVM = 0 for a delta light [tr (48)-(50)]
//   start at camera:   dVCM = 1 / p_camera_dir,     dVC = dVM = 0            [tr (31)-(33)]
//   arrive at i:       dVCM *= d^2 (not on the first segment from a light at infinity, whose start
//                      is a direction: tr sec. 5.1); dVCM, dVC, dVM /= cos_i
//                      (completing [tr (31)-(33)] or [tr (34)-(36)])
//   scatter at i (non-delta, sampled with pdf_dir, reverse pdf_rev, outgoing cos_o; [tr (34)-(36)]):
//                      dVC  = cos_o / pdf_dir * (dVC pdf_rev + dVCM + eta_i)
//                      dVM  = cos_o / pdf_dir * (dVM pdf_rev + dVCM / eta + m_i)
//                      dVCM = 1 / pdf_dir
//   scatter at i (delta): dVCM = 0, dVC *= cos_o, dVM *= cos_o                     [tr (53)-(55)]
// where eta_i = eta and m_i = 1 when merging is possible at vertex i (a surface with a non-delta
// BSDF, merging enabled), else 0: merging at i is then not a strategy and drops out of every sum.
// Each (p)^2-style factor below is mis(p) = p^2; terms that switch a technique off use factor 0.
//
// vcm does not merge at the vertex next to the light (direct light is left to light sampling, the
// emitter hit and light tracing, as SPPM leaves it to light sampling): on the light side that
// vertex is y1 (not mergeable), on the camera side it is the last vertex before an emitter hit,
// whose merging term dVC_last (the eta_i term of the last scatter, carried like dVC) the emitter
// hit's weight leaves out, and the vertex that samples a light (direct_light_weight, mergeable
// false).
#pragma once

namespace phos::integrators::vcm {

// The power heuristic's exponent 2 (Veach 1997, sec. 9.2.4) applied to a pdf ratio.
inline float mis(float x) { return x * x; }

// Which strategies take part, as the recursion's two constant factors: eta_VCM [tr (20)] and its
// inverse, squared by the power heuristic.
struct MisFactors {
    float vm = 0;  // mis(eta) when merging is used, else 0
    float vc = 0;  // mis(1 / eta) when connections are used, else 0
    static MisFactors of(bool connect, bool merge, float eta) {
        return {merge ? mis(eta) : 0.0f, connect && eta > 0 ? mis(1 / eta) : 0.0f};
    }
};

struct SubpathMis {
    float dVCM = 0, dVC = 0, dVM = 0;
    float dVC_last = 0;  // the part of dVC that is merging at the last scattering vertex
};

// The density MIS gives direct light sampling of a light point (the subpath's start, the emitter
// hit, the light sample): its emission position density pdf_pos (area measure; 1 for point and
// spot lights) for lights in the scene, its direction density pdf_dir (solid angle) for lights at
// infinity, times the light's selection probability pmf. Whatever density sample_Li really drew the
// point with, the same convention in every strategy keeps the weights a partition of unity.
inline float direct_density(float pmf, float pdf_pos, float pdf_dir, bool at_infinity) {
    return pmf * (at_infinity ? pdf_dir : pdf_pos);
}

// A light subpath leaving its light: direct_pdf_a is the density of choosing that point by
// direct light sampling (area measure, solid angle for lights at infinity), emit_pdf that of
// emitting this ray (position x direction), both times the light's selection probability.
// [tr (31)-(33)], completed by arrive(); a delta light has no dVC, dVM [tr (48)-(50)], a light at
// infinity no cos (tr sec. 5.1).
inline SubpathMis start_light(float direct_pdf_a, float emit_pdf, float cos_light, bool delta_light,
                              bool infinite_light, const MisFactors& f) {
    SubpathMis m;
    m.dVCM = mis(direct_pdf_a / emit_pdf);
    m.dVC = delta_light ? 0.0f : mis((infinite_light ? 1.0f : cos_light) / emit_pdf);
    m.dVM = m.dVC * f.vc;
    return m;
}

// A camera subpath leaving the camera in a direction of density camera_pdf_dir [tr (31)-(33)],
// completed by arrive().
inline SubpathMis start_camera(float camera_pdf_dir) { return {mis(1 / camera_pdf_dir), 0, 0, 0}; }

// The subpath reaches its next vertex after `distance`, arriving with |cos| `cos_in` there: the
// area-measure conversion that completes [tr (31)-(33)] after a start and [tr (34)-(36)] after a
// scatter; `scale_by_distance` false on the first segment from a light at infinity (tr sec. 5.1).
inline void arrive(SubpathMis& m, float distance, float cos_in, bool scale_by_distance) {
    if (scale_by_distance) m.dVCM *= mis(distance * distance);
    const float c = 1 / mis(cos_in);
    m.dVCM *= c;
    m.dVC *= c;
    m.dVM *= c;
    m.dVC_last *= c;
}

// The subpath scatters at a vertex into a direction sampled from a non-delta lobe [tr (34)-(36)],
// completed by arrive() at the next vertex.
inline void scatter(SubpathMis& m, float cos_out, float pdf_dir, float pdf_rev, bool mergeable,
                    const MisFactors& f) {
    const float g = mis(cos_out / pdf_dir);
    const float merge_here = g * (mergeable ? f.vm : 0.0f);
    const float dvc = g * (m.dVC * mis(pdf_rev) + m.dVCM) + merge_here;
    const float dvm = g * (m.dVM * mis(pdf_rev) + m.dVCM * f.vc + (mergeable ? 1.0f : 0.0f));
    m.dVC = dvc;
    m.dVM = dvm;
    m.dVCM = mis(1 / pdf_dir);
    m.dVC_last = merge_here;
}

// The subpath scatters through a delta lobe (mirror, smooth glass) [tr (53)-(55)]: pdf_dir and
// pdf_rev are the same delta and cancel.
inline void scatter_delta(SubpathMis& m, float cos_out) {
    m.dVCM = 0;
    m.dVC *= mis(cos_out);
    m.dVM *= mis(cos_out);
    m.dVC_last = 0;
}

// The weight of one side of a connection between a subpath's last vertex v (state m, reverse pdf
// pdf_rev of v's BSDF from the connection's direction back to v's predecessor) and the other
// subpath's vertex, whose BSDF would have reached v with area density pdf_a: the sum of the
// ratios of this side's strategies to the connection. The light side is [tr (40)], the camera
// side [tr (41)]; light tracing's light side is the same sum [tr (46)] (its camera side 0,
// [tr (47)]).
inline float connect_side(const SubpathMis& m, float pdf_a, float pdf_rev, bool mergeable,
                          const MisFactors& f) {
    return mis(pdf_a) * ((mergeable ? f.vm : 0.0f) + m.dVCM + m.dVC * mis(pdf_rev));
}

// The camera subpath hits an emitter (the s = 0 strategy): direct_pdf_a and emit_pdf as in
// start_light for the point and direction found (times the selection probability). With
// `merge_next_to_light` false, merging at the vertex before the emitter is no strategy. The camera
// side is [tr (43)], the light side 0 [tr (42)], the weight [tr (37)].
inline float emitter_hit_weight(const SubpathMis& camera, float direct_pdf_a, float emit_pdf,
                                bool merge_next_to_light = true) {
    const float dvc = merge_next_to_light ? camera.dVC : camera.dVC - camera.dVC_last;
    const float w = mis(direct_pdf_a) * camera.dVCM + mis(emit_pdf) * dvc;
    return 1 / (1 + w);
}

// Direct light sampling (s = 1): the light point was chosen with solid-angle density direct_pdf_w
// (0 for a delta light, which BSDF sampling cannot reach) and times the selection probability;
// emit_pdf its emission density towards the vertex; bsdf_pdf_dir / rev the vertex's BSDF pdfs
// towards the light and back along the camera path; direct_pdf_a the point's direct density
// (direct_density, times the light samples counted); emit_to_vertex = cos_to_light / distance^2 (cos_to_light
// for lights at infinity) converting emit_pdf to the vertex's area measure. w_light is [tr (44)], w_camera
// [tr (45)], the weight [tr (37)].
inline float direct_light_weight(const SubpathMis& camera, float bsdf_pdf_dir, float bsdf_pdf_rev,
                                 float direct_pdf_a, float emit_pdf, float direct_pdf_w, bool mergeable,
                                 float emit_to_vertex, const MisFactors& f) {
    const float w_light = direct_pdf_w > 0 ? mis(bsdf_pdf_dir / direct_pdf_w) : 0.0f;
    const float w_camera = mis(emit_pdf * emit_to_vertex / direct_pdf_a) *
                           ((mergeable ? f.vm : 0.0f) + camera.dVCM + camera.dVC * mis(bsdf_pdf_rev));
    return 1 / (w_light + 1 + w_camera);
}

// Merging a camera vertex (state camera, its BSDF pdfs pdf_dir towards the light vertex's incoming
// direction and pdf_rev back along the camera path) with a light vertex (state light). w_light is
// [tr (38)], w_camera [tr (39)], the weight [tr (37)].
inline float merge_weight(const SubpathMis& camera, const SubpathMis& light, float camera_pdf_dir,
                          float camera_pdf_rev, const MisFactors& f) {
    const float w_light = light.dVCM * f.vc + light.dVM * mis(camera_pdf_dir);
    const float w_camera = camera.dVCM * f.vc + camera.dVM * mis(camera_pdf_rev);
    return 1 / (w_light + 1 + w_camera);
}

}  // namespace phos::integrators::vcm
