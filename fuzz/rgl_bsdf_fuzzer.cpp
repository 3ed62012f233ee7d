// libFuzzer harness for the RGL `.bsdf` measured-BSDF reader (io/bsdf: the tensor-file container,
// its field table, the fields and their consistency). The input is the file. A file that is
// accepted must give interpolants whose samples lie in the unit square with finite, non-negative
// densities, finite values and a finite, non-negative albedo estimate.
#include <cmath>

#include "fuzz/fuzz_support.h"
#include "io/bsdf/rgl_bsdf_file.h"

namespace {

bool in_unit_square(phos::Vec2 p) { return p.x >= 0 && p.x <= 1 && p.y >= 0 && p.y <= 1; }

void check_warp(const phos::scene::PiecewiseLinear2D& w, const float* param) {
    for (float a : {0.0f, 0.3f, 0.999f})
        for (float b : {0.0f, 0.61f, 1.0f}) {
            const auto s = w.sample(phos::Vec2(a, b), param);
            if (!in_unit_square(s.p) || !std::isfinite(s.pdf) || s.pdf < 0)
                phos::fuzz::invariant_failed(
                    "a warp's sample is outside the square or its density is not finite");
            const auto i = w.invert(s.p, param);
            if (!std::isfinite(i.p.x) || !std::isfinite(i.p.y) || !std::isfinite(i.pdf) || i.pdf < 0)
                phos::fuzz::invariant_failed("a warp's inverse is not finite");
        }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static phos::fuzz::Scratch scratch;
    const std::string path = scratch.write("m.bsdf", std::string(reinterpret_cast<const char*>(data), size));
    phos::fuzz::expect_reader_errors([&] {
        const auto m = phos::io::read_rgl_bsdf(path);
        if (!m) phos::fuzz::invariant_failed("no BSDF was returned");
        for (float phi : {-3.0f, 0.5f})
            for (float theta : {0.0f, 0.8f, 1.6f}) {
                const float param[3] = {phi, theta, m->spectral() ? 550.0f : 1.0f};
                check_warp(m->vndf(), param);
                check_warp(m->luminance(), param);
                // Each a convex combination of finite table values, so finite.
                const float v[3] = {m->spectra().eval(phos::Vec2(0.4f, 0.7f), param),
                                    m->ndf().eval(phos::Vec2(0.2f, 0.9f)),
                                    m->sigma().eval(phos::Vec2(0.5f, 0.5f))};
                const float a = m->albedo(phi, theta);
                if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]) ||
                    !std::isfinite(a) || a < 0)
                    phos::fuzz::invariant_failed("an interpolated value or the albedo is not finite");
            }
    });
    return 0;
}
