// Block agreement (see block_agreement.h). The noise model, for one estimator rendered with seeds
// a and b, at block j (n_j pixels) and channel c:
//  - the block mean of one render has, if its pixels were independent, the variance
//      v_j = sum over the block's pixels of (a_i - b_i)^2 / 2, divided by n_j^2
//    ((a_i - b_i)^2 / 2 estimates a pixel's variance without bias, with one degree of freedom);
//  - photon methods correlate neighbouring pixels through the photons they share (and a photon
//    map's total flux is one random number for the whole image), so the block mean's true variance
//    is larger. The block-level difference d_j = (mean_a - mean_b)^2 / 2 estimates it without that
//    assumption but with a single degree of freedom, so one inflation factor for the image is fitted
//    from all blocks: f = sum_j d_j / sum_j v_j over blocks and channels, never below 1;
//  - rare bright samples (a caustic found by a path tracer's BSDF sample, a light path through
//    glass) make the noise heavy-tailed: in many seed pairs a block's 64 pixel differences miss
//    most of its variance, and the same pair's mean is low for the same reason. Blocks next to each
//    other share their light transport, so the neighbourhood's estimate is the steadier one: v_j is
//    replaced by the larger of itself and the mean of v over the 3 x 3 blocks around j. (On the
//    Cornell box with a glass sphere, path tracing at 64 spp: one pair's own estimate of a wall
//    block's deviation was 0.0008 against 0.0047 measured over 24 seeds; the neighbourhood's, 0.010.)
//  - the mean of the pair (a + b) / 2, which is compared, has variance f v_j / 2.
// The tolerance of a block is
//      sigmas' sqrt(var_tested + var_reference) + bias_tested + bias_reference + floor
// with sigmas' the Student-t quantile for the block's degrees of freedom (Welch-Satterthwaite over
// the two variance estimates of n_j degrees of freedom each) at the Gaussian tail of `sigmas`, and
// floor = settings.floor (|reference block mean| + reference image mean): where the image is
// deterministic (a sky seen directly has no noise) the integrators still differ by their rounding,
// bdpt and vcm summing the image in fixed point (2e-4 of a sky block against path), and blocks
// black in both agree.
// Sums run in double, in image order: results are reproducible.
#include "film/block_agreement.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/format.h"

namespace phos::film {
namespace {

constexpr const char* kChannelNames[3] = {"red", "green", "blue"};

// One image's block statistics: per block and channel (3: the channel average) the pair's mean
// and the pixel-independent variance of one render's block mean.
struct PairBlocks {
    int bx = 0, by = 0;  // blocks across and down
    std::vector<std::array<double, 4>> mean, pixel_var;
    std::vector<std::array<double, 4>> pooled_var;  // max(own, mean over the 3 x 3 blocks around)
    std::vector<int> pixels;                        // per block
    double inflation = 1;                           // f, fitted over the colour channels
    double image_mean = 0, image_var = 0;           // channel average: the pair's image mean and its variance

    double var(size_t j, int c) const { return inflation * pooled_var[j][size_t(c)] / 2; }
};

PairBlocks pair_blocks(const SeedPair& p, int block) {
    PairBlocks s;
    const int w = p.a.width, h = p.a.height;
    s.bx = (w + block - 1) / block;
    s.by = (h + block - 1) / block;
    const size_t n = size_t(s.bx) * size_t(s.by);
    s.mean.assign(n, {});
    s.pixel_var.assign(n, {});
    s.pixels.assign(n, 0);
    std::vector<std::array<double, 4>> mean_a(n, std::array<double, 4>{}), mean_b = mean_a;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t j = size_t(y / block) * size_t(s.bx) + size_t(x / block);
            const Rgb& a = p.a.at(x, y);
            const Rgb& b = p.b.at(x, y);
            for (int c = 0; c < 4; ++c) {
                const double va = c < 3 ? a[c] : a.average(), vb = c < 3 ? b[c] : b.average();
                mean_a[j][size_t(c)] += va;
                mean_b[j][size_t(c)] += vb;
                s.pixel_var[j][size_t(c)] += (va - vb) * (va - vb) / 2;
            }
            ++s.pixels[j];
        }
    double block_sum = 0, pixel_sum = 0;
    for (size_t j = 0; j < n; ++j) {
        const double nj = s.pixels[j];
        for (size_t c = 0; c < 4; ++c) {
            mean_a[j][c] /= nj;
            mean_b[j][c] /= nj;
            s.mean[j][c] = (mean_a[j][c] + mean_b[j][c]) / 2;
            s.pixel_var[j][c] /= nj * nj;
            if (c == 3) continue;
            const double d = mean_a[j][c] - mean_b[j][c];
            block_sum += d * d / 2;
            pixel_sum += s.pixel_var[j][c];
        }
    }
    if (pixel_sum > 0) s.inflation = std::max(1.0, block_sum / pixel_sum);
    s.pooled_var = s.pixel_var;
    for (int y = 0; y < s.by; ++y)
        for (int x = 0; x < s.bx; ++x) {
            std::array<double, 4> sum{};
            int count = 0;
            for (int ny = std::max(0, y - 1); ny <= std::min(s.by - 1, y + 1); ++ny)
                for (int nx = std::max(0, x - 1); nx <= std::min(s.bx - 1, x + 1); ++nx, ++count)
                    for (size_t c = 0; c < 4; ++c)
                        sum[c] += s.pixel_var[size_t(ny) * size_t(s.bx) + size_t(nx)][c];
            std::array<double, 4>& v = s.pooled_var[size_t(y) * size_t(s.bx) + size_t(x)];
            for (size_t c = 0; c < 4; ++c) v[c] = std::max(v[c], sum[c] / count);
        }
    // The image mean as the pixel-weighted mean of the blocks; its variance treats the blocks as
    // independent (each inflated by f).
    const double total = double(w) * double(h);
    for (size_t j = 0; j < n; ++j) {
        const double weight = s.pixels[j] / total;
        s.image_mean += weight * s.mean[j][3];
        s.image_var += weight * weight * s.var(j, 3);
    }
    return s;
}

void check_sizes(const SeedPair& tested, const SeedPair& reference, int block) {
    if (block < 1) throw InputError("block size " + std::to_string(block) + " is not positive");
    const Image* images[4] = {&tested.a, &tested.b, &reference.a, &reference.b};
    for (const Image* i : images)
        if (i->width != tested.a.width || i->height != tested.a.height ||
            i->pixels.size() != size_t(i->width) * size_t(i->height) || i->pixels.empty())
            throw InputError("agreement: the renders must be non-empty and of one size (" +
                             std::to_string(tested.a.width) + "x" + std::to_string(tested.a.height) +
                             " and " + std::to_string(i->width) + "x" + std::to_string(i->height) + ")");
}

// The bias a kernel of radius r pixels may cause in the mean of a B x B block (at block (x, y),
// channel c, from the reference's block means m):
//  - blur: the blurred block mean is a weighted mean of its own and its neighbours' true means. A
//    pixel at distance d < r from the block's side draws the fraction (r - d) / 2r of a 1-D box
//    kernel's mass from across it; averaged over the block that is r / 4B per side, r / 2B per axis,
//    about r / B for both (less for kernels peaked at the centre). So the block mean moves by at
//    most min(1, r / B) times the largest difference between m and a neighbour's mean.
//  - edges: where a surface ends inside the kernel's disc (a wall's edge, a corner), the disc
//    finds photons on only part of its area and reads dark: at distance d = t r from the edge it
//    misses the circular segment (acos t - t sqrt(1 - t^2)) / pi, which averages 2 / (3 pi) = 0.21
//    over the band 0 <= t <= 1. An edge across the block darkens a band r pixels wide: 0.21 r / B
//    of the block mean.
double kernel_allowance(const BiasAllowance& bias, const PairBlocks& ref, int block, int x, int y, int c) {
    if (bias.kernel <= 0) return 0;
    const double m = ref.mean[size_t(y) * size_t(ref.bx) + size_t(x)][size_t(c)];
    double step = 0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const int nx = x + dx, ny = y + dy;
            if (nx < 0 || ny < 0 || nx >= ref.bx || ny >= ref.by) continue;
            step =
                std::max(step, std::abs(ref.mean[size_t(ny) * size_t(ref.bx) + size_t(nx)][size_t(c)] - m));
        }
    const double r_over_b = bias.kernel / block;
    return std::min(1.0, r_over_b) * step + 2 / (3 * M_PI) * r_over_b * std::abs(m);
}

}  // namespace

double BlockComparison::ratio() const {
    if (reference == 0) return mean == 0 ? 1.0 : std::numeric_limits<double>::infinity();
    return mean / reference;
}

double BlockComparison::excess() const {
    const double diff = std::abs(mean - reference);
    if (tolerance <= 0) return diff == 0 ? 0.0 : std::numeric_limits<double>::infinity();
    return diff / tolerance;
}

bool Agreement::mean_agrees() const { return std::abs(mean_ratio - 1) <= mean_tolerance; }

int block_comparisons(int width, int height, int block) {
    return 3 * ((width + block - 1) / block) * ((height + block - 1) / block);
}

double tolerance_sigmas(double comparisons, double false_failure) {
    // The z with P(|Z| > z) = erfc(z / sqrt 2) = false_failure / comparisons, by bisection.
    const double p = false_failure / std::max(1.0, comparisons);
    double lo = 0, hi = 40;
    for (int i = 0; i < 100; ++i) {
        const double mid = (lo + hi) / 2;
        (std::erfc(mid / std::sqrt(2.0)) > p ? lo : hi) = mid;
    }
    return hi;
}

double student_sigmas(double z, double dof) {
    // Cornish-Fisher expansion of the t quantile in powers of 1/dof (Abramowitz & Stegun 26.7.5).
    const double z2 = z * z, n = std::max(dof, 1.0);
    const double g1 = (z2 + 1) * z / 4;
    const double g2 = ((5 * z2 + 16) * z2 + 3) * z / 96;
    const double g3 = (((3 * z2 + 19) * z2 + 17) * z2 - 15) * z / 384;
    const double g4 = ((((79 * z2 + 776) * z2 + 1482) * z2 - 1920) * z2 - 945) * z / 92160;
    return z + g1 / n + g2 / (n * n) + g3 / (n * n * n) + g4 / (n * n * n * n);
}

Agreement compare_blocks(const SeedPair& tested, const BiasAllowance& tested_bias, const SeedPair& reference,
                         const BiasAllowance& reference_bias, const BlockSettings& settings) {
    check_sizes(tested, reference, settings.block);
    const PairBlocks t = pair_blocks(tested, settings.block);
    const PairBlocks r = pair_blocks(reference, settings.block);
    Agreement out;
    out.inflation = t.inflation;
    out.reference_inflation = r.inflation;

    const double image_floor = settings.floor * std::abs(r.image_mean);
    bool first = true;
    for (int y = 0; y < t.by; ++y)
        for (int x = 0; x < t.bx; ++x) {
            const size_t j = size_t(y) * size_t(t.bx) + size_t(x);
            const double n = t.pixels[j];
            for (int c = 0; c < 3; ++c) {
                const double vt = t.var(j, c), vr = r.var(j, c);
                // Welch-Satterthwaite: the degrees of freedom of vt + vr, each estimated from n pixels.
                const double dof = vt + vr > 0 ? (vt + vr) * (vt + vr) / ((vt * vt + vr * vr) / n) : n;
                BlockComparison b;
                b.x = x * settings.block;
                b.y = y * settings.block;
                b.channel = c;
                b.mean = t.mean[j][size_t(c)];
                b.reference = r.mean[j][size_t(c)];
                b.tolerance = student_sigmas(settings.sigmas, dof) * std::sqrt(vt + vr) +
                              kernel_allowance(tested_bias, r, settings.block, x, y, c) +
                              kernel_allowance(reference_bias, r, settings.block, x, y, c) +
                              settings.floor * std::abs(b.reference) + image_floor;
                out.blocks.push_back(b);
                if (first || b.excess() > out.worst.excess()) out.worst = b;
                first = false;
                if (b.excess() > 1) out.failing.push_back(b);
            }
        }

    // The image mean (channel average): its noise over the blocks, the images' allowances and the floor.
    if (r.image_mean == 0) {
        out.mean_ratio = t.image_mean == 0 ? 1.0 : std::numeric_limits<double>::infinity();
    } else {
        out.mean_ratio = t.image_mean / r.image_mean;
        out.mean_tolerance = settings.sigmas * std::sqrt(t.image_var + r.image_var) / std::abs(r.image_mean) +
                             tested_bias.image + reference_bias.image + settings.floor;
    }
    return out;
}

std::string describe(const BlockComparison& b) {
    return printf_string("block (%d, %d) %s: %.4g x the reference (%.3g / %.3g, %.2f tolerances off)", b.x,
                         b.y, kChannelNames[b.channel], b.ratio(), b.mean, b.reference, b.excess());
}

}  // namespace phos::film
