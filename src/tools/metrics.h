// Image-error metrics for comparing a render against a reference (DESIGN.md §6): MSE, relMSE,
// PSNR, and the perceptual FLIP (tools/flip.h). Every function takes (test, reference), reads
// the RGB channels only (alpha is ignored) and requires equal sizes.
#pragma once
#include <cstdint>
#include <vector>

#include "tools/flip.h"
#include "tools/image_io.h"

namespace bounce {

// relMSE's epsilon: keeps black reference pixels from dividing by zero while barely changing
// the value where the reference is brighter than ~0.1. It is the value commonly used to report
// Monte-Carlo rendering error (e.g. Rousselle et al., "Robust Denoising using Feature and Color
// Information", 2013).
constexpr double kRelMseEpsilon = 0.01;

// Mean over pixels and RGB channels of (test - reference)^2, on the linear values.
double meanSquaredError(const ImageRGBA32F& test, const ImageRGBA32F& reference);

// Mean over pixels and RGB channels of (test - reference)^2 / (reference^2 + kRelMseEpsilon),
// on the linear values: scale-independent, so dark and bright regions count alike.
double relativeMeanSquaredError(const ImageRGBA32F& test, const ImageRGBA32F& reference);

// PSNR in dB of display-referred images: both sRGB-encoded (clamped to [0,1]), peak 1. This is
// the PSNR image tools report for PNGs. +infinity for identical images.
double psnrLdr(const ImageRGBA32F& test, const ImageRGBA32F& reference);

// PSNR in dB of scene-referred images: on the linear values, with the peak taken as the
// reference's largest RGB value (there is no fixed white in HDR). +infinity when identical.
double psnrHdr(const ImageRGBA32F& test, const ImageRGBA32F& reference);

// Ghosting and lag under motion: where a scene changed between two poses, and the error there.
// The trail mask holds the pixels whose reference luminance (mean over their 3x3 block, so a
// reference's own noise does not mark pixels) changed by more than kTrailChange of the larger
// of the two (at least kTrailFloor) between `earlier` and `reference`, dilated by one pixel: the
// moving objects' old and new places and their shadows. A ghost is left there; lag shows there.
constexpr double kTrailChange = 0.25;
constexpr double kTrailFloor = 0.05;
std::vector<uint8_t> trailMask(const ImageRGBA32F& reference, const ImageRGBA32F& earlier);

struct TrailError {
  size_t pixels = 0;            // in the mask
  double relMseTrail = 0.0;     // relMSE over the mask's pixels (0 if it is empty)
  double relMseRest = 0.0;      // relMSE over the other pixels
  double luminanceRatio = 1.0;  // sum of test luminance / sum of reference luminance in the mask
};
TrailError trailError(const ImageRGBA32F& test, const ImageRGBA32F& reference,
                      const std::vector<uint8_t>& mask);

// Pixels with a NaN or infinite RGB value (such images cannot be compared meaningfully).
size_t countNonFinitePixels(const ImageRGBA32F& image);

}  // namespace bounce
