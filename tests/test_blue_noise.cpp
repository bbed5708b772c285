// Blue-noise rank maps (void-and-cluster): each map is a permutation, a seed fixes it, and the
// maps are measurably blue. Every statistic is also taken of white noise (a shuffled
// permutation), whose value follows from probability alone, so each test shows that it can tell
// the two apart; the bounds come from that math or from geometry, as the comments say.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numeric>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "core/blue_noise.h"
#include "core/error.h"

namespace bounce {
namespace {

constexpr uint64_t SEED = 20240611;

std::vector<uint32_t> whiteNoiseRanks(uint32_t side, uint64_t seed) {
  std::vector<uint32_t> ranks(size_t(side) * side);
  std::iota(ranks.begin(), ranks.end(), 0u);
  std::mt19937_64 rng(seed);
  std::shuffle(ranks.begin(), ranks.end(), rng);
  return ranks;
}

bool isPermutation(std::vector<uint32_t> values) {
  std::sort(values.begin(), values.end());
  for (uint32_t i = 0; i < values.size(); ++i)
    if (values[i] != i) return false;
  return true;
}

// ---- spectrum ----------------------------------------------------------------------------------

// The signed frequency of DFT index k along a ring of `side` samples: 0, 1, ..., -2, -1.
int signedFrequency(uint32_t k, uint32_t side) {
  return k < side / 2 ? int(k) : int(k) - int(side);
}

// One length-side DFT, out[k] = sum_x in[x * stride] e^(-2 pi i k x / side).
void dft(const std::complex<double>* in, size_t stride, uint32_t side,
         const std::vector<std::complex<double>>& twiddles, std::complex<double>* out,
         size_t outStride) {
  for (uint32_t k = 0; k < side; ++k) {
    std::complex<double> sum = 0.0;
    for (uint32_t x = 0; x < side; ++x) sum += in[x * stride] * twiddles[(size_t(k) * x) % side];
    out[k * outStride] = sum;
  }
}

// |F(u, v)|^2 of the 2D DFT of the map's values (rank + 0.5) / N with their mean (exactly 0.5 for
// a permutation) removed, row-major by (v, u). Separable: the DFT of every row, then of every
// column of that, 2 side^3 multiply-adds instead of side^4.
std::vector<double> powerSpectrum(const std::vector<uint32_t>& ranks, uint32_t side) {
  const size_t n = ranks.size();
  std::vector<std::complex<double>> twiddles(side);
  for (uint32_t k = 0; k < side; ++k) twiddles[k] = std::polar(1.0, -2.0 * M_PI * k / side);
  std::vector<std::complex<double>> values(n), rows(n), spectrum(n);
  for (size_t i = 0; i < n; ++i) values[i] = (ranks[i] + 0.5) / double(n) - 0.5;
  for (uint32_t y = 0; y < side; ++y)
    dft(&values[size_t(y) * side], 1, side, twiddles, &rows[size_t(y) * side], 1);
  for (uint32_t u = 0; u < side; ++u) dft(&rows[u], side, side, twiddles, &spectrum[u], side);
  std::vector<double> power(n);
  for (size_t i = 0; i < n; ++i) power[i] = std::norm(spectrum[i]);
  return power;
}

// Mean power over the frequencies 0 < |f| <= side/8 (cycles per tile) over the mean power over
// all frequencies but DC: 1 for a flat (white) spectrum, near 0 for blue noise.
double lowFrequencyPowerRatio(const std::vector<uint32_t>& ranks, uint32_t side) {
  const std::vector<double> power = powerSpectrum(ranks, side);
  double lowSum = 0.0, allSum = 0.0;
  size_t lowCount = 0, allCount = 0;
  for (uint32_t v = 0; v < side; ++v) {
    for (uint32_t u = 0; u < side; ++u) {
      if (u == 0 && v == 0) continue;
      const double p = power[size_t(v) * side + u];
      allSum += p;
      ++allCount;
      if (std::hypot(signedFrequency(u, side), signedFrequency(v, side)) <= side / 8.0) {
        lowSum += p;
        ++lowCount;
      }
    }
  }
  return (lowSum / lowCount) / (allSum / allCount);
}

// The power averaged over rings of radius r +- 0.5, relative to the mean power, for r = 1..side/2.
std::vector<double> radialPowerProfile(const std::vector<uint32_t>& ranks, uint32_t side) {
  const std::vector<double> power = powerSpectrum(ranks, side);
  std::vector<double> sum(side / 2 + 1, 0.0), count(side / 2 + 1, 0.0);
  double mean = 0.0;
  for (uint32_t v = 0; v < side; ++v) {
    for (uint32_t u = 0; u < side; ++u) {
      if (u == 0 && v == 0) continue;
      const double p = power[size_t(v) * side + u];
      mean += p / double(power.size() - 1);
      const long ring = std::lround(std::hypot(signedFrequency(u, side), signedFrequency(v, side)));
      if (ring <= long(side / 2)) {
        sum[ring] += p;
        count[ring] += 1.0;
      }
    }
  }
  std::vector<double> profile(side / 2 + 1, 0.0);
  for (size_t r = 1; r < profile.size(); ++r) profile[r] = sum[r] / count[r] / mean;
  return profile;
}

// ---- point sets of a threshold ----------------------------------------------------------------

struct Pixel {
  int x, y;
};

// The pixels with rank < k: what a dither threshold of k/N turns on.
std::vector<Pixel> pixelsBelowRank(const std::vector<uint32_t>& ranks, uint32_t side, uint32_t k) {
  std::vector<Pixel> pixels;
  for (uint32_t i = 0; i < ranks.size(); ++i)
    if (ranks[i] < k) pixels.push_back({int(i % side), int(i / side)});
  return pixels;
}

int ringDistance(int a, int b, int side) {
  const int d = std::abs(a - b);
  return std::min(d, side - d);
}

double minToroidalDistance(const std::vector<Pixel>& pixels, uint32_t side) {
  int minSquared = INT32_MAX;
  for (size_t i = 0; i < pixels.size(); ++i) {
    for (size_t j = i + 1; j < pixels.size(); ++j) {
      const int dx = ringDistance(pixels[i].x, pixels[j].x, int(side));
      const int dy = ringDistance(pixels[i].y, pixels[j].y, int(side));
      minSquared = std::min(minSquared, dx * dx + dy * dy);
    }
  }
  return std::sqrt(double(minSquared));
}

// Pairs of the set that share an edge (distance 1), for the printed diagnostics.
size_t adjacentPairs(const std::vector<uint32_t>& ranks, uint32_t side, uint32_t k) {
  size_t pairs = 0;
  for (uint32_t y = 0; y < side; ++y) {
    for (uint32_t x = 0; x < side; ++x) {
      if (ranks[y * side + x] >= k) continue;
      pairs += ranks[y * side + (x + 1) % side] < k;
      pairs += ranks[((y + 1) % side) * side + x] < k;
    }
  }
  return pairs;
}

// The variance, over all side^2 toroidal positions, of how many pixels of rank < k a
// window x window square holds.
double windowCountVariance(const std::vector<uint32_t>& ranks, uint32_t side, uint32_t k,
                           uint32_t window) {
  double sum = 0.0, sumSquares = 0.0;
  for (uint32_t y0 = 0; y0 < side; ++y0) {
    for (uint32_t x0 = 0; x0 < side; ++x0) {
      double count = 0.0;
      for (uint32_t dy = 0; dy < window; ++dy)
        for (uint32_t dx = 0; dx < window; ++dx)
          count += ranks[((y0 + dy) % side) * side + (x0 + dx) % side] < k;
      sum += count;
      sumSquares += count * count;
    }
  }
  const double positions = double(side) * side;
  const double mean = sum / positions;
  return sumSquares / positions - mean * mean;
}

// The count of a fixed area of A pixels when k of the N pixels are picked uniformly at random
// is hypergeometric: variance A p (1 - p) (N - A) / (N - 1), p = k / N.
double whiteNoiseCountVariance(uint32_t side, uint32_t k, uint32_t window) {
  const double n = double(side) * side, area = double(window) * window, p = k / n;
  return area * p * (1.0 - p) * (n - area) / (n - 1.0);
}

// ---- the tests ---------------------------------------------------------------------------------

TEST(BlueNoise, RanksArePermutations) {
  for (uint32_t side : {4u, 16u, 64u}) {
    const std::vector<uint32_t> ranks = generateBlueNoiseRanks(side, SEED);
    ASSERT_EQ(ranks.size(), size_t(side) * side) << "side " << side;
    EXPECT_TRUE(isPermutation(ranks)) << "side " << side;
  }
}

TEST(BlueNoise, SameSeedSameMapOtherSeedOtherMap) {
  for (uint32_t side : {16u, 64u}) {
    const std::vector<uint32_t> first = generateBlueNoiseRanks(side, SEED);
    EXPECT_EQ(generateBlueNoiseRanks(side, SEED), first) << "side " << side;
    EXPECT_NE(generateBlueNoiseRanks(side, SEED + 1), first) << "side " << side;
  }
}

TEST(BlueNoise, RejectsBadSideAndSigma) {
  // Not powers of two, or outside [4, 256] (2 and 512 are powers of two).
  for (uint32_t side : {0u, 2u, 3u, 48u, 512u}) {
    EXPECT_THROW(generateBlueNoiseRanks(side, SEED), Error) << "side " << side;
    EXPECT_THROW(generateBlueNoise2D(side, SEED), Error) << "side " << side;
  }
  EXPECT_THROW(generateBlueNoiseRanks(16, SEED, 0.0f), Error);
  EXPECT_THROW(generateBlueNoiseRanks(16, SEED, -1.5f), Error);
  EXPECT_THROW(generateBlueNoiseRanks(16, SEED, NAN), Error);
}

// White noise: every frequency but DC has the same expected power (the values of a random
// permutation are exchangeable), so the ratio is 1 up to sampling error. |F|^2 at one frequency
// is about exponentially distributed (relative sd 1), and the disk |f| <= side/8 holds about
// pi (side/8)^2 frequencies, half of them independent (F(-f) = conj F(f)): ~100 at side 64, so
// the white ratio is 1 +- 0.1, and 0.5 is 5 sd below it. Blue noise must remove at least 3/4
// of that low-frequency power (ratio < 0.25, 7.5 sd below white): the suppression the map
// exists for, since a low-frequency error is what a small denoising filter cannot remove.
TEST(BlueNoise, LowFrequencyPowerIsSuppressed) {
  for (uint32_t side : {64u, 128u}) {
    const double blue = lowFrequencyPowerRatio(generateBlueNoiseRanks(side, SEED), side);
    const double white = lowFrequencyPowerRatio(whiteNoiseRanks(side, SEED), side);
    std::printf(
        "[ blue noise ] side %u: power at |f| <= side/8 over mean power: blue %.5f, white %.3f\n",
        side, blue, white);
    EXPECT_LT(blue, 0.25) << "side " << side;
    EXPECT_GT(white, 0.5) << "side " << side;
  }
  const std::vector<double> profile = radialPowerProfile(generateBlueNoiseRanks(64, SEED), 64);
  std::printf("[ blue noise ] side 64 radial power / mean, r = 2, 4, ..., 32:");
  for (size_t r = 2; r < profile.size(); r += 2) std::printf(" %.2f", profile[r]);
  std::printf("\n");
}

// The densest packing of k disks in the torus's area N is hexagonal, so k points at least d apart
// need k (sqrt(3)/2) d^2 <= N: d <= dHex = sqrt(2 N / (sqrt(3) k)). Lagae and Dutre 2008 ("A
// comparison of methods for generating Poisson disk distributions") call d / dHex the relative
// radius of a point set; sets they rate well distributed have about 0.65-0.85, white noise has
// about 0. At k = N/16 we require >= 0.5 (dHex = 4.30, so >= 2.15 px). White noise: 256 of 4096
// pixels have ~ 2 * 4096 * (1/16)^2 = 32 expected edge-sharing pairs, so P(min distance > 1) is
// about e^-32 and its relative radius is 1/4.30 = 0.23.
//
// At N/4 and N/2 the minimum distance cannot tell blue from white noise: at N/2 a set with no
// two 4-neighbours is a maximum independent set of the torus grid, i.e. one colour of the
// checkerboard (the most regular pattern there is, not noise), and a fixed-width filter (sigma
// 1.5 px at every level) leaves some edge-sharing pairs at N/4 as well. What every threshold
// must show instead is stratification: the number of set pixels in any 8x8 window varies much
// less than for random pixels (next test).
TEST(BlueNoise, SparseThresholdKeepsPointsApart) {
  for (uint32_t side : {64u, 128u}) {
    const uint32_t n = side * side, k = n / 16;
    const std::vector<uint32_t> blue = generateBlueNoiseRanks(side, SEED);
    const std::vector<uint32_t> white = whiteNoiseRanks(side, SEED);
    const double hexSpacing = std::sqrt(2.0 * n / (std::sqrt(3.0) * k));
    const double blueDistance = minToroidalDistance(pixelsBelowRank(blue, side, k), side);
    const double whiteDistance = minToroidalDistance(pixelsBelowRank(white, side, k), side);
    std::printf(
        "[ blue noise ] side %u, rank < N/16: min distance blue %.3f, white %.3f (hexagonal "
        "%.3f)\n",
        side, blueDistance, whiteDistance, hexSpacing);
    EXPECT_GE(blueDistance, 0.5 * hexSpacing) << "side " << side;
    EXPECT_LT(whiteDistance, 0.5 * hexSpacing) << "side " << side;
  }
}

// Stratification at the thresholds N/16, N/4 and N/2: for white noise the count in an 8x8 window
// has the hypergeometric variance (whiteNoiseCountVariance). The count is the map filtered by a
// box, so its variance is the power spectrum weighted by the box's low-pass response: the same
// quantity as the spectral test for one threshold, with the same requirement (blue < 1/4 of
// white). The white-noise measurement is checked against its formula (> 1/2 of it): the variance
// over positions of one 64x64 map is a mean over about N/64 = 64 independent windows, relative sd
// about sqrt(2/64) = 0.18, so 1/2 is ~3 sd below. For a well-spread set only the pixels near a
// window's edge make its count vary, so the variance grows with the perimeter rather than the
// area and the blue/white ratio falls roughly like point spacing / window side: N/16 (spacing
// 4 px, two spacings per window) is the threshold with the least reduction.
TEST(BlueNoise, EveryThresholdIsStratified) {
  constexpr uint32_t side = 64, n = side * side, window = 8;
  const std::vector<uint32_t> blue = generateBlueNoiseRanks(side, SEED);
  const std::vector<uint32_t> white = whiteNoiseRanks(side, SEED);
  for (uint32_t k : {n / 16, n / 4, n / 2}) {
    const double expectedWhite = whiteNoiseCountVariance(side, k, window);
    const double blueVariance = windowCountVariance(blue, side, k, window);
    const double whiteVariance = windowCountVariance(white, side, k, window);
    std::printf(
        "[ blue noise ] rank < %u: 8x8 count variance blue %.3f, white %.3f (formula %.3f); "
        "min distance blue %.3f, white %.3f; edge-sharing pairs blue %zu, white %zu\n",
        k, blueVariance, whiteVariance, expectedWhite,
        minToroidalDistance(pixelsBelowRank(blue, side, k), side),
        minToroidalDistance(pixelsBelowRank(white, side, k), side), adjacentPairs(blue, side, k),
        adjacentPairs(white, side, k));
    EXPECT_LT(blueVariance, 0.25 * expectedWhite) << "k " << k;
    EXPECT_GT(whiteVariance, 0.5 * expectedWhite) << "k " << k;
  }
}

// Two channels: each a permutation, different from each other, and uncorrelated. For independent
// random permutations the correlation coefficient has mean 0 and sd 1/sqrt(N - 1) = 0.016 at
// N = 4096. Blue-noise maps have almost no power in the ~20% of frequencies below their cutoff,
// which lowers the effective number of independent terms to ~0.8 N: sd ~0.018, so |r| < 0.1 is
// more than 5 sd, while a channel correlated with the other (say the same map, shifted) would
// show |r| near 1.
TEST(BlueNoise, TwoChannelsAreIndependentPermutations) {
  constexpr uint32_t side = 64, n = side * side;
  const std::vector<uint32_t> packed = generateBlueNoise2D(side, SEED);
  ASSERT_EQ(packed.size(), size_t(n));
  std::vector<uint32_t> first(n), second(n);
  for (uint32_t i = 0; i < n; ++i) {
    first[i] = packed[i] & 0xffffu;
    second[i] = packed[i] >> 16;
  }
  EXPECT_TRUE(isPermutation(first));
  EXPECT_TRUE(isPermutation(second));
  EXPECT_NE(first, second);
  EXPECT_EQ(first, generateBlueNoiseRanks(side, SEED));
  EXPECT_EQ(second, generateBlueNoiseRanks(side, SEED + 1));

  // Both channels are permutations of 0..n-1, so their means and variances are equal and known.
  const double mean = (n - 1) / 2.0, variance = (double(n) * n - 1.0) / 12.0;
  double covariance = 0.0;
  for (uint32_t i = 0; i < n; ++i) covariance += (first[i] - mean) * (second[i] - mean) / n;
  const double correlation = covariance / variance;
  std::printf("[ blue noise ] 2D channels: correlation %.4f\n", correlation);
  EXPECT_LT(std::abs(correlation), 0.1);
}

}  // namespace
}  // namespace bounce
