// Blue-noise rank maps (dither arrays) for decorrelating per-pixel random numbers across the
// screen: a pixel's sample index or threshold comes from a small tiled texture whose values are
// spread evenly in space, so the error of neighbouring pixels has little low-frequency content
// and is removed by a small denoising or temporal filter instead of showing as blotches.
//
// Built by the void-and-cluster method (R. Ulichney 1993, "The void-and-cluster method for dither
// array generation", Proc. SPIE 1913). Every prefix of the ranking (the pixels with rank < k, for
// any k) is itself an evenly spread point set, and the map tiles without seams: distances are
// measured on the torus. Generated on the CPU in O(N^2) for N = side^2 pixels (Release, one
// core: about 25 ms for 64x64, 0.4 s for 128x128, 10 s for 256x256); the result depends only on
// (side, seed, sigma).
#pragma once
#include <cstdint>
#include <vector>

namespace bounce {

// A side x side toroidal blue-noise rank map: every value 0..side*side-1 exactly once, row-major
// (index y * side + x). side must be a power of two in [4, 256] and sigma (the standard deviation
// of the Gaussian energy filter in pixels; Ulichney uses 1.5) must be positive; otherwise throws
// bounce::Error.
std::vector<uint32_t> generateBlueNoiseRanks(uint32_t side, uint64_t seed, float sigma = 1.5f);

// Two independent rank maps (seeds seed and seed+1), packed per texel as (rankA | rankB << 16),
// for 2D samples: u = (rank + 0.5) / (side*side). Same limits on side as above.
std::vector<uint32_t> generateBlueNoise2D(uint32_t side, uint64_t seed);

}  // namespace bounce
