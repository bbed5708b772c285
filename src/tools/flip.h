// FLIP, the perceptual image-difference evaluator of
//   [FLIP]    Andersson, Nilsson, Akenine-Möller, Oskarsson, Åström, Fairchild, "FLIP: A
//             Difference Evaluator for Alternating Images", HPG 2020 (PACMCGIT 3(2), 15).
//   [HDRFLIP] Andersson, Nilsson, Shirley, Akenine-Möller, "Visualizing Errors in Rendered High
//             Dynamic Range Images", Eurographics 2021 short paper.
// Our own implementation from the papers; it reproduces the values of the authors' tool
// (NVlabs/flip v1.6) on the reference pair in shared/references to a few 1e-4.
//
// Both variants return a per-pixel error map in [0,1] (0 = indistinguishable when alternating
// between the images, 1 = maximal) and its pooled statistics.
#pragma once
#include <optional>
#include <vector>

#include "tools/image_io.h"

namespace bounce {

// The angular resolution of the observer: pixels per degree of visual angle for a screen
// `screenWidthMeters` wide with `screenWidthPixels` pixels, seen from `distanceMeters` (the
// small-angle form the FLIP tool uses).
constexpr float pixelsPerDegree(float distanceMeters, float screenWidthMeters,
                                float screenWidthPixels) {
  return distanceMeters * (screenWidthPixels / screenWidthMeters) * (3.14159265358979f / 180.0f);
}
// The FLIP tool's default observer: a 0.7 m wide 3840-pixel monitor at 0.7 m, 67.02 pixels per
// degree (the tool prints it rounded, as "67"). The reference values in shared/references were
// computed with it; exactly 67 changes them by about 2e-4 relative.
constexpr float kDefaultPixelsPerDegree = pixelsPerDegree(0.7f, 0.7f, 3840.0f);

// Pooled statistics as the authors' tool reports them. The weighted percentiles weight each
// pixel's error by the error itself, so they describe where the *bulk of the error* lies: the
// weighted median is the error value below which half of the summed error is found.
struct FlipStatistics {
  double mean = 0.0;
  double weightedMedian = 0.0;
  double firstWeightedQuartile = 0.0;
  double thirdWeightedQuartile = 0.0;
  double min = 0.0;
  double max = 0.0;
};

// HDR-FLIP evaluates LDR-FLIP at `count` exposures (in stops) spread evenly over [start, stop].
struct FlipExposureRange {
  float start = 0.0f;
  float stop = 0.0f;
  int count = 2;
};

struct FlipResult {
  int width = 0;
  int height = 0;
  std::vector<float> errorMap;  // one value in [0,1] per pixel, rows top to bottom
  FlipStatistics statistics;
  std::optional<FlipExposureRange> exposures;  // set by HDR-FLIP
};

// LDR-FLIP [FLIP]. Both images hold linear RGB of display-referred content (what readImage
// gives for PNG/JPG); values are clamped to [0,1]. Sizes must match.
FlipResult computeLdrFlip(const ImageRGBA32F& test, const ImageRGBA32F& reference,
                          float pixelsPerDegree = kDefaultPixelsPerDegree);

// HDR-FLIP [HDRFLIP]: scene-referred linear RGB. Without `exposures` the range is chosen from
// the reference (automaticExposureRange).
FlipResult computeHdrFlip(const ImageRGBA32F& test, const ImageRGBA32F& reference,
                          float pixelsPerDegree = kDefaultPixelsPerDegree,
                          std::optional<FlipExposureRange> exposures = std::nullopt);

// [HDRFLIP], "Computing start and stop exposures": start = log2(x85 / Lmax), stop = log2(x85 /
// Lmedian), where x85 is the input the ACES tone curve maps to 0.85 and L is the reference's
// luminance; count = max(2, ceil(stop - start)), one exposure per stop or so. Lmedian is the upper
// median over all pixels as in the authors' tool, or over the lit pixels when more than half are
// black.
FlipExposureRange automaticExposureRange(const ImageRGBA32F& reference);

// The tone curve of HDR-FLIP: Narkowicz's fit of the ACES filmic curve with his 0.6 pre-scale,
// per channel, not clamped.
float acesToneMap(float x);

// Mean, weighted median/quartiles (see FlipStatistics), min and max of an error map.
FlipStatistics poolFlipErrors(const std::vector<float>& errorMap);

}  // namespace bounce
