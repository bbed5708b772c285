// What the ReSTIR DI tests (test_restir_di.cpp, test_di_light_grid.cpp,
// test_restir_di_animation.cpp) share: the frame lit by DI alone, their scenes (the wall, city by
// night and its street view), the direct-light reference, and the statistics over independent
// images with which they compare the two (8x8 block means and their standard errors, per-pixel
// variance, the relMSE that noise alone gives).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "frame/hybrid_frame.h"
#include "rt/gpu_scene.h"
#include "scene/scene.h"
#include "tools/image_io.h"
#include "vk/context.h"

namespace bounce::test {

// Rec. 709 luminance of pixel i.
double pixelLuminance(const ImageRGBA32F& image, size_t i);

// The hybrid frame lit by DI alone: no GI, no reflection rays, full-resolution shadows.
HybridSettings diSettings(uint32_t width, uint32_t height, const DiSettings& di);

// The pixel-by-pixel mean of images of one size.
ImageRGBA32F meanImage(const std::vector<ImageRGBA32F>& images);

// Mean luminance of the columns [from, to) (0 where there are none).
double meanOfColumns(const ImageRGBA32F& image, uint32_t from, uint32_t to);
// Largest luminance in the columns [from, to).
double maxOfColumns(const ImageRGBA32F& image, uint32_t from, uint32_t to);

// A floor split by a wall along x = 0, taller than the point light (lights[0]) at x = -1, seen
// from above in the wall's plane: the image's left part sees what the light reaches, its right
// part (x > 0) only surfaces the light cannot reach. The scene is symmetric about the wall.
Scene wallScene();

// `city` at 22 h (no sun, the dim night sky); without its lamps when `lamps` is false (no spot
// lights, lamp covers that do not emit: the city before issue 20).
Scene cityAtNight(bool lamps);
// A view down the avenue at x = 0 from 5 m up, over a crossing: eight lamps on the avenue's two
// sides and the crossing street's light pools, facades, little sky.
Camera cityStreetCamera();

// The reference path tracer limited to direct light (one scattering event, camera rays through
// pixel centres) in `batches` independent batches of `spp` samples (seeds 1, 2, ...).
std::vector<ImageRGBA32F> directReference(vk::Context& context, GpuScene& gpuScene,
                                          const Scene& scene, const Camera& camera, uint32_t width,
                                          uint32_t height, int batches, uint32_t spp);

// `runs` independent runs of `frame` (resetHistory before each) of `framesPerRun` frames each:
// each run's mean di-shade image (runs are independent, frames of one run correlated by reuse).
std::vector<ImageRGBA32F> runMeans(HybridFrame& frame, const Camera& camera, int runs,
                                   int framesPerRun);

// Each 8x8 block's mean luminance in each of a set of independent images: its mean over the
// images and the standard error of that mean (two-pass sample variance over the count).
struct BlockStatistics {
  std::vector<std::vector<double>> perImage;  // [image][block]

  void add(const ImageRGBA32F& image);
  size_t blockCount() const { return perImage.empty() ? 0 : perImage[0].size(); }
  double mean(size_t b) const;
  double standardError(size_t b) const;
};
// The block statistics of each of `images`.
BlockStatistics blockStatistics(const std::vector<ImageRGBA32F>& images);

// How far the blocks of a test's images lie from the reference's, in combined standard errors.
struct BlockComparison {
  double worstZ = 0.0;  // the largest |test - reference| / SE over the blocks
  size_t outside = 0;   // blocks beyond maxZ
};
// Compares block by block and prints each block beyond `maxZ`, the test's named `testName`.
BlockComparison compareBlocks(const BlockStatistics& test, const BlockStatistics& reference,
                              double maxZ, const char* testName);

// The relMSE that noise alone gives, expected: the mean over pixels and channels of
// (variance of the test's mean + variance of the reference's mean) / (reference^2 + epsilon),
// each variance the sample variance of independent estimates over their count. relMSE minus
// this is the squared bias's share.
double noiseRelMse(const std::vector<ImageRGBA32F>& test,
                   const std::vector<ImageRGBA32F>& reference, const ImageRGBA32F& referenceMean);

// Per-pixel variance (luminance) over independent images, averaged over the pixels.
struct PixelVariance {
  std::vector<double> sum, sumSq;
  int n = 0;

  void add(const ImageRGBA32F& image);
  double meanVariance() const;
};
// The per-pixel variance of di-shade over `runs` consecutive frames of `frame`, averaged over
// the pixels: one frame's variance where frames do not reuse (--di uniform).
double oneFrameVariance(HybridFrame& frame, const Camera& camera, int runs);

}  // namespace bounce::test
