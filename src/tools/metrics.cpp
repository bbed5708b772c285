#include "tools/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace bounce {
namespace {

void requireSameSize(const ImageRGBA32F& test, const ImageRGBA32F& reference) {
  if (test.width != reference.width || test.height != reference.height) {
    fail("image metrics: the test image is {}x{} but the reference is {}x{}", test.width,
         test.height, reference.width, reference.height);
  }
  if (test.pixelCount() == 0) fail("image metrics: the images are empty");
}

// Mean over pixels and RGB of perSample(test, reference), accumulated in double.
template <typename PerSample>
double meanOverRgb(const ImageRGBA32F& test, const ImageRGBA32F& reference, PerSample&& perSample) {
  requireSameSize(test, reference);
  double sum = 0.0;
  for (size_t i = 0; i < test.pixelCount(); ++i) {
    for (int c = 0; c < 3; ++c)
      sum += perSample(double(test.pixels[4 * i + c]), double(reference.pixels[4 * i + c]));
  }
  return sum / (3.0 * double(test.pixelCount()));
}

// One channel's term of relMSE (relativeMeanSquaredError, trailError).
double relativeSquaredError(double t, double r) {
  return (t - r) * (t - r) / (r * r + kRelMseEpsilon);
}

double psnrFromMse(double mse, double peak) {
  if (mse == 0.0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(peak * peak / mse);
}

double srgbEncodedClamped(double linear) {
  return linearToSrgb(float(std::clamp(linear, 0.0, 1.0)));
}

}  // namespace

double meanSquaredError(const ImageRGBA32F& test, const ImageRGBA32F& reference) {
  return meanOverRgb(test, reference, [](double t, double r) { return (t - r) * (t - r); });
}

double relativeMeanSquaredError(const ImageRGBA32F& test, const ImageRGBA32F& reference) {
  return meanOverRgb(test, reference, relativeSquaredError);
}

double psnrLdr(const ImageRGBA32F& test, const ImageRGBA32F& reference) {
  const double mse = meanOverRgb(test, reference, [](double t, double r) {
    const double d = srgbEncodedClamped(t) - srgbEncodedClamped(r);
    return d * d;
  });
  return psnrFromMse(mse, 1.0);
}

double psnrHdr(const ImageRGBA32F& test, const ImageRGBA32F& reference) {
  const double mse = meanSquaredError(test, reference);
  double peak = 0.0;
  for (size_t i = 0; i < reference.pixelCount(); ++i) {
    for (int c = 0; c < 3; ++c) peak = std::max(peak, double(reference.pixels[4 * i + c]));
  }
  if (peak <= 0.0) peak = 1.0;  // a black reference: fall back to unit peak
  return psnrFromMse(mse, peak);
}

namespace {

double luminanceAt(const ImageRGBA32F& image, size_t i) {
  return 0.2126 * image.pixels[4 * i] + 0.7152 * image.pixels[4 * i + 1] +
         0.0722 * image.pixels[4 * i + 2];
}

// Mean luminance over the 3x3 block around (x, y), inside the image.
double blockLuminance(const ImageRGBA32F& image, int x, int y) {
  double sum = 0.0;
  int count = 0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int u = x + dx, v = y + dy;
      if (u < 0 || v < 0 || u >= int(image.width) || v >= int(image.height)) continue;
      sum += luminanceAt(image, size_t(v) * image.width + size_t(u));
      ++count;
    }
  return sum / count;
}

}  // namespace

std::vector<uint8_t> trailMask(const ImageRGBA32F& reference, const ImageRGBA32F& earlier) {
  requireSameSize(earlier, reference);
  const int w = int(reference.width), h = int(reference.height);
  std::vector<uint8_t> changed(reference.pixelCount(), 0), mask(reference.pixelCount(), 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double now = blockLuminance(reference, x, y), before = blockLuminance(earlier, x, y);
      const double scale = std::max({now, before, kTrailFloor});
      changed[size_t(y) * w + x] = std::abs(now - before) > kTrailChange * scale;
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int dy = -1; dy <= 1 && !mask[size_t(y) * w + x]; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int u = x + dx, v = y + dy;
          if (u >= 0 && v >= 0 && u < w && v < h && changed[size_t(v) * w + u]) {
            mask[size_t(y) * w + x] = 1;
            break;
          }
        }
  return mask;
}

TrailError trailError(const ImageRGBA32F& test, const ImageRGBA32F& reference,
                      const std::vector<uint8_t>& mask) {
  requireSameSize(test, reference);
  if (mask.size() != reference.pixelCount())
    fail("image metrics: the trail mask has {} pixels, the images {}", mask.size(),
         reference.pixelCount());
  double trail = 0.0, rest = 0.0, testLuminance = 0.0, referenceLuminance = 0.0;
  TrailError e;
  for (size_t i = 0; i < reference.pixelCount(); ++i) {
    double sum = 0.0;
    for (int c = 0; c < 3; ++c)
      sum += relativeSquaredError(test.pixels[4 * i + c], reference.pixels[4 * i + c]);
    if (mask[i]) {
      trail += sum / 3.0;
      testLuminance += luminanceAt(test, i);
      referenceLuminance += luminanceAt(reference, i);
      ++e.pixels;
    } else {
      rest += sum / 3.0;
    }
  }
  const size_t others = reference.pixelCount() - e.pixels;
  e.relMseTrail = e.pixels > 0 ? trail / double(e.pixels) : 0.0;
  e.relMseRest = others > 0 ? rest / double(others) : 0.0;
  e.luminanceRatio = referenceLuminance > 0.0 ? testLuminance / referenceLuminance : 1.0;
  return e;
}

size_t countNonFinitePixels(const ImageRGBA32F& image) {
  size_t count = 0;
  for (size_t i = 0; i < image.pixelCount(); ++i) {
    const float* p = &image.pixels[4 * i];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) ++count;
  }
  return count;
}

}  // namespace bounce
