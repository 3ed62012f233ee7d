// The -v statistics of a photon-map build (see map_report.h).
#include "photon/map_report.h"

#include <string>

#include "core/format.h"
#include "core/log.h"
#include "dist/ranks.h"

namespace phos::photon {

namespace {

// "1 thread", "4 threads".
std::string threads_text(int n) { return std::to_string(n) + (n == 1 ? " thread" : " threads"); }

// Each wanted map's photons and emissions; the warning for one the emission cap cut short.
void report_maps(Stats& stats, const TraceOptions& to, const TracedPhotons& traced, const PhotonMaps& maps,
                 bool has_lights) {
    for (int m = 0; m < kMapCount; ++m) {
        if (!to.wanted[m]) continue;
        stats.add_value(std::string(map_name(m)) + " map",
                        std::to_string(maps.map[m].size()) + " photons from " +
                            std::to_string(maps.emitted[m]) + " emitted" +
                            (traced.reached[m] ? ""
                             : !has_lights     ? " (no lights)"
                                               : " (emission cap reached before the budget)"));
        // Without lights nothing is emitted: the app's no-lights warning says so, not --max-emitted.
        if (!traced.reached[m] && to.target[m] > 0 && has_lights)
            log::warn_once(std::string("pm-cap-") + map_name(m),
                           std::string("photon map: the ") + map_name(m) + " map got " +
                               std::to_string(maps.map[m].size()) + " of " + std::to_string(to.target[m]) +
                               " photons before the emission cap (--max-emitted)");
    }
}

// Where the tracing's and the build's time went: on many cores, a top-level share that grows with
// the thread count means those passes over the whole map wait for memory.
void report_rates(Stats& stats, const TracedPhotons& traced, const MapBuildTimes& times) {
    // How busy the tracing threads were: below ~95 % the pipeline waits (commits, the last
    // batches); at ~100 % a rate that grows less than the thread count is the cores' own speed.
    if (traced.pipeline_seconds > 0 && traced.threads > 0)
        stats.add_value(
            "photon tracing threads busy",
            printf_string("%.1f %%",
                          100.0 * traced.batch_seconds / (traced.threads * traced.pipeline_seconds)) +
                printf_string(" (batches %.3f s on ", traced.batch_seconds) + threads_text(traced.threads) +
                printf_string(" in %.3f s;", traced.pipeline_seconds) +
                printf_string(" commits %.3f s, serial)", traced.commit_seconds));
    const double stored = double(times.stored);
    stats.add_value(
        "photon tracing rate",
        printf_string("%.3g stored photons/s", times.trace_seconds > 0 ? stored / times.trace_seconds : 0.0));
    stats.add_value("photon map build thread time",
                    printf_string("top levels %.3f s, ", times.build.top_seconds) +
                        printf_string("below them %.3f s", times.build.below_seconds) +
                        printf_string(" in %.3f s", times.build_seconds) +
                        (traced.threads > 0 ? " on " + threads_text(traced.threads) : std::string()));
    stats.add_value(
        "photon map build rate",
        printf_string("%.3g photons/s", times.build_seconds > 0 ? stored / times.build_seconds : 0.0));
}

}  // namespace

void report_map_build(Stats& stats, const TraceOptions& to, const TracedPhotons& traced,
                      const PhotonMaps& maps, const MapBuildTimes& times, bool has_lights) {
    if (!maps.volume_beams.empty() || !maps.volume_caustic_beams.empty())
        stats.add_value("beam BVH memory",
                        printf_string("%.3g MB", double(maps.volume_beams.memory_bytes() +
                                                        maps.volume_caustic_beams.memory_bytes()) /
                                                     1e6));
    stats.add_value("photons emitted", std::to_string(traced.total_emitted));
    stats.add_photons_emitted(traced.total_emitted);
    report_maps(stats, to, traced, maps, has_lights);
    if (to.wanted[kCausticMap] && to.caustic_projection)
        stats.add_value("caustic projection maps",
                        printf_string("%.3g %% of the emitted power aimed at specular objects",
                                      100.0 * traced.caustic_fraction) +
                            printf_string(", built in %.3f s", traced.projection_seconds) +
                            printf_string(", caustic tracing %.3g stored photons/s",
                                          traced.caustic_seconds > 0
                                              ? double(maps.caustic().size()) / traced.caustic_seconds
                                              : 0.0));
    stats.add_value("bytes per photon", std::to_string(sizeof(Photon)));
    if (dist::distributed())  // each rank traced its batches; all received every batch
        stats.add_value("photon batches exchanged (MPI)",
                        printf_string("%.3g MB", double(traced.exchanged_bytes) * 1e-6) +
                            printf_string(" in %.3f s", traced.exchange_seconds));
    stats.add_value("photon map pages faulted in",
                    printf_string("%.3g MB", double(traced.faulted_bytes) * 1e-6) +
                        printf_string(" in %.3f s of the trace", traced.fault_in_seconds));
    report_rates(stats, traced, times);
}

}  // namespace phos::photon
