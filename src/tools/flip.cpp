// FLIP and HDR-FLIP; see flip.h for the papers. Comments name the part of [FLIP] (its colour
// pipeline, feature pipeline, final difference) or [HDRFLIP] each step follows. Images are
// processed as float planes; every 2D filter is separable, so a 1080p pair costs a few hundred
// multiply-adds per pixel per pass.
#include "tools/flip.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "core/error.h"
#include "core/parallel_for.h"
#include "tools/color_space.h"

namespace bounce {
namespace {

constexpr float kPi = 3.14159265358979f;

// ---- Constants ---------------------------------------------------------------------------------

// [FLIP] colour pipeline, spatial filtering: the contrast sensitivity function of each opponent
// channel, in the spatial domain, is a sum of two Gaussians of the visual angle x (degrees),
//   S(x) = a1 sqrt(pi/b1) exp(-pi^2 x^2 / b1) + a2 sqrt(pi/b2) exp(-pi^2 x^2 / b2),
// with the paper's fitted constants. Achromatic and red-green need one Gaussian (a2 = 0).
struct GaussianSum {
  float a1, b1, a2, b2;
};
constexpr GaussianSum kAchromaticCsf{1.0f, 0.0047f, 0.0f, 1e-5f};
constexpr GaussianSum kRedGreenCsf{1.0f, 0.0053f, 0.0f, 1e-5f};
constexpr GaussianSum kBlueYellowCsf{34.1f, 0.04f, 13.5f, 0.025f};
// The filters reach 3 standard deviations of the widest Gaussian; exp(-pi^2 x^2 / b) has
// variance b / (2 pi^2).
constexpr float kWidestCsfScale = 0.04f;

// [FLIP] colour pipeline, colour metric: the HyAB distance is raised to qc, then errors below
// pc * cmax are mapped linearly onto [0, pt] and the rest onto (pt, 1], so that most of the
// range is spent on small, common differences.
constexpr float kColorExponent = 0.7f;        // qc
constexpr float kColorCompressStart = 0.4f;   // pc
constexpr float kColorCompressValue = 0.95f;  // pt

// [FLIP] feature pipeline: edge and point detectors are the first and second derivatives of a
// Gaussian whose peak-to-trough distance (2 sigma) matches the w = 0.082 degree width of the
// human edge detector; the feature difference is raised to qf.
constexpr float kFeatureWidthDegrees = 0.082f;  // w
constexpr float kFeatureExponent = 0.5f;        // qf

// [FLIP] colour pipeline: the Hunt effect (chroma looks weaker at low luminance) is modelled by
// scaling a* and b* by 0.01 L*.
constexpr float kHuntScale = 0.01f;

// [HDRFLIP], computing start and stop exposures: the exposure range is placed so that the
// reference's brightest pixel and its median pixel each reach this tone-mapped value at one end of
// the range.
constexpr double kExposureTarget = 0.85;
// A sanity bound: 64 stops is far beyond any rendered image's dynamic range.
constexpr int kMaxExposures = 64;

// ITU-R BT.709 relative luminance of linear RGB.
float luminance(const glm::vec3& rgb) {
  return 0.2126f * rgb.x + 0.7152f * rgb.y + 0.0722f * rgb.z;
}

// ---- Planes and separable filtering ------------------------------------------------------------

struct Plane {
  int width = 0;
  int height = 0;
  std::vector<float> values;

  Plane(int w, int h) : width(w), height(h), values(size_t(w) * size_t(h), 0.0f) {}
  float* row(int y) { return values.data() + size_t(y) * width; }
  const float* row(int y) const { return values.data() + size_t(y) * width; }
};

// A linear RGB image in [0,1], the input of LDR-FLIP.
struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<glm::vec3> rgb;
};

using Kernel = std::vector<float>;  // odd length, centred on the middle tap

int kernelRadius(const Kernel& kernel) {
  return int(kernel.size() / 2);
}

// Correlates every row with `kernel`, repeating the edge pixels beyond the border.
Plane filterRows(const Plane& in, const Kernel& kernel) {
  const int radius = kernelRadius(kernel);
  Plane out(in.width, in.height);
  parallelForRows(in.height, [&](int rowBegin, int rowEnd) {
    std::vector<float> padded(size_t(in.width) + 2 * radius);
    for (int y = rowBegin; y < rowEnd; ++y) {
      const float* src = in.row(y);
      for (int i = 0; i < int(padded.size()); ++i)
        padded[i] = src[std::clamp(i - radius, 0, in.width - 1)];
      float* dst = out.row(y);
      for (size_t tap = 0; tap < kernel.size(); ++tap) {
        const float weight = kernel[tap];
        const float* shifted = padded.data() + tap;
        for (int x = 0; x < in.width; ++x) dst[x] += weight * shifted[x];
      }
    }
  });
  return out;
}

// Correlates every column with `kernel`, repeating the edge rows beyond the border.
Plane filterColumns(const Plane& in, const Kernel& kernel) {
  const int radius = kernelRadius(kernel);
  Plane out(in.width, in.height);
  parallelForRows(in.height, [&](int rowBegin, int rowEnd) {
    for (int y = rowBegin; y < rowEnd; ++y) {
      float* dst = out.row(y);
      for (size_t tap = 0; tap < kernel.size(); ++tap) {
        const float weight = kernel[tap];
        const float* src = in.row(std::clamp(y + int(tap) - radius, 0, in.height - 1));
        for (int x = 0; x < in.width; ++x) dst[x] += weight * src[x];
      }
    }
  });
  return out;
}

// Runs perPixel(index) for every pixel of a width x height image, in row bands on a few threads.
template <typename PerPixel>
void forEachPixel(int width, int height, PerPixel&& perPixel) {
  parallelForRows(height, [&](int rowBegin, int rowEnd) {
    for (size_t i = size_t(rowBegin) * width; i < size_t(rowEnd) * width; ++i) perPixel(i);
  });
}

void addInPlace(Plane& sum, const Plane& term) {
  for (size_t i = 0; i < sum.values.size(); ++i) sum.values[i] += term.values[i];
}

// ---- Colour pipeline ---------------------------------------------------------------------------

struct OpponentImage {  // YCxCz planes
  Plane y, cx, cz;
};

OpponentImage toOpponent(const RgbImage& image) {
  OpponentImage out{Plane(image.width, image.height), Plane(image.width, image.height),
                    Plane(image.width, image.height)};
  forEachPixel(image.width, image.height, [&](size_t i) {
    const glm::vec3 o = color::xyzToYCxCz(color::linearRgbToXyz(image.rgb[i]));
    out.y.values[i] = o.x;
    out.cx.values[i] = o.y;
    out.cz.values[i] = o.z;
  });
  return out;
}

int csfFilterRadius(float pixelsPerDegree) {
  const float sigmaDegrees = std::sqrt(kWidestCsfScale / (2.0f * kPi * kPi));
  return int(std::ceil(3.0f * sigmaDegrees * pixelsPerDegree));
}

// The 2D CSF filter of one channel, sum_i w_i exp(-pi^2 (x^2 + y^2) / b_i) normalised to unit
// sum, is a sum of separable terms. Returns one 1D kernel u_i per Gaussian such that the 2D
// filter is sum_i u_i(x) u_i(y): u_i = sqrt(w_i / total) g_i with total = sum_i w_i (sum g_i)^2.
std::vector<Kernel> csfKernels(const GaussianSum& csf, float pixelsPerDegree) {
  const int radius = csfFilterRadius(pixelsPerDegree);
  std::vector<Kernel> kernels;
  std::vector<double> weights;
  double total = 0.0;
  for (const auto& [a, b] : {std::pair{csf.a1, csf.b1}, std::pair{csf.a2, csf.b2}}) {
    if (a == 0.0f) continue;
    Kernel g(2 * radius + 1);
    double sum = 0.0;
    for (int i = -radius; i <= radius; ++i) {
      const double x = i / double(pixelsPerDegree);
      g[i + radius] = float(std::exp(-double(kPi) * kPi * x * x / b));
      sum += g[i + radius];
    }
    const double weight = a * std::sqrt(kPi / b);
    total += weight * sum * sum;
    kernels.push_back(std::move(g));
    weights.push_back(weight);
  }
  for (size_t k = 0; k < kernels.size(); ++k) {
    const float scale = float(std::sqrt(weights[k] / total));
    for (float& w : kernels[k]) w *= scale;
  }
  return kernels;
}

struct CsfFilters {
  std::vector<Kernel> achromatic, redGreen, blueYellow;
};

Plane applyCsf(const Plane& channel, const std::vector<Kernel>& kernels) {
  Plane sum(channel.width, channel.height);
  for (const Kernel& kernel : kernels)
    addInPlace(sum, filterColumns(filterRows(channel, kernel), kernel));
  return sum;
}

OpponentImage applyCsf(const OpponentImage& image, const CsfFilters& filters) {
  return {applyCsf(image.y, filters.achromatic), applyCsf(image.cx, filters.redGreen),
          applyCsf(image.cz, filters.blueYellow)};
}

glm::vec3 huntAdjust(const glm::vec3& lab) {
  return {lab.x, kHuntScale * lab.x * lab.y, kHuntScale * lab.x * lab.z};
}

// HyAB [Abasi et al. 2020]: city-block in lightness plus Euclidean in chroma, better than
// Euclidean CIELAB for the large differences rendering errors produce.
float hyab(const glm::vec3& a, const glm::vec3& b) {
  return std::abs(a.x - b.x) + glm::length(glm::vec2(a.y - b.y, a.z - b.z));
}

glm::vec3 linearRgbToHuntLab(const glm::vec3& rgb) {
  return huntAdjust(color::xyzToCielab(color::linearRgbToXyz(rgb)));
}

// [FLIP] cmax: the largest distance in the colour space, between pure green and pure blue.
float maxColorDifference() {
  const float distance =
      hyab(linearRgbToHuntLab({0.0f, 1.0f, 0.0f}), linearRgbToHuntLab({0.0f, 0.0f, 1.0f}));
  return std::pow(distance, kColorExponent);
}

float compressColorDifference(float distance, float cmax) {
  const float d = std::pow(distance, kColorExponent);
  const float knee = kColorCompressStart * cmax;
  if (d < knee) return d * kColorCompressValue / knee;
  return kColorCompressValue + (d - knee) / (cmax - knee) * (1.0f - kColorCompressValue);
}

// Filtered YCxCz back to linear RGB, clamped to the displayable cube (filtering can leave it),
// then to Hunt-adjusted CIELAB.
glm::vec3 filteredToHuntLab(const OpponentImage& image, size_t i) {
  const glm::vec3 yCxCz(image.y.values[i], image.cx.values[i], image.cz.values[i]);
  const glm::vec3 rgb = glm::clamp(color::xyzToLinearRgb(color::yCxCzToXyz(yCxCz)), 0.0f, 1.0f);
  return linearRgbToHuntLab(rgb);
}

Plane colorDifference(const OpponentImage& reference, const OpponentImage& test) {
  const float cmax = maxColorDifference();
  Plane out(reference.y.width, reference.y.height);
  forEachPixel(out.width, out.height, [&](size_t i) {
    const float distance = hyab(filteredToHuntLab(reference, i), filteredToHuntLab(test, i));
    out.values[i] = compressColorDifference(distance, cmax);
  });
  return out;
}

// ---- Feature pipeline --------------------------------------------------------------------------

struct FeatureKernels {
  Kernel gaussian;          // sums to 1
  Kernel firstDerivative;   // edges: positive and negative lobes each sum to +-1
  Kernel secondDerivative;  // points: likewise
};

// Scales the positive taps to sum to 1 and the negative ones to -1, so a detector answers 0 on
// flat regions and at most 1 on a full black-white step ([FLIP] feature pipeline).
void normalizeLobes(Kernel& kernel) {
  float positive = 0.0f, negative = 0.0f;
  for (float w : kernel) (w > 0.0f ? positive : negative) += std::abs(w);
  for (float& w : kernel) w /= (w > 0.0f ? positive : negative);
}

FeatureKernels featureKernels(float pixelsPerDegree) {
  const float sigma = 0.5f * kFeatureWidthDegrees * pixelsPerDegree;
  const int radius = int(std::ceil(3.0f * sigma));
  FeatureKernels k{Kernel(2 * radius + 1), Kernel(2 * radius + 1), Kernel(2 * radius + 1)};
  for (int i = -radius; i <= radius; ++i) {
    const float x = float(i);
    const float g = std::exp(-x * x / (2.0f * sigma * sigma));
    k.gaussian[i + radius] = g;
    k.firstDerivative[i + radius] = -x * g;
    k.secondDerivative[i + radius] = (x * x / (sigma * sigma) - 1.0f) * g;
  }
  const float sum = std::accumulate(k.gaussian.begin(), k.gaussian.end(), 0.0f);
  for (float& w : k.gaussian) w /= sum;
  normalizeLobes(k.firstDerivative);
  normalizeLobes(k.secondDerivative);
  return k;
}

// The achromatic channel of YCxCz rescaled to [0,1] (which is relative luminance Y / Yn).
Plane normalizedAchromatic(const Plane& y) {
  Plane out(y.width, y.height);
  for (size_t i = 0; i < y.values.size(); ++i) out.values[i] = (y.values[i] + 16.0f) / 116.0f;
  return out;
}

struct FeatureMagnitudes {
  Plane edge, point;  // gradient magnitude of the edge and point detector responses
};

// The 2D detectors are derivative-of-Gaussian in one axis times Gaussian in the other, so each
// of the four responses is two 1D passes; the row passes are shared.
FeatureMagnitudes detectFeatures(const Plane& achromatic, const FeatureKernels& k) {
  const Plane rowsGaussian = filterRows(achromatic, k.gaussian);
  const Plane dx = filterColumns(filterRows(achromatic, k.firstDerivative), k.gaussian);
  const Plane ddx = filterColumns(filterRows(achromatic, k.secondDerivative), k.gaussian);
  const Plane dy = filterColumns(rowsGaussian, k.firstDerivative);
  const Plane ddy = filterColumns(rowsGaussian, k.secondDerivative);
  FeatureMagnitudes out{Plane(achromatic.width, achromatic.height),
                        Plane(achromatic.width, achromatic.height)};
  forEachPixel(achromatic.width, achromatic.height, [&](size_t i) {
    out.edge.values[i] = std::sqrt(dx.values[i] * dx.values[i] + dy.values[i] * dy.values[i]);
    out.point.values[i] = std::sqrt(ddx.values[i] * ddx.values[i] + ddy.values[i] * ddy.values[i]);
  });
  return out;
}

// [FLIP] feature pipeline: the larger of the edge and point differences, scaled by 1/sqrt(2)
// (the largest possible gradient magnitude difference) and raised to qf.
Plane featureDifference(const FeatureMagnitudes& reference, const FeatureMagnitudes& test) {
  Plane out(reference.edge.width, reference.edge.height);
  const float normalization = 1.0f / std::sqrt(2.0f);
  forEachPixel(out.width, out.height, [&](size_t i) {
    const float edge = std::abs(reference.edge.values[i] - test.edge.values[i]);
    const float point = std::abs(reference.point.values[i] - test.point.values[i]);
    out.values[i] = std::pow(normalization * std::max(edge, point), kFeatureExponent);
  });
  return out;
}

// ---- LDR-FLIP ----------------------------------------------------------------------------------

// [FLIP] final difference: feature differences amplify colour differences, E = Ec^(1 - Ef).
std::vector<float> ldrFlipErrorMap(const RgbImage& reference, const RgbImage& test,
                                   float pixelsPerDegree) {
  const CsfFilters csf{csfKernels(kAchromaticCsf, pixelsPerDegree),
                       csfKernels(kRedGreenCsf, pixelsPerDegree),
                       csfKernels(kBlueYellowCsf, pixelsPerDegree)};
  const OpponentImage referenceOpponent = toOpponent(reference);
  const OpponentImage testOpponent = toOpponent(test);
  const Plane color =
      colorDifference(applyCsf(referenceOpponent, csf), applyCsf(testOpponent, csf));

  const FeatureKernels features = featureKernels(pixelsPerDegree);
  const Plane feature =
      featureDifference(detectFeatures(normalizedAchromatic(referenceOpponent.y), features),
                        detectFeatures(normalizedAchromatic(testOpponent.y), features));

  std::vector<float> error(color.values.size());
  forEachPixel(color.width, color.height,
               [&](size_t i) { error[i] = std::pow(color.values[i], 1.0f - feature.values[i]); });
  return error;
}

void requireSameSize(const ImageRGBA32F& test, const ImageRGBA32F& reference) {
  if (test.width != reference.width || test.height != reference.height) {
    fail("FLIP: the test image is {}x{} but the reference is {}x{}", test.width, test.height,
         reference.width, reference.height);
  }
  if (test.pixelCount() == 0) fail("FLIP: the images are empty");
}

void requirePixelsPerDegree(float pixelsPerDegree) {
  if (!(pixelsPerDegree > 0.0f && pixelsPerDegree <= 1000.0f)) {
    fail("FLIP: pixels per degree must be in (0, 1000], got {}", pixelsPerDegree);
  }
}

// `transform` maps a linear input channel value to the [0,1] value LDR-FLIP sees.
template <typename Transform>
RgbImage toFlipInput(const ImageRGBA32F& image, Transform&& transform) {
  RgbImage out{image.width, image.height, std::vector<glm::vec3>(image.pixelCount())};
  forEachPixel(image.width, image.height, [&](size_t i) {
    for (int c = 0; c < 3; ++c) {
      const float v = transform(image.pixels[4 * i + c]);
      out.rgb[i][c] = v > 0.0f ? std::min(v, 1.0f) : 0.0f;  // also maps NaN to 0
    }
  });
  return out;
}

// The upper median (the element at index n/2 once sorted); `values` is reordered.
float medianOf(std::vector<float>& values) {
  const auto middle = values.begin() + values.size() / 2;
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

// The input the tone curve maps to `target`: solves the curve's rational form for x.
double acesInputFor(double target) {
  // acesToneMap(x) = (p2 x^2 + p1 x) / (q2 x^2 + q1 x + q0) with Narkowicz's constants and the
  // 0.6 pre-scale folded in.
  const double p2 = 0.36 * 2.51, p1 = 0.6 * 0.03, q2 = 0.36 * 2.43, q1 = 0.6 * 0.59, q0 = 0.14;
  const double a = p2 - target * q2, b = p1 - target * q1, c = -target * q0;
  return (-b + std::sqrt(b * b - 4.0 * a * c)) / (2.0 * a);
}

}  // namespace

float acesToneMap(float x) {
  // Narkowicz 2015, "ACES Filmic Tone Mapping Curve", with his 0.6 pre-exposure.
  const float v = 0.6f * x;
  return (v * (2.51f * v + 0.03f)) / (v * (2.43f * v + 0.59f) + 0.14f);
}

FlipStatistics poolFlipErrors(const std::vector<float>& errorMap) {
  FlipStatistics stats;
  if (errorMap.empty()) return stats;
  std::vector<float> sorted = errorMap;
  std::sort(sorted.begin(), sorted.end());
  double sum = 0.0;
  for (float e : sorted) sum += e;
  stats.mean = sum / double(sorted.size());
  stats.min = sorted.front();
  stats.max = sorted.back();
  // Weighted percentile as the FLIP tool defines it: the first error value, in increasing
  // order, at which the running sum of errors exceeds the fraction p of their total.
  const auto weightedPercentile = [&](double p) {
    double running = 0.0;
    for (float e : sorted) {
      running += e;
      if (running > p * sum) return double(e);
    }
    return 0.0;  // all errors are zero
  };
  stats.weightedMedian = weightedPercentile(0.5);
  stats.firstWeightedQuartile = weightedPercentile(0.25);
  stats.thirdWeightedQuartile = weightedPercentile(0.75);
  return stats;
}

FlipExposureRange automaticExposureRange(const ImageRGBA32F& reference) {
  std::vector<float> luminances(reference.pixelCount());
  float maxLuminance = 0.0f;
  for (size_t i = 0; i < luminances.size(); ++i) {
    const float* p = &reference.pixels[4 * i];
    luminances[i] = luminance({p[0], p[1], p[2]});
    maxLuminance = std::max(maxLuminance, luminances[i]);
  }
  if (!(maxLuminance > 0.0f) || !std::isfinite(maxLuminance)) return {0.0f, 0.0f, 2};  // black
  // The upper median of all pixels, as the authors' tool takes it. When more than half of the
  // image is black (their tool's range would end at +infinity) we take the median of the lit
  // pixels instead.
  float medianLuminance = medianOf(luminances);
  if (!(medianLuminance > 0.0f)) {
    std::erase_if(luminances, [](float y) { return !(y > 0.0f); });
    medianLuminance = medianOf(luminances);
  }
  const double x85 = acesInputFor(kExposureTarget);
  FlipExposureRange range;
  range.start = float(std::log2(x85 / maxLuminance));
  range.stop = float(std::log2(x85 / medianLuminance));
  range.count = std::max(2, int(std::ceil(range.stop - range.start)));
  return range;
}

FlipResult computeLdrFlip(const ImageRGBA32F& test, const ImageRGBA32F& reference,
                          float pixelsPerDegree) {
  requireSameSize(test, reference);
  requirePixelsPerDegree(pixelsPerDegree);
  const auto identity = [](float v) { return v; };
  FlipResult result{test.width, test.height, {}, {}, std::nullopt};
  result.errorMap = ldrFlipErrorMap(toFlipInput(reference, identity), toFlipInput(test, identity),
                                    pixelsPerDegree);
  result.statistics = poolFlipErrors(result.errorMap);
  return result;
}

FlipResult computeHdrFlip(const ImageRGBA32F& test, const ImageRGBA32F& reference,
                          float pixelsPerDegree, std::optional<FlipExposureRange> exposures) {
  requireSameSize(test, reference);
  requirePixelsPerDegree(pixelsPerDegree);
  const FlipExposureRange range = exposures ? *exposures : automaticExposureRange(reference);
  if (range.count < 1 || range.count > kMaxExposures || !(range.start <= range.stop)) {
    fail(
        "HDR-FLIP: cannot evaluate exposures {} to {} in {} steps (at most {} steps; an automatic "
        "range spans one step per stop between the reference's brightest and median pixel)",
        range.start, range.stop, range.count, kMaxExposures);
  }
  FlipResult result{
      test.width, test.height, std::vector<float>(test.pixelCount(), 0.0f), {}, range};
  const float step = range.count > 1 ? (range.stop - range.start) / float(range.count - 1) : 0.0f;
  // [HDRFLIP]: LDR-FLIP of the tone-mapped pair at each exposure; a pixel's error is its
  // largest error over the exposures.
  for (int i = 0; i < range.count; ++i) {
    const float scale = std::exp2(range.start + float(i) * step);
    const auto toneMap = [scale](float v) { return acesToneMap(v * scale); };
    const std::vector<float> ldr = ldrFlipErrorMap(toFlipInput(reference, toneMap),
                                                   toFlipInput(test, toneMap), pixelsPerDegree);
    for (size_t p = 0; p < ldr.size(); ++p)
      result.errorMap[p] = std::max(result.errorMap[p], ldr[p]);
  }
  result.statistics = poolFlipErrors(result.errorMap);
  return result;
}

}  // namespace bounce
