// Whether two estimators of one image agree, block by block: the mean of every B x B block of an
// integrator's renders against a reference's, within a tolerance made of the noise both show
// between two seeds, the bias each may have by construction, and a floor for rounding and black
// blocks
// (the agreement matrix in tests/agreement and `phos agree`).
#pragma once

#include <string>
#include <vector>

#include "core/image.h"

namespace phos::film {

// Two renders of one estimator that differ only in the seed (same size).
struct SeedPair {
    const Image& a;
    const Image& b;
};

// What an estimator may differ from the true image by besides noise, as its integrator documents
// it (integrators/registry.h agreement_bias): a density-estimation kernel of radius r pixels (at the
// end of the render) blurs the image and loses light beside the edges of surfaces, and the image
// mean may be off by the fraction `image`. All 0 for an unbiased estimator. What that allows at a
// block is derived in block_agreement.cpp (kernel_allowance).
struct BiasAllowance {
    double kernel = 0;  // r, in pixels
    double image = 0;
};

struct BlockSettings {
    int block = 8;  // block side in pixels (the last row and column of blocks may be smaller)
    // The tolerance in Gaussian standard deviations of the noise (tolerance_sigmas); each block
    // widens it to the Student-t quantile of as many degrees of freedom as its pixels (its noise is
    // estimated from them).
    double sigmas = 5;
    // Rounding: this times the reference's block mean plus its image mean (see block_agreement.cpp).
    double floor = 1e-3;
};

// One block and channel compared.
struct BlockComparison {
    int x = 0, y = 0;  // the block's top-left pixel
    int channel = 0;   // 0 red, 1 green, 2 blue
    double mean = 0, reference = 0;
    double tolerance = 0;  // allowed |mean - reference|
    // mean / reference (+inf when only the reference is black, 1 when both are).
    double ratio() const;
    // |mean - reference| / tolerance: above 1 the block disagrees.
    double excess() const;
};

struct Agreement {
    double mean_ratio = 1;                 // image mean / reference image mean (channel average)
    double mean_tolerance = 0;             // allowed |mean_ratio - 1|
    std::vector<BlockComparison> blocks;   // every block and channel, in image order
    BlockComparison worst;                 // the largest excess()
    std::vector<BlockComparison> failing;  // excess() > 1, in image order
    // The factors by which the block means' noise exceeds what independent pixels would give,
    // fitted from the seeds (>= 1): neighbouring pixels that share photons are correlated.
    double inflation = 1, reference_inflation = 1;

    bool mean_agrees() const;
    bool agrees() const { return mean_agrees() && failing.empty(); }
};

// Compares `tested` with `reference` block by block (see block_agreement.cpp for the noise model).
// InputError if the four images differ in size or the block is not positive.
Agreement compare_blocks(const SeedPair& tested, const BiasAllowance& tested_bias, const SeedPair& reference,
                         const BiasAllowance& reference_bias, const BlockSettings& settings);

// Block comparisons (blocks x channels) of one pair of images.
int block_comparisons(int width, int height, int block);

// The tolerance in standard deviations for `comparisons` two-sided Gaussian tests whose chance of
// any false failure is at most `false_failure` (Bonferroni: each test at false_failure /
// comparisons).
double tolerance_sigmas(double comparisons, double false_failure = 1e-4);
// The Student-t quantile with `dof` degrees of freedom at the tail probability of `sigmas`
// Gaussian standard deviations (Cornish-Fisher expansion: within 0.5 % for dof >= 16 at sigmas <= 6; 6 % low
// at dof 8).
double student_sigmas(double sigmas, double dof);

// "block (16, 8) green: 0.812 x the reference (3.4 tolerances off)".
std::string describe(const BlockComparison& block);

}  // namespace phos::film
