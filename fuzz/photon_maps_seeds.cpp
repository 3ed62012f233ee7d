// Writes the photon_maps target's seeds (fuzz/photon_maps_fuzzer.cpp) into DIR: small saved maps
// as a photonmap checkpoint holds them: surface maps alone; with the irradiance cache; volume
// maps with the volume cache and beams. Binary files are made here rather than kept in the
// repository. Usage: photon_maps_seeds DIR (called by scripts/fuzz.sh).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/rng.h"
#include "photon/photon_maps.h"

namespace {

using namespace phos;
using namespace phos::photon;

// n photons in the unit cube (on the floor z = 0 when `surface`, with its normal).
std::vector<Photon> random_photons(int n, bool surface, uint64_t seed) {
    Sampler rng(seed);
    std::vector<Photon> v;
    for (int i = 0; i < n; ++i) {
        const Vec3 p(rng.next(), rng.next(), surface ? 0.0f : rng.next());
        Spectrum power;
        for (int k = 0; k < spectrum::kSpectrumSamples; ++k) power[k] = rng.next();
        const Wavelengths lambda = Wavelengths::visible(rng.next());
        const Vec3 wi(rng.next() - 0.5f, rng.next() - 0.5f, 1.0f);
        v.emplace_back(p, power, lambda, wi, surface ? Vec3(0, 0, 1) : Vec3(0.0f));
    }
    return v;
}

void write(const std::string& path, const PhotonMaps& maps) {
    std::ofstream(path, std::ios::binary) << maps.save();
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: photon_maps_seeds DIR\n");
        return 2;
    }
    const std::string dir = argv[1];
    std::filesystem::create_directories(dir);
    KdTreeOptions small;
    small.leaf_size = 4;

    PhotonMaps surface;
    surface.map[kGlobalMap].build(random_photons(40, true, 1), small);
    surface.map[kCausticMap].build(random_photons(12, true, 2), small);
    surface.emitted[kGlobalMap] = 100, surface.emitted[kCausticMap] = 900;
    write(dir + "/surface", surface);

    EstimateOptions eo;
    eo.k = 8;
    surface.cache.build(surface.map[kGlobalMap], eo, 4);
    write(dir + "/surface-cache", surface);

    PhotonMaps volume;
    volume.map[kVolumeMap].build(random_photons(16, false, 3), small);
    volume.map[kVolumeCausticMap].build(random_photons(6, false, 4), small);
    volume.emitted[kVolumeMap] = 50;
    VolumeEstimateOptions vo;
    vo.k = 8;
    volume.volume_cache.build(volume.map[kVolumeMap], vo, volume.map[kVolumeCausticMap], vo, 3);
    std::vector<PhotonSphere> spheres;
    for (const Photon& p : volume.map[kVolumeMap].photons())
        spheres.push_back({p.position, 0.1f, p.colour(), p.wi()});
    volume.volume_beams.build(spheres, 2);
    spheres.resize(5);
    volume.volume_caustic_beams.build(spheres, 2);
    write(dir + "/volume", volume);
    return 0;
}
