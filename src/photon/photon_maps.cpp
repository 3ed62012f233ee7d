// The photon maps' byte form (see photon_maps.h): each structure writes and checks its own part.
#include "photon/photon_maps.h"

#include "core/byte_buffer.h"

namespace phos::photon {
namespace {

// "PHOSMAP1": the payload's format (photon record, map count and the caches' layouts).
constexpr uint64_t kMapsMagic = 0x3150414d534f4850ULL;

}  // namespace

std::string PhotonMaps::save() const {
    std::string out;
    ByteWriter w(out);
    w.put(kMapsMagic);
    for (int m = 0; m < kMapCount; ++m) {
        map[m].save(w);
        w.put(emitted[m]);
    }
    cache.save(w);
    volume_cache.save(w);
    volume_beams.save(w);
    volume_caustic_beams.save(w);
    return out;
}

PhotonMaps PhotonMaps::load(const std::string& bytes, const std::string& what) {
    ByteReader r(bytes, what);
    if (r.get<uint64_t>() != kMapsMagic) r.fail("not a photon map record of this phos version");
    PhotonMaps maps;
    for (int m = 0; m < kMapCount; ++m) {
        maps.map[m].load(r);
        maps.emitted[m] = r.get<uint64_t>();
    }
    maps.cache.load(r);
    maps.volume_cache.load(r);
    maps.volume_beams.load(r);
    maps.volume_caustic_beams.load(r);
    if (!r.at_end()) r.fail("unexpected bytes after the maps");
    return maps;
}

}  // namespace phos::photon
