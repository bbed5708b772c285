// Void-and-cluster dither arrays, after R. Ulichney 1993, "The void-and-cluster method for dither
// array generation", Proc. SPIE 1913, pp. 332-343.
//
// The method works on a binary pattern on the torus and its "energy": the pattern convolved with
// a Gaussian filter, so a pixel's energy is high where many 1s are close by. The 1 of highest
// energy is the "tightest cluster", the 0 of lowest energy the "largest void". Ranks are handed
// out so that every prefix of the ranking stays as evenly spread as possible:
//   phase 0: a random pattern of about 10% 1s is made homogeneous by moving the tightest cluster
//            into the largest void until that changes nothing;
//   phase 1: the 1s of that pattern get the ranks below their count, highest first, by removing
//            tightest clusters one by one;
//   phase 2: up to half of the pixels, the largest void is filled and gets the next rank;
//   phase 3: from half to all pixels the 0s are the minority, so Ulichney inverts the pattern and
//            hands the next rank to the tightest cluster of 0s (see rankByFillingVoids for why this
//            is the same pixel as the largest void of 1s).
#include "core/blue_noise.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

#include "core/error.h"

namespace bounce {
namespace {

constexpr uint32_t MIN_SIDE = 4;
constexpr uint32_t MAX_SIDE = 256;  // ranks are packed in 16 bits by generateBlueNoise2D
// Ulichney starts from a pattern of about 10% 1s.
constexpr double INITIAL_DENSITY = 0.1;

bool isPowerOfTwo(uint32_t x) {
  return x != 0 && (x & (x - 1)) == 0;
}

void checkSide(uint32_t side) {
  if (side < MIN_SIDE || side > MAX_SIDE || !isPowerOfTwo(side))
    fail("blue noise: side {} must be a power of two in [{}, {}]", side, MIN_SIDE, MAX_SIDE);
}

// The shortest distance from 0 to d along a ring of `side` pixels.
uint32_t ringDistance(uint32_t d, uint32_t side) {
  return std::min(d, side - d);
}

// Ulichney's energy filter exp(-r^2 / (2 sigma^2)) for every toroidal offset: entry dy*side + dx
// is the filter at the wrapped distance between pixels (x, y) and (x + dx, y + dy).
std::vector<double> toroidalGaussian(uint32_t side, double sigma) {
  std::vector<double> kernel(size_t(side) * side);
  for (uint32_t dy = 0; dy < side; ++dy) {
    for (uint32_t dx = 0; dx < side; ++dx) {
      const double rx = ringDistance(dx, side), ry = ringDistance(dy, side);
      kernel[size_t(dy) * side + dx] = std::exp(-(rx * rx + ry * ry) / (2.0 * sigma * sigma));
    }
  }
  return kernel;
}

// A binary pattern on the side x side torus with its energy, energy[p] = sum over the 1s q of
// kernel(p - q), kept up to date as single pixels are set or cleared (O(N) per change instead of
// a full O(N^2) convolution).
class EnergyField {
 public:
  EnergyField(uint32_t side, const std::vector<double>& kernel)
      : side_(side),
        kernel_(&kernel),
        isOne_(size_t(side) * side, 0),
        energy_(isOne_.size(), 0.0) {}

  uint32_t pixelCount() const { return uint32_t(isOne_.size()); }
  uint32_t oneCount() const { return ones_; }
  double energy(uint32_t pixel) const { return energy_[pixel]; }

  void insertOne(uint32_t pixel) {
    isOne_[pixel] = 1;
    ++ones_;
    addKernel(pixel, 1.0);
  }

  void removeOne(uint32_t pixel) {
    isOne_[pixel] = 0;
    --ones_;
    addKernel(pixel, -1.0);
  }

  // The 1 with the highest energy; the lowest index among equals.
  uint32_t tightestCluster() const {
    uint32_t best = 0;
    double bestEnergy = -INFINITY;
    for (uint32_t p = 0; p < pixelCount(); ++p) {
      if (isOne_[p] && energy_[p] > bestEnergy) {
        bestEnergy = energy_[p];
        best = p;
      }
    }
    return best;
  }

  // The 0 with the lowest energy; the lowest index among equals.
  uint32_t largestVoid() const {
    uint32_t best = 0;
    double bestEnergy = INFINITY;
    for (uint32_t p = 0; p < pixelCount(); ++p) {
      if (!isOne_[p] && energy_[p] < bestEnergy) {
        bestEnergy = energy_[p];
        best = p;
      }
    }
    return best;
  }

 private:
  // energy[q] += weight * kernel(q - pixel) for every pixel q. With the kernel stored by offset,
  // each row of the torus reads one kernel row, rotated by the pixel's column: two contiguous runs.
  void addKernel(uint32_t pixel, double weight) {
    const uint32_t px = pixel % side_, py = pixel / side_;
    const uint32_t rowMask = side_ - 1;  // side is a power of two: & rowMask is mod side
    for (uint32_t y = 0; y < side_; ++y) {
      const double* kernelRow = &(*kernel_)[size_t((y - py) & rowMask) * side_];
      double* energyRow = &energy_[size_t(y) * side_];
      for (uint32_t x = px; x < side_; ++x) energyRow[x] += weight * kernelRow[x - px];
      for (uint32_t x = 0; x < px; ++x) energyRow[x] += weight * kernelRow[x + side_ - px];
    }
  }

  uint32_t side_;
  const std::vector<double>* kernel_;
  std::vector<uint8_t> isOne_;
  std::vector<double> energy_;
  uint32_t ones_ = 0;
};

// About INITIAL_DENSITY of the pixels, at least one, chosen uniformly by a partial Fisher-Yates
// shuffle. The bounded draws are rng() % n rather than std::uniform_int_distribution, whose
// algorithm differs between standard libraries, so a seed gives the same map everywhere (the
// modulo bias is below n / 2^64).
void insertRandomOnes(EnergyField& field, uint64_t seed) {
  const uint32_t pixels = field.pixelCount();
  const uint32_t ones = std::max(1u, uint32_t(std::lround(pixels * INITIAL_DENSITY)));
  std::vector<uint32_t> order(pixels);
  for (uint32_t p = 0; p < pixels; ++p) order[p] = p;
  std::mt19937_64 rng(seed);
  for (uint32_t i = 0; i < ones; ++i) {
    const uint32_t pick = i + uint32_t(rng() % (pixels - i));
    std::swap(order[i], order[pick]);
    field.insertOne(order[i]);
  }
}

// Phase 0: move the tightest cluster into the largest void until the pixel just removed is
// itself a largest void. Each move lowers the pattern's total pairwise energy (the moved 1 goes
// from energy E, counting the other 1s only, to a strictly lower one), so the loop ends; the cap
// only guards against rounding in the running energies making two equal values compare unequal
// forever.
void spreadOnes(EnergyField& field) {
  const uint32_t maxMoves = 16 * field.pixelCount();
  for (uint32_t move = 0; move < maxMoves; ++move) {
    const uint32_t cluster = field.tightestCluster();
    field.removeOne(cluster);
    const uint32_t emptiest = field.largestVoid();
    if (field.energy(emptiest) >= field.energy(cluster)) {
      field.insertOne(cluster);  // the removed pixel is (one of) the largest voids: stable
      return;
    }
    field.insertOne(emptiest);
  }
}

// Phase 1: the 1s of the homogeneous pattern take the ranks 0..ones-1; the tightest cluster is
// removed first and gets the highest of them, so the 1s left at each step stay spread out.
void rankByRemovingClusters(EnergyField field, std::vector<uint32_t>& ranks) {
  for (uint32_t rank = field.oneCount(); rank-- > 0;) {
    const uint32_t cluster = field.tightestCluster();
    field.removeOne(cluster);
    ranks[cluster] = rank;
  }
}

// Phases 2 and 3: ranks [field.oneCount(), endRank) go to pixels filled in one at a time.
// Phase 2 fills the largest void of the 1s. Phase 3 (Ulichney: invert the pattern, then take the
// tightest cluster of the now-minority 0s) picks the same pixel: on the torus every pixel sees
// the whole kernel, so energyOfZeros(p) + energyOfOnes(p) = sum of the kernel, the same for all
// p, and the 0 with the highest energy of 0s is the 0 with the lowest energy of 1s. Both phases
// therefore run this one rule, with the same tie-break (lowest index).
void rankByFillingVoids(EnergyField& field, uint32_t endRank, std::vector<uint32_t>& ranks) {
  for (uint32_t rank = field.oneCount(); rank < endRank; ++rank) {
    const uint32_t emptiest = field.largestVoid();
    field.insertOne(emptiest);
    ranks[emptiest] = rank;
  }
}

}  // namespace

std::vector<uint32_t> generateBlueNoiseRanks(uint32_t side, uint64_t seed, float sigma) {
  checkSide(side);
  if (!(sigma > 0.0f) || !std::isfinite(sigma))
    fail("blue noise: sigma {} must be a positive number of pixels", sigma);
  const std::vector<double> kernel = toroidalGaussian(side, sigma);

  EnergyField field(side, kernel);
  insertRandomOnes(field, seed);
  spreadOnes(field);  // phase 0

  std::vector<uint32_t> ranks(field.pixelCount());
  rankByRemovingClusters(field, ranks);                      // phase 1, on a copy
  rankByFillingVoids(field, field.pixelCount() / 2, ranks);  // phase 2
  rankByFillingVoids(field, field.pixelCount(), ranks);      // phase 3
  return ranks;
}

std::vector<uint32_t> generateBlueNoise2D(uint32_t side, uint64_t seed) {
  const std::vector<uint32_t> first = generateBlueNoiseRanks(side, seed);
  const std::vector<uint32_t> second = generateBlueNoiseRanks(side, seed + 1);
  std::vector<uint32_t> packed(first.size());
  for (size_t i = 0; i < packed.size(); ++i) packed[i] = first[i] | second[i] << 16;
  return packed;
}

}  // namespace bounce
