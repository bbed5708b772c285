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
  return meanOverRgb(test, reference, [](double t, double r) {
    return (t - r) * (t - r) / (r * r + kRelMseEpsilon);
  });
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

size_t countNonFinitePixels(const ImageRGBA32F& image) {
  size_t count = 0;
  for (size_t i = 0; i < image.pixelCount(); ++i) {
    const float* p = &image.pixels[4 * i];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) ++count;
  }
  return count;
}

}  // namespace bounce
