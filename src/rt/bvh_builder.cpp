// Binned SAH construction after Wald 2007, "On fast construction of SAH-based bounding volume
// hierarchies" (IEEE RT'07): at each node, primitives are dropped into K equal-width bins along
// each axis of their centroid bounds, the K-1 planes between bins are scored with the surface
// area heuristic from prefix/suffix sweeps over the bins, and the range is partitioned at the
// best plane. Per-primitive work is one bin update per axis, so a level costs O(n) and the
// build O(n log n) with small constants. Ranges of at most 8 primitives are split by an exact
// SAH sweep instead of bins.
//
// Threading (all of it invisible in the output, see bvh_builder.h): large ranges are binned by
// several threads at once, and subtrees above a size threshold become tasks on a TaskPool, each
// writing its nodes into its own array; the arrays are spliced into one pre-order array at the
// end.
//
// The box and centroid arithmetic uses SSE, which every x86-64 CPU has.
#include "rt/bvh_builder.h"

#include <immintrin.h>

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <deque>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>

#include "core/error.h"
#include "rt/huge_pages.h"
#include "rt/task_pool.h"

namespace bounce::rt {
namespace {

constexpr uint32_t kMaxBins = 64;
// Child count that marks, while building, a subtree built by another task; `index` is the task.
constexpr uint32_t kSubtreeTaskChild = 0xFFFFFFFFu;
// Inputs smaller than this are built on the calling thread: starting threads costs more.
constexpr uint32_t kMinPrimitivesForThreads = 4 * 1024;
// Ranges at least this large are binned by several threads.
constexpr uint32_t kMinPrimitivesForParallelBinning = 128 * 1024;
constexpr uint32_t kBinningChunk = 32 * 1024;
// Ranges of fewer primitives are binned with at most kFewBins bins: clearing and sweeping the
// bins is most of such a small range's cost, and on `city` the trees' SAH cost stayed within
// 0.05 % (docs/ray-tracing.md, "Build times").
constexpr uint32_t kFewBinsBelow = 32;
constexpr uint32_t kFewBins = 8;
// Bounds of the empty child slot: min > max on every axis, so a slab test that picks the near
// plane by the sign of the ray direction always finds tNear > tFar.
constexpr float kEmptyChildBound = 1e30f;

// ---- boxes in SSE registers -------------------------------------------------------------------

// Axis-aligned box in two SSE registers; lane 3 is unused.
struct Box4 {
  __m128 lower = _mm_set1_ps(std::numeric_limits<float>::infinity());
  __m128 upper = _mm_set1_ps(-std::numeric_limits<float>::infinity());

  void extend(__m128 lo, __m128 hi) {
    lower = _mm_min_ps(lower, lo);
    upper = _mm_max_ps(upper, hi);
  }
  void extend(const Box4& b) { extend(b.lower, b.upper); }
};

glm::vec3 toVec3(__m128 v) {
  alignas(16) float f[4];
  _mm_store_ps(f, v);
  return {f[0], f[1], f[2]};
}

__m128 toM128(const glm::vec3& v) {
  return _mm_setr_ps(v.x, v.y, v.z, 0.0f);
}

// Half the surface area of a non-empty box (the SAH only compares ratios). Lane 3 is masked
// off first: it may hold a primitive index whose bits read as a (slow) denormal float.
float halfArea(const Box4& b) {
  const __m128 xyz = _mm_castsi128_ps(_mm_setr_epi32(-1, -1, -1, 0));
  __m128 d = _mm_sub_ps(_mm_and_ps(b.upper, xyz), _mm_and_ps(b.lower, xyz));
  __m128 products = _mm_mul_ps(d, _mm_shuffle_ps(d, d, _MM_SHUFFLE(3, 0, 2, 1)));  // xy yz zx
  __m128 sum = _mm_add_ss(products, _mm_shuffle_ps(products, products, _MM_SHUFFLE(3, 3, 3, 1)));
  sum = _mm_add_ss(sum, _mm_shuffle_ps(products, products, _MM_SHUFFLE(3, 3, 3, 2)));
  return _mm_cvtss_f32(sum);
}

// The same in double, for the statistics, where an empty box counts as area 0.
double halfArea(const glm::vec3& lo, const glm::vec3& hi) {
  if (lo.x > hi.x) return 0.0;
  double dx = double(hi.x) - lo.x, dy = double(hi.y) - lo.y, dz = double(hi.z) - lo.z;
  return dx * dy + dy * dz + dz * dx;
}

// ---- primitive references ---------------------------------------------------------------------

// One primitive as the builder moves it around: 48 bytes, three aligned SSE loads. The
// primitive's index rides in lane 3 of `lower`, which only ever meets min/max (never
// arithmetic, where its bits could be a slow denormal).
struct alignas(16) PrimRef {
  float lower[3];
  uint32_t index;
  float upper[3];
  float unused0;
  float centroid[3];
  float unused1;

  __m128 lo() const { return _mm_load_ps(lower); }
  __m128 hi() const { return _mm_load_ps(upper); }
  __m128 c() const { return _mm_load_ps(centroid); }
};
static_assert(sizeof(PrimRef) == 48);

// ---- binning (Wald 2007, section 3) -----------------------------------------------------------

// Maps centroids to bins: k = floor(K * (c - min) / extent), clamped to [0, K-1]. An axis whose
// centroid extent is zero (or too small to divide by) gets scale 0, putting everything in bin 0,
// so it never offers a split.
struct BinMapping {
  __m128 origin;
  __m128 scale;
  __m128 lastBin;
  uint32_t binCount = 0;
  bool degenerate = true;  // no axis can split

  BinMapping(const Box4& centroidBounds, uint32_t bins) : binCount(bins) {
    glm::vec3 lo = toVec3(centroidBounds.lower);
    glm::vec3 extent = toVec3(centroidBounds.upper) - lo;
    glm::vec3 s(0.0f);
    for (int axis = 0; axis < 3; ++axis) {
      float axisScale = float(bins) / extent[axis];
      if (extent[axis] > 0.0f && std::isfinite(axisScale)) {
        s[axis] = axisScale;
        degenerate = false;
      }
    }
    origin = toM128(lo);
    scale = toM128(s);
    lastBin = _mm_set1_ps(float(bins - 1));
  }

  // Continuous bin coordinate per axis, in [0, K-1]; its integer part is the bin. Binning and
  // partitioning both go through here, so they never disagree about a primitive's side.
  // (maxps returns its second operand for NaN, so even a NaN lands in bin 0.)
  __m128 binCoordinates(__m128 centroid) const {
    __m128 f = _mm_mul_ps(_mm_sub_ps(centroid, origin), scale);
    return _mm_min_ps(_mm_max_ps(f, _mm_setzero_ps()), lastBin);
  }
};

// One cache line per bin: its box and its count sit together, and a bin's address is a shift
// and an add of the bin index, computed for all three axes in one SSE operation.
struct alignas(64) Bin {
  __m128 lower, upper;
  uint32_t count;
};
static_assert(sizeof(Bin) == 64);

// Only the first binCount bins of each axis are initialised and used: clearing all kMaxBins
// would cost more than binning a small range.
struct Bins {
  Bin bins[3][kMaxBins];

  explicit Bins(uint32_t binCount) {
    const Box4 empty;
    for (int axis = 0; axis < 3; ++axis)
      for (uint32_t b = 0; b < binCount; ++b) {
        bins[axis][b].lower = empty.lower;
        bins[axis][b].upper = empty.upper;
        bins[axis][b].count = 0;
      }
  }
  // Exact (min/max and integer sums), so merging per-thread bins in any order gives the same
  // bins as one thread would.
  void merge(const Bins& other, uint32_t binCount) {
    for (int axis = 0; axis < 3; ++axis)
      for (uint32_t b = 0; b < binCount; ++b) {
        Bin& bin = bins[axis][b];
        const Bin& add = other.bins[axis][b];
        bin.lower = _mm_min_ps(bin.lower, add.lower);
        bin.upper = _mm_max_ps(bin.upper, add.upper);
        bin.count += add.count;
      }
  }
};

void binPrimitive(const PrimRef& ref, const BinMapping& mapping, Bins& bins) {
  constexpr int kBinShift = 6;
  static_assert(sizeof(Bin) == 1 << kBinShift);
  const __m128i axisOffset =
      _mm_setr_epi32(0, kMaxBins * sizeof(Bin), 2 * kMaxBins * sizeof(Bin), 0);
  const __m128i bin = _mm_cvttps_epi32(mapping.binCoordinates(ref.c()));
  alignas(16) int32_t offset[4];  // byte offset of the primitive's bin on each axis
  _mm_store_si128(reinterpret_cast<__m128i*>(offset),
                  _mm_add_epi32(_mm_slli_epi32(bin, kBinShift), axisOffset));
  const __m128 lo = ref.lo(), hi = ref.hi();
  char* base = reinterpret_cast<char*>(bins.bins);
  for (int axis = 0; axis < 3; ++axis) {
    Bin& b = *reinterpret_cast<Bin*>(base + offset[axis]);
    b.lower = _mm_min_ps(b.lower, lo);
    b.upper = _mm_max_ps(b.upper, hi);
    ++b.count;
  }
}

// Neighbouring primitives of a mesh usually fall into the same bins, so each bin update
// would wait for the previous one to reach memory. Large ranges alternate between two sets of
// bins to break that chain.
void binPrimitives(const PrimRef* refs, uint32_t begin, uint32_t end, const BinMapping& mapping,
                   Bins& bins) {
  constexpr uint32_t kMinForTwoSets = 256;
  if (end - begin < kMinForTwoSets) {
    for (uint32_t i = begin; i < end; ++i) binPrimitive(refs[i], mapping, bins);
    return;
  }
  Bins odd(mapping.binCount);
  uint32_t i = begin;
  for (; i + 1 < end; i += 2) {
    binPrimitive(refs[i], mapping, bins);
    binPrimitive(refs[i + 1], mapping, odd);
  }
  if (i < end) binPrimitive(refs[i], mapping, bins);
  bins.merge(odd, mapping.binCount);
}

// ---- choosing a split -------------------------------------------------------------------------

struct SahSplit {
  int axis = -1;  // -1: no valid plane
  uint32_t firstRightBin = 0;
  uint32_t leftCount = 0;
  float cost = std::numeric_limits<float>::infinity();  // A_L * N_L + A_R * N_R
  Box4 leftBounds, rightBounds;
};

// One step of a sweep on all three axes at once: the boxes that step adds on axis 0, 1 and 2,
// transposed so that lane a of each vector belongs to axis a. A step is a bin (binned SAH) or
// one primitive in centroid order (exact SAH).
struct SweepColumn {
  __m128 lowerX, lowerY, lowerZ, upperX, upperY, upperZ;
  __m128i count;
};

// Boxes (lower_a, upper_a) for axes a = 0, 1, 2, with their primitive counts.
SweepColumn makeColumn(__m128 l0, __m128 l1, __m128 l2, __m128 u0, __m128 u1, __m128 u2,
                       __m128i count) {
  __m128 l3 = _mm_setzero_ps(), u3 = _mm_setzero_ps();
  _MM_TRANSPOSE4_PS(l0, l1, l2, l3);
  _MM_TRANSPOSE4_PS(u0, u1, u2, u3);
  return {l0, l1, l2, u0, u1, u2, count};
}

// Running union of sweep columns (lane = axis).
struct ColumnAccumulator {
  __m128 lowerX = _mm_set1_ps(std::numeric_limits<float>::infinity());
  __m128 lowerY = lowerX, lowerZ = lowerX;
  __m128 upperX = _mm_set1_ps(-std::numeric_limits<float>::infinity());
  __m128 upperY = upperX, upperZ = upperX;
  __m128i count = _mm_setzero_si128();

  void add(const SweepColumn& c) {
    lowerX = _mm_min_ps(lowerX, c.lowerX);
    lowerY = _mm_min_ps(lowerY, c.lowerY);
    lowerZ = _mm_min_ps(lowerZ, c.lowerZ);
    upperX = _mm_max_ps(upperX, c.upperX);
    upperY = _mm_max_ps(upperY, c.upperY);
    upperZ = _mm_max_ps(upperZ, c.upperZ);
    count = _mm_add_epi32(count, c.count);
  }
  // Half area times primitive count per axis (NaN where the count is 0; callers mask those).
  __m128 areaTimesCount() const {
    __m128 dx = _mm_sub_ps(upperX, lowerX), dy = _mm_sub_ps(upperY, lowerY),
           dz = _mm_sub_ps(upperZ, lowerZ);
    __m128 area =
        _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dy), _mm_mul_ps(dy, dz)), _mm_mul_ps(dz, dx));
    return _mm_mul_ps(area, _mm_cvtepi32_ps(count));
  }
};

__m128 select(__m128 mask, __m128 ifSet, __m128 ifClear) {
  return _mm_or_ps(_mm_and_ps(mask, ifSet), _mm_andnot_ps(mask, ifClear));
}

struct PlaneChoice {
  int axis = -1;                                        // -1: no valid plane
  uint32_t firstRight = 0;                              // the first column on the right side
  float cost = std::numeric_limits<float>::infinity();  // A_L * N_L + A_R * N_R
};

// Scores the planes between columns: suffix sweep first, then prefix sweep (Wald 2007, 3.2),
// all three axes side by side. Costs are left unnormalised (not divided by the parent's area)
// so a flat or point-like parent needs no special case; absurdly large boxes make them
// infinite, which only means no SAH split is taken. A plane with nothing on one side is
// invalid (this is also how an axis with no centroid extent, all in bin 0, drops out). Ties
// keep the lowest column, then the lowest axis, so the choice is deterministic.
PlaneChoice sweepColumns(const SweepColumn* columns, uint32_t count) {
  __m128 rightCost[kMaxBins];
  __m128i rightCount[kMaxBins];
  ColumnAccumulator right;
  for (uint32_t b = count - 1; b > 0; --b) {
    right.add(columns[b]);
    rightCost[b] = right.areaTimesCount();
    rightCount[b] = right.count;
  }
  const __m128 infinity = _mm_set1_ps(std::numeric_limits<float>::infinity());
  __m128 bestCost = infinity;
  __m128i bestColumn = _mm_setzero_si128();
  ColumnAccumulator left;
  for (uint32_t b = 1; b < count; ++b) {
    left.add(columns[b - 1]);
    __m128 bothSidesUsed =
        _mm_castsi128_ps(_mm_and_si128(_mm_cmpgt_epi32(left.count, _mm_setzero_si128()),
                                       _mm_cmpgt_epi32(rightCount[b], _mm_setzero_si128())));
    __m128 cost = select(bothSidesUsed, _mm_add_ps(left.areaTimesCount(), rightCost[b]), infinity);
    __m128 better = _mm_cmplt_ps(cost, bestCost);
    bestCost = select(better, cost, bestCost);
    bestColumn = _mm_castps_si128(
        select(better, _mm_castsi128_ps(_mm_set1_epi32(int32_t(b))), _mm_castsi128_ps(bestColumn)));
  }
  alignas(16) float costs[4];
  alignas(16) int32_t firstRight[4];
  _mm_store_ps(costs, bestCost);
  _mm_store_si128(reinterpret_cast<__m128i*>(firstRight), bestColumn);
  PlaneChoice best;
  for (int axis = 0; axis < 3; ++axis) {
    if (costs[axis] < best.cost) {
      best.axis = axis;
      best.firstRight = uint32_t(firstRight[axis]);
      best.cost = costs[axis];
    }
  }
  return best;
}

SahSplit findBestSplit(const Bins& bins, const BinMapping& mapping) {
  const uint32_t binCount = mapping.binCount;
  SweepColumn columns[kMaxBins];
  for (uint32_t b = 0; b < binCount; ++b) {
    const Bin &x = bins.bins[0][b], &y = bins.bins[1][b], &z = bins.bins[2][b];
    columns[b] =
        makeColumn(x.lower, y.lower, z.lower, x.upper, y.upper, z.upper,
                   _mm_setr_epi32(int32_t(x.count), int32_t(y.count), int32_t(z.count), 0));
  }
  PlaneChoice plane = sweepColumns(columns, binCount);
  SahSplit best;
  if (plane.axis < 0) return best;
  best.axis = plane.axis;
  best.firstRightBin = plane.firstRight;
  best.cost = plane.cost;
  for (uint32_t b = 0; b < binCount; ++b) {
    const Bin& bin = bins.bins[best.axis][b];
    bool isLeft = b < best.firstRightBin;
    (isLeft ? best.leftBounds : best.rightBounds).extend(bin.lower, bin.upper);
    if (isLeft) best.leftCount += bin.count;
  }
  return best;
}

// Ranges this small skip binning: sorting their centroids per axis and sweeping every plane
// between them (the "full sweep" SAH that binning approximates) is both cheaper than setting
// up bins and exact. It is the binned sweep with one primitive per column.
constexpr uint32_t kMaxExactSahSize = 8;

struct ExactSplit {
  SahSplit sah;
  uint8_t order[kMaxExactSahSize];  // the range's primitives sorted along sah.axis
};

// Two primitives have one possible split; no sorting or sweeping needed.
ExactSplit splitPair(const PrimRef* refs) {
  ExactSplit split;
  split.sah.axis = 0;
  split.sah.leftCount = 1;
  split.sah.leftBounds.extend(refs[0].lo(), refs[0].hi());
  split.sah.rightBounds.extend(refs[1].lo(), refs[1].hi());
  split.sah.cost = halfArea(split.sah.leftBounds) + halfArea(split.sah.rightBounds);
  split.order[0] = 0;
  split.order[1] = 1;
  return split;
}

// Set bits of each byte value: a table, because x86-64's baseline has no popcnt instruction
// (std::popcount became a library call).
constexpr std::array<uint8_t, 256> kBitCount = [] {
  std::array<uint8_t, 256> table{};
  for (uint32_t v = 0; v < 256; ++v) table[v] = uint8_t(std::popcount(v));
  return table;
}();

// Stable sort of n <= 8 keys (padded to 8 with +inf) by counting, for each key, the keys
// below it and the equal keys before it: that count is its place. No data-dependent branches,
// where an insertion sort mispredicts about once per key.
void sortByRank(const float* keys, uint32_t n, uint8_t* order) {
  static_assert(kMaxExactSahSize == 8);
  const __m128 low = _mm_load_ps(keys), high = _mm_load_ps(keys + 4);
  for (uint32_t i = 0; i < n; ++i) {
    const __m128 key = _mm_set1_ps(keys[i]);
    const uint32_t below = uint32_t(_mm_movemask_ps(_mm_cmplt_ps(low, key))) |
                           uint32_t(_mm_movemask_ps(_mm_cmplt_ps(high, key))) << 4;
    const uint32_t equal = uint32_t(_mm_movemask_ps(_mm_cmpeq_ps(low, key))) |
                           uint32_t(_mm_movemask_ps(_mm_cmpeq_ps(high, key))) << 4;
    order[kBitCount[below | (equal & ((1u << i) - 1u))]] = uint8_t(i);
  }
}

ExactSplit findBestExactSplit(const PrimRef* refs, uint32_t n) {
  if (n == 2) return splitPair(refs);
  __m128 lower[kMaxExactSahSize], upper[kMaxExactSahSize];
  // Keys padded with +inf, which no (finite) centroid equals or exceeds.
  alignas(16) float keys[3][kMaxExactSahSize];
  std::fill(&keys[0][0], &keys[0][0] + 3 * kMaxExactSahSize,
            std::numeric_limits<float>::infinity());
  for (uint32_t i = 0; i < n; ++i) {
    lower[i] = refs[i].lo();
    upper[i] = refs[i].hi();
    for (int axis = 0; axis < 3; ++axis) keys[axis][i] = refs[i].centroid[axis];
  }
  uint8_t order[3][kMaxExactSahSize];
  for (int axis = 0; axis < 3; ++axis) sortByRank(keys[axis], n, order[axis]);
  SweepColumn columns[kMaxExactSahSize];
  const __m128i one = _mm_setr_epi32(1, 1, 1, 0);
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t x = order[0][i], y = order[1][i], z = order[2][i];
    columns[i] = makeColumn(lower[x], lower[y], lower[z], upper[x], upper[y], upper[z], one);
  }
  PlaneChoice plane = sweepColumns(columns, n);
  ExactSplit best;
  best.sah.axis = plane.axis;  // always valid: every column holds one primitive
  best.sah.leftCount = plane.firstRight;
  best.sah.cost = plane.cost;
  std::copy(order[plane.axis], order[plane.axis] + n, best.order);
  for (uint32_t i = 0; i < n; ++i) {
    uint32_t k = best.order[i];
    (i < best.sah.leftCount ? best.sah.leftBounds : best.sah.rightBounds)
        .extend(lower[k], upper[k]);
  }
  return best;
}

// Node levels an object-median build needs below a range of n primitives; the depth limit
// is kept by allowing an SAH split only while both halves can still finish this way.
uint32_t medianLevels(uint64_t n, uint32_t maxLeafSize) {
  uint32_t levels = 0;
  while (n > maxLeafSize) {
    n = (n + 1) / 2;
    ++levels;
  }
  return levels;
}

// ---- partitioning -----------------------------------------------------------------------------

// A range of primitives that lives in one of the builder's two PrimRef buffers: partitions
// copy a range from its buffer into the other one.
struct BuildRange {
  uint32_t begin = 0;
  uint32_t end = 0;
  Box4 bounds;          // union of the primitives' boxes
  Box4 centroidBounds;  // bounds of their centroids, which the bins divide
  uint32_t depth = 1;   // depth of the node this range becomes if it is split (root = 1)
  uint32_t buffer = 0;  // which buffer holds the range
  uint32_t size() const { return end - begin; }
};

// Stable partition from src into dst: primitives whose bin on `Axis` lies left of the plane
// go to [begin, begin + leftCount), the others after them. Out of place and without branches
// on the data: an in-place (Hoare) partition mispredicts about every other primitive on
// random input, which cost more than the extra copy. The centroid bounds of both sides are
// gathered on the way, ready for binning the children.
template <int Axis>
void partitionAtPlane(const PrimRef* src, PrimRef* dst, uint32_t begin, uint32_t end,
                      uint32_t leftCount, const BinMapping& mapping, uint32_t firstRightBin,
                      Box4& leftCentroids, Box4& rightCentroids) {
  const __m128 plane = _mm_set1_ps(float(firstRightBin));
  const __m128 posInf = _mm_set1_ps(std::numeric_limits<float>::infinity());
  const __m128 signBit = _mm_set1_ps(-0.0f);
  // Local accumulators stay in registers (the stores through `out` could alias references).
  __m128 leftLower = leftCentroids.lower, leftUpper = leftCentroids.upper;
  __m128 rightLower = rightCentroids.lower, rightUpper = rightCentroids.upper;
  PrimRef* left = dst + begin;
  PrimRef* right = dst + begin + leftCount;
  for (uint32_t i = begin; i < end; ++i) {
    const PrimRef& ref = src[i];
    __m128 c = ref.c();
    // trunc(x) < k  <=>  x < k for x >= 0 and integer k, so this matches the bin index.
    __m128 below = _mm_cmplt_ps(mapping.binCoordinates(c), plane);
    __m128 isLeft = _mm_shuffle_ps(below, below, _MM_SHUFFLE(Axis, Axis, Axis, Axis));
    const uint32_t goesLeft = uint32_t(_mm_movemask_ps(isLeft)) & 1u;
    PrimRef* out = goesLeft ? left : right;
    *out = ref;
    left += goesLeft;
    right += 1u - goesLeft;
    // Branch-free side selection: `away` is -inf on the primitive's side and +inf on the
    // other, so max(c, away) is c or +inf and min(c, -away) is c or -inf.
    __m128 leftAway = _mm_xor_ps(posInf, _mm_and_ps(isLeft, signBit));
    __m128 rightAway = _mm_xor_ps(leftAway, signBit);
    leftLower = _mm_min_ps(leftLower, _mm_max_ps(c, leftAway));
    leftUpper = _mm_max_ps(leftUpper, _mm_min_ps(c, rightAway));
    rightLower = _mm_min_ps(rightLower, _mm_max_ps(c, rightAway));
    rightUpper = _mm_max_ps(rightUpper, _mm_min_ps(c, leftAway));
  }
  leftCentroids = {leftLower, leftUpper};
  rightCentroids = {rightLower, rightUpper};
}

void partitionAtPlane(int axis, const PrimRef* src, PrimRef* dst, uint32_t begin, uint32_t end,
                      uint32_t leftCount, const BinMapping& mapping, uint32_t firstRightBin,
                      Box4& leftCentroids, Box4& rightCentroids) {
  auto run = [&](auto partition) {
    partition(src, dst, begin, end, leftCount, mapping, firstRightBin, leftCentroids,
              rightCentroids);
  };
  if (axis == 0) run(partitionAtPlane<0>);
  if (axis == 1) run(partitionAtPlane<1>);
  if (axis == 2) run(partitionAtPlane<2>);
}

void boundRange(const PrimRef* refs, uint32_t begin, uint32_t end, Box4& bounds,
                Box4& centroidBounds) {
  for (uint32_t i = begin; i < end; ++i) {
    bounds.extend(refs[i].lo(), refs[i].hi());
    centroidBounds.extend(refs[i].c(), refs[i].c());
  }
}

// Fallback when the SAH cannot split (all centroids equal) or would break the depth limit:
// halve the range at the centroid median of its widest axis, or simply by position when all
// centroids coincide. Always makes progress, so degenerate input still terminates.
uint32_t splitAtObjectMedian(PrimRef* refs, const BuildRange& range) {
  uint32_t mid = range.begin + range.size() / 2;
  glm::vec3 extent = toVec3(range.centroidBounds.upper) - toVec3(range.centroidBounds.lower);
  int axis = extent.x >= extent.y ? (extent.x >= extent.z ? 0 : 2) : (extent.y >= extent.z ? 1 : 2);
  if (extent[axis] > 0.0f) {
    std::nth_element(
        refs + range.begin, refs + mid, refs + range.end,
        [axis](const PrimRef& a, const PrimRef& b) { return a.centroid[axis] < b.centroid[axis]; });
  }
  return mid;
}

// ---- output -----------------------------------------------------------------------------------

struct ChildRef {
  Box4 bounds;
  uint32_t index = gpu::BVH_INVALID;
  uint32_t count = 0;
};

void setChild(gpu::GpuBvhNode& node, bool right, const ChildRef& child) {
  glm::vec3 lo = toVec3(child.bounds.lower), hi = toVec3(child.bounds.upper);
  if (right) {
    node.rightMin = lo;
    node.rightMax = hi;
    node.rightIndex = child.index;
    node.rightCount = child.count;
  } else {
    node.leftMin = lo;
    node.leftMax = hi;
    node.leftIndex = child.index;
    node.leftCount = child.count;
  }
}

bool isInteriorChild(uint32_t index, uint32_t count) {
  return count == 0 && index != gpu::BVH_INVALID;
}

// ---- the recursive build ----------------------------------------------------------------------

class Construction {
 public:
  // `refs` holds the input; `scratch` has room for as many PrimRefs.
  Construction(const BvhBuildOptions& options, TaskPool* pool, PrimRef* refs, PrimRef* scratch,
               uint32_t* primitiveOrder, uint32_t primitiveCount)
      : options_(options), pool_(pool), buffers_{refs, scratch}, primitiveOrder_(primitiveOrder) {
    // Enough tasks per thread to balance uneven SAH splits; the threshold does not affect the
    // output, only the schedule.
    if (pool_) {
      uint32_t perTask = primitiveCount / (pool_->threadCount() * 16);
      spawnThreshold_ = std::max<uint32_t>(perTask, 1024);
    }
  }

  std::vector<gpu::GpuBvhNode> build(const BuildRange& root) {
    if (root.size() == 0) {
      gpu::GpuBvhNode node;
      setEmptyChild(node, false);
      setEmptyChild(node, true);
      return {node};
    }
    Subtree& top = subtrees_.emplace_back();
    // A binary tree over n primitives has at most n - 1 interior nodes; reserving that (address
    // space only, until written) avoids regrowing a large array.
    if (!pool_) reserveLarge(top.nodes, root.size());
    ChildRef rootChild = buildRange(top, root, /*mayHandOff=*/false);
    if (pool_) pool_->wait();
    if (!isInteriorChild(rootChild.index, rootChild.count)) {
      // A leaf or empty root still needs a node: the leaf on the left, nothing on the right.
      gpu::GpuBvhNode node;
      setChild(node, false, rootChild);
      setEmptyChild(node, true);
      return {node};
    }
    if (subtrees_.size() == 1) return std::move(top.nodes);  // already in pre-order
    return spliceSubtrees();
  }

 private:
  struct Subtree {
    std::vector<gpu::GpuBvhNode> nodes;  // local pre-order; index 0 is this subtree's root
  };

  ChildRef buildRange(Subtree& out, const BuildRange& range, bool mayHandOff) {
    if (mayHandOff && pool_ && range.size() >= spawnThreshold_) return handOff(range);
    std::optional<std::pair<BuildRange, BuildRange>> halves = split(range);
    if (!halves) return makeLeaf(range);
    uint32_t node = uint32_t(out.nodes.size());
    out.nodes.emplace_back();
    ChildRef left = buildRange(out, halves->first, true);
    ChildRef right = buildRange(out, halves->second, true);
    setChild(out.nodes[node], false, left);
    setChild(out.nodes[node], true, right);
    return {range.bounds, node, 0};
  }

  // Builds the range as another task's subtree; the parent records a placeholder child.
  ChildRef handOff(const BuildRange& range) {
    Subtree* subtree;
    uint32_t id;
    {
      std::lock_guard lock(subtreesMutex_);
      id = uint32_t(subtrees_.size());
      subtree = &subtrees_.emplace_back();
    }
    pool_->submit([this, subtree, range] {
      reserveLarge(subtree->nodes, range.size());
      buildRange(*subtree, range, /*mayHandOff=*/false);
    });
    return {range.bounds, id, kSubtreeTaskChild};
  }

  ChildRef makeLeaf(const BuildRange& range) {
    const PrimRef* refs = buffers_[range.buffer];
    for (uint32_t i = range.begin; i < range.end; ++i) primitiveOrder_[i] = refs[i].index;
    return {range.bounds, range.begin, range.size()};
  }

  // Splits the range, or returns nothing when it should be a leaf. Tiny ranges get an exact
  // SAH sweep; larger ones are binned.
  std::optional<std::pair<BuildRange, BuildRange>> split(const BuildRange& range) {
    const uint32_t n = range.size();
    if (n <= 1) return std::nullopt;
    if (n <= kMaxExactSahSize) {
      ExactSplit exact = findBestExactSplit(buffers_[range.buffer] + range.begin, n);
      switch (decide(exact.sah, range)) {
        case Decision::Leaf:
          return std::nullopt;
        case Decision::Median:
          return medianHalves(range);
        case Decision::Sah:
          return exactHalves(range, exact);
      }
    }
    const uint32_t bins =
        n < kFewBinsBelow ? std::min(kFewBins, options_.binCount) : options_.binCount;
    BinMapping mapping(range.centroidBounds, std::min(bins, n));
    if (mapping.degenerate) {
      if (n <= options_.maxLeafSize) return std::nullopt;
      return medianHalves(range);
    }
    SahSplit sah = findBestSplit(binRange(range, mapping), mapping);
    switch (decide(sah, range)) {
      case Decision::Leaf:
        return std::nullopt;
      case Decision::Median:
        return medianHalves(range);
      case Decision::Sah:
        break;
    }
    return sahHalves(range, mapping, sah);
  }

  enum class Decision { Leaf, Sah, Median };

  // SAH termination (Wald 2007, eq. 1 with C_i = 1): a range that may be a leaf becomes one
  // unless splitting is cheaper. A split that would break the depth limit is replaced by a
  // leaf where allowed, else by an object-median split.
  Decision decide(const SahSplit& sah, const BuildRange& range) const {
    const uint32_t n = range.size();
    const bool leafAllowed = n <= options_.maxLeafSize;
    const float parentArea = halfArea(range.bounds);
    const bool sahPrefersLeaf =
        sah.axis < 0 || options_.traversalCost * parentArea + sah.cost >= float(n) * parentArea;
    if (leafAllowed && sahPrefersLeaf) return Decision::Leaf;
    if (sah.axis < 0 || !withinDepthLimit(sah.leftCount, n - sah.leftCount, range.depth))
      return leafAllowed ? Decision::Leaf : Decision::Median;
    return Decision::Sah;
  }

  // Applies an exact split in place: the range is small, so it stays in its buffer.
  std::pair<BuildRange, BuildRange> exactHalves(const BuildRange& range, const ExactSplit& exact) {
    PrimRef* refs = buffers_[range.buffer] + range.begin;
    const uint32_t n = range.size();
    bool inOrder = true;
    for (uint32_t i = 0; i < n; ++i) inOrder &= exact.order[i] == i;
    if (!inOrder) {
      PrimRef sorted[kMaxExactSahSize];
      for (uint32_t i = 0; i < n; ++i) sorted[i] = refs[exact.order[i]];
      std::copy(sorted, sorted + n, refs);
    }
    BuildRange left, right;
    left.buffer = right.buffer = range.buffer;
    left.begin = range.begin;
    left.end = right.begin = range.begin + exact.sah.leftCount;
    right.end = range.end;
    left.bounds = exact.sah.leftBounds;
    right.bounds = exact.sah.rightBounds;
    // Both halves take the exact path again, which needs no centroid bounds; only the
    // object-median fallback of a half too large for a leaf reads them.
    if (n > options_.maxLeafSize + 1)
      for (uint32_t i = 0; i < n; ++i)
        (i < exact.sah.leftCount ? left : right).centroidBounds.extend(refs[i].c(), refs[i].c());
    left.depth = right.depth = range.depth + 1;
    return {left, right};
  }

  bool withinDepthLimit(uint32_t leftCount, uint32_t rightCount, uint32_t depth) const {
    uint32_t deeper = medianLevels(std::max(leftCount, rightCount), options_.maxLeafSize);
    return depth + deeper <= options_.maxDepth;
  }

  Bins binRange(const BuildRange& range, const BinMapping& mapping) {
    Bins bins(mapping.binCount);
    if (!pool_ || range.size() < kMinPrimitivesForParallelBinning) {
      binPrimitives(buffers_[range.buffer], range.begin, range.end, mapping, bins);
      return bins;
    }
    uint32_t chunks = (range.size() + kBinningChunk - 1) / kBinningChunk;
    std::vector<std::unique_ptr<Bins>> partial(chunks);
    pool_->parallelFor(chunks, [&](uint32_t chunk) {
      uint32_t begin = range.begin + chunk * kBinningChunk;
      uint32_t end = std::min(range.end, begin + kBinningChunk);
      partial[chunk] = std::make_unique<Bins>(mapping.binCount);
      binPrimitives(buffers_[range.buffer], begin, end, mapping, *partial[chunk]);
    });
    for (const auto& p : partial) bins.merge(*p, mapping.binCount);
    return bins;
  }

  std::pair<BuildRange, BuildRange> sahHalves(const BuildRange& range, const BinMapping& mapping,
                                              const SahSplit& sah) {
    BuildRange left, right;
    const uint32_t mid = range.begin + sah.leftCount;
    partitionAtPlane(sah.axis, buffers_[range.buffer], buffers_[1 - range.buffer], range.begin,
                     range.end, sah.leftCount, mapping, sah.firstRightBin, left.centroidBounds,
                     right.centroidBounds);
    left.buffer = right.buffer = 1 - range.buffer;
    left.begin = range.begin;
    left.end = right.begin = mid;
    right.end = range.end;
    left.bounds = sah.leftBounds;
    right.bounds = sah.rightBounds;
    left.depth = right.depth = range.depth + 1;
    return {left, right};
  }

  std::pair<BuildRange, BuildRange> medianHalves(const BuildRange& range) {
    PrimRef* refs = buffers_[range.buffer];
    uint32_t mid = splitAtObjectMedian(refs, range);
    BuildRange left, right;
    left.buffer = right.buffer = range.buffer;
    left.begin = range.begin;
    left.end = right.begin = mid;
    right.end = range.end;
    boundRange(refs, left.begin, left.end, left.bounds, left.centroidBounds);
    boundRange(refs, right.begin, right.end, right.bounds, right.centroidBounds);
    left.depth = right.depth = range.depth + 1;
    return {left, right};
  }

  // Concatenates the subtrees in depth-first pre-order, replacing placeholders with the
  // absolute index of the subtree's root: the same array a single thread would have written.
  std::vector<gpu::GpuBvhNode> spliceSubtrees() {
    size_t total = 0;
    for (const Subtree& s : subtrees_) total += s.nodes.size();
    std::vector<gpu::GpuBvhNode> out;
    reserveLarge(out, total);
    emitNode(out, 0, 0);
    return out;
  }

  uint32_t emitNode(std::vector<gpu::GpuBvhNode>& out, uint32_t subtree, uint32_t local) {
    uint32_t index = uint32_t(out.size());
    out.push_back(subtrees_[subtree].nodes[local]);
    for (bool right : {false, true}) {
      gpu::GpuBvhNode node = out[index];
      uint32_t childIndex = right ? node.rightIndex : node.leftIndex;
      uint32_t childCount = right ? node.rightCount : node.leftCount;
      uint32_t emitted;
      if (childCount == kSubtreeTaskChild)
        emitted = emitNode(out, childIndex, 0);
      else if (isInteriorChild(childIndex, childCount))
        emitted = emitNode(out, subtree, childIndex);
      else
        continue;
      gpu::GpuBvhNode& written = out[index];
      (right ? written.rightIndex : written.leftIndex) = emitted;
      (right ? written.rightCount : written.leftCount) = 0;
    }
    return index;
  }

  const BvhBuildOptions& options_;
  TaskPool* pool_;
  PrimRef* buffers_[2];
  uint32_t* primitiveOrder_;
  uint32_t spawnThreshold_ = std::numeric_limits<uint32_t>::max();
  std::mutex subtreesMutex_;
  std::deque<Subtree> subtrees_;  // deque: handed-off subtrees keep their address
};

// ---- input ------------------------------------------------------------------------------------

void validateOptions(const BvhBuildOptions& options) {
  if (options.maxLeafSize < 1 || options.maxLeafSize > 1024)
    fail("BVH build: maxLeafSize {} outside [1, 1024]", options.maxLeafSize);
  if (options.binCount < 2 || options.binCount > kMaxBins)
    fail("BVH build: binCount {} outside [2, {}]", options.binCount, kMaxBins);
  if (!(options.traversalCost >= 0.0f) || !std::isfinite(options.traversalCost))
    fail("BVH build: traversalCost {} must be finite and >= 0", options.traversalCost);
  if (options.maxDepth < 1 || options.maxDepth > gpu::BVH_STACK_SIZE)
    fail("BVH build: maxDepth {} outside [1, {}]", options.maxDepth, gpu::BVH_STACK_SIZE);
}

struct RootBounds {
  Box4 bounds;
  Box4 centroidBounds;
  uint32_t firstInvalid = std::numeric_limits<uint32_t>::max();
};

// Whether a primitive is valid, without a branch per test: |x| < inf fails for NaN and both
// infinities, and min <= max for NaN too.
bool validPrimitiveSse(__m128 lo, __m128 hi, __m128 c) {
  const __m128 absMask = _mm_castsi128_ps(_mm_set1_epi32(0x7FFFFFFF));
  const __m128 infinity = _mm_set1_ps(std::numeric_limits<float>::infinity());
  __m128 ok = _mm_and_ps(_mm_cmplt_ps(_mm_and_ps(lo, absMask), infinity),
                         _mm_cmplt_ps(_mm_and_ps(hi, absMask), infinity));
  ok = _mm_and_ps(ok, _mm_cmplt_ps(_mm_and_ps(c, absMask), infinity));
  ok = _mm_and_ps(ok, _mm_cmple_ps(lo, hi));
  return (_mm_movemask_ps(ok) & 7) == 7;
}

RootBounds fillPrimRefs(std::span<const Aabb> boxes, std::span<const glm::vec3> centroids,
                        uint32_t begin, uint32_t end, PrimRef* refs) {
  RootBounds result;
  for (uint32_t i = begin; i < end; ++i) {
    const Aabb& box = boxes[i];
    const glm::vec3& c = centroids[i];
    if (!validPrimitiveSse(toM128(box.min), toM128(box.max), toM128(c))) {
      result.firstInvalid = std::min(result.firstInvalid, i);
      continue;
    }
    PrimRef& ref = refs[i];
    ref = PrimRef{{box.min.x, box.min.y, box.min.z},
                  i,
                  {box.max.x, box.max.y, box.max.z},
                  0.0f,
                  {c.x, c.y, c.z},
                  0.0f};
    result.bounds.extend(ref.lo(), ref.hi());
    result.centroidBounds.extend(ref.c(), ref.c());
  }
  return result;
}

// Copies the input into PrimRefs (in parallel for large inputs) and checks it; reports the
// lowest bad index so the message does not depend on scheduling.
RootBounds makePrimRefs(std::span<const Aabb> boxes, std::span<const glm::vec3> centroids,
                        PrimRef* refs, TaskPool* pool) {
  const uint32_t n = uint32_t(boxes.size());
  RootBounds root;
  if (!pool) {
    root = fillPrimRefs(boxes, centroids, 0, n, refs);
  } else {
    uint32_t chunks = (n + kBinningChunk - 1) / kBinningChunk;
    std::vector<RootBounds> partial(chunks);
    pool->parallelFor(chunks, [&](uint32_t chunk) {
      uint32_t begin = chunk * kBinningChunk;
      partial[chunk] =
          fillPrimRefs(boxes, centroids, begin, std::min(n, begin + kBinningChunk), refs);
    });
    for (const RootBounds& p : partial) {
      root.bounds.extend(p.bounds);
      root.centroidBounds.extend(p.centroidBounds);
      root.firstInvalid = std::min(root.firstInvalid, p.firstInvalid);
    }
  }
  if (root.firstInvalid != std::numeric_limits<uint32_t>::max()) {
    uint32_t i = root.firstInvalid;
    fail(
        "BVH build: primitive {} has a NaN, infinite or inverted box ({}, {}, {})..({}, {}, {}) "
        "or centroid ({}, {}, {})",
        i, boxes[i].min.x, boxes[i].min.y, boxes[i].min.z, boxes[i].max.x, boxes[i].max.y,
        boxes[i].max.z, centroids[i].x, centroids[i].y, centroids[i].z);
  }
  return root;
}

}  // namespace

BvhBuildOptions tlasBuildOptions() {
  BvhBuildOptions options;
  options.maxLeafSize = 1;
  return options;
}

void setEmptyChild(gpu::GpuBvhNode& node, bool right) {
  ChildRef empty;
  empty.bounds.lower = _mm_set1_ps(kEmptyChildBound);
  empty.bounds.upper = _mm_set1_ps(-kEmptyChildBound);
  setChild(node, right, empty);
}

BvhBuildStats measureBvh(std::span<const gpu::GpuBvhNode> nodes, uint32_t root,
                         float traversalCost) {
  BvhBuildStats stats;
  if (nodes.empty()) return stats;
  struct Visit {
    uint32_t node;
    uint32_t depth;
  };
  auto nodeArea = [&](const gpu::GpuBvhNode& n) {
    bool leftEmpty = n.leftMin.x > n.leftMax.x, rightEmpty = n.rightMin.x > n.rightMax.x;
    glm::vec3 lo = leftEmpty    ? n.rightMin
                   : rightEmpty ? n.leftMin
                                : glm::min(n.leftMin, n.rightMin);
    glm::vec3 hi = leftEmpty    ? n.rightMax
                   : rightEmpty ? n.leftMax
                                : glm::max(n.leftMax, n.rightMax);
    return halfArea(lo, hi);
  };
  const double rootArea = nodeArea(nodes[root]);
  double weightedNodes = 0.0, weightedPrimitives = 0.0;
  std::vector<Visit> stack{{root, 1}};
  while (!stack.empty()) {
    Visit v = stack.back();
    stack.pop_back();
    const gpu::GpuBvhNode& n = nodes[v.node];
    ++stats.nodeCount;
    stats.maxDepth = std::max(stats.maxDepth, v.depth);
    weightedNodes += nodeArea(n);
    for (bool right : {false, true}) {
      uint32_t index = right ? n.rightIndex : n.leftIndex;
      uint32_t count = right ? n.rightCount : n.leftCount;
      if (count > 0) {
        ++stats.leafCount;
        stats.primitiveCount += count;
        weightedPrimitives +=
            count * (right ? halfArea(n.rightMin, n.rightMax) : halfArea(n.leftMin, n.leftMax));
      } else if (index != gpu::BVH_INVALID) {
        stack.push_back({index, v.depth + 1});
      }
    }
  }
  if (rootArea > 0.0)
    stats.sahCost = (traversalCost * weightedNodes + weightedPrimitives) / rootArea;
  return stats;
}

namespace {

// measureBvh for the builder's own output, which lists every node of one tree in depth-first
// pre-order from node 0: a parent precedes its children, so one pass in array order can
// carry depths down, with no stack. Same sums as measureBvh, added in another order.
BvhBuildStats measurePreOrderTree(std::span<const gpu::GpuBvhNode> nodes, float traversalCost) {
  BvhBuildStats stats;
  if (nodes.empty()) return stats;
  std::vector<uint8_t> depth(nodes.size());
  depth[0] = 1;
  double weightedNodes = 0.0, weightedPrimitives = 0.0, rootArea = 0.0;
  for (size_t i = 0; i < nodes.size(); ++i) {
    const gpu::GpuBvhNode& n = nodes[i];
    const bool leftEmpty = n.leftMin.x > n.leftMax.x, rightEmpty = n.rightMin.x > n.rightMax.x;
    const glm::vec3 lo = leftEmpty    ? n.rightMin
                         : rightEmpty ? n.leftMin
                                      : glm::min(n.leftMin, n.rightMin);
    const glm::vec3 hi = leftEmpty    ? n.rightMax
                         : rightEmpty ? n.leftMax
                                      : glm::max(n.leftMax, n.rightMax);
    const double area = halfArea(lo, hi);
    if (i == 0) rootArea = area;
    weightedNodes += area;
    stats.maxDepth = std::max<uint32_t>(stats.maxDepth, depth[i]);
    if (n.leftCount > 0) {
      ++stats.leafCount;
      stats.primitiveCount += n.leftCount;
      weightedPrimitives += n.leftCount * halfArea(n.leftMin, n.leftMax);
    } else if (n.leftIndex != gpu::BVH_INVALID) {
      depth[n.leftIndex] = uint8_t(depth[i] + 1);
    }
    if (n.rightCount > 0) {
      ++stats.leafCount;
      stats.primitiveCount += n.rightCount;
      weightedPrimitives += n.rightCount * halfArea(n.rightMin, n.rightMax);
    } else if (n.rightIndex != gpu::BVH_INVALID) {
      depth[n.rightIndex] = uint8_t(depth[i] + 1);
    }
  }
  stats.nodeCount = uint32_t(nodes.size());
  if (rootArea > 0.0)
    stats.sahCost = (traversalCost * weightedNodes + weightedPrimitives) / rootArea;
  return stats;
}

}  // namespace

void BvhScratch::Free::operator()(void* p) const {
  std::free(p);
}

void* BvhScratch::reserve(size_t bytes) {
  if (bytes <= bytes_ && block_) return block_.get();
  constexpr size_t kAlign = 64;
  const size_t rounded = std::max<size_t>(kAlign, (bytes + kAlign - 1) / kAlign * kAlign);
  block_.reset();
  block_.reset(std::aligned_alloc(kAlign, rounded));
  if (!block_) throw std::bad_alloc();
  bytes_ = rounded;
  adviseHugePages(block_.get(), rounded);
  return block_.get();
}

Bvh buildBvh(std::span<const Aabb> boxes, std::span<const glm::vec3> centroids,
             const BvhBuildOptions& options, BvhScratch* scratchMemory) {
  const auto start = std::chrono::steady_clock::now();
  validateOptions(options);
  if (boxes.size() != centroids.size())
    fail("BVH build: {} boxes but {} centroids", boxes.size(), centroids.size());
  if (boxes.size() >= gpu::BVH_INVALID)
    fail("BVH build: {} primitives exceed the 32-bit index range", boxes.size());
  const uint32_t n = uint32_t(boxes.size());
  if (medianLevels(n, options.maxLeafSize) > options.maxDepth)
    fail("BVH build: {} primitives with leaves of {} need a depth over the limit {}", n,
         options.maxLeafSize, options.maxDepth);

  uint32_t threads =
      options.threadCount ? options.threadCount : std::max(1u, std::thread::hardware_concurrency());
  if (n < kMinPrimitivesForThreads) threads = 1;
  std::optional<TaskPool> pool;
  if (threads > 1) pool.emplace(threads);
  TaskPool* poolPtr = pool ? &*pool : nullptr;

  // Uninitialised on purpose: makePrimRefs writes every element of `refs`, and the
  // partitions write `scratch` before reading it.
  BvhScratch ownMemory;
  PrimRef* refs = static_cast<PrimRef*>(
      (scratchMemory ? scratchMemory : &ownMemory)->reserve(2 * sizeof(PrimRef) * size_t(n)));
  PrimRef* scratch = refs + n;
  RootBounds root = makePrimRefs(boxes, centroids, refs, poolPtr);

  Bvh bvh;
  reserveLarge(bvh.primitiveOrder, n);
  bvh.primitiveOrder.resize(n);
  BuildRange rootRange;
  rootRange.begin = 0;
  rootRange.end = n;
  rootRange.bounds = root.bounds;
  rootRange.centroidBounds = root.centroidBounds;
  Construction construction(options, poolPtr, refs, scratch, bvh.primitiveOrder.data(), n);
  bvh.nodes = construction.build(rootRange);

  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (options.measureTree) bvh.stats = measurePreOrderTree(bvh.nodes, options.traversalCost);
  bvh.stats.primitiveCount = n;
  bvh.stats.nodeCount = uint32_t(bvh.nodes.size());
  bvh.stats.seconds = seconds;
  bvh.stats.primitivesPerSecond = seconds > 0.0 ? n / seconds : 0.0;
  bvh.stats.threadsUsed = threads;
  return bvh;
}

}  // namespace bounce::rt
