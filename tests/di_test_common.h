// What the ReSTIR DI tests (test_restir_di.cpp, test_di_light_grid.cpp,
// test_restir_di_animation.cpp) share: the frame lit by DI alone, their scenes (the wall, city by
// night and its street view), the direct-light reference, and the statistics over independent
// images with which they compare the two (8x8 block means and their standard errors, per-pixel
// variance, the relMSE that noise alone gives).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
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

// The light-animation sequence on wallScene() (48x32, `view` captured after each step):
// 8 frames as built (`before`), the light moved to x = +1 behind the wall for one frame
// (`moved`) and 23 more (`settled`), switched off for one frame (`off`), then back as built
// for one frame (`back`).
struct WallSequence {
  static constexpr uint32_t kWidth = 48, kHeight = 32;
  static constexpr uint32_t kLeftEnd = kWidth / 2 - 4, kRightStart = kWidth / 2 + 4;
  ImageRGBA32F before, moved, settled, off, back;
  uint32_t validationErrors = 0;
};
WallSequence runWallSequence(const DiSettings& di, const std::string& view);

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

// How far the blocks of a test's images lie from the reference's, in combined standard errors.
struct BlockComparison {
  double worstZ = 0.0;  // the largest |test - reference| / SE over the blocks
  size_t outside = 0;   // blocks beyond maxZ
};

// The counts of compareWithDirectReference (the unbiased tests' 16 x 4 frames, 8 x 128 spp).
struct DirectComparisonRuns {
  int runs = 16, framesPerRun = 4;  // independent runs of the hybrid frame, frames of each
  int batches = 8;                  // independent batches of the reference
  uint32_t spp = 128;               // samples per pixel of each batch
  double maxZ = 3.0;                // a block beyond this many standard errors is `outside`
};

// What compareWithDirectReference measured.
struct DirectComparison {
  ImageRGBA32F hybridMean, referenceMean;
  BlockComparison blocks;
  size_t blockCount = 0;
  double relMse = 0.0;
  // The relMSE that noise alone gives, expected (both images' noise): relMSE minus this is the
  // squared bias's share.
  double noiseShare = 0.0;
  double meanRatio = 0.0;  // mean luminance of the hybrid over the reference's
};

// The DI tests' unbiasedness check: the mean di-shade of `runs` independent runs of
// `framesPerRun` frames of `frame` (resetHistory before each: runs are independent, frames of
// one run correlated by reuse) against `batches` x `spp` samples of directReference: each 8x8
// block's mean luminance, with standard errors over the runs and batches (blocks beyond `maxZ`
// printed, the test's image named `testName`), and the whole image's relMSE.
DirectComparison compareWithDirectReference(vk::Context& context, GpuScene& gpuScene,
                                            const Scene& scene, const Camera& camera,
                                            HybridFrame& frame, uint32_t width, uint32_t height,
                                            const DirectComparisonRuns& runs, const char* testName);

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
